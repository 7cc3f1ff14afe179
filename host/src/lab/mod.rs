//! Bench-test analysis: turns replicate measurements into parameter values (issue 3,
//! item 1). One module per test; each has SI formula functions citing the seed equation
//! and an `analyze` that reads a CSV table (columns named with their units) into a
//! [`LabReport`] whose quantities carry the replicate [`Summary`] (n, mean, sample SD,
//! range and 95% confidence interval of the mean).
//!
//! | test | module | seed |
//! |---|---|---|
//! | density by displacement | [`density`] | 000 §2.5.1 |
//! | Poisson's ratio | [`poisson`] | 000 eq. (8) |
//! | Hertz apparent modulus, K(θ) | [`hertz_modulus`], [`hertz_k`] | 000 eqs. (9)–(11), Table 2; 001 eqs. (19)–(22) |
//! | shear modulus | [`shear_modulus`] | 000 eq. (12) |
//! | tensile modulus | [`tensile_modulus`] | 001 eq. (23) |
//! | restitution, 45° plate | [`restitution_plate`] | 000 eqs. (13)–(18) |
//! | restitution, 3-D camera | [`restitution_camera`], [`rotation_energy`] | 001 eqs. (2)–(15) |
//! | static friction | [`static_friction`] | 000 eq. (19), 001 eq. (1) |
//! | rolling friction | [`rolling_friction`] | 000 eq. (20), 001 eq. (17) |
//! | bond parameters | [`bond`] | 001 eqs. (26)–(28) |
//!
//! The text of seed 001 has lost its equation numbers; we count them in order, anchored on
//! its own references to eqs. (2), (6), (9)–(12) and (23).

pub mod bond;
pub mod columns;
pub mod density;
pub mod error;
pub mod hertz_k;
pub mod hertz_modulus;
pub mod poisson;
pub mod report;
pub mod restitution_camera;
pub mod restitution_plate;
pub mod rolling_friction;
pub mod rotation_energy;
pub mod shear_modulus;
pub mod static_friction;
pub mod summary;
pub mod tensile_modulus;
pub mod units;

pub use error::LabError;
pub use report::{LabReport, Quantity, Replicate, Value};
pub use summary::{summarize, Summary, SummaryError};
