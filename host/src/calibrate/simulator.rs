//! The simulator interface of the calibration: one fully specified run in, one observed
//! response out.
//!
//! The calibration never calls a physics engine directly. It asks a [`Simulator`] for the
//! response of each [`RunSpec`], so the same workflow runs the repose DEM experiment
//! (`crate::experiments`, issue 4 §2a) or, in tests, a cheap deterministic stand-in
//! ([`super::surrogate::Seed000Surrogate`]). A simulator must be a pure function of the
//! spec: the run cache stores results under the spec's hash and replays them on resume.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::study::parameters::{Owner, REGISTRY};
use crate::study::RunSpec;

/// What one run observed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RunResult {
    /// The response in the target quantity's unit (the repose angle, degrees).
    pub response: f64,
}

/// A simulator failure, in words.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct SimulationError(pub String);

/// Something that turns a run specification into an observed response.
pub trait Simulator: Sync {
    /// A stable identifier of the simulator and its version. It is stored with every cached
    /// run, so results of another simulator are never replayed, and printed in the report.
    fn id(&self) -> String;

    /// One sentence for the report: what this simulator is.
    fn description(&self) -> String;

    /// Simulates `spec` and returns its response. Must be deterministic in `spec`.
    fn simulate(&self, spec: &RunSpec) -> Result<RunResult, SimulationError>;

    /// Draws the simulated pile of `spec` into `dir` and returns the picture's path, when
    /// the simulator can (the default cannot).
    fn pile_picture(&self, spec: &RunSpec, dir: &Path) -> Result<Option<PathBuf>, SimulationError> {
        let _ = (spec, dir);
        Ok(None)
    }
}

/// Every registered parameter's value in `spec` (registry name → value in the parameter's
/// unit, SI), read from the spec's materials and pairs; parameters whose material or pair
/// the spec lacks are left out.
pub fn parameter_values(spec: &RunSpec) -> BTreeMap<String, f64> {
    REGISTRY
        .iter()
        .filter_map(|p| {
            let value = match p.owner {
                Owner::Material(m) => spec.materials.get(m).and_then(|mat| match p.property {
                    "poisson" => Some(mat.poisson),
                    "shear_modulus_pa" => Some(mat.shear_modulus_pa),
                    "density_kg_m3" => Some(mat.density_kg_m3),
                    _ => None,
                }),
                Owner::Pair(pair) => spec.pairs.get(pair).and_then(|v| match p.property {
                    "restitution" => Some(v.restitution),
                    "static_friction" => Some(v.static_friction),
                    "rolling_friction" => Some(v.rolling_friction),
                    _ => None,
                }),
            }?;
            Some((p.name.to_owned(), value))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::{Experiment, Study};

    #[test]
    fn values_are_the_runs_settings_and_the_held_values() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../testdata/peanut-pods-saline/study.toml"
        );
        let study = Study::load(Path::new(path)).unwrap();
        let set = BTreeMap::from([("pod-pod.static_friction".to_owned(), 0.854)]);
        let spec = study
            .run_spec(Experiment::Repose, &BTreeMap::new(), &set, "quick")
            .unwrap();
        let v = parameter_values(&spec);
        assert_eq!(v.len(), REGISTRY.len());
        assert_eq!(v["pod-pod.static_friction"], 0.854);
        // Seed 000 §3.4's held values: the study's values or the ranges' centres.
        assert_eq!(v["pod.poisson"], 0.386);
        assert_eq!(v["pod-steel.static_friction"], 0.589);
        assert!((v["pod-pod.restitution"] - 0.340).abs() < 1e-12);
    }
}
