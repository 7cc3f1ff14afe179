//! Finite differences against the placements' scatter. A rig with a random placement (a pod
//! pile, a poured bed) is predicted by the mean of a few placements, and every parameter set
//! is simulated at the same placements, so each placement gives its own finite difference.
//! Their spread is the difference's standard error ([`super::sensitivity::jacobian_and_scatter`]).
//! A granular pile is chaotic: a step of 0.01 in a friction coefficient can move one
//! placement's angle by ten degrees either way, and then the mean difference is noise. This
//! module says which differences stand out of their scatter, so that a ranking built on
//! noise is reported as such rather than believed.
//!
//! A difference is within its scatter when |t| = |value|/SE is below Student's two-sided
//! [`CONFIDENCE`] quantile with (placements − 1) degrees of freedom: 12.7 for two
//! placements, 3.18 for four, 2.26 for ten. Two placements can hardly show anything.
//!
//! ```
//! use arachis::diagnose::scatter::ScatteredDifference;
//! use arachis::rigs::single_sphere::PARAMETERS;
//! let d = ScatteredDifference { param: &PARAMETERS[0], obs: 0, value: 3.0, se: 1.0, placements: 4 };
//! assert!(d.within_scatter()); // t = 3 < 3.18
//! assert!(!ScatteredDifference { placements: 10, ..d }.within_scatter()); // 3 > 2.26
//! ```

use statrs::distribution::{ContinuousCDF, StudentsT};

use super::params::ParamInfo;
use super::sensitivity::Linearisation;

/// Two-sided confidence level of the test of a difference against zero.
pub const CONFIDENCE: f64 = 0.95;

/// One parameter's finite difference at one measured condition, with its standard error.
#[derive(Clone, Copy, Debug)]
pub struct ScatteredDifference {
    /// The parameter.
    pub param: &'static ParamInfo,
    /// The condition's index in the data.
    pub obs: usize,
    /// ∂ŷ/∂θ, the observable's unit per the parameter's unit.
    pub value: f64,
    /// Its standard error from the placements (same unit).
    pub se: f64,
    /// Placements the difference was paired over (at least 2).
    pub placements: u32,
}

impl ScatteredDifference {
    /// value / SE.
    pub fn t(&self) -> f64 {
        self.value / self.se
    }

    /// |t| at which the difference stands out of its scatter: Student's t quantile at
    /// (1 + [`CONFIDENCE`])/2 with placements − 1 degrees of freedom.
    pub fn threshold(&self) -> f64 {
        threshold(self.placements)
    }

    /// Whether the difference is within [`ScatteredDifference::threshold`] standard errors of
    /// zero.
    pub fn within_scatter(&self) -> bool {
        lost_in_noise(self.value, self.se, self.placements)
    }
}

/// |t| at which a difference paired over `placements` stands out of its scatter: Student's t
/// quantile at (1 + [`CONFIDENCE`])/2 with placements − 1 degrees of freedom.
pub fn threshold(placements: u32) -> f64 {
    let df = f64::from(placements.max(2) - 1);
    StudentsT::new(0.0, 1.0, df)
        .map(|t| t.inverse_cdf((1.0 + CONFIDENCE) / 2.0))
        .unwrap_or(f64::INFINITY)
}

/// Whether a difference `value` with standard error `se` over `placements` (a rig simulated
/// at several placements; `se` 0 means it was simulated once) lies within its scatter.
pub fn lost_in_noise(value: f64, se: f64, placements: u32) -> bool {
    se > 0.0 && (value / se).abs() < threshold(placements)
}

/// Every finite difference of `lin` that has a standard error (those of replicated rigs),
/// the calibrated parameters' first, then the candidates'; `placements(obs)` is the number
/// of placements of condition `obs`.
pub fn differences(
    lin: &Linearisation,
    placements: impl Fn(usize) -> u32,
) -> Vec<ScatteredDifference> {
    let blocks = [
        (
            &lin.calibrated,
            &lin.calibrated_jacobian,
            &lin.calibrated_scatter,
        ),
        (
            &lin.candidates,
            &lin.candidate_jacobian,
            &lin.candidate_scatter,
        ),
    ];
    let mut out = Vec::new();
    for (params, jacobian, scatter) in blocks {
        for (j, &param) in params.iter().enumerate() {
            for obs in 0..jacobian.nrows() {
                let se = scatter[(obs, j)];
                if se > 0.0 {
                    out.push(ScatteredDifference {
                        param,
                        obs,
                        value: jacobian[(obs, j)],
                        se,
                        placements: placements(obs),
                    });
                }
            }
        }
    }
    out
}

/// Whether every difference of the parameter named `name` that has a standard error is
/// within its scatter (false when it has none).
pub fn lost_in_scatter(differences: &[ScatteredDifference], name: &str) -> bool {
    let mut of = differences
        .iter()
        .filter(|d| d.param.name == name)
        .peekable();
    of.peek().is_some() && of.all(ScatteredDifference::within_scatter)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::params::Catalogue;
    use nalgebra::DMatrix;

    #[test]
    fn a_difference_counts_only_where_it_stands_out_of_its_scatter() {
        let catalogue = Catalogue::of_rigs(["rebound"]);
        let base = catalogue.base().next().unwrap();
        let effect = catalogue.effect("drag").unwrap();
        let lin = Linearisation {
            predictions: vec![0.0; 2],
            calibrated: vec![base],
            calibrated_jacobian: DMatrix::from_column_slice(2, 1, &[5.0, -5.0]),
            candidates: vec![effect],
            candidate_jacobian: DMatrix::from_column_slice(2, 1, &[1.0, 0.3]),
            prior_rows: Vec::new(),
            // Over four placements (threshold 3.18): the base parameter's difference is 3.5 SE
            // from 0, the effect's 1 and 0.3; the base parameter's second condition was
            // simulated once (no SE).
            calibrated_scatter: DMatrix::from_column_slice(2, 1, &[5.0 / 3.5, 0.0]),
            candidate_scatter: DMatrix::from_column_slice(2, 1, &[1.0, 1.0]),
        };
        let d = differences(&lin, |_| 4);
        assert_eq!(d.len(), 3);
        // Student's t, 3 degrees of freedom, 97.5 %: 3.182 (any table).
        assert!((d[0].threshold() - 3.182).abs() < 1e-3);
        assert!(!d[0].within_scatter() && (d[0].t() - 3.5).abs() < 1e-12);
        assert!(d[1].within_scatter() && d[2].within_scatter());
        assert!(!lost_in_scatter(&d, base.name));
        assert!(lost_in_scatter(&d, effect.name));
        assert!(!lost_in_scatter(&d, "no such parameter"));
    }
}
