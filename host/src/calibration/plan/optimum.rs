//! Stage 4: the calibrated optimum by Derringer–Suich desirability on the fitted surface
//! (seed 000 §3.6.1; seed 001 §3.2; DESIGN §9).
//!
//! The goal is the target measurement: d = 1 at the measured value T and falls linearly to
//! 0 at T ± w, where w is the largest distance of any response-surface run from T (so the
//! ramps span what the design observed, as Design-Expert's default limits do, but
//! symmetric about the target, which need not be the middle of the observed range). The
//! search is `optimize::optimise_desirability` (multi-start Nelder–Mead, deterministic
//! starts) over the design's search box ([`ResponseSurface::search_half_width`]). Many
//! points may reach D = 1 on a surface that crosses T along a ridge; among the solutions
//! within [`DESIRABILITY_TIE`] of the best, the one nearest the box centre is taken, where
//! the fitted surface is best supported (smallest prediction variance).

use serde::Serialize;

use super::super::executor::Executor;
use super::super::rig::ParameterValues;
use super::super::{CalibrateError, Objective};
use super::response_surface::ResponseSurface;
use crate::optimize::{
    optimise_desirability, DesirableSolution, Goal, GoalKind, ResponseSurface as _, SearchOptions,
};

/// Distinct solutions the search lists (it starts from four times as many points).
const SOLUTIONS: usize = 20;
/// Solutions whose desirability is within this of the best count as equally good.
pub const DESIRABILITY_TIE: f64 = 1e-6;
/// Smallest ramp half-width, as a fraction of |T|, when every response equals the target.
const MIN_HALF_WIDTH_FRACTION: f64 = 1e-6;

/// The desirability goal, in the response's unit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoalRange {
    /// Target T.
    pub target: f64,
    /// Lower limit T − w.
    pub low: f64,
    /// Upper limit T + w.
    pub high: f64,
}

/// The optimum's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Optimum {
    /// The goal.
    pub goal: GoalRange,
    /// Coded point in the response surface's coding, one per factor.
    pub coded: Vec<f64>,
    /// The calibrated factors' values (name → value in the factor's unit).
    #[serde(rename = "actual")]
    pub values: ParameterValues,
    /// Overall desirability D.
    pub desirability: f64,
    /// The fitted surface's prediction there, response units.
    pub predicted: f64,
    /// Distinct solutions the search found with D > 0.
    pub solutions_found: usize,
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
    executor: &Executor,
    target: &Objective<'_>,
    fitted: &ResponseSurface,
) -> Result<Optimum, CalibrateError> {
    let t = target.value;
    let spread = fitted
        .runs
        .iter()
        .map(|r| (r.response - t).abs())
        .fold(0.0_f64, f64::max);
    let w = spread.max(MIN_HALF_WIDTH_FRACTION * t.abs());
    let goal = Goal::new(GoalKind::Target(t), t - w, t + w)?;
    let polynomial = fitted.surface();
    let half = fitted.search_half_width();
    // The optimiser searches [−1, 1]^k; the surface is scaled to the search box.
    let surface = |u: &[f64]| {
        let x: Vec<f64> = u.iter().map(|v| v * half).collect();
        polynomial.predict(&x)
    };
    let k = fitted.factors.len();
    let found = executor.install(|| {
        optimise_desirability(
            &[(&surface, goal)],
            k,
            &SearchOptions::for_solutions(SOLUTIONS),
        )
    })?;
    let chosen = most_central_best(&found).ok_or_else(|| {
        CalibrateError::Plan(format!(
            "the fitted surface never comes within {w} of the target {t} inside the \
             response-surface box"
        ))
    })?;
    let coded: Vec<f64> = chosen.coded.iter().map(|u| u * half).collect();
    let values = fitted
        .factors
        .iter()
        .zip(&coded)
        .map(|(f, &x)| (f.name.clone(), f.actual(x)))
        .collect();
    Ok(Optimum {
        goal: GoalRange {
            target: t,
            low: t - w,
            high: t + w,
        },
        coded,
        values,
        desirability: chosen.desirability,
        predicted: chosen.predictions[0],
        solutions_found: found.len(),
    })
}
