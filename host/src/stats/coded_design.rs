//! A design in coded units: factor names, one row of coded settings per run, and the
//! response. Actual levels are coded as x_coded = (x − centre) / half-range, with centre and
//! half-range from the actual values that −1 and +1 stand for.
//!
//! ```
//! use arachis::stats::FactorLevels;
//! let x1 = FactorLevels::new(0.186, 0.586).unwrap(); // seed 000 Table 3, Poisson's ratio
//! assert!((x1.code(0.586) - 1.0).abs() < 1e-12);
//! assert!((x1.code(0.386)).abs() < 1e-12);
//! ```

use serde::Serialize;

use super::curvature::LEVEL_TOLERANCE;
use super::StatsError;

/// The actual values a factor's coded −1 and +1 stand for (the factor's own unit).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FactorLevels {
    /// Actual value at coded −1.
    pub low: f64,
    /// Actual value at coded +1.
    pub high: f64,
}

impl FactorLevels {
    /// Levels `low` < `high`, both finite.
    pub fn new(low: f64, high: f64) -> Result<Self, String> {
        if !(low.is_finite() && high.is_finite() && low < high) {
            return Err(format!(
                "low level {low} must be a finite number below the high level {high}"
            ));
        }
        Ok(Self { low, high })
    }

    /// x_coded = (x − (low + high)/2) / ((high − low)/2).
    pub fn code(&self, actual: f64) -> f64 {
        let centre = 0.5 * (self.low + self.high);
        let half_range = 0.5 * (self.high - self.low);
        (actual - centre) / half_range
    }
}

/// A design in coded units with one response.
#[derive(Debug, Clone, PartialEq)]
pub struct CodedDesign {
    /// Factor names in column order (term names are built from them).
    pub factor_names: Vec<String>,
    /// Coded settings, `runs[run][factor]`.
    pub runs: Vec<Vec<f64>>,
    /// Response per run (response units).
    pub response: Vec<f64>,
}

impl CodedDesign {
    /// Checks shapes, finiteness, and that every factor takes at least two levels.
    pub fn new(
        factor_names: Vec<String>,
        runs: Vec<Vec<f64>>,
        response: Vec<f64>,
    ) -> Result<Self, StatsError> {
        if factor_names.is_empty() {
            return Err(StatsError::BadShape("no factors given".to_owned()));
        }
        if runs.len() != response.len() || runs.iter().any(|r| r.len() != factor_names.len()) {
            return Err(StatsError::BadShape(format!(
                "{} runs of {} factors do not match {} responses",
                runs.len(),
                factor_names.len(),
                response.len()
            )));
        }
        if runs
            .iter()
            .flatten()
            .chain(&response)
            .any(|v| !v.is_finite())
        {
            return Err(StatsError::BadShape("a value is not finite".to_owned()));
        }
        for (i, name) in factor_names.iter().enumerate() {
            let first = runs.first().map_or(0.0, |r| r[i]);
            if runs.iter().all(|r| (r[i] - first).abs() < LEVEL_TOLERANCE) {
                return Err(StatsError::OneLevel {
                    factor: name.clone(),
                    value: first,
                    runs: runs.len(),
                });
            }
        }
        Ok(Self {
            factor_names,
            runs,
            response,
        })
    }
}
