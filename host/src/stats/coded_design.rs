//! A design in coded units: factor names, one row of coded settings per run, and the
//! response. Actual levels are coded as x_coded = (x − centre) / half-range, with centre and
//! half-range from the actual values that −1 and +1 stand for.
//!
//! Papers print actual levels rounded, and a rounded centre can sit far from the true
//! midpoint: seed 000 Table 7 codes x3 as −1 = 0.327, 0 = 0.334, +1 = 0.340, while
//! (0.327 + 0.340)/2 = 0.3335, so 0.334 would code to +0.077 instead of 0. For such tables a
//! printed centre can be given: the three printed values then code to exactly −1, 0 and +1,
//! and any other value is rejected.
//!
//! ```
//! use arachis::stats::FactorLevels;
//! let x1 = FactorLevels::new(0.186, 0.586).unwrap(); // seed 000 Table 3, Poisson's ratio
//! assert!((x1.code(0.586).unwrap() - 1.0).abs() < 1e-12);
//! assert!(x1.code(0.386).unwrap().abs() < 1e-12);
//! let x3 = FactorLevels::with_printed_centre(0.327, 0.334, 0.340).unwrap(); // Table 7
//! assert_eq!(x3.code(0.334), Ok(0.0));
//! assert!(x3.code(0.335).is_err());
//! ```

use serde::Serialize;

use super::curvature::LEVEL_TOLERANCE;
use super::StatsError;

/// Two printed values are the same level when they differ by less than this fraction of
/// the factor's range (absorbs binary rounding of decimal input, nothing more).
const SAME_LEVEL_FRACTION: f64 = 1e-9;

/// The actual values a factor's coded −1 and +1 stand for (the factor's own unit), and
/// optionally the whole coding table as printed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FactorLevels {
    /// Actual value at coded −1.
    pub low: f64,
    /// Actual value at coded +1.
    pub high: f64,
    /// Printed (actual, coded) pairs; when non-empty, only these actual values are
    /// accepted and each codes to its pair.
    #[serde(skip)]
    pub printed: Vec<(f64, f64)>,
}

impl FactorLevels {
    /// Levels `low` < `high`, both finite, coded linearly.
    pub fn new(low: f64, high: f64) -> Result<Self, String> {
        if !(low.is_finite() && high.is_finite() && low < high) {
            return Err(format!(
                "low level {low} must be a finite number below the high level {high}"
            ));
        }
        Ok(Self {
            low,
            high,
            printed: Vec::new(),
        })
    }

    /// A coding table as printed, in increasing order: three levels (−1, 0, +1, seed 000
    /// Table 7) or five (−α, −1, 0, +1, +α, seed 001 Table 9). A five-level table needs α;
    /// `None` takes the printed ratio (+α level − centre)/(+1 level − centre), which inherits
    /// the rounding of the printed levels.
    pub fn with_printed_levels(actual: &[f64], alpha: Option<f64>) -> Result<Self, String> {
        if actual.iter().any(|v| !v.is_finite()) || actual.windows(2).any(|w| w[0] >= w[1]) {
            return Err(format!(
                "printed levels {actual:?} must be finite and increasing"
            ));
        }
        let coded = match actual.len() {
            3 => vec![-1.0, 0.0, 1.0],
            5 => {
                let ratio = (actual[4] - actual[2]) / (actual[3] - actual[2]);
                let a = alpha.unwrap_or(ratio);
                if !(a.is_finite() && a > 1.0) {
                    return Err(format!("axial distance alpha {a} must exceed 1"));
                }
                vec![-a, -1.0, 0.0, 1.0, a]
            }
            n => return Err(format!("a printed coding table has 3 or 5 levels, got {n}")),
        };
        let one = coded.iter().position(|c| *c == 1.0).unwrap_or(2);
        let mut levels = Self::new(actual[one - 2], actual[one])?;
        levels.printed = actual.iter().copied().zip(coded).collect();
        Ok(levels)
    }

    /// A three-level table as printed (−1, 0, +1), `low` < `centre` < `high`.
    pub fn with_printed_centre(low: f64, centre: f64, high: f64) -> Result<Self, String> {
        Self::with_printed_levels(&[low, centre, high], None)
    }

    /// x_coded = (x − (low + high)/2) / ((high − low)/2); with a printed table, each printed
    /// level maps to its coded value and other values are an error.
    pub fn code(&self, actual: f64) -> Result<f64, String> {
        if self.printed.is_empty() {
            let centre = 0.5 * (self.low + self.high);
            let half_range = 0.5 * (self.high - self.low);
            return Ok((actual - centre) / half_range);
        }
        let tolerance = SAME_LEVEL_FRACTION * (self.high - self.low);
        self.printed
            .iter()
            .find(|(level, _)| (actual - level).abs() <= tolerance)
            .map(|(_, coded)| *coded)
            .ok_or_else(|| {
                let listed: Vec<String> = self.printed.iter().map(|(a, _)| a.to_string()).collect();
                format!(
                    "{actual} is none of the printed levels {}",
                    listed.join(" / ")
                )
            })
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
