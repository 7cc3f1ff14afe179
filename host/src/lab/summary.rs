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
    let mean = values.iter().sum::<f64>() / count;
    let ss: f64 = values.iter().map(|v| (v - mean).powi(2)).sum();
    let sd = (ss / (count - 1.0)).sqrt();
    let half_width = t_quantile(n - 1) * sd / count.sqrt();
    Ok(Summary {
        n: n as u64,
        mean,
        sd,
        min: values.iter().copied().fold(f64::INFINITY, f64::min),
        max: values.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ci95_low: mean - half_width,
        ci95_high: mean + half_width,
    })
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

    #[test]
    fn nan_is_an_error() {
        assert_eq!(
            summarize(&[1.0, f64::NAN]),
            Err(SummaryError::NotFinite { index: 1 })
        );
    }
}
