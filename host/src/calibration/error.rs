//! Why a calibration stopped: each variant names the stage, run or file at fault so the
//! command line can print it as is.

use std::path::PathBuf;

use thiserror::Error;

use crate::doe::DesignError;
use crate::optimize::OptimizeError;
use crate::stats::StatsError;

/// A calibration that could not finish.
#[derive(Debug, Error)]
pub enum CalibrateError {
    /// The study cannot support the plan (too few varied parameters, no direction, …).
    #[error("the study cannot be calibrated: {0}")]
    Plan(String),
    /// The rig refused a run's specification (an unknown parameter, a missing setting).
    #[error("{stage} run {run}: cannot build its specification: {reason}")]
    Spec {
        /// The stage (screening, steepest ascent, …).
        stage: &'static str,
        /// 1-based run number within the stage.
        run: usize,
        /// Why.
        reason: String,
    },
    /// A design point lies outside a parameter's physical limits.
    #[error("{stage} run {run}: {parameter} = {value} is outside its physical limits: {reason}")]
    OutOfLimits {
        /// The stage.
        stage: &'static str,
        /// 1-based run number within the stage.
        run: usize,
        /// Registry name of the parameter.
        parameter: String,
        /// The offending value, in the parameter's unit.
        value: f64,
        /// The limit in words.
        reason: String,
    },
    /// The rig failed on one run.
    #[error("{stage} run {run} (spec {hash}): the simulation failed: {reason}")]
    Simulation {
        /// The stage.
        stage: &'static str,
        /// 1-based run number within the stage.
        run: usize,
        /// The run's spec hash.
        hash: String,
        /// The rig's message.
        reason: String,
    },
    /// A design could not be built.
    #[error("{stage}: {source}")]
    Design {
        /// The stage.
        stage: &'static str,
        /// The design error.
        source: DesignError,
    },
    /// A regression or ANOVA could not be computed.
    #[error("{stage}: {source}")]
    Stats {
        /// The stage.
        stage: &'static str,
        /// The statistics error.
        source: StatsError,
    },
    /// The desirability search failed.
    #[error("optimisation: {0}")]
    Optimize(#[from] OptimizeError),
    /// An output or cache file could not be written or read.
    #[error("{path}: {reason}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// Why.
        reason: String,
    },
    /// The rayon thread pool could not be built.
    #[error("cannot start {jobs} worker threads: {reason}")]
    Threads {
        /// Threads asked for.
        jobs: usize,
        /// Why.
        reason: String,
    },
}
