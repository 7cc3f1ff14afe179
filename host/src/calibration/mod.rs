//! The calibration engine: one plan for every rig (issue 17). It knows nothing of pods or
//! plants; it drives a [`Rig`] — parameter values and a replicate in, named responses out
//! — through seed 000's and seed 001's sequence of designs:
//!
//! 1. screening by Plackett–Burman, with or without centre points and curvature;
//! 2. a path of steepest ascent toward the target;
//! 3. a Box–Behnken or central composite design around the best path point, fitted;
//! 4. the desirability optimum on the fitted surface;
//! 5. validation runs of the optimum.
//!
//! A [`Problem`] is what a study becomes once loaded: the [`Factor`]s, the
//! [`PlanSettings`], and the target and validation [`Objective`]s with their rigs.
//! [`calibrate`] runs it on an [`Executor`] (threads, run cache, progress) and returns
//! every stage's numbers; the `report` module writes them out. The plan's stages live in
//! [`plan`], one file each.

pub mod error;
pub mod executor;
pub mod factor;
pub mod objective;
pub mod plan;
pub mod progress;
pub mod rig;
pub mod run_cache;
pub mod settings;
pub mod spec_hash;

pub use error::CalibrateError;
pub use executor::{BatchRun, Executor, FinishedRun, PlannedRun, Remote, RemoteRun, RunRecord};
pub use factor::Factor;
pub use objective::Objective;
pub use plan::Stages;
pub use progress::Progress;
pub use rig::{Condition, ParameterValues, Responses, Rig, RigError, RunRequest};
pub use settings::PlanSettings;
pub use spec_hash::SpecHash;

/// Folder of stored runs inside a calibration's output folder.
pub const RUNS_DIR: &str = "runs";

/// A calibration to run.
pub struct Problem<'a> {
    /// Every varied parameter, in the study's order (screening columns).
    pub factors: Vec<Factor>,
    /// The plan.
    pub plan: PlanSettings,
    /// What the optimum must hit.
    pub target: Objective<'a>,
    /// What the optimum is checked against (often the target's measurement again).
    pub validation: Objective<'a>,
}

/// A finished calibration and how much work it took.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Every stage's numbers.
    pub stages: Stages,
    /// Runs simulated by this call.
    pub simulated: usize,
    /// Runs replayed from the run cache.
    pub replayed: usize,
}

/// Runs the whole plan of `problem` on `executor`.
pub fn calibrate(problem: &Problem<'_>, executor: &Executor) -> Result<Outcome, CalibrateError> {
    let before = executor.counts();
    let stages = plan::run_plan(problem, executor)?;
    let after = executor.counts();
    Ok(Outcome {
        stages,
        simulated: after.0 - before.0,
        replayed: after.1 - before.1,
    })
}
