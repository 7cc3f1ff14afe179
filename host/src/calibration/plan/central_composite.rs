//! The central composite response surface of seed 001 (§3.2, Tables 9–11): its box and its
//! design.
//!
//! As in seed 001 Table 9, the best path point is the centre and its neighbours on the path
//! are the ±1 levels (Table 8's points 2 and 4 around point 3); the axial points lie at ±α
//! (1.414) and the plan adds centre points (Table 10: five, 13 runs for two factors). The
//! optimum is searched inside the star points (seed 001 §3.2: 4 ≤ X7 ≤ 6, 8 ≤ X8 ≤ 12).

use super::response_surface::BoxChoice;
use crate::doe::{central_composite, Alpha, Design, DesignError, Factor};

/// Fewest factors of a central composite design.
pub const MIN_FACTORS: usize = 2;
/// Most factors carried (a three-factor design has 8 cube, 6 axial and the centre runs).
pub const MAX_FACTORS: usize = 3;

/// The box's path positions (0-based, possibly −1 or past the end): the neighbours of the
/// best point `best` (0-based).
pub fn box_positions(best: usize) -> ([i64; 2], BoxChoice) {
    let b = best as i64;
    ([b - 1, b + 1], BoxChoice::AroundBest)
}

/// The design over `factors`, axial distance `alpha` (coded), `centre_points` centre runs.
pub fn design(factors: &[Factor], alpha: f64, centre_points: usize) -> Result<Design, DesignError> {
    central_composite(factors, Alpha::Value(alpha), centre_points)
}
