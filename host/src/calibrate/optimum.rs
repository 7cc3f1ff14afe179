//! Stage 4: the calibrated optimum by Derringer–Suich desirability on the fitted surface
//! (seed 000 §3.6.1; DESIGN §9).
//!
//! The goal is the target measurement: d = 1 at the measured value T and falls linearly to
//! 0 at T ± w, where w is the largest distance of any Box–Behnken response from T (so the
//! ramps span what the design observed, as Design-Expert's default limits do, but
//! symmetric about the target, which need not be the middle of the observed range). The
//! search is `optimize::optimise_desirability` over the coded box [−1, 1]^k (multi-start
//! Nelder–Mead, deterministic starts). Many points may reach D = 1 on a surface that
//! crosses T along a ridge; among the solutions within [`DESIRABILITY_TIE`] of the best,
//! the one nearest the box centre is taken, where the fitted surface is best supported
//! (smallest prediction variance of a Box–Behnken design).

use std::collections::BTreeMap;

use serde::Serialize;

use super::box_behnken::BoxBehnkenStage;
use super::screening::Screening;
use super::{CalibrateError, Runner, TargetInfo};
use crate::optimize::{optimise_desirability, DesirableSolution, Goal, GoalKind, SearchOptions};
use crate::study::parameters::lookup;

/// Distinct solutions the search lists (it starts from four times as many points).
const SOLUTIONS: usize = 20;
/// Solutions whose desirability is within this of the best count as equally good.
pub const DESIRABILITY_TIE: f64 = 1e-6;
/// Smallest ramp half-width, as a fraction of |T|, when every response equals the target.
const MIN_HALF_WIDTH_FRACTION: f64 = 1e-6;

/// The desirability goal, in the response's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoalInfo {
    /// Target T.
    pub target: f64,
    /// Lower limit T − w.
    pub low: f64,
    /// Upper limit T + w.
    pub high: f64,
}

/// One parameter of the calibrated set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterRow {
    /// Registry name.
    pub name: String,
    /// Report label.
    pub label: String,
    /// Unit.
    pub unit: String,
    /// Calibrated or held value, in `unit`.
    pub value: f64,
    /// "calibrated" (from the optimum) or "held" (the study's value or range centre).
    pub role: String,
    /// The study's screening range.
    pub low: f64,
    /// The study's screening range.
    pub high: f64,
}

/// The optimum's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Optimum {
    /// The goal.
    pub goal: GoalInfo,
    /// Coded point in the Box–Behnken coding, one per factor.
    pub coded: Vec<f64>,
    /// The calibrated factors' values (registry name → value).
    pub actual: BTreeMap<String, f64>,
    /// Overall desirability D.
    pub desirability: f64,
    /// The fitted surface's prediction there, response units.
    pub predicted: f64,
    /// Distinct solutions the search found with D > 0.
    pub solutions_found: usize,
    /// Every varied parameter at the calibrated set (seed 000 §3.6.2's list).
    pub parameters: Vec<ParameterRow>,
}

/// Among the solutions within [`DESIRABILITY_TIE`] of the best, the one nearest the box
/// centre (`None` when there is none).
pub fn most_central_best(found: &[DesirableSolution]) -> Option<&DesirableSolution> {
    let best = found.first()?.desirability;
    let norm = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>();
    found
        .iter()
        .filter(|s| s.desirability >= best - DESIRABILITY_TIE)
        .min_by(|a, b| norm(&a.coded).total_cmp(&norm(&b.coded)))
}

/// Runs stage 4.
pub fn run(
    runner: &Runner<'_>,
    target: &TargetInfo,
    screening: &Screening,
    bbd: &BoxBehnkenStage,
) -> Result<Optimum, CalibrateError> {
    let t = target.value;
    let spread = bbd
        .runs
        .iter()
        .map(|r| (r.response - t).abs())
        .fold(0.0_f64, f64::max);
    let w = spread.max(MIN_HALF_WIDTH_FRACTION * t.abs());
    let goal = Goal::new(GoalKind::Target(t), t - w, t + w)?;
    let surface = bbd.surface();
    let k = bbd.factors.len();
    let found = runner.install(|| {
        optimise_desirability(
            &[(&surface, goal)],
            k,
            &SearchOptions::for_solutions(SOLUTIONS),
        )
    })?;
    let chosen = most_central_best(&found).ok_or_else(|| {
        CalibrateError::Plan(format!(
            "the fitted surface never comes within {w} of the target {t} inside the \
                 Box–Behnken box"
        ))
    })?;
    let actual: BTreeMap<String, f64> = bbd
        .factors
        .iter()
        .zip(&chosen.coded)
        .map(|(f, &x)| {
            (
                f.name.clone(),
                0.5 * (f.low + f.high) + x * 0.5 * (f.high - f.low),
            )
        })
        .collect();
    let study = runner.study();
    let parameters = screening
        .factors
        .iter()
        .map(|f| {
            let (value, role) = match actual.get(&f.name) {
                Some(v) => (*v, "calibrated"),
                None => (
                    lookup(&f.name)
                        .and_then(|s| study.held_value(s))
                        .unwrap_or(0.5 * (f.low + f.high)),
                    "held",
                ),
            };
            ParameterRow {
                name: f.name.clone(),
                label: f.label.clone(),
                unit: f.unit.clone(),
                value,
                role: role.to_owned(),
                low: f.low,
                high: f.high,
            }
        })
        .collect();
    Ok(Optimum {
        goal: GoalInfo {
            target: t,
            low: t - w,
            high: t + w,
        },
        coded: chosen.coded.clone(),
        actual,
        desirability: chosen.desirability,
        predicted: chosen.predictions[0],
        solutions_found: found.len(),
        parameters,
    })
}
