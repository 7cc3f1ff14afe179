//! Plackett–Burman screening designs with 12 and 20 runs.
//!
//! Construction (Plackett & Burman 1946): the first run is the generator row; each further
//! run is the previous one shifted cyclically one place to the right; a last run has every
//! column at −1. With N runs there are N − 1 two-level columns; real factors take the first
//! columns and the rest are dummy columns, whose effects estimate error (seed 000 §3.3:
//! "three dummy terms were reserved for error analysis"). Optional centre points follow
//! (seed 001 Table 6 has three).
//!
//! Generators:
//! - 12 runs: `+ + − + + + − − − + −` (DESIGN §9; Plackett & Burman 1946).
//! - 20 runs: `+ + − − + + + + − + − + − − − − + + −` (Plackett & Burman 1946).
//!
//! The standard order is this construction's row order; Design-Expert does not document its
//! own "Std" numbering for Plackett–Burman designs, so no claim is made that the two agree.
//! (Shifting the generator *down the columns* instead of along the rows gives a different
//! set of rows on the first k columns, which does not match the seeds.)
//!
//! Seed 000 Table 4 (8 factors + 3 dummies) and seed 001 Table 6 (9 factors + 2 dummies,
//! 3 centre points) are row permutations of this construction (`tests/doe_seed_designs.rs`).
//!
//! ```
//! use arachis::doe::{plackett_burman, Factor, PlackettBurmanRuns};
//! let f: Vec<Factor> = (1..=8)
//!     .map(|i| Factor::new(&format!("x{i}"), "-", 0.0, 1.0).unwrap())
//!     .collect();
//! let d = plackett_burman(PlackettBurmanRuns::Twelve, &f, 0).unwrap();
//! assert_eq!(d.runs(), 12);
//! assert_eq!(d.dummy_columns.len(), 3);
//! ```

use super::design::{centre_rows, Design, PointType};
use super::factor::check_unique_names;
use super::{DesignError, Factor};

/// Generator row of the 12-run design (DESIGN §9): `+ + − + + + − − − + −`.
pub const GENERATOR_12: [i8; 11] = [1, 1, -1, 1, 1, 1, -1, -1, -1, 1, -1];

/// Generator row of the 20-run design (Plackett & Burman 1946):
/// `+ + − − + + + + − + − + − − − − + + −`.
pub const GENERATOR_20: [i8; 19] = [
    1, 1, -1, -1, 1, 1, 1, 1, -1, 1, -1, 1, -1, -1, -1, -1, 1, 1, -1,
];

/// Number of runs of a Plackett–Burman design (centre points not counted).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlackettBurmanRuns {
    /// 12 runs, up to 11 factors.
    Twelve,
    /// 20 runs, up to 19 factors.
    Twenty,
}

impl PlackettBurmanRuns {
    /// The generator row.
    pub fn generator(self) -> &'static [i8] {
        match self {
            Self::Twelve => &GENERATOR_12,
            Self::Twenty => &GENERATOR_20,
        }
    }

    /// Runs without centre points (N).
    pub fn runs(self) -> usize {
        self.generator().len() + 1
    }
}

/// The Plackett–Burman design of `runs` runs for `factors` (at most N − 1), the remaining
/// columns being dummies named `dummy1`, `dummy2`, … (rename with
/// [`Design::with_dummy_names`]), followed by `centre_points` centre runs.
pub fn plackett_burman(
    runs: PlackettBurmanRuns,
    factors: &[Factor],
    centre_points: usize,
) -> Result<Design, DesignError> {
    let generator = runs.generator();
    let columns = generator.len();
    if factors.is_empty() || factors.len() > columns {
        return Err(DesignError::FactorCount {
            design: "Plackett-Burman",
            k: factors.len(),
            allowed: format!("1 to {columns} for {} runs", runs.runs()),
        });
    }
    check_unique_names(factors)?;
    let mut coded: Vec<Vec<f64>> = (0..columns)
        .map(|shift| {
            // Run `shift` is the generator shifted right `shift` places.
            (0..columns)
                .map(|j| f64::from(generator[(j + columns - shift) % columns]))
                .collect()
        })
        .collect();
    coded.push(vec![-1.0; columns]);
    let mut point_types = vec![PointType::Factorial; coded.len()];
    let (centre, centre_types) = centre_rows(centre_points, columns);
    coded.extend(centre);
    point_types.extend(centre_types);
    let dummies = (1..=columns - factors.len())
        .map(|i| format!("dummy{i}"))
        .collect();
    Ok(Design::new(
        &format!("Plackett-Burman {}", runs.runs()),
        factors.to_vec(),
        dummies,
        coded,
        point_types,
    ))
}
