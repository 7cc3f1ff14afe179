//! The fractions of normal, cocoon and single-grain pods in a sample (seed 000 §2.1–2.2).
//!
//! Seed 000 counted the pods of ten plants by shape ("the number and percentage of pods of
//! different shapes ... were statistically determined") and generated its 900 simulated pods
//! "according to the measured proportions" (§2.7), but it does not print the proportions.
//! There is therefore no default mix: give the fractions, or the counts from your own sample.
//!
//! ```
//! use arachis::shapes::{PodKind, ShapeMix};
//! let mix = ShapeMix::from_counts([62, 25, 13]).unwrap();
//! assert_eq!(mix.fraction(PodKind::Cocoon), 0.25);
//! assert_eq!(mix.apportion(900), [558, 225, 117]);
//! ```

use super::error::ShapeError;
use super::pod_shape::PodKind;

/// How far the fractions' sum may stray from 1 (rounding of printed percentages).
pub const MIX_SUM_TOLERANCE: f64 = 1e-6;

/// Fractions of the three pod kinds, in the order of [`PodKind::ALL`]; each ≥ 0, sum 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeMix {
    fractions: [f64; 3],
}

impl ShapeMix {
    /// A mix from fractions `[normal, cocoon, single_grain]`: each finite and ≥ 0, summing
    /// to 1 within [`MIX_SUM_TOLERANCE`] (then rescaled to sum exactly to 1).
    pub fn new(fractions: [f64; 3]) -> Result<Self, ShapeError> {
        for (kind, f) in PodKind::ALL.iter().zip(fractions) {
            if !(f.is_finite() && f >= 0.0) {
                return Err(ShapeError::InvalidMix {
                    reason: format!(
                        "fraction of {} pods is {f}; it must be a finite number ≥ 0",
                        kind.name()
                    ),
                });
            }
        }
        let sum: f64 = fractions.iter().sum();
        if (sum - 1.0).abs() > MIX_SUM_TOLERANCE {
            return Err(ShapeError::InvalidMix {
                reason: format!("fractions {fractions:?} sum to {sum}, not 1"),
            });
        }
        Ok(ShapeMix {
            fractions: fractions.map(|f| f / sum),
        })
    }

    /// A mix from pod counts `[normal, cocoon, single_grain]` (at least one pod).
    pub fn from_counts(counts: [u64; 3]) -> Result<Self, ShapeError> {
        let total: u64 = counts.iter().sum();
        if total == 0 {
            return Err(ShapeError::InvalidMix {
                reason: "all pod counts are zero".to_owned(),
            });
        }
        Self::new(counts.map(|c| c as f64 / total as f64))
    }

    /// The fraction of `kind`.
    pub fn fraction(&self, kind: PodKind) -> f64 {
        self.fractions[kind as usize]
    }

    /// Pod counts of each kind for `n` pods by largest remainders (Hamilton's method;
    /// ties go to the earlier kind), so the counts sum to `n` exactly.
    pub fn apportion(&self, n: usize) -> [usize; 3] {
        let counts = apportion(&self.fractions, n);
        [counts[0], counts[1], counts[2]]
    }

    /// The kind drawn by a uniform number `u` in [0, 1) (inverse of the cumulative mix).
    pub fn pick(&self, u: f64) -> PodKind {
        let mut cumulative = 0.0;
        for kind in PodKind::ALL {
            cumulative += self.fraction(kind);
            if u < cumulative {
                return kind;
            }
        }
        // u ≥ the rounded total: the last kind with a non-zero fraction.
        *PodKind::ALL
            .iter()
            .rev()
            .find(|k| self.fraction(**k) > 0.0)
            .unwrap_or(&PodKind::Normal)
    }
}

/// `n` items split by `fractions` (summing to 1) by largest remainders: each gets the floor
/// of its quota, and the ones left go to the largest remainders, ties to the first.
pub fn apportion(fractions: &[f64], n: usize) -> Vec<usize> {
    let quotas: Vec<f64> = fractions.iter().map(|f| f * n as f64).collect();
    let mut counts: Vec<usize> = quotas.iter().map(|q| q.floor() as usize).collect();
    let mut left = n.saturating_sub(counts.iter().sum::<usize>());
    let mut order: Vec<usize> = (0..quotas.len()).collect();
    order.sort_by(|&i, &j| {
        let (ri, rj) = (quotas[i] - quotas[i].floor(), quotas[j] - quotas[j].floor());
        rj.total_cmp(&ri).then(i.cmp(&j))
    });
    for &i in order.iter().cycle() {
        if left == 0 {
            break;
        }
        counts[i] += 1;
        left -= 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_negative_and_bad_sums() {
        assert!(ShapeMix::new([-0.1, 0.6, 0.5]).is_err());
        assert!(ShapeMix::new([0.5, 0.3, 0.1]).is_err());
        assert!(ShapeMix::new([f64::NAN, 0.5, 0.5]).is_err());
        assert!(ShapeMix::from_counts([0, 0, 0]).is_err());
        assert!(ShapeMix::new([0.5, 0.3, 0.2]).is_ok());
    }

    #[test]
    fn apportion_sums_to_n_and_pick_follows_fractions() {
        let mix = ShapeMix::new([0.5, 0.3, 0.2]).unwrap();
        assert_eq!(mix.apportion(7), [4, 2, 1]);
        assert_eq!(mix.apportion(900).iter().sum::<usize>(), 900);
        assert_eq!(mix.pick(0.49), PodKind::Normal);
        assert_eq!(mix.pick(0.5), PodKind::Cocoon);
        assert_eq!(mix.pick(0.95), PodKind::SingleGrain);
        assert_eq!(mix.pick(1.0), PodKind::SingleGrain);
    }
}
