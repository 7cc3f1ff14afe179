//! Central composite designs: the 2^k factorial cube, 2k axial (star) points at ±α on each
//! axis, and centre points.
//!
//! Standard order: the cube in Yates order, then the axial pairs (−α, +α) for A, B, …, then
//! the centre points. The axial distance α is
//! - rotatable: α = (2^k)^(1/4) (DESIGN §9; 1.414 for k = 2, 1.682 for k = 3),
//! - face-centred: α = 1,
//! - spherical: α = √k,
//! - or a given value, such as seed 001's printed 1.414 (Table 9).
//!
//! Seed 001 Table 10 (2 factors, α = 1.414, 5 centre points, 13 runs) is this design in a
//! randomised order (`tests/doe_seed_designs.rs`).
//!
//! ```
//! use arachis::doe::{central_composite, Alpha, Factor};
//! let f: Vec<Factor> = ["X7", "X8"]
//!     .iter()
//!     .map(|n| Factor::new(n, "-", 0.0, 1.0).unwrap())
//!     .collect();
//! let d = central_composite(&f, Alpha::Rotatable, 5).unwrap();
//! assert_eq!(d.runs(), 13);
//! assert!((Alpha::Rotatable.value(2).unwrap() - 2f64.sqrt()).abs() < 1e-12);
//! ```

use super::design::{centre_rows, yates_corners, Design, PointType};
use super::factor::check_unique_names;
use super::{DesignError, Factor};

/// Fewest factors of a central composite design.
pub const MIN_FACTORS: usize = 2;
/// Most factors accepted (a 2^10 cube is already 1024 corner runs).
pub const MAX_FACTORS: usize = 10;

/// How the axial distance α is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Alpha {
    /// α = (2^k)^(1/4), rotatable (DESIGN §9).
    Rotatable,
    /// α = 1, axial points on the faces of the cube.
    FaceCentred,
    /// α = √k, axial points on the sphere through the corners.
    Spherical,
    /// A given α in coded units (e.g. 1.414 as printed in seed 001 Table 9).
    Value(f64),
}

impl Alpha {
    /// α in coded units for `k` factors.
    pub fn value(self, k: usize) -> Result<f64, DesignError> {
        let k = k as f64;
        let a = match self {
            Self::Rotatable => k.exp2().powf(0.25),
            Self::FaceCentred => 1.0,
            Self::Spherical => k.sqrt(),
            Self::Value(a) => a,
        };
        if a.is_finite() && a > 0.0 {
            Ok(a)
        } else {
            Err(DesignError::BadAlpha(a))
        }
    }

    /// Parses `rotatable`, `face`, `spherical` or a positive number.
    pub fn parse(text: &str) -> Result<Self, DesignError> {
        match text.trim().to_ascii_lowercase().as_str() {
            "rotatable" => Ok(Self::Rotatable),
            "face" | "face-centred" | "face-centered" => Ok(Self::FaceCentred),
            "spherical" => Ok(Self::Spherical),
            other => match other.parse::<f64>() {
                Ok(a) if a.is_finite() && a > 0.0 => Ok(Self::Value(a)),
                Ok(a) => Err(DesignError::BadAlpha(a)),
                Err(_) => Err(DesignError::BadFactorSpec {
                    spec: text.to_owned(),
                    reason: "alpha must be rotatable, face, spherical or a positive number".into(),
                }),
            },
        }
    }
}

/// The central composite design for `factors` (2 to 10) with axial distance `alpha` and
/// `centre_points` centre runs.
pub fn central_composite(
    factors: &[Factor],
    alpha: Alpha,
    centre_points: usize,
) -> Result<Design, DesignError> {
    let k = factors.len();
    if !(MIN_FACTORS..=MAX_FACTORS).contains(&k) {
        return Err(DesignError::FactorCount {
            design: "central composite",
            k,
            allowed: format!("{MIN_FACTORS} to {MAX_FACTORS}"),
        });
    }
    check_unique_names(factors)?;
    let a = alpha.value(k)?;
    let mut coded = yates_corners(k);
    let mut point_types = vec![PointType::Factorial; coded.len()];
    for axis in 0..k {
        for sign in [-1.0, 1.0] {
            let mut row = vec![0.0; k];
            row[axis] = sign * a;
            coded.push(row);
            point_types.push(PointType::Axial);
        }
    }
    let (centre, centre_types) = centre_rows(centre_points, k);
    coded.extend(centre);
    point_types.extend(centre_types);
    Ok(Design::new(
        "central composite",
        factors.to_vec(),
        Vec::new(),
        coded,
        point_types,
    ))
}
