//! Stage 5: a simulation of the calibrated optimum against the validation measurement, with
//! the relative error ψ = |ζ′ − ζ|/ζ × 100 % (seed 000 eq. (21); §3.6.2 reports 0.42 %)
//! and the pass mark `[plan.validation] max_relative_error_pct`.
//!
//! The one chosen optimum is simulated `[plan.validation] replicates` times with independent pod
//! placements (the study's random seed advanced per replicate) and ψ is taken on their mean.
//! Seed 000 §3.6.2 instead simulated several of its hundred solutions and kept the closest
//! (30.93°, ψ = 0.42 %), which selects on run-to-run scatter; averaging replicates of one
//! point measures the calibrated parameters, not the luck of a run.

use std::collections::BTreeMap;

use serde::Serialize;

use super::optimum::Optimum;
use super::{CalibrateError, PlannedRun, RunRecord, Runner};
use crate::stats::relative_error_percent;
use crate::study::Experiment;

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "validation";

/// The validation's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Validation {
    /// The experiment simulated.
    pub experiment: Experiment,
    /// The quantity compared.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The measurement's condition.
    pub condition: BTreeMap<String, f64>,
    /// The measured mean ζ.
    pub measured: f64,
    /// The simulated value ζ′ at the optimum: the mean of the replicates.
    pub simulated: f64,
    /// Sample SD of the replicates, in `unit`.
    pub simulated_sd: f64,
    /// The surface's prediction at the optimum, for comparison.
    pub predicted: f64,
    /// ψ, %.
    pub relative_error_pct: f64,
    /// The largest accepted ψ, %.
    pub max_relative_error_pct: f64,
    /// ψ ≤ the largest accepted.
    pub passed: bool,
    /// The validation runs (replicates of the optimum).
    pub runs: Vec<RunRecord>,
}

/// Runs stage 5.
pub fn run(runner: &Runner<'_>, optimum: &Optimum) -> Result<Validation, CalibrateError> {
    let study = runner.study();
    let m = study.validation();
    let measured = m
        .mean()
        .ok_or_else(|| CalibrateError::Plan("the validation measurement has no mean".into()))?;
    let planned: Vec<PlannedRun> = (0..study.file().plan.validation.replicates())
        .map(|replicate| PlannedRun {
            coded: optimum.coded.clone(),
            values: optimum.actual.clone(),
            replicate,
        })
        .collect();
    let runs = runner.run_batch(STAGE, m.experiment, &m.condition, &planned)?;
    let n = runs.len() as f64;
    let simulated = runs.iter().map(|r| r.response).sum::<f64>() / n;
    let simulated_sd = (runs
        .iter()
        .map(|r| (r.response - simulated).powi(2))
        .sum::<f64>()
        / (n - 1.0).max(1.0))
    .sqrt();
    let psi = relative_error_percent(simulated, measured);
    let max = study.file().plan.validation.max_relative_error_pct;
    Ok(Validation {
        experiment: m.experiment,
        quantity: m.quantity.clone(),
        unit: m.unit.clone(),
        condition: m.condition.clone(),
        measured,
        simulated,
        simulated_sd,
        predicted: optimum.predicted,
        relative_error_pct: psi,
        max_relative_error_pct: max,
        passed: psi <= max,
        runs,
    })
}
