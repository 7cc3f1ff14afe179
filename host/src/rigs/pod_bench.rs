//! The pod bench rigs of seed 000 as calibration rigs: the repose angle by cylinder lifting
//! (§2.7), sliding on a tilting plate (§2.6.2) and compression between two plates (§2.5.3),
//! each a virtual experiment of `crate::experiments` over a pod study's materials, pods,
//! pairs, run mode and simulation settings.
//!
//! A run's specification is the study's full [`RunSpec`] with the run's values applied and
//! the placement seed advanced by the replicate, so every pile is named by what makes it.
//! Filled pod templates are shared by all runs (one [`TemplateCache`]), which changes
//! nothing computed, only the time spent filling. The rig id carries the crate version:
//! cached runs of another build are not replayed across a version bump.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use crate::calibration::{Responses, Rig, RigError, RunRequest, SpecHash};
use crate::experiments::picture::write_pile_picture;
use crate::experiments::repose::ReposeDetails;
use crate::experiments::{
    run_experiment, ModeName, Observation, ObservationDetails, RunOptions, TemplateCache,
};
use crate::study::parameters::{Owner, REGISTRY};
use crate::study::{Experiment, RunSpec, Study};

/// File name of the simulated pile's picture in the figures folder (SVG: it carries the
/// caption, which a PNG cannot, see `experiments::picture`).
pub const PILE_PICTURE: &str = "pile_simulated.svg";

/// One pod bench rig of a study, in one run mode.
pub struct PodBenchRig<'a> {
    study: &'a Study,
    experiment: Experiment,
    mode: ModeName,
    templates: Arc<TemplateCache>,
    /// Repose details of the runs simulated in this process, for the pile picture.
    details: Mutex<BTreeMap<SpecHash, ReposeDetails>>,
}

impl<'a> PodBenchRig<'a> {
    /// The rig of `experiment` over `study` in `mode`.
    pub fn new(study: &'a Study, experiment: Experiment, mode: ModeName) -> Self {
        Self {
            study,
            experiment,
            mode,
            templates: Arc::new(TemplateCache::new()),
            details: Mutex::new(BTreeMap::new()),
        }
    }

    /// The full specification of `request`.
    pub fn run_spec(&self, request: &RunRequest<'_>) -> Result<RunSpec, RigError> {
        crate::experiments::check_values(self.study, request.values)
            .map_err(|e| RigError(e.to_string()))?;
        let mut spec = self
            .study
            .run_spec(
                self.experiment,
                request.condition,
                request.values,
                self.mode.as_str(),
            )
            .map_err(RigError)?;
        spec.simulation.random_seed = spec
            .simulation
            .random_seed
            .wrapping_add(u64::from(request.replicate));
        Ok(spec)
    }

    fn observe(&self, spec: &RunSpec) -> Result<Observation, RigError> {
        let options = RunOptions {
            vtk_dir: None,
            templates: Some(Arc::clone(&self.templates)),
        };
        run_experiment(
            self.study,
            spec.experiment,
            &parameter_values(spec),
            self.mode,
            spec.simulation.random_seed,
            &options,
        )
        .map_err(|e| RigError(e.to_string()))
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

/// The observation's responses: its quantity and the other quantities its details carry.
fn responses(observation: &Observation) -> Responses {
    let mut out = Responses::from([(observation.quantity.to_owned(), observation.value)]);
    match &observation.details {
        ObservationDetails::InclineSlide(d) => {
            out.insert("static_friction".into(), d.static_friction);
        }
        ObservationDetails::Compression(d) => {
            out.insert("peak_force".into(), d.peak_force_n);
        }
        ObservationDetails::Repose(_) => {}
    }
    out
}

impl Rig for PodBenchRig<'_> {
    fn id(&self) -> String {
        format!("arachis-dem-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        let what = match self.experiment {
            Experiment::Repose => "repose by cylinder lifting, seed 000 §2.7",
            Experiment::InclineSlide => "sliding on a tilting plate, seed 000 §2.6.2",
            Experiment::Compression => "compression between two plates, seed 000 §2.5.3",
            Experiment::PlateDrop => "drop on the 45° plate, seed 000 §2.6.1",
            Experiment::Rolling => "rolling on an incline, seed 000 §2.6.3",
        };
        format!("Arachis DEM virtual bench experiment (fixed-point core; {what})")
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let spec = self.run_spec(request)?;
        Ok(serde_json::to_value(spec).expect("a run spec serialises"))
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let spec = self.run_spec(request)?;
        let observation = self.observe(&spec)?;
        if let ObservationDetails::Repose(details) = &observation.details {
            self.details
                .lock()
                .map_err(|_| RigError("a simulation thread panicked".into()))?
                .insert(spec.spec_hash(), details.clone());
        }
        Ok(responses(&observation))
    }

    fn picture(&self, request: &RunRequest<'_>, dir: &Path) -> Result<Option<PathBuf>, RigError> {
        if self.experiment != Experiment::Repose {
            return Ok(None);
        }
        let spec = self.run_spec(request)?;
        let hash = spec.spec_hash();
        let known = self
            .details
            .lock()
            .map_err(|_| RigError("a simulation thread panicked".into()))?
            .get(&hash)
            .cloned();
        // A run replayed from the cache has no pile in memory: simulate it again (the same
        // spec gives the same pile, bit for bit).
        let details = match known {
            Some(d) => d,
            None => match self.observe(&spec)?.details {
                ObservationDetails::Repose(d) => d,
                _ => return Err(RigError("the repose rig observed no pile".into())),
            },
        };
        let path = dir.join(PILE_PICTURE);
        let title = format!("simulated pile at the optimum (spec {hash})");
        write_pile_picture(&path, &details, &title).map_err(|e| RigError(format!("{e:#}")))?;
        Ok(Some(path))
    }
}
