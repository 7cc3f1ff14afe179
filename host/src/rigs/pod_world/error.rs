//! What can go wrong in a virtual experiment, each with enough context to fix the input.

use thiserror::Error;

/// A failed virtual experiment.
#[derive(Debug, Error)]
pub enum ExperimentError {
    /// The experiment name is not one of the five rigs.
    #[error("unknown experiment '{name}': expected one of {expected}")]
    UnknownExperiment {
        /// The name given.
        name: String,
        /// The accepted names.
        expected: String,
    },
    /// A rig of the study's list that has no virtual experiment yet.
    #[error("the {experiment} rig is not built yet (built: repose, incline_slide, compression)")]
    NotBuilt {
        /// The experiment.
        experiment: &'static str,
    },
    /// The mode name is not `quick` or `full`.
    #[error("unknown mode '{name}': expected quick or full")]
    UnknownMode {
        /// The name given.
        name: String,
    },
    /// The study has no settings for the mode.
    #[error("the study has no [plan.modes.{mode}] table")]
    MissingMode {
        /// The mode.
        mode: String,
    },
    /// A parameter key is not in the registry.
    #[error("unknown parameter '{key}'{hint}")]
    UnknownParameter {
        /// The key given.
        key: String,
        /// ", did you mean …?" or empty.
        hint: String,
    },
    /// A parameter value is outside its physical limits.
    #[error("parameter '{key}' = {value}: {reason}")]
    BadValue {
        /// The registry key.
        key: String,
        /// The value given (SI).
        value: f64,
        /// Why it is refused.
        reason: String,
    },
    /// The study lacks something the experiment needs (a material, a pair, a value).
    #[error("the study cannot drive the {experiment} experiment: {reason}")]
    Study {
        /// The experiment.
        experiment: &'static str,
        /// What is missing.
        reason: String,
    },
    /// Pod shapes could not be built or filled.
    #[error("pod shapes: {0}")]
    Shape(#[from] crate::shapes::ShapeError),
    /// The DEM core refused the set-up.
    #[error("DEM set-up of the {experiment} experiment: {reason}")]
    Setup {
        /// The experiment.
        experiment: &'static str,
        /// The core's error.
        reason: arachis_core::error::SetupError,
    },
    /// The DEM core refused a value of the study, named by its key.
    #[error("DEM set-up of the {experiment} experiment: the study's {key}: {reason}")]
    SetupAt {
        /// The experiment.
        experiment: &'static str,
        /// The study key whose values the core refused, e.g. `pairs."pod-steel"`.
        key: String,
        /// The core's error.
        reason: arachis_core::error::SetupError,
    },
    /// The DEM core stopped during a step.
    #[error("DEM step of the {experiment} experiment at t = {time_s:.4} s: {reason}")]
    Step {
        /// The experiment.
        experiment: &'static str,
        /// Simulated time, s.
        time_s: f64,
        /// The core's error.
        reason: arachis_core::error::StepError,
    },
    /// The simulated pile could not be measured.
    #[error("repose angle of the simulated pile: {0}")]
    Repose(#[from] crate::repose::ReposeError),
    /// The experiment ran but its observable is undefined (e.g. the pod never stopped).
    #[error("the {experiment} experiment gave no observable: {reason}")]
    NoObservable {
        /// The experiment.
        experiment: &'static str,
        /// Why.
        reason: String,
    },
    /// Writing VTK frames failed.
    #[error("writing VTK frames: {0}")]
    Output(String),
}
