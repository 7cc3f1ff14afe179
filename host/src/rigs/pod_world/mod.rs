//! A pod world: what the pod bench rigs simulate — materials, pods of a shape mix, contact
//! pairs, the ranges a study varies, run modes and simulation settings — and everything
//! those rigs share: the full specification of a run ([`run_spec::RunSpec`]), the
//! resolution of a run's values into core materials and pairs ([`setup`]), filled pod
//! templates ([`templates`]), VTK frames ([`frames`]) and the parameter registry
//! ([`parameters`]).
//!
//! A study's `[materials]`, `[pods]`, `[pairs]`, `[parameters]` and `[plan.modes]`,
//! `[plan.simulation]` sections are this world ([`PodWorld`] borrows them). The rigs
//! themselves (repose by cylinder lifting, incline, compression) are one file each in
//! `crate::rigs`.

pub mod error;
pub mod experiment;
pub mod frames;
pub mod observation;
pub mod parameters;
pub mod run_spec;
pub mod sections;
pub mod settings;
pub mod setup;
pub mod templates;
pub mod values;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

pub use error::ExperimentError;
pub use experiment::Experiment;
pub use observation::{Observation, ObservationDetails, RunOptions};
pub use parameters::{ParameterRange, ParameterSpec, REGISTRY};
pub use run_spec::RunSpec;
pub use sections::{Material, Pair, Particles, Pods, Spheres};
pub use settings::{Mode, Simulation};
pub use templates::TemplateCache;
pub use values::{check_values, parse_assignment, ModeName, ParameterValues};

use parameters::Owner;

/// The pod world of a study (module notes): borrowed sections, and the folder that scanned
/// STL paths are relative to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PodWorld<'a> {
    /// `[materials.<name>]`.
    pub materials: &'a BTreeMap<String, Material>,
    /// `[pods]` or `[spheres]`.
    pub particles: Particles<'a>,
    /// `[pairs."<a>-<b>"]`.
    pub pairs: &'a BTreeMap<String, Pair>,
    /// `[parameters."<name>"]`: what a calibration varies and over which ranges.
    pub parameters: &'a BTreeMap<String, ParameterRange>,
    /// `[plan.modes.<name>]`.
    pub modes: &'a BTreeMap<String, Mode>,
    /// `[plan.simulation]`.
    pub simulation: &'a Simulation,
    /// The study file's folder.
    pub dir: &'a Path,
}

/// A parameter the world varies, with its range and report label.
#[derive(Debug, Clone, PartialEq)]
pub struct Varied<'a> {
    /// The registry entry.
    pub spec: &'static ParameterSpec,
    /// The range in the study.
    pub range: &'a ParameterRange,
    /// The report label (the study's, else the registry's).
    pub label: String,
}

impl<'a> PodWorld<'a> {
    /// The varied parameters, in registry order (seed 000 Table 3's x1…x8).
    pub fn varied(&self) -> Vec<Varied<'a>> {
        REGISTRY
            .iter()
            .filter_map(|spec| {
                self.parameters.get(spec.name).map(|range| Varied {
                    spec,
                    range,
                    label: range.label.clone().unwrap_or_else(|| spec.label.to_owned()),
                })
            })
            .collect()
    }

    /// The value the world gives for `spec` in its material or pair, if any.
    pub fn base_value(&self, spec: &ParameterSpec) -> Option<f64> {
        match spec.sets.owner {
            Owner::Material(m) => self
                .materials
                .get(m)
                .and_then(|mat| match spec.sets.property {
                    "poisson" => Some(mat.poisson),
                    "shear_modulus_pa" => Some(mat.shear_modulus_pa),
                    "density_kg_m3" => Some(mat.density_kg_m3),
                    _ => None,
                }),
            Owner::Pair(p) => self
                .pairs
                .get(p)
                .and_then(|pair| pair.property(spec.sets.property)),
        }
    }

    /// The value held when `spec` is not being varied: the world's value, else the centre
    /// of its range (seed 000 §3.4 holds x1, x2, x6–x8 at their ranges' centres). `None`
    /// when the world has neither (the parameter's owner is absent).
    pub fn held_value(&self, spec: &ParameterSpec) -> Option<f64> {
        self.base_value(spec)
            .or_else(|| self.parameters.get(spec.name).map(ParameterRange::centre))
    }

    /// Scanned STL paths, resolved against the study file's folder.
    pub fn stl_paths(&self) -> Vec<(&'static str, PathBuf)> {
        let Particles::Pods(pods) = self.particles else {
            return Vec::new();
        };
        pods.stl
            .entries()
            .into_iter()
            .map(|(shape, p)| (shape, self.dir.join(p)))
            .collect()
    }
}

/// Parses an experiment name (`repose`, `plate_drop`, `incline_slide`, `rolling`,
/// `compression`).
pub fn parse_experiment(name: &str) -> Result<Experiment, ExperimentError> {
    Experiment::ALL
        .into_iter()
        .find(|e| e.name() == name)
        .ok_or_else(|| ExperimentError::UnknownExperiment {
            name: name.to_owned(),
            expected: Experiment::ALL.map(|e| e.name()).join(", "),
        })
}
