//! The pooled two-sample t-test (equal variances) and the relative error used to compare
//! simulation with measurement.
//!
//! t = (ȳ₁ − ȳ₂) / (s_p √(1/n₁ + 1/n₂)), s_p² = ((n₁−1)s₁² + (n₂−1)s₂²)/(n₁+n₂−2),
//! on n₁+n₂−2 degrees of freedom; p is two-sided (statrs' Student t).
//!
//! ```
//! use arachis::stats::pooled_t_test;
//! // Seed 001 Table 12: simulated vs field harvest loss, %.
//! let test = pooled_t_test(&[3.75, 4.02, 4.27, 3.18], &[4.01, 3.83, 4.04, 3.42]).unwrap();
//! assert!(test.p > 0.05);
//! ```

use serde::Serialize;

use super::p_values::t_two_sided;
use super::StatsError;

/// Result of a pooled two-sample t-test.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PooledTTest {
    /// Mean of the first sample (its units).
    pub mean_1: f64,
    /// Mean of the second sample (same units).
    pub mean_2: f64,
    /// Pooled standard deviation s_p (same units).
    pub pooled_sd: f64,
    /// t statistic (dimensionless).
    pub t: f64,
    /// Degrees of freedom n₁ + n₂ − 2.
    pub df: usize,
    /// Two-sided p-value.
    pub p: f64,
}

/// Pooled two-sample t-test of equal means. Each sample needs two values, and the pooled
/// variance must be positive.
pub fn pooled_t_test(sample_1: &[f64], sample_2: &[f64]) -> Result<PooledTTest, StatsError> {
    let (n1, n2) = (sample_1.len(), sample_2.len());
    if n1 < 2 || n2 < 2 {
        return Err(StatsError::BadShape(format!(
            "a t-test needs at least two values in each sample, got {n1} and {n2}"
        )));
    }
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    let sum_sq = |s: &[f64], m: f64| s.iter().map(|v| (v - m).powi(2)).sum::<f64>();
    let (mean_1, mean_2) = (mean(sample_1), mean(sample_2));
    let df = n1 + n2 - 2;
    let pooled_var = (sum_sq(sample_1, mean_1) + sum_sq(sample_2, mean_2)) / df as f64;
    if pooled_var <= 0.0 {
        return Err(StatsError::BadShape(
            "both samples are constant: the pooled variance is zero".to_owned(),
        ));
    }
    let pooled_sd = pooled_var.sqrt();
    let t = (mean_1 - mean_2) / (pooled_sd * (1.0 / n1 as f64 + 1.0 / n2 as f64).sqrt());
    Ok(PooledTTest {
        mean_1,
        mean_2,
        pooled_sd,
        t,
        df,
        p: t_two_sided(t, df as f64),
    })
}

/// Relative error ψ = |value − reference| / |reference| × 100 % (seed 000 eq. (21), where the
/// reference is the bench-test value; seed 001 Table 12 takes the simulation as reference).
pub fn relative_error_percent(value: f64, reference: f64) -> f64 {
    100.0 * (value - reference).abs() / reference.abs()
}
