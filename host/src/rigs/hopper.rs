//! The hopper rig: pod spheres of the bench bed (radius 4 mm) settle in a flat-bottomed steel
//! silo of radius 40 mm and run out through a circular orifice in its floor
//! (`arachis_core::scenario::hopper`). The response is the mass flow rate, g/s: the mass that
//! crosses the orifice plate between [`WINDOW_START_S`] and [`WINDOW_END_S`] after the
//! shutter opens, over that time. The condition that moves it is the orifice diameter, mm.
//!
//! Why this rig diagnoses: by Beverloo's law, W = C·ρ_b·√g·(D − k·d)^(5/2), the orifice
//! diameter D enters through the empty annulus k·d that particles cannot use. Friction and
//! rolling resistance change C and k a little; cohesion makes the particles hold on to each
//! other and to the rim, which chokes small orifices far more than large ones. So the shape of
//! W against D tells cohesion from friction where one diameter cannot.
//!
//! Parameters: the bench bed's six pair coefficients (`pod-pod.static_friction`, …, the same
//! names as in every rig) and three optional pod–pod effects, off unless set, with the pod
//! world's names: `pod-pod.cohesion_j_m3` (SJKR), `pod-pod.epsd_rolling_friction` and
//! `pod-pod.viscoelastic_time_s`. Replicate r inserts from seed [`BASE_SEED`] + r. Fixed point:
//! the same request gives the same bits.

use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{BenchBed, POD_MATERIAL, TIMESTEP_S};
use arachis_core::scenario::hopper::{
    discharged_mass_g, Hopper, MAX_ORIFICE_DIAMETER_UM, MIN_ORIFICE_DIAMETER_UM, SHUTTER_TRAVEL_S,
};
use serde_json::json;

use super::bench_bed::{self, PairCoefficient};
use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::parameter::{diagnosis_parameters_with_effects, Parameter, RigParameter};
use super::pod_world::parameters::{ParameterSpec, EFFECTS as POD_EFFECTS};
use crate::arena::OwnedStorage;
use crate::calibration::{Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "hopper";
/// The mass flow rate response, g/s.
pub const MASS_FLOW_RATE: &str = "mass_flow_rate";
/// The orifice-diameter condition, mm.
pub const ORIFICE_DIAMETER: &str = "orifice_diameter_mm";
/// The particle-count condition (a count of spheres).
pub const PARTICLES: &str = "particles";
/// Spheres in the silo unless a measurement says otherwise: a fill about 2.5 orifice
/// diameters high at the largest orifice searched, so the flow is steady over the window.
pub const DEFAULT_PARTICLES: u32 = 1200;
/// Seed of replicate 0's insertion.
pub const BASE_SEED: u64 = 0x5EED_4099;
/// Time from insertion to opening, s: the highest sphere, launched down at 0.2 m/s, falls
/// the 0.24 m of the insertion region in 0.2 s, and the fill comes to rest in the rest.
pub const SETTLE_TIME_S: f64 = 0.30;
/// Start of the measuring window after opening, s: the shutter has reached the catch floor
/// ([`SHUTTER_TRAVEL_S`]) and the flow has started.
pub const WINDOW_START_S: f64 = 0.10;
/// End of the measuring window after opening, s.
pub const WINDOW_END_S: f64 = 0.30;
/// Millimetres per metre and micrometres per millimetre.
const UM_PER_MM: f64 = 1.0e3;

/// What a parameter of the hopper sets.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Setting {
    /// A coefficient of the bench bed's pairs.
    Coefficient(PairCoefficient),
    /// An optional effect of the pod–pod pair.
    Effect(Effect),
}

/// An optional pod–pod effect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    /// SJKR cohesion energy density, J/m³.
    Cohesion,
    /// EPSD rolling friction coefficient.
    EpsdRolling,
    /// Viscoelastic relaxation time, s.
    Viscoelastic,
}

/// The bench bed's coefficient `c` as a hopper parameter.
const fn coefficient(c: &Parameter<PairCoefficient>) -> Parameter<Setting> {
    Parameter {
        name: c.name,
        label: c.label,
        description: c.description,
        unit: c.unit,
        sets: Setting::Coefficient(c.sets),
        limits: c.limits,
        fd_step: c.fd_step,
        scale: c.scale,
    }
}

/// The pod world's optional effect `p` as a hopper parameter setting `effect`.
const fn effect(p: &ParameterSpec, effect: Effect) -> Parameter<Setting> {
    Parameter {
        name: p.name,
        label: p.label,
        description: p.description,
        unit: p.unit,
        sets: Setting::Effect(effect),
        limits: p.limits,
        fd_step: p.fd_step,
        scale: p.scale,
    }
}

const C: &[Parameter<PairCoefficient>; 6] = &bench_bed::COEFFICIENTS;

/// The rig's calibratable parameters: the bench bed's pair coefficients.
pub const COEFFICIENTS: [Parameter<Setting>; 6] = [
    coefficient(&C[0]),
    coefficient(&C[1]),
    coefficient(&C[2]),
    coefficient(&C[3]),
    coefficient(&C[4]),
    coefficient(&C[5]),
];

/// The rig's optional effects, with the pod world's names and steps.
pub const EFFECTS: [Parameter<Setting>; 3] = [
    effect(&POD_EFFECTS[0], Effect::Cohesion),
    effect(&POD_EFFECTS[1], Effect::EpsdRolling),
    effect(&POD_EFFECTS[2], Effect::Viscoelastic),
];

/// The rig's parameters for a diagnosis: the coefficients, then the effects.
pub const PARAMETERS: [RigParameter; 9] =
    diagnosis_parameters_with_effects(&COEFFICIENTS, &EFFECTS);

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "pod spheres running out of a flat-bottomed silo through an orifice (mass flow rate)",
    world: WorldKind::Fixed,
    random: true,
    quantities: &[Quantity {
        name: MASS_FLOW_RATE,
        unit: "g/s",
        label: "mass flow rate, g/s",
    }],
    conditions: &[
        ConditionKey::new(ORIFICE_DIAMETER, "orifice diameter, mm", Limits::Positive).within(
            (
                MIN_ORIFICE_DIAMETER_UM as f64 / UM_PER_MM,
                MAX_ORIFICE_DIAMETER_UM as f64 / UM_PER_MM,
            ),
            (28.0, 60.0),
        ),
        ConditionKey::new(PARTICLES, "spheres in the silo", Limits::Positive),
    ],
    parameters: &PARAMETERS,
    build: |_, _| Ok(Box::new(HopperRig)),
};

/// One run's set-up.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Setup {
    hopper: Hopper,
    pod_pod: PairSpec,
    pod_steel: PairSpec,
    effects: EffectSpec,
}

/// The hopper rig (module notes).
#[derive(Debug, Clone, Copy, Default)]
pub struct HopperRig;

impl HopperRig {
    /// The set-up of `request`; an unknown parameter or condition, or a value outside its
    /// limits, is refused.
    fn setup(request: &RunRequest<'_>) -> Result<Setup, RigError> {
        let mut coefficients = crate::calibration::ParameterValues::new();
        let mut effects = EffectSpec::default();
        for (key, &value) in request.values {
            let Some(p) = COEFFICIENTS.iter().chain(&EFFECTS).find(|p| p.name == key) else {
                let known: Vec<&str> = COEFFICIENTS
                    .iter()
                    .chain(&EFFECTS)
                    .map(|p| p.name)
                    .collect();
                return Err(RigError(format!(
                    "the {NAME} rig has no parameter '{key}' (it has {})",
                    known.join(", ")
                )));
            };
            p.limits
                .check(value)
                .map_err(|why| RigError(format!("{key}: {why}")))?;
            match p.sets {
                Setting::Coefficient(_) => {
                    coefficients.insert(key.clone(), value);
                }
                Setting::Effect(Effect::Cohesion) => effects.cohesion_energy_density_j_m3 = value,
                Setting::Effect(Effect::EpsdRolling) => effects.epsd_rolling_friction = value,
                Setting::Effect(Effect::Viscoelastic) => effects.viscoelastic_time_s = value,
            }
        }
        let (pod_pod, pod_steel) = bench_bed::pairs(&coefficients)?;
        let mut particles = f64::from(DEFAULT_PARTICLES);
        let mut diameter_mm = None;
        for (key, &value) in request.condition {
            let condition = KIND.condition(key).ok_or_else(|| {
                RigError(format!(
                    "the {NAME} rig takes the conditions {ORIFICE_DIAMETER} and {PARTICLES}, \
                     not '{key}'"
                ))
            })?;
            condition
                .check(value)
                .map_err(|why| RigError(format!("{key}: {why}")))?;
            match key.as_str() {
                PARTICLES => particles = value,
                _ => diameter_mm = Some(value),
            }
        }
        let diameter_mm = diameter_mm.ok_or_else(|| {
            RigError(format!(
                "a {NAME} measurement must give {ORIFICE_DIAMETER} (the orifice's diameter, mm)"
            ))
        })?;
        if particles.fract() != 0.0 || particles > f64::from(Hopper::max_particles()) {
            return Err(RigError(format!(
                "{PARTICLES} = {particles} must be a whole number of spheres, at most {}",
                Hopper::max_particles()
            )));
        }
        Ok(Setup {
            hopper: Hopper {
                particles: particles as u32,
                seed: BASE_SEED.wrapping_add(u64::from(request.replicate)),
                orifice_diameter_um: (diameter_mm * UM_PER_MM).round() as i64,
            },
            pod_pod,
            pod_steel,
            effects,
        })
    }
}

fn core_error(e: impl std::fmt::Display) -> RigError {
    RigError(format!("the hopper failed: {e}"))
}

/// Steps of `seconds` at the bench bed's time step.
fn steps(seconds: f64) -> u64 {
    (seconds / TIMESTEP_S).round() as u64
}

impl Rig for HopperRig {
    fn id(&self) -> String {
        format!("arachis-hopper-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis hopper (fixed-point core; pod spheres of radius 4 mm running out of a steel \
         silo of radius 40 mm through an orifice plate)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let s = Self::setup(request)?;
        let pair = |p: &PairSpec| json!([p.restitution, p.friction, p.rolling_friction]);
        let mut spec = json!({
            "rig": NAME,
            "particles": s.hopper.particles,
            "seed": s.hopper.seed,
            "orifice_diameter_um": s.hopper.orifice_diameter_um,
            "dt_s": TIMESTEP_S,
            "settle_time_s": SETTLE_TIME_S,
            "window_s": [WINDOW_START_S, WINDOW_END_S],
            "pod_pod": pair(&s.pod_pod),
            "pod_steel": pair(&s.pod_steel),
        });
        if s.effects != EffectSpec::default() {
            spec["pod_pod_effects"] = json!([
                s.effects.cohesion_energy_density_j_m3,
                s.effects.epsd_rolling_friction,
                s.effects.viscoelastic_time_s
            ]);
        }
        Ok(spec)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let s = Self::setup(request)?;
        let mut lengths = s.hopper.storage_lengths();
        if s.effects.needs_history() {
            lengths = lengths.with_effects();
        }
        let mut arenas = OwnedStorage::<Fx>::new(lengths);
        let mut world = s.hopper.build(arenas.storage()).map_err(core_error)?;
        BenchBed::set_pairs(&mut world, s.pod_pod, s.pod_steel).map_err(core_error)?;
        if s.effects != EffectSpec::default() {
            world
                .set_pair_effects(POD_MATERIAL, POD_MATERIAL, s.effects)
                .map_err(core_error)?;
        }
        let run = |world: &mut World<'_, Fx>, seconds: f64| {
            crate::stepping::run(world, steps(seconds)).map_err(core_error)
        };
        run(&mut world, SETTLE_TIME_S)?;
        Hopper::open(&mut world).map_err(core_error)?;
        run(&mut world, SHUTTER_TRAVEL_S)?;
        Hopper::catch(&mut world).map_err(core_error)?;
        run(&mut world, WINDOW_START_S - SHUTTER_TRAVEL_S)?;
        let before = discharged_mass_g(&world);
        run(&mut world, WINDOW_END_S - WINDOW_START_S)?;
        let after = discharged_mass_g(&world);
        Ok(Responses::from([(
            MASS_FLOW_RATE.to_owned(),
            (after - before) / (WINDOW_END_S - WINDOW_START_S),
        )]))
    }
}
