//! The plan of a plant calibration: the nine factors with their levels and every setting of
//! the stages (screening centre points and significance, path step and length, central
//! composite α and centre points, the factors it takes, the validation limit).
//!
//! [`Plan::seed001`] is seed 001's plan as printed (Table 5 levels, Tables 6–10, §3); a plant
//! study file (`crate::plant_study`) builds its own from the file, so `arachis calibrate`
//! runs whatever plan the study states while `arachis plant-calibrate` keeps the seed's.

use serde::Serialize;

use super::factors::{by_label, PlantFactor, TABLE5};
use super::{ccd, optimum, path, screening};
use crate::doe::PlackettBurmanRuns;

/// Every setting of a plant calibration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// The nine factors x1…x9 (seed 001 Table 5 labels, settings and units) with the plan's
    /// low/high levels (SI).
    pub factors: [PlantFactor; 9],
    /// Runs of the Plackett–Burman design (12 or 20).
    pub screening_runs: usize,
    /// Centre points of the screening design.
    pub screening_centre_points: usize,
    /// Screening significance level (p below it: significant).
    pub significance: f64,
    /// Level at which a screened factor is carried on (p at or below it).
    pub carry_level: f64,
    /// Coded step of the largest-|b| factor per path point.
    pub path_step_coded: f64,
    /// Path points run at once.
    pub path_first_points: usize,
    /// Longest path.
    pub path_max_points: usize,
    /// Axial distance α of the central composite design, coded.
    pub ccd_alpha: f64,
    /// Centre points of the central composite design.
    pub ccd_centre_points: usize,
    /// Factors the plan names for the path and the central composite design (overriding the
    /// screening's choice); `None` takes the screening's.
    pub carry: Option<Vec<String>>,
    /// Where `carry` comes from and why (stated in the report).
    pub carry_reason: Option<String>,
    /// Pass mark of the validation pull, % relative error.
    pub max_relative_error_pct: f64,
}

impl Plan {
    /// Seed 001's plan: Table 5 levels, 12-run Plackett–Burman with 3 centre points
    /// (Table 6), p < 0.05 significant and p ≤ 0.01 carried (Table 7), path steps of a
    /// quarter range, 5 points (Table 8), α = 1.414 with 5 centre points (Tables 9–10),
    /// validation within 5 % (issue 6). The screening chooses the carried factors.
    pub fn seed001() -> Self {
        Self {
            factors: TABLE5,
            screening_runs: 12,
            screening_centre_points: screening::CENTRE_POINTS,
            significance: screening::SIGNIFICANCE,
            carry_level: screening::CARRY_LEVEL,
            path_step_coded: path::STEP_CODED,
            path_first_points: path::FIRST_POINTS,
            path_max_points: path::MAX_POINTS,
            ccd_alpha: ccd::ALPHA,
            ccd_centre_points: ccd::CENTRE_POINTS,
            carry: None,
            carry_reason: None,
            max_relative_error_pct: optimum::MAX_RELATIVE_ERROR_PCT,
        }
    }

    /// The factor labelled `label`, with this plan's levels.
    pub fn factor(&self, label: &str) -> Option<&PlantFactor> {
        self.factors.iter().find(|f| f.label == label)
    }

    /// The nine settings with the factors `labels` at `values`, the others at their range
    /// centres (the held values).
    pub fn settings_with(&self, labels: &[String], values: &[f64]) -> [f64; 9] {
        core::array::from_fn(|j| {
            labels
                .iter()
                .position(|l| l == self.factors[j].label)
                .map_or(self.factors[j].centre(), |i| values[i])
        })
    }

    /// The Plackett–Burman size, if `screening_runs` is one `doe` builds.
    pub fn plackett_burman_runs(&self) -> Option<PlackettBurmanRuns> {
        match self.screening_runs {
            12 => Some(PlackettBurmanRuns::Twelve),
            20 => Some(PlackettBurmanRuns::Twenty),
            _ => None,
        }
    }

    /// Why the plan cannot run, if it cannot: factors out of Table 5's order, levels not
    /// low < high or outside physical limits, a carry list that is not 2–3 distinct labels,
    /// or a design setting out of range.
    pub fn check(&self) -> Result<(), String> {
        for (f, t) in self.factors.iter().zip(&TABLE5) {
            if f.label != t.label || f.setting != t.setting {
                return Err(format!("factor {} is not seed 001 Table 5's", f.label));
            }
            if f.low >= f.high || f.low.is_nan() || f.high.is_nan() {
                return Err(format!(
                    "factor {}: low {} must be below high {}",
                    f.label, f.low, f.high
                ));
            }
            f.check(f.low)?;
            f.check(f.high)?;
        }
        if self.plackett_burman_runs().is_none() {
            return Err(format!(
                "a Plackett–Burman design for 9 factors has 12 or 20 runs, got {}",
                self.screening_runs
            ));
        }
        if let Some(c) = &self.carry {
            check_carry(c)?;
        }
        let unit = |v: f64| v > 0.0 && v < 1.0;
        if !(unit(self.significance) && unit(self.carry_level)) {
            return Err("significance levels must lie in (0, 1)".into());
        }
        if !(self.path_step_coded > 0.0 && self.path_step_coded.is_finite()) {
            return Err("the path step must be a positive coded length".into());
        }
        if self.path_first_points < 3 || self.path_max_points < self.path_first_points {
            return Err(
                "the path needs at least 3 points and at most as many as its longest".into(),
            );
        }
        if !(self.ccd_alpha >= 1.0 && self.ccd_alpha.is_finite()) || self.ccd_centre_points < 1 {
            return Err("the central composite design needs α ≥ 1 and a centre point".into());
        }
        if !(self.max_relative_error_pct > 0.0 && self.max_relative_error_pct.is_finite()) {
            return Err("the validation limit must be a positive %".into());
        }
        Ok(())
    }
}

/// Refuses a carry list that is not [`screening::MIN_CARRIED`]–[`screening::MAX_CARRIED`]
/// distinct Table 5 labels.
pub fn check_carry(carry: &[String]) -> Result<(), String> {
    let range = screening::MIN_CARRIED..=screening::MAX_CARRIED;
    if !range.contains(&carry.len()) {
        return Err(format!(
            "the central composite stage takes {} to {} factors, got {}",
            range.start(),
            range.end(),
            carry.len()
        ));
    }
    for (i, l) in carry.iter().enumerate() {
        if by_label(l).is_none() {
            return Err(format!("unknown factor '{l}' (seed 001 Table 5 has x1…x9)"));
        }
        if carry[..i].contains(l) {
            return Err(format!("factor '{l}' given twice"));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed_plan_checks_and_holds_the_centres() {
        let plan = Plan::seed001();
        plan.check().unwrap();
        let s = plan.settings_with(&["x8".into()], &[1.0e6]);
        assert_eq!(s[7], 1.0e6);
        assert_eq!(s[0], TABLE5[0].centre());
    }

    #[test]
    fn bad_plans_are_refused() {
        let mut plan = Plan::seed001();
        plan.factors[6].low = plan.factors[6].high;
        assert!(plan.check().unwrap_err().contains("x7"));
        let mut plan = Plan::seed001();
        plan.carry = Some(vec!["x7".into(), "x7".into()]);
        assert!(plan.check().unwrap_err().contains("twice"));
        let mut plan = Plan::seed001();
        plan.screening_runs = 16;
        assert!(plan.check().unwrap_err().contains("12 or 20"));
    }
}
