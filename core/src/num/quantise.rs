//! Set-up quantisation: SI inputs, already converted to internal units, into a [`Scalar`],
//! refusing what the fixed-point format cannot hold (DESIGN §4).
//!
//! ```
//! use arachis_core::num::quantise::{quantise, quantise_coordinate};
//! use arachis_core::num::Fx;
//! assert!(quantise::<Fx>(4.0, "sphere radius").is_ok());
//! assert!(quantise::<Fx>(1e-12, "sphere radius").is_err()); // rounds to zero
//! assert!(quantise_coordinate::<Fx>(1e-12, "position").is_ok());
//! assert!(quantise_coordinate::<Fx>(f64::NAN, "position").is_err());
//! ```

use super::Scalar;
use crate::error::SetupError;
use crate::material::finite;

/// Largest magnitude accepted at set-up in internal units: inside the Q32.32 range (±2.1e9)
/// with headroom for the sums the stepper forms.
pub const MAX_INTERNAL_MAGNITUDE: f64 = 1.0e9;

/// Quantise a set-up value (internal units) into `S`, refusing non-finite values, values
/// beyond [`MAX_INTERNAL_MAGNITUDE`], and non-zero values that would round to zero.
pub fn quantise<S: Scalar>(x: f64, what: &'static str) -> Result<S, SetupError> {
    let q = quantise_coordinate(x, what)?;
    if x != 0.0 && q == S::ZERO {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    Ok(q)
}

/// Quantise a coordinate-like value (position, velocity, offset): like [`quantise`] but
/// values below the resolution may round to zero.
pub fn quantise_coordinate<S: Scalar>(x: f64, what: &'static str) -> Result<S, SetupError> {
    let x = finite(x, what)?;
    if x.abs() > MAX_INTERNAL_MAGNITUDE {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    let q = S::from_f64(x);
    if !q.is_valid() {
        return Err(SetupError::NotRepresentable { what, value: x });
    }
    Ok(q)
}
