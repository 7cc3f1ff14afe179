//! What the rigs of pod spheres in bulk share (the [`super::hopper`], the [`super::drum`]
//! and the [`super::bulk_density`] pour): their parameters — the bench bed's six pair coefficients
//! (`pod-pod.static_friction`, …, the same names as in every rig) and three optional pod–pod
//! effects, off unless set, with the pod world's names and finite-difference steps
//! (`pod-pod.cohesion_j_m3`, SJKR; `pod-pod.epsd_rolling_friction`;
//! `pod-pod.viscoelastic_time_s`) — how a run's values become the core's pairs, and how a
//! request names its spheres and its one condition ([`Declared`]).
//!
//! ```
//! use arachis::calibration::ParameterValues;
//! use arachis::rigs::sphere_bulk::Values;
//! let values = ParameterValues::from([("pod-pod.cohesion_j_m3".to_owned(), 2.0e4)]);
//! let v = Values::of("hopper", &values).unwrap();
//! assert_eq!(v.effects.cohesion_energy_density_j_m3, 2.0e4);
//! assert_eq!(v.pod_pod.friction, 0.854); // DESIGN §8's, not given
//! ```

use arachis_core::body::StorageLengths;
use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{BenchBed, POD_MATERIAL, TIMESTEP_S};
use serde_json::json;

use super::bench_bed::{self, PairCoefficient};
use super::kind::RigKind;
use super::parameter::{diagnosis_parameters_with_effects, Parameter, RigParameter};
use super::pod_world::parameters::{ParameterSpec, EFFECTS as POD_EFFECTS};
use crate::calibration::{ParameterValues, RigError, RunRequest};

/// The particle-count condition of every bulk rig (a count of spheres).
pub const PARTICLES: &str = "particles";
/// Micrometres per millimetre: the rigs take lengths in mm, the scenarios in µm.
pub const UM_PER_MM: f64 = 1.0e3;

/// What a parameter of a sphere-bulk rig sets.
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

/// The bench bed's coefficient `c` as a sphere-bulk parameter.
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

/// The pod world's optional effect `p` as a sphere-bulk parameter setting `effect`, with the
/// finite-difference step `fd_step` of a bulk rig.
const fn effect(p: &ParameterSpec, effect: Effect, fd_step: f64) -> Parameter<Setting> {
    Parameter {
        name: p.name,
        label: p.label,
        description: p.description,
        unit: p.unit,
        sets: Setting::Effect(effect),
        limits: p.limits,
        fd_step,
        scale: p.scale,
    }
}

const C: &[Parameter<PairCoefficient>; 6] = &bench_bed::COEFFICIENTS;

/// The calibratable parameters: the bench bed's pair coefficients.
pub const COEFFICIENTS: [Parameter<Setting>; 6] = [
    coefficient(&C[0]),
    coefficient(&C[1]),
    coefficient(&C[2]),
    coefficient(&C[3]),
    coefficient(&C[4]),
    coefficient(&C[5]),
];

/// The optional effects, with the pod world's names and steps.
pub const EFFECTS: [Parameter<Setting>; 3] = [
    effect(&POD_EFFECTS[0], Effect::Cohesion, COHESION_STEP_J_M3),
    effect(&POD_EFFECTS[1], Effect::EpsdRolling, EPSD_STEP),
    effect(&POD_EFFECTS[2], Effect::Viscoelastic, VISCOELASTIC_STEP_S),
];

/// Finite-difference steps of the effects on a bulk rig, larger than on one pod: a bed's
/// response to an effect must stand above the scatter between placements. Measured on
/// smooth spheres (μs 0.3, μr 0.02; 2026-11-27, one placement each): cohesion 2e4 J/m³
/// raises the drum's angle by 3–4° (placement SD about 0.7°) and cuts the hopper's rate at
/// 40 mm by 11 %; EPSD rolling 0.05 raises the drum's angle by 1.5–2°; viscoelastic damping
/// of 1e-5 s moves neither beyond its scatter.
pub const COHESION_STEP_J_M3: f64 = 2.0e4;
/// EPSD rolling friction step (see [`COHESION_STEP_J_M3`]).
pub const EPSD_STEP: f64 = 0.05;
/// Viscoelastic relaxation-time step, s (see [`COHESION_STEP_J_M3`]).
pub const VISCOELASTIC_STEP_S: f64 = 1.0e-5;

/// The parameters for a diagnosis: the coefficients, then the effects.
pub const PARAMETERS: [RigParameter; 9] =
    diagnosis_parameters_with_effects(&COEFFICIENTS, &EFFECTS);

/// A run's parameter values as the core takes them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Values {
    /// The pod–pod pair.
    pub pod_pod: PairSpec,
    /// The pod–steel pair.
    pub pod_steel: PairSpec,
    /// The pod–pod pair's optional effects.
    pub effects: EffectSpec,
}

impl Values {
    /// The values of `values` over DESIGN §8's, for the rig named `rig` (in messages); an
    /// unknown parameter or a value outside its limits is refused.
    pub fn of(rig: &str, values: &ParameterValues) -> Result<Self, RigError> {
        let mut coefficients = ParameterValues::new();
        let mut effects = EffectSpec::default();
        for (key, &value) in values {
            let Some(p) = COEFFICIENTS.iter().chain(&EFFECTS).find(|p| p.name == key) else {
                let known: Vec<&str> = COEFFICIENTS
                    .iter()
                    .chain(&EFFECTS)
                    .map(|p| p.name)
                    .collect();
                return Err(RigError(format!(
                    "the {rig} rig has no parameter '{key}' (it has {})",
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
        Ok(Values {
            pod_pod,
            pod_steel,
            effects,
        })
    }

    /// Whether an optional effect is on.
    fn any_effect(&self) -> bool {
        self.effects != EffectSpec::default()
    }

    /// `lengths` with room for the effects' contact history when they keep one.
    pub fn storage_lengths(&self, lengths: StorageLengths) -> StorageLengths {
        if self.effects.needs_history() {
            lengths.with_effects()
        } else {
            lengths
        }
    }

    /// Set the pairs and effects in a world built with the bench bed's materials.
    pub fn apply(&self, world: &mut World<'_, Fx>) -> Result<(), String> {
        BenchBed::set_pairs(world, self.pod_pod, self.pod_steel).map_err(|e| e.to_string())?;
        if self.any_effect() {
            world
                .set_pair_effects(POD_MATERIAL, POD_MATERIAL, self.effects)
                .map_err(|e| e.to_string())?;
        }
        Ok(())
    }

    /// The values as a run specification's entries: the pairs' coefficients, and the effects
    /// only when one is on (so a specification without effects keeps its hash).
    pub fn specification(&self, spec: &mut serde_json::Value) {
        let pair = |p: &PairSpec| json!([p.restitution, p.friction, p.rolling_friction]);
        spec["pod_pod"] = pair(&self.pod_pod);
        spec["pod_steel"] = pair(&self.pod_steel);
        if self.any_effect() {
            spec["pod_pod_effects"] = json!([
                self.effects.cohesion_energy_density_j_m3,
                self.effects.epsd_rolling_friction,
                self.effects.viscoelastic_time_s
            ]);
        }
    }
}

/// What a bulk rig declares of its requests: its catalogue entry, its one condition (whose
/// key a measurement must give), and its spheres.
#[derive(Debug, Clone, Copy)]
pub struct Declared {
    /// The rig in the catalogue (name and conditions).
    pub kind: &'static RigKind,
    /// The key of the rig's own condition.
    pub condition: &'static str,
    /// What that condition is, with its unit, for the message when it is missing.
    pub condition_about: &'static str,
    /// Spheres unless a request's [`PARTICLES`] says otherwise.
    pub default_particles: u32,
    /// Fewest spheres the rig can measure with.
    pub min_particles: fn() -> u32,
    /// Most spheres the rig's scenario can insert.
    pub max_particles: fn() -> u32,
    /// Seed of replicate 0's insertion; replicate r inserts from this + r.
    pub base_seed: u64,
}

/// A bulk rig's request, read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Read {
    /// The parameter values.
    pub values: Values,
    /// Spheres to insert.
    pub particles: u32,
    /// The value of the rig's own condition.
    pub condition: f64,
    /// The insertion seed of the replicate.
    pub seed: u64,
}

impl Declared {
    /// `request` read: values as [`Values::of`], conditions by the catalogue entry; an
    /// unknown condition, a value outside its limits, a missing own condition or a particle
    /// count that is not a whole number the scenario can insert is refused.
    pub fn read(&self, request: &RunRequest<'_>) -> Result<Read, RigError> {
        let name = self.kind.name;
        let values = Values::of(name, request.values)?;
        let mut particles = f64::from(self.default_particles);
        let mut condition = None;
        for (key, &value) in request.condition {
            let known = self.kind.condition(key).ok_or_else(|| {
                RigError(format!(
                    "the {name} rig takes the conditions {} and {PARTICLES}, not '{key}'",
                    self.condition
                ))
            })?;
            known
                .check(value)
                .map_err(|why| RigError(format!("{key}: {why}")))?;
            match key.as_str() {
                PARTICLES => particles = value,
                _ => condition = Some(value),
            }
        }
        let condition = condition.ok_or_else(|| {
            RigError(format!(
                "a {name} measurement must give {} ({})",
                self.condition, self.condition_about
            ))
        })?;
        let (min, max) = ((self.min_particles)(), (self.max_particles)());
        if particles.fract() != 0.0 || !(f64::from(min)..=f64::from(max)).contains(&particles) {
            return Err(RigError(format!(
                "{PARTICLES} = {particles} must be a whole number of spheres, {min} to {max}"
            )));
        }
        Ok(Read {
            values,
            particles: particles as u32,
            condition,
            seed: self.base_seed.wrapping_add(u64::from(request.replicate)),
        })
    }

    /// A core failure of this rig, in words.
    pub fn failed(&self, e: impl std::fmt::Display) -> RigError {
        RigError(format!("the {} failed: {e}", self.kind.name))
    }

    /// Step `world` through `seconds` (rounded to whole steps of the bench bed's time step)
    /// on the host's threads.
    pub fn run_for(&self, world: &mut World<'_, Fx>, seconds: f64) -> Result<(), RigError> {
        let steps = (seconds / TIMESTEP_S).round() as u64;
        crate::stepping::run(world, steps).map_err(|e| self.failed(e))
    }
}
