//! Ranking the candidate effects (DESIGN §10 step 2): a score test of each effect's
//! sensitivity against the standardised residuals, after removing what the calibrated
//! parameters can already absorb.
//!
//! With W = diag(1/SE of each condition mean), r = W(ȳ − ŷ), J̃ = W·J (calibrated parameters)
//! and s̃ = W·s (the effect's sensitivity at its off value), let P be the orthogonal projector
//! onto the column space of J̃ (from nalgebra's SVD, rank-revealing) and s⊥ = (I − P)s̃. Then
//!
//!   z = s⊥ᵀ r / ‖s⊥‖,
//!
//! which is N(0, 1) when the effect is absent and the model is otherwise right, whatever small
//! error the calibration has (that error lies in span J̃, which s⊥ is orthogonal to). This is
//! the score (Rao) test of θ = 0 in the linearised model with the calibrated parameters
//! profiled out. Because an effect can only be switched on (θ ≥ 0, its off value is the lower
//! bound), the test is one-sided: p = 1 − Φ(z) (for a boundary null, z² follows the
//! ½χ²₀ + ½χ²₁ mixture, the same p). Effects are ranked by z; an effect is **claimed** when
//! p < α/m, Bonferroni over the m testable candidates, so the chance of any false claim is
//! ≤ α.
//!
//! - **Not identifiable:** ‖s⊥‖ < [`IDENTIFIABLE_FRACTION`]·‖s̃‖ — the calibration absorbs
//!   (almost) all of the effect's signature, e.g. with one condition per experiment; or
//!   s̃ = 0 — no measured experiment responds to it. Such effects are reported, never ranked.
//! - **Not distinguishable:** two effects whose s⊥ point the same way (cosine >
//!   [`COLLINEAR_COSINE`]) explain the same misfit; opposite directions are told apart by the
//!   sign (θ ≥ 0).
//! - θ̂ = s⊥ᵀr/‖s⊥‖² is the one-step estimate of the effect parameter, SE 1/‖s⊥‖.
//!
//! **Bench priors** (`[diagnosis.prior]`, mean ± sd of a calibrated parameter) enter as one
//! more observation each: r gets the row (mean − θ)/sd, J̃ the row 1/sd in the parameter's
//! column, and every effect's s̃ a 0. A tight prior keeps its parameter from absorbing an
//! effect's signature, so an effect the calibration would hide becomes testable, and a
//! calibration far from its bench value counts as misfit.

use anyhow::Result;
use nalgebra::{DMatrix, DVector};
use statrs::distribution::{ContinuousCDF, Normal};

use super::params::ParamInfo;
use super::residuals::Dataset;
use super::sensitivity::Linearisation;
#[cfg(test)]
use super::sensitivity::PriorRow;

/// Family-wise false-claim level over the candidate set.
pub const FAMILY_ALPHA: f64 = 0.05;
/// An effect whose signature is less than this fraction outside what calibration absorbs is
/// reported as not identifiable.
pub const IDENTIFIABLE_FRACTION: f64 = 0.05;
/// Cosine above which two effects' projected signatures are called indistinguishable.
pub const COLLINEAR_COSINE: f64 = 0.9;
/// Singular values below this fraction of the largest count as zero when building P.
const RANK_TOLERANCE: f64 = 1e-9;

/// Verdict on one candidate.
#[derive(Clone, Debug, PartialEq)]
pub enum Status {
    /// Testable; `claimed` when significant after the Bonferroni correction.
    Tested {
        /// Significant at α/m.
        claimed: bool,
    },
    /// No measured experiment responds to it.
    NoSensitivity,
    /// The calibration absorbs its signature.
    NotIdentifiable,
}

/// Score-test result for one candidate.
#[derive(Clone, Debug)]
pub struct Candidate {
    /// The effect.
    pub effect: &'static ParamInfo,
    /// One-sided score statistic z.
    pub z: f64,
    /// One-sided p-value 1 − Φ(z).
    pub p_value: f64,
    /// Bonferroni-adjusted p-value min(1, m·p).
    pub p_adjusted: f64,
    /// ‖s⊥‖/‖s̃‖: the share of the signature that calibration cannot absorb.
    pub identifiable_fraction: f64,
    /// One-step estimate θ̂ (parameter unit) and its SE.
    pub estimate: f64,
    /// Standard error of θ̂.
    pub std_error: f64,
    /// Verdict.
    pub status: Status,
    /// Projected, standardised signature s⊥ (one entry per condition).
    pub projected: DVector<f64>,
}

/// The ranking.
#[derive(Clone, Debug)]
pub struct Ranking {
    /// Testable candidates by decreasing z, then the others.
    pub candidates: Vec<Candidate>,
    /// Number of testable candidates m (the Bonferroni divisor).
    pub tested: usize,
    /// Pairs of testable effects that cannot be told apart, with their cosine.
    pub indistinguishable: Vec<(&'static str, &'static str, f64)>,
}

impl Ranking {
    /// The top-ranked testable candidate.
    pub fn top(&self) -> Option<&Candidate> {
        self.candidates
            .first()
            .filter(|c| matches!(c.status, Status::Tested { .. }))
    }
    /// Whether any effect is claimed.
    pub fn any_claimed(&self) -> bool {
        self.candidates
            .iter()
            .any(|c| c.status == Status::Tested { claimed: true })
    }
}

/// Rank the candidates of `lin` against the measurements `data`.
pub fn rank(data: &Dataset, lin: &Linearisation) -> Result<Ranking> {
    let w: Vec<f64> = data.obs.iter().map(|o| 1.0 / o.se_mean).collect();
    let mut r = data.standardised(&lin.predictions);
    r.extend(lin.prior_rows.iter().map(|p| p.residual));
    let r = DVector::from_vec(r);
    let basis = column_basis(&lin.weighted_calibrated(&w));
    let normal = Normal::new(0.0, 1.0)?;
    let mut cands = Vec::new();
    for (k, effect) in lin.candidates.iter().enumerate() {
        let s = lin.weighted_candidate(k, &w);
        let full = s.norm();
        let perp = &s - &basis * (basis.transpose() * &s);
        let pn = perp.norm();
        let frac = if full > 0.0 { pn / full } else { 0.0 };
        let status = if full == 0.0 {
            Status::NoSensitivity
        } else if frac < IDENTIFIABLE_FRACTION {
            Status::NotIdentifiable
        } else {
            Status::Tested { claimed: false }
        };
        let (z, est, se) = if matches!(status, Status::Tested { .. }) {
            let sr = perp.dot(&r);
            (sr / pn, sr / (pn * pn), 1.0 / pn)
        } else {
            (0.0, 0.0, f64::INFINITY)
        };
        cands.push(Candidate {
            effect,
            z,
            p_value: 1.0 - normal.cdf(z),
            p_adjusted: 1.0,
            identifiable_fraction: frac,
            estimate: est,
            std_error: se,
            status,
            projected: perp,
        });
    }
    let m = cands
        .iter()
        .filter(|c| matches!(c.status, Status::Tested { .. }))
        .count();
    for c in cands.iter_mut() {
        if let Status::Tested { .. } = c.status {
            c.p_adjusted = (c.p_value * m as f64).min(1.0);
            c.status = Status::Tested {
                claimed: c.p_value < FAMILY_ALPHA / m as f64,
            };
        } else {
            c.p_value = f64::NAN;
        }
    }
    cands.sort_by(|a, b| {
        let ta = matches!(a.status, Status::Tested { .. });
        let tb = matches!(b.status, Status::Tested { .. });
        tb.cmp(&ta).then(b.z.total_cmp(&a.z))
    });
    let mut indistinguishable = Vec::new();
    for i in 0..m {
        for j in i + 1..m {
            let (a, b) = (&cands[i], &cands[j]);
            let cos = a.projected.dot(&b.projected) / (a.projected.norm() * b.projected.norm());
            if cos > COLLINEAR_COSINE {
                indistinguishable.push((a.effect.name, b.effect.name, cos));
            }
        }
    }
    Ok(Ranking {
        candidates: cands,
        tested: m,
        indistinguishable,
    })
}

/// Rows of `m` scaled by `w`.
pub fn scale_rows(m: &DMatrix<f64>, w: &DVector<f64>) -> DMatrix<f64> {
    let mut out = m.clone();
    for (i, mut row) in out.row_iter_mut().enumerate() {
        row *= w[i];
    }
    out
}

/// Orthonormal basis of the column space of `a` (left singular vectors with non-negligible
/// singular values).
pub fn column_basis(a: &DMatrix<f64>) -> DMatrix<f64> {
    if a.ncols() == 0 || a.nrows() == 0 {
        return DMatrix::zeros(a.nrows(), 0);
    }
    let svd = a.clone().svd(true, false);
    let u = svd.u.expect("SVD computed with U");
    let smax = svd.singular_values.max();
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| smax > 0.0 && svd.singular_values[i] > RANK_TOLERANCE * smax)
        .collect();
    DMatrix::from_fn(a.nrows(), keep.len(), |i, j| u[(i, keep[j])])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::params::Catalogue;
    use crate::diagnose::residuals::{Obs, PureError};

    /// Three conditions with SE 1, measured means `m`, predictions 0.
    fn setup(m: [f64; 3], s_visco: [f64; 3], s_drag: [f64; 3]) -> (Dataset, Linearisation) {
        let obs = (0..3)
            .map(|i| Obs {
                experiment: 0,
                condition: Default::default(),
                x: 0.1 * (i + 1) as f64,
                values: vec![m[i]],
                n: 1,
                ss_within: 0.0,
                mean: m[i],
                se_mean: 1.0,
            })
            .collect();
        let data = Dataset {
            experiments: Vec::new(),
            obs,
            pure_error: vec![PureError { sd: 1.0, df: 10 }],
            priors: Vec::new(),
        };
        let catalogue = Catalogue::of_rigs(["rebound"]);
        let effect = |name| catalogue.effect(name).unwrap();
        let e = catalogue.base().next().unwrap();
        let lin = Linearisation {
            predictions: vec![0.0; 3],
            calibrated: vec![e],
            // The calibrated parameter shifts every condition alike: it absorbs the mean.
            calibrated_jacobian: DMatrix::from_element(3, 1, 1.0),
            candidates: vec![effect("viscoelastic"), effect("drag")],
            candidate_jacobian: DMatrix::from_fn(3, 2, |i, j| [s_visco, s_drag][j][i]),
            prior_rows: Vec::new(),
            calibrated_scatter: DMatrix::zeros(3, 1),
            candidate_scatter: DMatrix::zeros(3, 2),
        };
        (data, lin)
    }

    #[test]
    fn score_is_projected_and_one_sided() {
        // Residuals = 5 + 2·trend; visco signature = trend + 7 (its mean part is absorbed),
        // drag signature = −trend. Projected visco = trend = (−1, 0, 1), ‖·‖ = √2, so
        // z = (2·2)/√2 = 2√2 and θ̂ = 4/2 = 2; drag gets z = −2√2 (wrong sign: cannot explain).
        let (d, l) = setup([3.0, 5.0, 7.0], [6.0, 7.0, 8.0], [1.0, 0.0, -1.0]);
        let r = rank(&d, &l).unwrap();
        let top = r.top().unwrap();
        assert_eq!(top.effect.name, "viscoelastic");
        assert!((top.z - 2.0 * 2f64.sqrt()).abs() < 1e-12);
        assert!((top.estimate - 2.0).abs() < 1e-12);
        assert!((top.std_error - 1.0 / 2f64.sqrt()).abs() < 1e-12);
        assert!((top.identifiable_fraction - (2.0f64 / 149.0).sqrt()).abs() < 1e-12);
        assert!((r.candidates[1].z + 2.0 * 2f64.sqrt()).abs() < 1e-12);
        // p = 1 − Φ(2.828) = 0.00234; Bonferroni over 2: 0.00468 < 0.05: claimed.
        assert!((top.p_value - 0.002_338_8).abs() < 1e-6);
        assert!(r.any_claimed());
        // Opposite directions are told apart by the sign, not reported as collinear.
        assert!(r.indistinguishable.is_empty());
    }

    #[test]
    fn absorbed_or_insensitive_effects_are_not_ranked() {
        // Visco signature constant (fully absorbed), drag signature zero.
        let (d, l) = setup([3.0, 5.0, 7.0], [2.0, 2.0, 2.0], [0.0; 3]);
        let r = rank(&d, &l).unwrap();
        assert!(r.top().is_none());
        assert_eq!(r.candidates[0].status, Status::NotIdentifiable);
        assert_eq!(r.candidates[1].status, Status::NoSensitivity);
    }

    #[test]
    fn a_tight_bench_prior_stops_the_calibration_absorbing_an_effect() {
        // As above, the constant visco signature is absorbed by e, unless e is held to its
        // bench value (prior SD 0.01, calibration on it): then s⊥ ≈ s̃ = (2, 2, 2, 0) less a
        // projection of 6/10 003 along (1, 1, 1, 100), and z ≈ s̃ᵀr/‖s̃‖ = 30/√12.
        let (d, mut l) = setup([3.0, 5.0, 7.0], [2.0, 2.0, 2.0], [0.0; 3]);
        l.prior_rows.push(PriorRow {
            column: 0,
            inverse_sd: 100.0,
            residual: 0.0,
        });
        // Exactly: c = (1, 1, 1, 100), s⊥ = s̃ − c·(cᵀs̃)/‖c‖², with cᵀs̃ = 6, ‖c‖² = 10 003;
        // for r = (3, 5, 7, ρ): s⊥ᵀr = 30 − (6/10 003)(15 + 100ρ), ‖s⊥‖² = 12 − 36/10 003.
        let exact = |rho: f64| {
            (30.0 - 6.0 / 10_003.0 * (15.0 + 100.0 * rho)) / (12.0 - 36.0 / 10_003.0f64).sqrt()
        };
        let r = rank(&d, &l).unwrap();
        let top = r.top().unwrap();
        assert_eq!(top.effect.name, "viscoelastic");
        assert!((top.z - exact(0.0)).abs() < 1e-12, "{}", top.z);
        assert!(top.identifiable_fraction > 0.99);
        assert!(r.any_claimed());
        // A calibration off its bench value adds the prior row's residual ρ to r.
        l.prior_rows[0].residual = -5.0;
        let moved = rank(&d, &l).unwrap();
        assert!((moved.top().unwrap().z - exact(-5.0)).abs() < 1e-12);
    }

    #[test]
    fn same_direction_signatures_are_indistinguishable() {
        let (d, l) = setup([3.0, 5.0, 7.0], [-1.0, 0.0, 1.0], [-2.0, 0.1, 2.0]);
        let r = rank(&d, &l).unwrap();
        assert_eq!(r.indistinguishable.len(), 1);
    }
}
