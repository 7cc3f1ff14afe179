//! The Box–Behnken response surface of seed 000 (§3.5, Tables 7–9, eq. (22)): its box and
//! its design.
//!
//! The box: when the best path point and a neighbour bracket the target (their responses
//! lie on either side of it), those two points become coded −1 and +1 of each factor —
//! seed 000 §3.4 takes points 2 and 3 of Table 6 (29.36° and 31.48° around 31.06°). When no
//! neighbour brackets it (the best point is at the end of the path, or the path overshoots
//! on both sides), the box spans one step either side of the best point, which reaches past
//! the path's end where the target may lie. The design has the plan's centre points (seed
//! 000 Table 8: 17 = 12 + 5 runs); the optimum is searched inside the box.

use super::response_surface::BoxChoice;
use crate::doe::{box_behnken, Design, DesignError, Factor};

/// Fewest factors of a Box–Behnken design.
pub const MIN_FACTORS: usize = crate::doe::box_behnken::MIN_FACTORS;
/// Most factors (the largest Box–Behnken design available).
pub const MAX_FACTORS: usize = crate::doe::box_behnken::MAX_FACTORS;

/// The box's path positions (0-based, possibly −1 or past the end) for path `responses`,
/// the best point `best` (0-based) and the `target`.
pub fn box_positions(responses: &[f64], best: usize, target: f64) -> ([i64; 2], BoxChoice) {
    let brackets = |a: usize, b: usize| (responses[a] - target) * (responses[b] - target) <= 0.0;
    let b = best as i64;
    if best + 1 < responses.len() && brackets(best, best + 1) {
        ([b, b + 1], BoxChoice::Bracketing)
    } else if best >= 1 && brackets(best - 1, best) {
        ([b - 1, b], BoxChoice::Bracketing)
    } else {
        ([b - 1, b + 1], BoxChoice::AroundBest)
    }
}

/// The design over `factors` with `centre_points` centre runs.
pub fn design(factors: &[Factor], centre_points: usize) -> Result<Design, DesignError> {
    box_behnken(factors, centre_points)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed000_table6_brackets_between_points_2_and_3() {
        let y = [23.89, 29.36, 31.48, 35.01, 38.22];
        assert_eq!(box_positions(&y, 2, 31.06), ([1, 2], BoxChoice::Bracketing));
    }

    #[test]
    fn path_end_reaches_one_step_beyond() {
        let y = [20.0, 22.0, 24.0, 26.0, 28.0];
        assert_eq!(box_positions(&y, 4, 31.06), ([3, 5], BoxChoice::AroundBest));
    }
}
