//! The pod bench rigs behind the engine's [`Rig`] interface: the repose angle by cylinder
//! lifting ([`super::repose_cylinder`], seed 000 §2.7), sliding on a tilting plate
//! ([`super::incline`], §2.6.2) and compression between two plates
//! ([`super::compression`], §2.5.3), each over a [`PodWorld`] in one run mode.
//! [`run_pod_test`] runs one of them directly (the `simulate` command).
//!
//! A run's specification is the study's full [`RunSpec`] with the run's values applied and
//! the placement seed advanced by the replicate, so every pile is named by what makes it.
//! Filled pod templates are shared by all runs (one [`TemplateCache`]), which changes
//! nothing computed, only the time spent filling. The rig id carries the crate version:
//! cached runs of another build are not replayed across a version bump.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use super::kind::{ConditionKey, Quantity, RigKind, RigOptions, WorldKind, Worlds};
use super::parameter::{diagnosis_parameters_with_effects, RigParameter};
use super::pod_world::observation::ReposeDetails;
use super::pod_world::parameters::{Owner, EFFECTS};
use super::pod_world::run_spec::RunPair;
use super::pod_world::setup::RunInputs;
use super::pod_world::{
    check_values, Experiment, ExperimentError, ModeName, Observation, ObservationDetails,
    ParameterValues, PodWorld, RunOptions, RunSpec, TemplateCache, REGISTRY,
};
use super::repose_picture::write_pile_picture;
use crate::calibration::{Condition, Responses, Rig, RigError, RunRequest, SpecHash};
use crate::limits::Limits;

/// File name of the simulated pile's picture in the figures folder (SVG: it carries the
/// caption, which a PNG cannot, see `experiments::picture`).
pub const PILE_PICTURE: &str = "pile_simulated.svg";

/// A pod bench test: its experiment and the function that runs it.
#[derive(Debug, Clone, Copy)]
pub struct PodTest {
    /// The experiment.
    pub experiment: Experiment,
    /// Runs it on resolved inputs with a placement seed.
    pub run: fn(&RunInputs, u64, &RunOptions) -> Result<Observation, ExperimentError>,
}

/// A test that is measurable but not simulated yet.
fn not_built(inputs: &RunInputs, _: u64, _: &RunOptions) -> Result<Observation, ExperimentError> {
    Err(ExperimentError::NotBuilt {
        experiment: inputs.spec.experiment.name(),
    })
}

/// The plate drop's test (not built yet).
pub const PLATE_DROP_TEST: PodTest = PodTest {
    experiment: Experiment::PlateDrop,
    run: not_built,
};

/// The rolling test (not built yet).
pub const ROLLING_TEST: PodTest = PodTest {
    experiment: Experiment::Rolling,
    run: not_built,
};

/// Runs `test` over `world` at `condition` with the parameters in `values` (registry
/// keys → SI values, overriding the world's held values), in `mode`, with placement seed
/// `seed`.
///
/// Pure and deterministic: the same arguments give the same [`Observation`] bit for bit,
/// on any thread. Errors: an unknown key or a value outside its limits
/// ([`ExperimentError::UnknownParameter`], [`ExperimentError::BadValue`]) before anything
/// is simulated; a core refusal or step failure with the simulated time.
pub fn run_pod_test(
    world: &PodWorld<'_>,
    test: PodTest,
    condition: &Condition,
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
    let inputs = RunInputs::resolve(world, test.experiment, condition, values, mode, cache)?;
    (test.run)(&inputs, seed, options)
}

/// Water content, wet basis (seed 000 §2.1: 36.72 %): a condition of every pod rig.
pub const MOISTURE: ConditionKey = ConditionKey::new(
    "moisture_pct",
    "water content, % wet basis",
    Limits::NonNegative,
);

/// The pod rigs' parameters for a diagnosis: the registry's (seed 000 Table 3's x1…x8) as
/// base parameters, then the pod world's optional effects ([`EFFECTS`]) as candidates.
pub const PARAMETERS: [RigParameter; REGISTRY.len() + EFFECTS.len()] =
    diagnosis_parameters_with_effects(&REGISTRY, &EFFECTS);

/// Builds the pod bench rig of `test` over a study's pod world.
pub fn build<'a>(
    worlds: &Worlds<'a>,
    options: &RigOptions,
    test: PodTest,
) -> Result<Box<dyn Rig + 'a>, RigError> {
    let experiment = test.experiment;
    let world = worlds.pods.ok_or_else(|| {
        RigError(format!(
            "the {experiment} rig simulates pods: the study needs [materials], [pods], [pairs], \
             [plan.modes] and [plan.simulation]"
        ))
    })?;
    Ok(Box::new(PodBenchRig::new(
        world,
        test,
        options.mode.unwrap_or(ModeName::Quick),
    )))
}

/// The drop on the 45° plate (restitution, seed 000 §2.6.1): measurable, not yet simulated.
pub const PLATE_DROP: RigKind = RigKind {
    name: "plate_drop",
    about: "pod dropped on the 45° steel plate (restitution, seed 000 §2.6.1; not built yet)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: "restitution",
            unit: "-",
            label: "restitution, -",
        },
        Quantity {
            name: "rebound_distance",
            unit: "mm",
            label: "rebound distance, mm",
        },
    ],
    conditions: &[
        ConditionKey::new("drop_height_mm", "drop height, mm", Limits::Positive),
        ConditionKey::new("plate_angle_deg", "plate angle, degrees", Limits::Positive),
        MOISTURE,
    ],
    parameters: &PARAMETERS,
    build: |w, o| build(w, o, PLATE_DROP_TEST),
};

/// Rolling on an incline then a flat (rolling friction, seed 000 §2.6.3): measurable, not
/// yet simulated.
pub const ROLLING: RigKind = RigKind {
    name: "rolling",
    about: "pod rolled down an incline onto a flat (rolling friction, seed 000 §2.6.3; not \
            built yet)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: "rolling_distance",
            unit: "mm",
            label: "rolling distance, mm",
        },
        Quantity {
            name: "rolling_friction",
            unit: "-",
            label: "rolling friction, -",
        },
    ],
    conditions: &[
        ConditionKey::new("slope_deg", "slope, degrees", Limits::Positive),
        ConditionKey::new("release_height_mm", "release height, mm", Limits::Positive),
        MOISTURE,
    ],
    parameters: &PARAMETERS,
    build: |w, o| build(w, o, ROLLING_TEST),
};

/// One pod bench rig of a world, in one run mode.
pub struct PodBenchRig<'a> {
    world: PodWorld<'a>,
    test: PodTest,
    mode: ModeName,
    templates: Arc<TemplateCache>,
    /// Repose details of the runs simulated in this process, for the pile picture.
    details: Mutex<BTreeMap<SpecHash, ReposeDetails>>,
}

impl<'a> PodBenchRig<'a> {
    /// The rig of `test` over `world` in `mode`.
    pub fn new(world: PodWorld<'a>, test: PodTest, mode: ModeName) -> Self {
        Self {
            world,
            test,
            mode,
            templates: Arc::new(TemplateCache::new()),
            details: Mutex::new(BTreeMap::new()),
        }
    }

    /// The full specification of `request`.
    pub fn run_spec(&self, request: &RunRequest<'_>) -> Result<RunSpec, RigError> {
        check_values(&self.world, request.values).map_err(|e| RigError(e.to_string()))?;
        let mut spec = self
            .world
            .run_spec(
                self.test.experiment,
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
        run_pod_test(
            &self.world,
            self.test,
            &spec.condition,
            &parameter_values(spec),
            self.mode,
            spec.simulation.random_seed,
            &options,
        )
        .map_err(|e| RigError(e.to_string()))
    }
}

/// Every registered parameter's value in `spec` (registry name → value in the parameter's
/// unit, SI), read from the spec's materials and pairs, and every optional effect that is on
/// (an effect at 0 is off, as if not given); parameters whose material or pair the spec
/// lacks are left out. Fed back to [`RunInputs::resolve`], they specify the same run: a run
/// is simulated from what its specification says, so it can never differ from its cache
/// entry.
pub fn parameter_values(spec: &RunSpec) -> BTreeMap<String, f64> {
    let always = REGISTRY.iter().map(|p| (p, false));
    let effects = EFFECTS.iter().map(|p| (p, true));
    always
        .chain(effects)
        .filter_map(|(p, effect)| {
            let value = match p.sets.owner {
                Owner::Material(m) => spec.materials.get(m).and_then(|mat| match p.sets.property {
                    "poisson" => Some(mat.poisson),
                    "shear_modulus_pa" => Some(mat.shear_modulus_pa),
                    "density_kg_m3" => Some(mat.density_kg_m3),
                    _ => None,
                }),
                Owner::Pair(pair) => spec
                    .pairs
                    .get(pair)
                    .and_then(|v| pair_property(v, p.sets.property)),
            }?;
            // An effect at 0 is off: the run without it.
            (!(effect && value == 0.0)).then(|| (p.name.to_owned(), value))
        })
        .collect()
}

/// The value of a pair's coefficient or effect named `property` in a run spec.
fn pair_property(pair: &RunPair, property: &str) -> Option<f64> {
    match property {
        "restitution" => Some(pair.restitution),
        "static_friction" => Some(pair.static_friction),
        "rolling_friction" => Some(pair.rolling_friction),
        "cohesion_j_m3" => Some(pair.cohesion_j_m3),
        "epsd_rolling_friction" => Some(pair.epsd_rolling_friction),
        "viscoelastic_time_s" => Some(pair.viscoelastic_time_s),
        _ => None,
    }
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
        ObservationDetails::PodBulkDensity(d) => {
            out.insert(super::pod_bulk_density::BED_LEVEL.into(), d.level_mm);
        }
        ObservationDetails::PodHopper(d) => {
            out.insert(
                super::pod_hopper::DISCHARGED_FRACTION.into(),
                d.discharged_fraction,
            );
        }
        ObservationDetails::Repose(_) | ObservationDetails::PodDrum(_) => {}
    }
    out
}

impl Rig for PodBenchRig<'_> {
    fn id(&self) -> String {
        format!("arachis-dem-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        let what = match self.test.experiment {
            Experiment::Repose => "repose by cylinder lifting, seed 000 §2.7",
            Experiment::InclineSlide => "sliding on a tilting plate, seed 000 §2.6.2",
            Experiment::Compression => "compression between two plates, seed 000 §2.5.3",
            Experiment::PlateDrop => "drop on the 45° plate, seed 000 §2.6.1",
            Experiment::Rolling => "rolling on an incline, seed 000 §2.6.3",
            Experiment::PodBulkDensity => "poured bulk density",
            Experiment::PodDrum => "rotating drum",
            Experiment::PodHopper => "discharge through an orifice",
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
        if self.test.experiment != Experiment::Repose {
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
