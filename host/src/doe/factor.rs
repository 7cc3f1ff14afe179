//! A design factor: its name, unit and the actual levels that coded −1 and +1 stand for.
//!
//! Coding follows seed 001 §2.5: `x = (X − X₀)/ΔX`, with the centre `X₀ = (low + high)/2` and
//! the half-range `ΔX = (high − low)/2`, so coded −1 is `low`, 0 the centre and +1 `high`.
//! Points outside the cube (axial points of a central composite design) code to |x| > 1.
//!
//! ```
//! use arachis::doe::Factor;
//! let x5 = Factor::new("x5", "-", 0.332, 0.350).unwrap();
//! assert_eq!(x5.to_actual(-1.0), 0.332);
//! assert!((x5.to_actual(0.0) - 0.341).abs() < 1e-12);
//! assert!((x5.to_coded(0.346) - 0.5556).abs() < 1e-4);
//! ```

use super::DesignError;

/// One factor of a design. `low` and `high` are in `unit` and map to coded −1 and +1.
#[derive(Debug, Clone, PartialEq)]
pub struct Factor {
    /// Column name (as the seed names it, e.g. `x3`).
    pub name: String,
    /// Unit of `low` and `high` (free text, e.g. `MPa`, `1e5 N/m^3`; `-` for dimensionless).
    pub unit: String,
    /// Actual level at coded −1, in `unit`.
    pub low: f64,
    /// Actual level at coded +1, in `unit`.
    pub high: f64,
}

/// Largest |level| of a factor, in its unit: no quantity of a DEM study comes near it, and it
/// keeps every derived value finite: axial points (α ≤ a few), and squared terms, 1e200
/// (±1e308 levels once gave axial points of ±inf and NaN).
pub const MAX_LEVEL_MAGNITUDE: f64 = 1e100;

impl Factor {
    /// A factor with coded −1 at `low` and +1 at `high` (both in `unit`).
    /// Rejects an empty name, non-finite levels, levels beyond ±[`MAX_LEVEL_MAGNITUDE`] and
    /// `low >= high`.
    pub fn new(name: &str, unit: &str, low: f64, high: f64) -> Result<Self, DesignError> {
        let bad = |reason: String| DesignError::BadFactor {
            name: name.to_owned(),
            reason,
        };
        if name.trim().is_empty() {
            return Err(bad("the name is empty".into()));
        }
        if !low.is_finite() || !high.is_finite() {
            return Err(bad(format!(
                "levels {low} and {high} must be finite numbers"
            )));
        }
        if low.abs().max(high.abs()) > MAX_LEVEL_MAGNITUDE {
            return Err(bad(format!(
                "levels {low:e} and {high:e} are beyond ±{MAX_LEVEL_MAGNITUDE:e}: the axial \
                 points and squared terms of a design would leave double precision"
            )));
        }
        if low >= high {
            return Err(bad(format!(
                "low level {low} must be below high level {high}"
            )));
        }
        Ok(Self {
            name: name.trim().to_owned(),
            unit: unit.trim().to_owned(),
            low,
            high,
        })
    }

    /// A factor given by the actual levels of its axial points (coded ±`alpha`), as
    /// Design-Expert offers for central composite designs: the ±1 levels are
    /// `centre ± (axial_high − axial_low)/(2 alpha)`. Seed 001 Table 9 is built this way:
    /// X7 axial 4.00…6.00 with α = 1.414 gives ±1 levels 4.293 and 5.707.
    pub fn from_axial_levels(
        name: &str,
        unit: &str,
        axial_low: f64,
        axial_high: f64,
        alpha: f64,
    ) -> Result<Self, DesignError> {
        if !(alpha.is_finite() && alpha > 0.0) {
            return Err(DesignError::BadAlpha(alpha));
        }
        let centre = 0.5 * (axial_low + axial_high);
        let half = 0.5 * (axial_high - axial_low) / alpha;
        Self::new(name, unit, centre - half, centre + half)
    }

    /// Parses `name:low:high[:unit]` (the `--factors` syntax of `arachis doe design`).
    pub fn parse(spec: &str) -> Result<Self, DesignError> {
        let bad = |reason: &str| DesignError::BadFactorSpec {
            spec: spec.to_owned(),
            reason: reason.to_owned(),
        };
        let parts: Vec<&str> = spec.split(':').collect();
        if !(3..=4).contains(&parts.len()) {
            return Err(bad("expected name:low:high or name:low:high:unit"));
        }
        let number = |text: &str, which: &str| {
            text.trim()
                .parse::<f64>()
                .map_err(|_| bad(&format!("{which} level '{text}' is not a number")))
        };
        let low = number(parts[1], "low")?;
        let high = number(parts[2], "high")?;
        let unit = parts.get(3).copied().unwrap_or("-");
        Self::new(parts[0], unit, low, high)
    }

    /// Centre level `(low + high)/2`, in `unit`.
    pub fn centre(&self) -> f64 {
        0.5 * (self.low + self.high)
    }

    /// Half-range `(high − low)/2`, in `unit`: the actual change per coded unit.
    pub fn half_range(&self) -> f64 {
        0.5 * (self.high - self.low)
    }

    /// Actual level (in `unit`) of coded value `x`: `X = X₀ + x ΔX`. Coded ±1 return `low` and
    /// `high` exactly, so printed levels are not disturbed by rounding.
    pub fn to_actual(&self, x: f64) -> f64 {
        if x == -1.0 {
            self.low
        } else if x == 1.0 {
            self.high
        } else {
            self.centre() + x * self.half_range()
        }
    }

    /// Coded value of actual level `value` (in `unit`): `x = (X − X₀)/ΔX` (seed 001 §2.5).
    pub fn to_coded(&self, value: f64) -> f64 {
        (value - self.centre()) / self.half_range()
    }
}

/// Checks that no two factors share a name.
pub(crate) fn check_unique_names(factors: &[Factor]) -> Result<(), DesignError> {
    for (i, f) in factors.iter().enumerate() {
        if factors[..i].iter().any(|g| g.name == f.name) {
            return Err(DesignError::DuplicateName(f.name.clone()));
        }
    }
    Ok(())
}
