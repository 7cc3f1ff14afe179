//! Box–Behnken designs for 3 to 7 factors (Box & Behnken 1960).
//!
//! Each block of factors runs a two-level full factorial (in standard order) with all other
//! factors at their centre; centre points follow. The blocks are:
//! - k = 3, 4, 5: every pair of factors, in lexicographic order (AB, AC, …), giving
//!   12, 24 and 40 runs;
//! - k = 6: the six published triples (1,2,4), (2,3,5), (3,4,6), (1,4,5), (2,5,6), (1,3,6),
//!   giving 48 runs;
//! - k = 7: the seven published triples (4,5,6), (1,6,7), (2,5,7), (1,2,4), (3,4,7),
//!   (1,3,5), (2,3,6) — a balanced incomplete block design in which every pair of factors
//!   meets exactly once — giving 56 runs.
//!
//! These are the block structures of Box & Behnken (1960), also used by Design-Expert,
//! Matlab's `bbdesign` and R's `rsm::bbd`; taking all pairs for 6 and 7 factors would give
//! 60 and 84 runs instead.
//!
//! Within a block the varied factors run through their 2² or 2³ corners in Yates order, so
//! for 3 factors the standard order is AB (−−, +−, −+, ++), AC, BC, then the centre points.
//! For 4 and 5 factors Design-Expert may list the pairs in its orthogonal-blocking order; the
//! set of runs is the same.
//!
//! Seed 000 Table 8 (3 factors, 5 centre points, 17 runs) is this design in a randomised
//! order (`tests/doe_seed_designs.rs`).
//!
//! ```
//! use arachis::doe::{box_behnken, Factor};
//! let f: Vec<Factor> = ["x3", "x4", "x5"]
//!     .iter()
//!     .map(|n| Factor::new(n, "-", 0.0, 1.0).unwrap())
//!     .collect();
//! assert_eq!(box_behnken(&f, 5).unwrap().runs(), 17);
//! ```

use super::design::{centre_rows, yates_corners, Design, PointType};
use super::factor::check_unique_names;
use super::{DesignError, Factor};

/// Fewest factors of a Box–Behnken design.
pub const MIN_FACTORS: usize = 3;
/// Most factors supported (the published block structures stop here for this crate).
pub const MAX_FACTORS: usize = 7;

/// Published blocks for 6 factors (1-based factor numbers), Box & Behnken (1960).
const BLOCKS_6: [[usize; 3]; 6] = [
    [1, 2, 4],
    [2, 3, 5],
    [3, 4, 6],
    [1, 4, 5],
    [2, 5, 6],
    [1, 3, 6],
];

/// Published blocks for 7 factors (1-based factor numbers), Box & Behnken (1960).
const BLOCKS_7: [[usize; 3]; 7] = [
    [4, 5, 6],
    [1, 6, 7],
    [2, 5, 7],
    [1, 2, 4],
    [3, 4, 7],
    [1, 3, 5],
    [2, 3, 6],
];

/// The blocks of factors (0-based) varied together for `k` factors.
pub fn blocks(k: usize) -> Result<Vec<Vec<usize>>, DesignError> {
    let one_based = |b: &[usize]| b.iter().map(|i| i - 1).collect::<Vec<_>>();
    match k {
        MIN_FACTORS..=5 => Ok((0..k)
            .flat_map(|i| (i + 1..k).map(move |j| vec![i, j]))
            .collect()),
        6 => Ok(BLOCKS_6.iter().map(|b| one_based(b)).collect()),
        MAX_FACTORS => Ok(BLOCKS_7.iter().map(|b| one_based(b)).collect()),
        _ => Err(DesignError::FactorCount {
            design: "Box-Behnken",
            k,
            allowed: format!("{MIN_FACTORS} to {MAX_FACTORS}"),
        }),
    }
}

/// The Box–Behnken design for `factors` (3 to 7), followed by `centre_points` centre runs.
pub fn box_behnken(factors: &[Factor], centre_points: usize) -> Result<Design, DesignError> {
    let k = factors.len();
    let blocks = blocks(k)?;
    check_unique_names(factors)?;
    let mut coded = Vec::new();
    for block in &blocks {
        for corner in yates_corners(block.len()) {
            let mut row = vec![0.0; k];
            for (&factor, &level) in block.iter().zip(&corner) {
                row[factor] = level;
            }
            coded.push(row);
        }
    }
    let mut point_types = vec![PointType::Edge; coded.len()];
    let (centre, centre_types) = centre_rows(centre_points, k);
    coded.extend(centre);
    point_types.extend(centre_types);
    Ok(Design::new(
        "Box-Behnken",
        factors.to_vec(),
        Vec::new(),
        coded,
        point_types,
    ))
}
