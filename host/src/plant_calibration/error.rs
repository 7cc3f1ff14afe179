//! Errors of the plant calibration, each saying which stage and why.

use crate::doe::DesignError;
use crate::optimize::OptimizeError;
use crate::stats::StatsError;

/// A plant-calibration failure.
#[derive(Debug, thiserror::Error)]
pub enum PlantCalibrationError {
    /// A design could not be built.
    #[error("{stage}: design: {source}")]
    Design {
        /// The stage.
        stage: &'static str,
        /// Why.
        source: DesignError,
    },
    /// A fit or ANOVA failed.
    #[error("{stage}: statistics: {source}")]
    Stats {
        /// The stage.
        stage: &'static str,
        /// Why.
        source: StatsError,
    },
    /// The optimiser failed.
    #[error("optimum: {0}")]
    Optimize(#[from] OptimizeError),
    /// A pull-off run failed.
    #[error("pull-off at x1…x9 = {values:?} failed: {reason}")]
    Simulation {
        /// The nine factor values of the run (SI).
        values: Vec<f64>,
        /// Why.
        reason: String,
    },
    /// The plan cannot go on (e.g. a factor leaves its physical limits).
    #[error("{0}")]
    Plan(String),
}
