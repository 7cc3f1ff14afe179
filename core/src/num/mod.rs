//! Numbers: the [`Scalar`] abstraction and the small linear-algebra types built on it.
//!
//! The same stepping code runs in Q32.32 fixed point ([`Fx`], the production path, integer
//! arithmetic only) and in `f64` (the reference path, used to *measure* quantisation error).

pub mod exact_sum;
pub mod fixed;
pub mod fixed_fast;
pub mod lanes;
pub mod quantise;
pub mod quat;
pub mod scalar;
pub mod vec3;

pub use fixed::Fx;
pub use fixed_fast::{Envelope, FxFast};
pub use quat::{Mat3, Quat};
pub use scalar::Scalar;
pub use vec3::Vec3;
