//! The path of steepest ascent (Box & Wilson 1951) from a first-order model.
//!
//! For a first-order model ŷ = b₀ + Σ bᵢ xᵢ in coded units the path moves along the gradient
//! (b₁, …, b_k). The factor with the largest |bᵢ| moves `base_step` coded units per step and
//! every other factor moves `base_step · bᵢ / max|b|`; point m is `origin + m · Δ`. For a path
//! of steepest *descent* negate the coefficients.
//!
//! The seeds' paths: seed 001 Table 8 moves X7 and X8 up together by a quarter of their
//! ranges per step from the low corner (origin (−1, −1), direction (1, 1), step 0.5). Its
//! direction is not the gradient of its own screening equation, whose X8 coefficient is
//! −1.68: the authors chose the direction that raises the force towards the measured one.
//! Seed 000 Table 6 is not a straight line at all (x5 rises 0.018, 0.018, 0.003, 0.003); see
//! `tests/doe_seed_designs.rs`.
//!
//! ```
//! use arachis::doe::{steepest_ascent, Factor};
//! let f = vec![
//!     Factor::new("X7", "1e5 N/m^3", 3.0, 7.0).unwrap(),
//!     Factor::new("X8", "1e5 Pa", 6.0, 14.0).unwrap(),
//! ];
//! let d = steepest_ascent(&f, &[1.0, 1.0], &[-1.0, -1.0], 0.5, 5).unwrap();
//! assert_eq!(d.actual_row(2), vec![5.0, 10.0]);
//! ```

use super::design::{Design, PointType};
use super::factor::check_unique_names;
use super::{DesignError, Factor};

/// Points along the path of steepest ascent of a first-order model with coded coefficients
/// `coefficients` (one per factor), starting at coded `origin`, with the largest-coefficient
/// factor moving `base_step` coded units per step; `points` points including the origin.
pub fn steepest_ascent(
    factors: &[Factor],
    coefficients: &[f64],
    origin: &[f64],
    base_step: f64,
    points: usize,
) -> Result<Design, DesignError> {
    let k = factors.len();
    if k == 0 {
        return Err(DesignError::FactorCount {
            design: "steepest ascent",
            k,
            allowed: "at least 1".into(),
        });
    }
    check_unique_names(factors)?;
    if coefficients.len() != k || origin.len() != k {
        return Err(DesignError::BadPath(format!(
            "{k} factors but {} coefficients and {} origin values",
            coefficients.len(),
            origin.len()
        )));
    }
    if coefficients.iter().chain(origin).any(|v| !v.is_finite()) {
        return Err(DesignError::BadPath(
            "coefficients and origin must be finite numbers".into(),
        ));
    }
    let largest = coefficients.iter().fold(0.0_f64, |m, b| m.max(b.abs()));
    if largest == 0.0 {
        return Err(DesignError::BadPath(
            "all coefficients are zero, so there is no direction".into(),
        ));
    }
    if !(base_step.is_finite() && base_step > 0.0) {
        return Err(DesignError::BadPath(format!(
            "step {base_step} must be a positive number of coded units"
        )));
    }
    if points < 2 {
        return Err(DesignError::BadPath(format!(
            "{points} points: a path needs at least 2"
        )));
    }
    let step: Vec<f64> = coefficients
        .iter()
        .map(|b| base_step * b / largest)
        .collect();
    let coded: Vec<Vec<f64>> = (0..points)
        .map(|m| {
            origin
                .iter()
                .zip(&step)
                .map(|(o, d)| o + m as f64 * d)
                .collect()
        })
        .collect();
    Ok(Design::new(
        "steepest ascent",
        factors.to_vec(),
        Vec::new(),
        coded,
        vec![PointType::Path; points],
    ))
}
