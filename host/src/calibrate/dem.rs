//! The repose DEM experiment as the calibration's simulator: each [`RunSpec`] becomes one
//! `experiments::run_experiment` call (cylinder lifting, seed 000 §2.7) with every
//! registered parameter at the spec's value, the spec's mode, and the spec's random seed as
//! the pod-placement seed. Filled pod templates are shared by all runs (one
//! [`TemplateCache`]), which changes nothing computed, only the time spent filling.
//!
//! The simulator id carries the crate version: cached runs of another build of Arachis are
//! not replayed across a version bump (within one version, the run cache trusts that equal
//! specs give equal piles, which the experiments module guarantees bit for bit).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::simulator::{parameter_values, RunResult, SimulationError, Simulator};
use crate::experiments::picture::write_pile_picture;
use crate::experiments::repose::ReposeDetails;
use crate::experiments::{
    run_experiment, ModeName, Observation, ObservationDetails, RunOptions, TemplateCache,
};
use crate::study::{RunSpec, SpecHash, Study};

/// File name of the simulated pile's picture in the figures folder (SVG: it carries the
/// caption, which a PNG cannot, see `experiments::picture`).
pub const PILE_PICTURE: &str = "pile_simulated.svg";

/// The DEM rigs of `crate::experiments`, answering calibration runs of `study`.
pub struct DemExperiment<'a> {
    study: &'a Study,
    templates: Arc<TemplateCache>,
    /// Repose details of the runs simulated in this process, for the pile picture.
    details: Mutex<BTreeMap<SpecHash, ReposeDetails>>,
}

impl<'a> DemExperiment<'a> {
    /// A simulator for runs of `study`.
    pub fn new(study: &'a Study) -> Self {
        Self {
            study,
            templates: Arc::new(TemplateCache::new()),
            details: Mutex::new(BTreeMap::new()),
        }
    }

    /// The mode name whose settings the spec carries.
    fn mode(&self, spec: &RunSpec) -> Result<ModeName, SimulationError> {
        let name = self
            .study
            .file()
            .plan
            .modes
            .iter()
            .find(|(_, m)| **m == spec.mode)
            .map(|(n, _)| n.clone())
            .ok_or_else(|| {
                SimulationError(format!("no study mode has the settings {:?}", spec.mode))
            })?;
        name.parse::<ModeName>()
            .map_err(|e| SimulationError(e.to_string()))
    }

    fn observe(&self, spec: &RunSpec) -> Result<Observation, SimulationError> {
        let options = RunOptions {
            vtk_dir: None,
            templates: Some(Arc::clone(&self.templates)),
        };
        run_experiment(
            self.study,
            spec.experiment,
            &parameter_values(spec),
            self.mode(spec)?,
            spec.simulation.random_seed,
            &options,
        )
        .map_err(|e| SimulationError(e.to_string()))
    }
}

impl Simulator for DemExperiment<'_> {
    fn id(&self) -> String {
        format!("arachis-dem-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis DEM virtual bench experiment (fixed-point core; repose by cylinder lifting, \
         seed 000 §2.7)"
            .to_owned()
    }

    fn simulate(&self, spec: &RunSpec) -> Result<RunResult, SimulationError> {
        let observation = self.observe(spec)?;
        let details = repose_details(observation.details)?;
        self.details
            .lock()
            .map_err(|_| SimulationError("a simulation thread panicked".into()))?
            .insert(spec.spec_hash(), details);
        Ok(RunResult {
            response: observation.value,
        })
    }

    fn pile_picture(&self, spec: &RunSpec, dir: &Path) -> Result<Option<PathBuf>, SimulationError> {
        let hash = spec.spec_hash();
        let known = self
            .details
            .lock()
            .map_err(|_| SimulationError("a simulation thread panicked".into()))?
            .get(&hash)
            .cloned();
        // A run replayed from the cache has no pile in memory: simulate it again (the same
        // spec gives the same pile, bit for bit).
        let details = match known {
            Some(d) => d,
            None => repose_details(self.observe(spec)?.details)?,
        };
        let path = dir.join(PILE_PICTURE);
        let title = format!("simulated pile at the optimum (spec {hash})");
        write_pile_picture(&path, &details, &title)
            .map_err(|e| SimulationError(format!("{e:#}")))?;
        Ok(Some(path))
    }
}

/// The pile of a repose observation; the calibration target is the repose angle, so any other
/// rig here is a wiring error, reported rather than ignored.
fn repose_details(details: ObservationDetails) -> Result<ReposeDetails, SimulationError> {
    match details {
        ObservationDetails::Repose(d) => Ok(d),
        _ => Err(SimulationError(
            "the calibration target must be the repose experiment".into(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::Experiment;

    fn study() -> Study {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../testdata/peanut-pods-saline/study.toml"
        );
        Study::load(Path::new(path)).unwrap()
    }

    #[test]
    fn the_spec_names_its_mode_and_an_unknown_one_is_an_error() {
        let study = study();
        let dem = DemExperiment::new(&study);
        let none = BTreeMap::new();
        for (name, mode) in [("quick", ModeName::Quick), ("full", ModeName::Full)] {
            let spec = study
                .run_spec(Experiment::Repose, &none, &none, name)
                .unwrap();
            assert_eq!(dem.mode(&spec).unwrap(), mode);
        }
        let mut spec = study
            .run_spec(Experiment::Repose, &none, &none, "quick")
            .unwrap();
        spec.mode.pods += 1;
        assert!(dem.mode(&spec).unwrap_err().0.contains("no study mode"));
    }
}
