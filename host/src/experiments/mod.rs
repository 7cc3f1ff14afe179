//! Virtual bench experiments (issue 4 §2): each rig is a deterministic function from a
//! study, parameter values, a mode and a placement seed to one observable.
//!
//! | rig | file | observable | bench test |
//! |---|---|---|---|
//! | repose | [`repose`] | `repose_angle`, deg | cylinder lifting, seed 000 §2.7, §3.6.1 |
//! | plate drop | [`plate_drop`] | `restitution`, - | drop on the 45° plate, seed 000 §2.6.1 |
//! | incline slide | [`incline_slide`] | `slide_angle`, deg | tilting plate, seed 000 §2.6.2 |
//! | rolling | [`rolling`] | `rolling_distance`, mm | incline then flat, seed 000 §2.6.3 |
//! | compression | [`compression`] | `apparent_modulus`, Pa | two plates, seed 000 §2.5.3 |
//!
//! The one entry point is [`run_experiment`]. It is pure: no global state, no clock, no
//! thread-dependent order; the same inputs give the same bits (the fixed-point core's
//! digest is part of the [`Observation`]), so it may be called from rayon threads, and a
//! run can be cached under its [`crate::study::RunSpec`] hash plus the seed.
//!
//! ```no_run
//! use arachis::experiments::*;
//! use arachis::study::Study;
//! let study = Study::load("testdata/peanut-pods-saline/study.toml".as_ref()).unwrap();
//! let mut values = ParameterValues::new();
//! values.insert("pod-pod.static_friction".into(), 0.854);
//! let obs = run_experiment(&study, ExperimentKind::Repose, &values, ModeName::Quick, 1,
//!                          &RunOptions::default()).unwrap();
//! println!("{} {} {}", obs.quantity, obs.value, obs.unit); // repose_angle 4x.x deg
//! ```

pub mod error;
pub mod frames;
pub mod picture;
pub mod repose;
pub mod setup;
pub mod templates;
pub mod values;

use std::path::PathBuf;
use std::sync::Arc;

use serde::Serialize;

pub use error::ExperimentError;
pub use templates::TemplateCache;
pub use values::{check_values, parse_assignment, ModeName, ParameterValues};

/// The five rigs; the study's own experiment names (`repose`, `plate_drop`,
/// `incline_slide`, `rolling`, `compression`).
pub type ExperimentKind = crate::study::Experiment;

/// Options that change what a run writes, never what it computes.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Write VTK frames of the run into this directory.
    pub vtk_dir: Option<PathBuf>,
    /// Filled pod templates shared across runs (a fresh cache per run when `None`).
    pub templates: Option<Arc<TemplateCache>>,
}

/// Per-rig details of an observation.
#[derive(Debug, Clone, Serialize)]
#[serde(tag = "rig", rename_all = "snake_case")]
pub enum ObservationDetails {
    /// Repose rig.
    Repose(repose::ReposeDetails),
}

/// The result of one virtual experiment.
#[derive(Debug, Clone, Serialize)]
pub struct Observation {
    /// The rig.
    pub experiment: ExperimentKind,
    /// The observable's name (a study quantity, e.g. `repose_angle`).
    pub quantity: &'static str,
    /// Its value, in `unit`.
    pub value: f64,
    /// Its unit (`deg`, `-`, `mm`, `Pa`).
    pub unit: &'static str,
    /// The core's state digest at the end (16 hex digits): equal inputs give equal digests.
    pub digest: String,
    /// The ParaView series written, when VTK frames were asked for.
    pub vtk_series: Option<PathBuf>,
    /// Rig-specific numbers for reports.
    pub details: ObservationDetails,
}

/// Runs `experiment` for `study` with the parameters in `values` (registry keys → SI values,
/// overriding the study's held values), in `mode`, with placement seed `seed`.
///
/// Pure and deterministic: the same arguments give the same [`Observation`] bit for bit,
/// on any thread. Errors: an unknown key or a value outside its limits
/// ([`ExperimentError::UnknownParameter`], [`ExperimentError::BadValue`]) before anything
/// is simulated; a core refusal or step failure with the simulated time.
pub fn run_experiment(
    study: &crate::study::Study,
    experiment: ExperimentKind,
    values: &ParameterValues,
    mode: ModeName,
    seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let own_cache;
    let cache = match &options.templates {
        Some(c) => c.as_ref(),
        None => {
            own_cache = TemplateCache::new();
            &own_cache
        }
    };
    let inputs = setup::RunInputs::resolve(study, experiment, values, mode, cache)?;
    match experiment {
        ExperimentKind::Repose => repose::run(&inputs, seed, options),
        other => Err(ExperimentError::UnknownExperiment {
            name: other.name().to_owned(),
            expected: "repose".into(),
        }),
    }
}

/// Parses an experiment name (`repose`, `plate_drop`, `incline_slide`, `rolling`,
/// `compression`).
pub fn parse_experiment(name: &str) -> Result<ExperimentKind, ExperimentError> {
    ExperimentKind::ALL
        .into_iter()
        .find(|e| e.name() == name)
        .ok_or_else(|| ExperimentError::UnknownExperiment {
            name: name.to_owned(),
            expected: ExperimentKind::ALL.map(|e| e.name()).join(", "),
        })
}
