//! Why an optimisation could not be set up or run.

use std::path::PathBuf;

use thiserror::Error;

/// An optimisation request that cannot be honoured.
#[derive(Debug, Error)]
pub enum OptimizeError {
    /// A fit file (the JSON written by `arachis doe analyze --json`) is unreadable or
    /// malformed; `place` says where in the file (a JSON path such as `coefficients[3].term`,
    /// or the parser's line and column).
    #[error("{path}: {place}: {reason}")]
    FitFile {
        /// The file.
        path: PathBuf,
        /// Where in the file.
        place: String,
        /// What is wrong.
        reason: String,
    },
    /// A goal is malformed or inconsistent (e.g. a target outside its limits).
    #[error("goal '{goal}': {reason}")]
    BadGoal {
        /// The goal as given.
        goal: String,
        /// What is wrong.
        reason: String,
    },
    /// Search settings that cannot work (no dimensions, zero starts, …).
    #[error("search: {0}")]
    BadSearch(String),
    /// The local optimiser failed.
    #[error("local optimiser: {0}")]
    Solver(String),
}
