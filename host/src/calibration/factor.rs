//! A calibration factor: a rig parameter the plan varies over a screened range, the value it
//! is held at when not varied, and its physical limits.
//!
//! Coding follows seed 001 §2.5: x = (X − X₀)/ΔX with X₀ = (low + high)/2 and
//! ΔX = (high − low)/2, so coded −1 is `low` and +1 `high`. Each stage codes its factors
//! in its own box (the screening's range, the response surface's box), so a stage's
//! factors are copies with other `low` and `high`.
//!
//! Two sets of limits: a run may take any value inside the screened range that the study
//! admits ([`Factor::admitted`], which a study may widen, e.g. a Poisson ratio screened up
//! to 0.586, seed 000 Table 3), but a path that extrapolates beyond the range stays inside
//! the parameter's own physical limits ([`Factor::physical`], e.g. ν < 0.5, μ ≥ 0).

use serde::Serialize;

use crate::doe::{DesignError, Factor as DoeFactor};
use crate::limits::Limits;

/// One factor (module notes). `low`, `high` and `held` are in `unit`. Serialised as a
/// design's factor: name, label, unit and range.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Factor {
    /// The parameter the rig reads (e.g. `pod-pod.static_friction`).
    pub name: String,
    /// Short report label (seed 000 Table 3's x1…x8, seed 001 Table 5's x1…x9).
    pub label: String,
    /// Unit of the values (`-` for dimensionless).
    pub unit: String,
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
    /// The value while the factor is not varied (the study's value or the range centre).
    #[serde(skip)]
    pub held: f64,
    /// Limits beyond the screened range.
    #[serde(skip)]
    pub physical: Limits,
    /// Limits of any run value.
    #[serde(skip)]
    pub admitted: Limits,
}

impl Factor {
    /// The `doe` factor of this coding (named by the label).
    pub fn doe(&self) -> Result<DoeFactor, DesignError> {
        DoeFactor::new(&self.label, &self.unit, self.low, self.high)
    }

    /// The centre (low + high)/2, in `unit`.
    pub fn centre(&self) -> f64 {
        0.5 * (self.low + self.high)
    }

    /// The value of coded level `x` in this coding, X₀ + x ΔX (no special case at ±1,
    /// unlike `doe::Factor::to_actual`).
    pub fn actual(&self, x: f64) -> f64 {
        0.5 * (self.low + self.high) + x * 0.5 * (self.high - self.low)
    }

    /// The coded level of `value` in this coding.
    pub fn coded(&self, value: f64) -> f64 {
        (value - 0.5 * (self.low + self.high)) / (0.5 * (self.high - self.low))
    }

    /// `value` where a path may take it: unchanged inside the screened range or the
    /// physical limits, else the nearest closed bound (μ at 0, e at 1) or, where the bound
    /// is open (ν < 0.5), the screened level on that side.
    pub fn admissible(&self, value: f64) -> f64 {
        if (self.low..=self.high).contains(&value) || self.physical.check(value).is_ok() {
            return value;
        }
        let edge = if value > self.high {
            self.high
        } else {
            self.low
        };
        self.physical.nearest_admissible(value).unwrap_or(edge)
    }

    /// This factor coded over [`low`, `high`] instead.
    pub fn with_levels(&self, low: f64, high: f64) -> Self {
        Self {
            low,
            high,
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn friction() -> Factor {
        Factor {
            name: "pod-pod.static_friction".into(),
            label: "x4".into(),
            unit: "-".into(),
            low: 0.837,
            high: 0.878,
            held: 0.8575,
            physical: Limits::Friction,
            admitted: Limits::Friction,
        }
    }

    #[test]
    fn a_path_stops_at_closed_bounds_and_screened_levels() {
        let f = friction();
        assert_eq!(f.admissible(-0.3), 0.0);
        assert_eq!(f.admissible(0.9), 0.9);
        let nu = Factor {
            low: 0.186,
            high: 0.586,
            physical: Limits::Poisson,
            admitted: Limits::PoissonContactModel,
            ..f
        };
        // Inside the screened range beyond 0.5: allowed; beyond the range: the open bound
        // has no nearest value, so the screened level holds.
        assert_eq!(nu.admissible(0.55), 0.55);
        assert_eq!(nu.admissible(0.7), 0.586);
        assert!((nu.coded(nu.actual(0.25)) - 0.25).abs() < 1e-12);
    }
}
