//! Stage 3: the Box–Behnken design around the best path point and its response-surface fit
//! (seed 000 §3.5, Tables 7–9, eq. (22)).
//!
//! The box: when the best path point and a neighbour bracket the target (their responses
//! lie on either side of it), those two points become coded −1 and +1 of each factor —
//! seed 000 §3.4 takes points 2 and 3 of Table 6 (29.36° and 31.48° around 31.06°). When no
//! neighbour brackets it (the best point is at the end of the path, or the path overshoots
//! on both sides), the box spans one step either side of the best point, which reaches past
//! the path's end where the target may lie. A factor the path does not move gets ± half a
//! step of its own coding.
//!
//! The design has the study's centre points (seed 000 Table 8: 17 = 12 + 5 runs), replicated
//! with advanced random seeds so they measure pure error. The model of `[plan.model]` is
//! fitted and tested with `stats::analyze` (Type III SS, lack of fit against pure error).

use serde::Serialize;

use super::screening::FactorInfo;
use super::steepest_ascent::SteepestAscent;
use super::{planned_runs, CalibrateError, RunRecord, Runner, TargetInfo};
use crate::doe::box_behnken;
use crate::optimize::Polynomial;
use crate::stats::{analyze, Anova, CodedDesign, ModelOrder};
use crate::study::plan::ModelOrder as PlanOrder;

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "box-behnken";

/// Two levels closer than this fraction of the factor's screening range are the same level.
const SAME_LEVEL_FRACTION: f64 = 1e-9;

/// The Box–Behnken stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BoxBehnkenStage {
    /// The factors with the box's levels (coded ±1).
    pub factors: Vec<FactorInfo>,
    /// How the box was chosen, in words.
    pub range_rule: String,
    /// Path positions (1-based, may be 0 or past the last point) of coded −1 and +1 of the
    /// lead factor.
    pub path_points: [i64; 2],
    /// Centre points.
    pub centre_points: u32,
    /// The runs, standard order, coded in the box's coding.
    pub runs: Vec<RunRecord>,
    /// The model fitted ("Linear", "2FI", "Quadratic").
    pub model: String,
    /// Its ANOVA and coded equation.
    pub anova: Anova,
}

impl BoxBehnkenStage {
    /// The fitted coded equation as a polynomial (cheap to evaluate, unlike rebuilding the
    /// terms per call with `Anova::predict`).
    pub fn surface(&self) -> Polynomial {
        let names = self.factors.iter().map(|f| f.label.clone()).collect();
        let terms: Vec<(&str, f64)> = self
            .anova
            .coefficients
            .iter()
            .map(|c| (c.term.as_str(), c.estimate))
            .collect();
        Polynomial::new(names, &terms).expect("the fit's terms are terms of its factors")
    }
}

/// The stats model order of the plan's `[plan.model] order`.
pub fn model_order(order: PlanOrder) -> ModelOrder {
    match order {
        PlanOrder::Linear => ModelOrder::Linear,
        PlanOrder::Interaction => ModelOrder::TwoFactorInteraction,
        PlanOrder::Quadratic => ModelOrder::Quadratic,
    }
}

/// The path positions (0-based, possibly −1 or past the end) of the box's −1 and +1, and
/// the rule in words.
pub fn box_positions(responses: &[f64], best: usize, target: f64) -> ([i64; 2], String) {
    let brackets = |a: usize, b: usize| (responses[a] - target) * (responses[b] - target) <= 0.0;
    let b = best as i64;
    if best + 1 < responses.len() && brackets(best, best + 1) {
        (
            [b, b + 1],
            format!(
                "path points {} and {} bracket the target (seed 000 §3.4)",
                best + 1,
                best + 2
            ),
        )
    } else if best >= 1 && brackets(best - 1, best) {
        (
            [b - 1, b],
            format!(
                "path points {} and {} bracket the target (seed 000 §3.4)",
                best,
                best + 1
            ),
        )
    } else {
        (
            [b - 1, b + 1],
            format!(
                "no neighbour of the best path point {} brackets the target, so the box spans \
                 one step either side of it",
                best + 1
            ),
        )
    }
}

/// Runs stage 3.
pub fn run(
    runner: &Runner<'_>,
    target: &TargetInfo,
    path: &SteepestAscent,
) -> Result<BoxBehnkenStage, CalibrateError> {
    let plan = &runner.study().file().plan;
    let responses: Vec<f64> = path.runs.iter().map(|r| r.response).collect();
    let (positions, rule) = box_positions(&responses, path.best - 1, target.value);
    let ends = [
        path.actual_point(&path.coded_point(path.position(positions[0]))),
        path.actual_point(&path.coded_point(path.position(positions[1]))),
    ];
    let step = plan.steepest_ascent.step_coded;
    let factors: Vec<FactorInfo> = path
        .factors
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let (mut low, mut high) = (ends[0][i].min(ends[1][i]), ends[0][i].max(ends[1][i]));
            if high - low <= SAME_LEVEL_FRACTION * (f.high - f.low) {
                let half = 0.5 * step * 0.5 * (f.high - f.low);
                (low, high) = (low - half, high + half);
                // A factor the path holds at a limit keeps the box on the admissible side.
                if f.admissible(low) != low {
                    (low, high) = (f.admissible(low), f.admissible(low) + 2.0 * half);
                } else if f.admissible(high) != high {
                    (low, high) = (f.admissible(high) - 2.0 * half, f.admissible(high));
                }
            }
            FactorInfo {
                low,
                high,
                ..f.clone()
            }
        })
        .collect();
    let doe_factors = factors
        .iter()
        .map(FactorInfo::factor)
        .collect::<Result<Vec<_>, _>>()
        .map_err(|source| CalibrateError::Design {
            stage: STAGE,
            source,
        })?;
    let centre_points = plan.box_behnken.centre_points;
    let design = box_behnken(&doe_factors, centre_points as usize).map_err(|source| {
        CalibrateError::Design {
            stage: STAGE,
            source,
        }
    })?;
    let planned = planned_runs(&factors, &design);
    let runs = runner.run_batch(STAGE, target.experiment, &target.condition, &planned)?;
    let order = model_order(plan.model.order);
    let labels: Vec<String> = factors.iter().map(|f| f.label.clone()).collect();
    let stats_err = |source| CalibrateError::Stats {
        stage: STAGE,
        source,
    };
    let coded = CodedDesign::new(
        labels,
        design.coded.clone(),
        runs.iter().map(|r| r.response).collect(),
    )
    .map_err(stats_err)?;
    let anova = analyze(&coded, order).map_err(stats_err)?;
    Ok(BoxBehnkenStage {
        factors,
        range_rule: rule,
        path_points: [positions[0] + 1, positions[1] + 1],
        centre_points,
        runs,
        model: order.label().to_owned(),
        anova,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seed000_table6_brackets_between_points_2_and_3() {
        let y = [23.89, 29.36, 31.48, 35.01, 38.22];
        let (pos, rule) = box_positions(&y, 2, 31.06);
        assert_eq!(pos, [1, 2]);
        assert!(rule.contains("points 2 and 3"));
    }

    #[test]
    fn path_end_reaches_one_step_beyond() {
        let y = [20.0, 22.0, 24.0, 26.0, 28.0];
        let (pos, rule) = box_positions(&y, 4, 31.06);
        assert_eq!(pos, [3, 5]);
        assert!(rule.contains("one step either side"));
    }
}
