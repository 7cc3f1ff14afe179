//! The bench-bed rig (DESIGN §8, the bed `arachis pour` runs): pod spheres of radius 4 mm
//! inserted at random into a steel cylinder of radius 50 mm, falling and settling on its
//! floor; the responses are the bed height (the 95th percentile of the sphere tops) and the
//! height of the centre of mass, both in mm, and the kinetic energy left, J.
//!
//! Parameters: the six coefficients of the pod–pod and pod–steel pairs, named as in the pod
//! world's registry (`pod-pod.static_friction`, …) so that a study means the same thing by
//! them in every rig; a coefficient not given keeps its DESIGN §8 value. The pod and steel
//! materials are DESIGN §8's. Conditions: the particle count and the settling time, by
//! default the DESIGN figure's (2 000 spheres, 20 000 steps of 2e-5 s). Replicate r inserts
//! from the DESIGN seed + r. Fixed point: the same request gives the same bits.

use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{
    BenchBed, DEFAULT_SEED, DESIGN_PARTICLES, DESIGN_SETTLE_STEPS, TIMESTEP_S,
};
use arachis_core::scenario::materials::{POD_POD, POD_STEEL};
use arachis_core::scenario::measure::{bed_height_mm, com_height_mm};
use arachis_core::units::ENERGY_J_TO_MJ;
use serde_json::json;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::parameter::{diagnosis_parameters, Parameter, RigParameter};
use crate::arena::OwnedStorage;
use crate::calibration::{ParameterValues, Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "bench_bed";
/// The bed height response, mm.
pub const BED_HEIGHT: &str = "bed_height";
/// The centre-of-mass height response, mm.
pub const COM_HEIGHT: &str = "com_height";
/// The kinetic energy left at the end, J: whether the bed has settled (DESIGN §8 counts it
/// settled below `SETTLED_KINETIC_ENERGY_J`, 1e-6 J).
pub const KINETIC_ENERGY: &str = "kinetic_energy";
/// The particle-count condition (a count of spheres).
pub const PARTICLES: &str = "particles";
/// The settling-time condition, s: simulated time from insertion to measurement.
pub const SETTLE_TIME: &str = "settle_time_s";
/// Settling time of the DESIGN figure, s (20 000 steps of 2e-5 s).
pub const DESIGN_SETTLE_TIME_S: f64 = DESIGN_SETTLE_STEPS as f64 * TIMESTEP_S;

/// Finite-difference steps of the coefficients: about 5 % of their calibrated values, so a
/// bed of a few hundred spheres moves by much more than the fixed-point resolution (1 µm)
/// while the packing stays in the same regime.
const RESTITUTION_STEP: f64 = 0.02;
const FRICTION_STEP: f64 = 0.04;
const ROLLING_STEP: f64 = 0.015;

/// What a parameter of the bed sets: one coefficient of one pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PairCoefficient {
    /// The pair.
    pub pair: Pair,
    /// The coefficient.
    pub coefficient: Coefficient,
}

/// A contact pair of the bed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pair {
    /// Pod sphere on pod sphere.
    PodPod,
    /// Pod sphere on the steel floor or cylinder.
    PodSteel,
}

/// A coefficient of a pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coefficient {
    /// Coefficient of restitution e.
    Restitution,
    /// Static friction coefficient μs.
    StaticFriction,
    /// Rolling friction coefficient μr.
    RollingFriction,
}

/// The coefficient `coefficient` of `pair`, named `name`: dimensionless, its limits by its
/// kind, its DESIGN §8 value as its typical magnitude.
const fn coefficient(
    name: &'static str,
    label: &'static str,
    description: &'static str,
    pair: Pair,
    coefficient: Coefficient,
) -> Parameter<PairCoefficient> {
    let design = match pair {
        Pair::PodPod => POD_POD,
        Pair::PodSteel => POD_STEEL,
    };
    let (limits, fd_step, scale) = match coefficient {
        Coefficient::Restitution => (Limits::Restitution, RESTITUTION_STEP, design.restitution),
        Coefficient::StaticFriction => (Limits::Friction, FRICTION_STEP, design.friction),
        Coefficient::RollingFriction => (Limits::Friction, ROLLING_STEP, design.rolling_friction),
    };
    Parameter {
        name,
        label,
        description,
        unit: "-",
        sets: PairCoefficient { pair, coefficient },
        limits,
        fd_step,
        scale,
    }
}

/// The rig's parameters: the pod–pod and pod–steel coefficients.
pub const COEFFICIENTS: [Parameter<PairCoefficient>; 6] = [
    coefficient(
        "pod-pod.restitution",
        "e pod–pod",
        "pod–pod coefficient of restitution",
        Pair::PodPod,
        Coefficient::Restitution,
    ),
    coefficient(
        "pod-pod.static_friction",
        "μs pod–pod",
        "pod–pod static friction coefficient",
        Pair::PodPod,
        Coefficient::StaticFriction,
    ),
    coefficient(
        "pod-pod.rolling_friction",
        "μr pod–pod",
        "pod–pod rolling friction coefficient",
        Pair::PodPod,
        Coefficient::RollingFriction,
    ),
    coefficient(
        "pod-steel.restitution",
        "e pod–steel",
        "pod–steel coefficient of restitution",
        Pair::PodSteel,
        Coefficient::Restitution,
    ),
    coefficient(
        "pod-steel.static_friction",
        "μs pod–steel",
        "pod–steel static friction coefficient",
        Pair::PodSteel,
        Coefficient::StaticFriction,
    ),
    coefficient(
        "pod-steel.rolling_friction",
        "μr pod–steel",
        "pod–steel rolling friction coefficient",
        Pair::PodSteel,
        Coefficient::RollingFriction,
    ),
];

/// The rig's parameters, for a diagnosis and for a study's `[parameters]`.
pub const PARAMETERS: [RigParameter; 6] = diagnosis_parameters(&COEFFICIENTS);

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "pod spheres poured into a steel cylinder (bed height, DESIGN §8)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[
        Quantity {
            name: BED_HEIGHT,
            unit: "mm",
            label: "bed height (95th percentile of sphere tops), mm",
        },
        Quantity {
            name: COM_HEIGHT,
            unit: "mm",
            label: "centre-of-mass height, mm",
        },
        Quantity {
            name: KINETIC_ENERGY,
            unit: "J",
            label: "kinetic energy left, J",
        },
    ],
    conditions: &[
        ConditionKey::new(PARTICLES, "spheres poured", Limits::Positive),
        ConditionKey::new(SETTLE_TIME, "settling time, s", Limits::Positive),
    ],
    parameters: &PARAMETERS,
    build: |_, _| Ok(Box::new(BenchBedRig)),
};

/// One run's set-up: the bed, its steps and its pairs.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Setup {
    bed: BenchBed,
    steps: u64,
    pod_pod: PairSpec,
    pod_steel: PairSpec,
}

/// The bench-bed rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct BenchBedRig;

impl BenchBedRig {
    /// The set-up of `request`; an unknown parameter or condition, or a value outside its
    /// limits, is refused.
    fn setup(request: &RunRequest<'_>) -> Result<Setup, RigError> {
        let (pod_pod, pod_steel) = pairs(request.values)?;
        let mut particles = f64::from(DESIGN_PARTICLES);
        let mut settle_time_s = DESIGN_SETTLE_TIME_S;
        for (key, &value) in request.condition {
            let condition = KIND.condition(key).ok_or_else(|| {
                RigError(format!(
                    "the {NAME} rig takes the conditions {PARTICLES} and {SETTLE_TIME}, not \
                     '{key}'"
                ))
            })?;
            condition
                .check(value)
                .map_err(|why| RigError(format!("{key}: {why}")))?;
            match key.as_str() {
                PARTICLES => particles = value,
                _ => settle_time_s = value,
            }
        }
        if particles.fract() != 0.0 || particles > f64::from(BenchBed::max_particles()) {
            return Err(RigError(format!(
                "{PARTICLES} = {particles} must be a whole number of spheres, at most {} (the \
                 insertion region of DESIGN §8)",
                BenchBed::max_particles()
            )));
        }
        let steps = (settle_time_s / TIMESTEP_S).round();
        if steps < 1.0 {
            return Err(RigError(format!(
                "{SETTLE_TIME} = {settle_time_s} s is shorter than one step of {TIMESTEP_S} s"
            )));
        }
        Ok(Setup {
            bed: BenchBed {
                particles: particles as u32,
                seed: DEFAULT_SEED.wrapping_add(u64::from(request.replicate)),
            },
            steps: steps as u64,
            pod_pod,
            pod_steel,
        })
    }
}

/// The pod–pod and pod–steel pairs with `values` applied over DESIGN §8's.
pub(crate) fn pairs(values: &ParameterValues) -> Result<(PairSpec, PairSpec), RigError> {
    let (mut pod_pod, mut pod_steel) = (POD_POD, POD_STEEL);
    for (key, &value) in values {
        let Some(c) = COEFFICIENTS.iter().find(|c| c.name == key) else {
            let known: Vec<&str> = COEFFICIENTS.iter().map(|c| c.name).collect();
            return Err(RigError(format!(
                "the {NAME} rig has no parameter '{key}' (it has {})",
                known.join(", ")
            )));
        };
        c.limits
            .check(value)
            .map_err(|why| RigError(format!("{key}: {why}")))?;
        let pair = match c.sets.pair {
            Pair::PodPod => &mut pod_pod,
            Pair::PodSteel => &mut pod_steel,
        };
        match c.sets.coefficient {
            Coefficient::Restitution => pair.restitution = value,
            Coefficient::StaticFriction => pair.friction = value,
            Coefficient::RollingFriction => pair.rolling_friction = value,
        }
    }
    Ok((pod_pod, pod_steel))
}

fn core_error(e: impl std::fmt::Display) -> RigError {
    RigError(format!("the bench bed failed: {e}"))
}

impl Rig for BenchBedRig {
    fn id(&self) -> String {
        format!("arachis-bench-bed-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis bench bed (fixed-point core; pod spheres of radius 4 mm poured into a steel \
         cylinder of radius 50 mm, DESIGN §8)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let setup = Self::setup(request)?;
        let pair = |p: &PairSpec| json!([p.restitution, p.friction, p.rolling_friction]);
        Ok(json!({
            "rig": NAME,
            "particles": setup.bed.particles,
            "seed": setup.bed.seed,
            "steps": setup.steps,
            "dt_s": TIMESTEP_S,
            "pod_pod": pair(&setup.pod_pod),
            "pod_steel": pair(&setup.pod_steel),
        }))
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let setup = Self::setup(request)?;
        let mut arenas = OwnedStorage::<Fx>::new(setup.bed.storage_lengths());
        let mut world = setup.bed.build(arenas.storage()).map_err(core_error)?;
        BenchBed::set_pairs(&mut world, setup.pod_pod, setup.pod_steel).map_err(core_error)?;
        crate::stepping::run(&mut world, setup.steps).map_err(core_error)?;
        let mut scratch = vec![0.0; world.spheres().len()];
        let bed = bed_height_mm(&world, &mut scratch)
            .ok_or_else(|| RigError("the bed has no spheres to measure".to_owned()))?;
        let com = com_height_mm(&world)
            .ok_or_else(|| RigError("the bed has no bodies to measure".to_owned()))?;
        Ok(Responses::from([
            (BED_HEIGHT.to_owned(), bed),
            (COM_HEIGHT.to_owned(), com),
            (
                KINETIC_ENERGY.to_owned(),
                world.kinetic_energy_mj() / ENERGY_J_TO_MJ,
            ),
        ]))
    }
}
