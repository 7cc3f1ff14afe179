//! The replicate summary every bench-test analysis reports: n, mean, sample standard
//! deviation, range and the 95% confidence interval of the mean.
//!
//! The interval is mean ± t(0.975, n−1)·s/√n with the Student t quantile from `statrs`,
//! which is what Design-Expert, Excel's `CONFIDENCE.T` and Matlab's `tinv` give.
//!
//! ```
//! let s = arachis::lab::summarize(&[1.0, 2.0, 3.0]).unwrap();
//! assert_eq!(s.mean, 2.0);
//! assert_eq!(s.sd, 1.0);
//! // t(0.975, 2) = 4.302653, so the half-width is 4.302653 / √3.
//! assert!((s.ci95_high - 2.0 - 4.302653 / 3f64.sqrt()).abs() < 1e-6);
//! ```

use serde::Serialize;
use statrs::distribution::{ContinuousCDF, StudentsT};
use thiserror::Error;

/// Confidence level of the reported interval of the mean.
pub const CONFIDENCE: f64 = 0.95;

/// Fewest replicates that give a sample standard deviation and a confidence interval.
pub const MIN_REPLICATES: usize = 2;

/// Summary of replicate values of one quantity (all in the quantity's unit).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Summary {
    /// Number of replicates.
    pub n: u64,
    /// Arithmetic mean.
    pub mean: f64,
    /// Sample standard deviation (divisor n − 1).
    pub sd: f64,
    /// Smallest replicate.
    pub min: f64,
    /// Largest replicate.
    pub max: f64,
    /// Lower end of the 95% confidence interval of the mean.
    pub ci95_low: f64,
    /// Upper end of the 95% confidence interval of the mean.
    pub ci95_high: f64,
}

/// Why a set of replicates cannot be summarised.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SummaryError {
    /// Fewer than [`MIN_REPLICATES`] values.
    #[error(
        "{n} replicate(s); a standard deviation and a 95% confidence interval need at least 2"
    )]
    TooFew {
        /// How many values there were.
        n: usize,
    },
    /// A value is NaN or infinite.
    #[error("replicate {index} is not a finite number")]
    NotFinite {
        /// 0-based position of the value.
        index: usize,
    },
    /// The summary itself is beyond double precision (replicates near ±1.8e308): it would
    /// be written as inf or NaN, so none is written.
    #[error("the replicates (up to {largest:e}) are too large for a summary in double precision")]
    Unrepresentable {
        /// The largest |replicate|.
        largest: f64,
    },
}

/// Summarises `values` (any unit; the summary is in the same unit).
pub fn summarize(values: &[f64]) -> Result<Summary, SummaryError> {
    let n = values.len();
    if n < MIN_REPLICATES {
        return Err(SummaryError::TooFew { n });
    }
    if let Some(index) = values.iter().position(|v| !v.is_finite()) {
        return Err(SummaryError::NotFinite { index });
    }
    let count = n as f64;
    // Unscaled first (scale 1 divides and multiplies exactly, so ordinary replicates keep
    // their bits); replicates near the top of the double range overflow the sum or the
    // squares (1e300 once gave an SD of inf), so they are summed scaled by the largest.
    let largest = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (mut mean, mut sd) = moments(values, 1.0);
    if !(mean.is_finite() && sd.is_finite()) && largest > 0.0 {
        (mean, sd) = moments(values, largest);
    }
    let half_width = t_quantile(n - 1) * sd / count.sqrt();
    let summary = Summary {
        n: n as u64,
        mean,
        sd,
        min: values.iter().copied().fold(f64::INFINITY, f64::min),
        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ci95_low: mean - half_width,
        ci95_high: mean + half_width,
    };
    let finite = [
        summary.mean,
        summary.sd,
        summary.ci95_low,
        summary.ci95_high,
    ]
    .iter()
    .all(|x| x.is_finite());
    if finite {
        Ok(summary)
    } else {
        Err(SummaryError::Unrepresentable { largest })
    }
}

/// Mean and sample standard deviation of `values`, summed as `value / scale`.
fn moments(values: &[f64], scale: f64) -> (f64, f64) {
    let count = values.len() as f64;
    let scaled_mean = values.iter().map(|v| v / scale).sum::<f64>() / count;
    let ss: f64 = values
        .iter()
        .map(|v| (v / scale - scaled_mean).powi(2))
        .sum();
    (scaled_mean * scale, (ss / (count - 1.0)).sqrt() * scale)
}

/// Two-sided Student t quantile t(1 − (1 − [`CONFIDENCE`])/2, df), df ≥ 1.
fn t_quantile(df: usize) -> f64 {
    // df ≥ 1 and finite, so the distribution is always constructible.
    let t = StudentsT::new(0.0, 1.0, df as f64).expect("df >= 1 is a valid Student t");
    t.inverse_cdf(1.0 - (1.0 - CONFIDENCE) / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ten_replicates_use_t_2_262() {
        // Printed t tables: t(0.975, 9) = 2.262157 (to 6 decimals).
        let v: Vec<f64> = (1..=10).map(f64::from).collect();
        let s = summarize(&v).unwrap();
        assert_eq!(s.n, 10);
        assert!((s.mean - 5.5).abs() < 1e-12);
        // Σ(i − 5.5)² = 82.5, s² = 82.5 / 9.
        assert!((s.sd - (82.5f64 / 9.0).sqrt()).abs() < 1e-12);
        let half = s.ci95_high - s.mean;
        let expected = 2.262157 * s.sd / 10f64.sqrt();
        assert!((half - expected).abs() < 5e-7 * s.sd / 10f64.sqrt() * 2.0);
        assert_eq!((s.min, s.max), (1.0, 10.0));
    }

    #[test]
    fn one_replicate_is_an_error() {
        assert_eq!(summarize(&[3.0]), Err(SummaryError::TooFew { n: 1 }));
        assert_eq!(summarize(&[]), Err(SummaryError::TooFew { n: 0 }));
    }

    /// Issue 23: replicates near the top of the double range give a finite summary where
    /// one exists (1e300 once gave an SD of inf), and an error, never inf or NaN, where none
    /// does.
    #[test]
    fn huge_replicates_give_a_finite_summary_or_an_error() {
        let s = summarize(&[1e300, 2e300, 3e300]).unwrap();
        assert!((s.mean / 2e300 - 1.0).abs() < 1e-15);
        assert!((s.sd / 1e300 - 1.0).abs() < 1e-15);
        assert!(s.ci95_high.is_finite() && s.ci95_low.is_finite());
        let e = summarize(&[1.7e308, -1.7e308]).unwrap_err();
        assert!(matches!(e, SummaryError::Unrepresentable { .. }), "{e}");
    }

    #[test]
    fn nan_is_an_error() {
        assert_eq!(
            summarize(&[1.0, f64::NAN]),
            Err(SummaryError::NotFinite { index: 1 })
        );
    }
}
