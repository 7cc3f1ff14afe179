//! What the five cheap rigs of the diagnosis loop share (rebound, press, fall, unload, roll,
//! one file each): one pod sphere (R 4 mm, seed 000 §3.1 pod
//! material with the calibrated Young's modulus) and, where needed, a steel floor, simulated
//! by the fixed-point core in a few hundred to a few thousand steps.
//!
//! | rig | condition | observable | responds to |
//! |---|---|---|---|
//! | `rebound` | drop height, m (impact speed √(2gh)) | rebound/impact speed ratio, - | restitution, viscoelastic |
//! | `press` | static load on the sphere, N | resting overlap on the floor, µm | Young's modulus, cohesion |
//! | `fall` | drop height, m | free-fall time, ms | drag |
//! | `unload` | peak load, N | resting overlap after unloading to half the peak, µm | Young's modulus, cohesion, hysteretic |
//! | `roll` | launch speed, m/s | speed after 0.2 s of rolling / launch speed, - | EPSD rolling resistance, drag |
//!
//! The rebound run starts at first touch with the impact speed (the free flight before it is
//! not simulated); the press run applies the load as a body force (gravity scaled to F/m) and
//! lets the sphere settle with constant-e damping (e fixed at [`PRESS_SETTLING_RESTITUTION`],
//! the press is quasi-static, so e does not enter the result); the fall run has no floor.
//! The unload run starts, like the press, at rest at the Hertz overlap of the peak load (the
//! contact's peak overlap α_max), then settles under half that load: elastically it rests at
//! 2^{-2/3} of the peak overlap, with a plastic fraction λ on the unloading curve of
//! [`arachis_core::contact::HystereticNormal`] at λ·α_max + (1 − λ)·2^{-2/3}·α_max — the
//! load–unload loop of a compression test (seed 001), the one cheap experiment that sees
//! hysteresis apart from restitution.

use arachis_core::effects::{EffectSpec, AIR_DENSITY_20C_KG_M3};
use arachis_core::prelude::*;
use serde::{Deserialize, Serialize};
use serde_json::json;

use super::kind::{BuildRig, ConditionKey, Quantity, RigKind, WorldKind};
use super::parameter::{RigParameter, Role};
use crate::arena::OwnedStorage;
use crate::calibration::{ParameterValues, Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// Sphere radius, m.
pub const SPHERE_RADIUS_M: f64 = 0.004;
/// Pod density, kg/m³ (seed 000 §3.1).
pub const POD_DENSITY_KG_M3: f64 = 582.36;
/// Pod Poisson's ratio (seed 000 §3.1).
pub const POD_POISSON: f64 = 0.386;
/// Standard gravity, m/s².
pub const GRAVITY_M_S2: f64 = 9.806_65;
/// Step limit guarding every run.
pub const MAX_STEPS: u64 = 2_000_000;

/// Steel (DESIGN §8) for the floor.
pub const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};

/// Every parameter the single-sphere rigs read (SI units in the names): the base
/// parameters a calibration sets and the optional effects, off at 0. The
/// `[diagnosis.calibration]` table of a study is this.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelParams {
    /// Pod–steel coefficient of restitution e ∈ (0, 1] (seed 000 eq. (4)).
    pub restitution: f64,
    /// Pod Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
    /// Effect: viscoelastic relaxation time A, s (0 = off).
    #[serde(default)]
    pub viscoelastic_time_s: f64,
    /// Effect: SJKR cohesion energy density k, J/m³ (0 = off).
    #[serde(default)]
    pub cohesion_j_m3: f64,
    /// Effect: air-drag coefficient Cd (0 = off).
    #[serde(default)]
    pub drag_coefficient: f64,
    /// Effect: hysteretic normal contact, plastic fraction λ ∈ [0, 1) (0 = off). Not written
    /// when 0, so study files from before the effect existed are reproduced byte for byte.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub plastic_fraction: f64,
    /// Effect: EPSD rolling resistance, rolling friction coefficient μr (0 = off; Ai et al.
    /// 2011 type C without its dashpot, the limit torque μr·R*·Fn of LIGGGHTS' `epsd2`). Not
    /// written when 0, as `plastic_fraction`.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub epsd_rolling_friction: f64,
}

/// serde helper: skip an effect parameter that is off.
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// The parameters with their roles and finite-difference steps: the base parameters first,
/// then the candidate effects (they map onto the core's [`arachis_core::effects`]); the
/// rolling effects last ([`ROLLING_EFFECTS`]).
pub const PARAMETERS: [RigParameter; 7] = [
    RigParameter {
        name: "restitution",
        key: "restitution",
        unit: "-",
        role: Role::Base,
        fd_step: 0.01,
        scale: 0.5,
        limits: Limits::Restitution,
        about: "pod-steel coefficient of restitution (constant-e damping, seed 000 eq. 4)",
    },
    RigParameter {
        name: "youngs_modulus",
        key: "youngs_modulus_pa",
        unit: "Pa",
        role: Role::Base,
        fd_step: 2.0e5,
        scale: 1.0e7,
        limits: Limits::Positive,
        about: "pod Young's modulus (Hertz stiffness, seed 000 eq. 3)",
    },
    RigParameter {
        name: "viscoelastic",
        key: "viscoelastic_time_s",
        unit: "s",
        role: Role::Effect,
        fd_step: 2.0e-6,
        scale: 1.0e-5,
        limits: Limits::NonNegative,
        about: "viscoelastic damping, restitution falls with impact speed (Brilliantov 1996)",
    },
    RigParameter {
        name: "cohesion",
        key: "cohesion_j_m3",
        unit: "J/m^3",
        role: Role::Effect,
        fd_step: 2.0e3,
        scale: 1.0e4,
        limits: Limits::NonNegative,
        about: "SJKR cohesion, attraction k x contact area (LIGGGHTS sjkr)",
    },
    RigParameter {
        name: "drag",
        key: "drag_coefficient",
        unit: "-",
        role: Role::Effect,
        fd_step: 0.05,
        scale: 0.5,
        limits: Limits::NonNegative,
        about: "air drag coefficient Cd, F = -0.5 rho Cd A |v| v",
    },
    RigParameter {
        name: "hysteretic",
        key: "plastic_fraction",
        unit: "-",
        role: Role::Effect,
        fd_step: 0.02,
        scale: 0.1,
        limits: Limits::FractionBelowOne,
        about: "hysteretic (plastic) normal contact, plastic fraction of the peak overlap (Walton & Braun 1986)",
    },
    RigParameter {
        name: "epsd_rolling",
        key: "epsd_rolling_friction",
        unit: "-",
        role: Role::Effect,
        fd_step: 0.002,
        scale: 0.02,
        limits: Limits::NonNegative,
        about: "EPSD rolling resistance, torque limit mu_r R* Fn (Ai et al. 2011; LIGGGHTS epsd2)",
    },
];

/// How many effects at the end of [`PARAMETERS`] act only on a turning sphere.
pub const ROLLING_EFFECTS: usize = 1;

/// The parameters that can act in a rig whose sphere does not turn (rebound, press, fall,
/// unload): all but the rolling effects. A diagnosis offers as candidates only the effects
/// its rigs declare, so a study without a rolling experiment is not offered rolling
/// resistance.
pub const PARAMETERS_WITHOUT_ROLLING: &[RigParameter] =
    PARAMETERS.split_at(PARAMETERS.len() - ROLLING_EFFECTS).0;

impl ModelParams {
    /// The value of the parameter keyed `key`.
    pub fn get(&self, key: &str) -> Option<f64> {
        Some(match key {
            "restitution" => self.restitution,
            "youngs_modulus_pa" => self.youngs_modulus_pa,
            "viscoelastic_time_s" => self.viscoelastic_time_s,
            "cohesion_j_m3" => self.cohesion_j_m3,
            "drag_coefficient" => self.drag_coefficient,
            "plastic_fraction" => self.plastic_fraction,
            "epsd_rolling_friction" => self.epsd_rolling_friction,
            _ => return None,
        })
    }

    /// Every parameter by key.
    pub fn values(&self) -> ParameterValues {
        PARAMETERS
            .iter()
            .map(|p| (p.key.to_owned(), self.get(p.key).unwrap_or(0.0)))
            .collect()
    }

    /// The parameters `values` sets: the base ones must be given, an effect left out is
    /// off; an unknown key is an error.
    pub fn from_values(values: &ParameterValues) -> Result<Self, RigError> {
        if let Some(key) = values
            .keys()
            .find(|k| PARAMETERS.iter().all(|p| p.key != *k))
        {
            let known: Vec<&str> = PARAMETERS.iter().map(|p| p.key).collect();
            return Err(RigError(format!(
                "the single-sphere rigs have no parameter '{key}' (they have {})",
                known.join(", ")
            )));
        }
        let get = |key: &str| values.get(key).copied();
        let base = |key: &str| {
            get(key).ok_or_else(|| RigError(format!("the single-sphere rigs need {key}")))
        };
        let p = Self {
            restitution: base("restitution")?,
            youngs_modulus_pa: base("youngs_modulus_pa")?,
            viscoelastic_time_s: get("viscoelastic_time_s").unwrap_or(0.0),
            cohesion_j_m3: get("cohesion_j_m3").unwrap_or(0.0),
            drag_coefficient: get("drag_coefficient").unwrap_or(0.0),
            plastic_fraction: get("plastic_fraction").unwrap_or(0.0),
            epsd_rolling_friction: get("epsd_rolling_friction").unwrap_or(0.0),
        };
        p.validate().map_err(RigError)?;
        Ok(p)
    }

    /// Checks ranges: e ∈ (0, 1], E > 0, effects ≥ 0 and λ < 1, all finite.
    pub fn validate(&self) -> Result<(), String> {
        for p in &PARAMETERS {
            let v = self.get(p.key).unwrap_or(0.0);
            if !v.is_finite() {
                return Err(format!("{} = {v} is not a finite number", p.name));
            }
            if p.role == Role::Effect && v < 0.0 {
                return Err(format!(
                    "effect {} = {v} {} must be >= 0 (0 is off)",
                    p.name, p.unit
                ));
            }
        }
        if !(self.restitution > 0.0 && self.restitution <= 1.0) {
            return Err(format!(
                "restitution = {} must be in (0, 1]",
                self.restitution
            ));
        }
        if self.plastic_fraction >= 1.0 {
            return Err(format!(
                "hysteretic = {} must be < 1",
                self.plastic_fraction
            ));
        }
        if self.youngs_modulus_pa <= 0.0 {
            return Err(format!(
                "youngs_modulus = {} Pa must be > 0",
                self.youngs_modulus_pa
            ));
        }
        Ok(())
    }
}
/// The pod sphere's material with the calibrated Young's modulus of `p`.
pub fn pod(p: &ModelParams) -> MaterialSpec {
    MaterialSpec {
        youngs_modulus_pa: p.youngs_modulus_pa,
        poisson: POD_POISSON,
        density_kg_m3: POD_DENSITY_KG_M3,
    }
}

/// The pod sphere's mass, kg.
pub fn mass_kg() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * SPHERE_RADIUS_M.powi(3) * POD_DENSITY_KG_M3
}

/// The pod–steel effective modulus E*, Pa (DESIGN §2).
pub fn e_star_pa(p: &ModelParams) -> f64 {
    let part = |m: &MaterialSpec| (1.0 - m.poisson * m.poisson) / m.youngs_modulus_pa;
    1.0 / (part(&pod(p)) + part(&STEEL))
}

/// Storage for the one-sphere worlds of these experiments.
pub fn one_sphere_arena() -> OwnedStorage<Fx> {
    OwnedStorage::new(StorageLengths::for_spheres(1, 1).with_effects())
}

/// Core errors (set-up or step) as rig errors with their message.
pub fn core_err(e: impl std::fmt::Display) -> RigError {
    RigError(format!("core: {e}"))
}

/// A pod sphere over a steel floor (z = 0), normal terms only, effects from `p`; the sphere
/// at height `z_m` (m) moving at `vz_m_s` (m/s) along z.
pub fn floor_world<'a>(
    a: &'a mut OwnedStorage<Fx>,
    p: &ModelParams,
    restitution: f64,
    z_m: f64,
    vz_m_s: f64,
) -> Result<World<'a, Fx>, RigError> {
    let launch = Launch {
        z_m,
        velocity_m_s: [0.0, 0.0, vz_m_s],
        spin_rad_s: [0.0; 3],
    };
    floor_world_with(a, p, restitution, None, launch)
}

/// Where and how the sphere of a floor world starts.
#[derive(Debug, Clone, Copy)]
pub struct Launch {
    /// Centre height, m.
    pub z_m: f64,
    /// Velocity, m/s.
    pub velocity_m_s: [f64; 3],
    /// Angular velocity, rad/s.
    pub spin_rad_s: [f64; 3],
}

/// A pod sphere over a steel floor (z = 0), effects from `p`: normal terms only when
/// `friction` is `None`, else with Mindlin's tangential spring and damping and the Coulomb
/// limit at that static friction coefficient (no CDT rolling friction either way).
pub fn floor_world_with<'a>(
    a: &'a mut OwnedStorage<Fx>,
    p: &ModelParams,
    restitution: f64,
    friction: Option<f64>,
    launch: Launch,
) -> Result<World<'a, Fx>, RigError> {
    let mut w = World::new(a.storage()).map_err(core_err)?;
    let pod_id = w.add_material(pod(p)).map_err(core_err)?;
    let steel = w.add_material(STEEL).map_err(core_err)?;
    let tangential = friction.is_some();
    let spec = PairSpec {
        restitution,
        friction: friction.unwrap_or(0.0),
        rolling_friction: 0.0,
        conventions: arachis_core::contact::Conventions::EDEM,
        terms: TermSwitches {
            mindlin_tangential: tangential,
            tangential_damping: tangential,
            coulomb_limit: tangential,
            rolling_cdt: false,
            ..TermSwitches::ALL
        },
    };
    w.set_pair(pod_id, steel, spec).map_err(core_err)?;
    w.set_pair_effects(
        pod_id,
        steel,
        EffectSpec {
            viscoelastic_time_s: p.viscoelastic_time_s,
            cohesion_energy_density_j_m3: p.cohesion_j_m3,
            plastic_fraction: p.plastic_fraction,
            // LIGGGHTS' `epsd2` has no dashpot; Ai et al.'s η_r is left at 0 to match it.
            epsd_rolling_friction: p.epsd_rolling_friction,
            ..EffectSpec::default()
        },
    )
    .map_err(core_err)?;
    w.set_air_drag(AIR_DENSITY_20C_KG_M3, p.drag_coefficient)
        .map_err(core_err)?;
    w.add_wall(WallSpec::fixed(
        WallGeometry::Plane {
            point_m: [0.0; 3],
            normal: [0.0, 0.0, 1.0],
        },
        steel,
    ))
    .map_err(core_err)?;
    let mut s = SphereSpec::at_rest(pod_id, SPHERE_RADIUS_M, [0.0, 0.0, launch.z_m]);
    s.velocity_m_s = launch.velocity_m_s;
    s.angular_velocity_rad_s = launch.spin_rad_s;
    w.add_sphere(s).map_err(core_err)?;
    Ok(w)
}

/// The Hertz overlap of the pod sphere on the floor under `load_n` (N), m:
/// α = (3F/(4E*√R))^{2/3} (Johnson 1985, §4.2).
pub fn hertz_overlap_m(p: &ModelParams, load_n: f64) -> f64 {
    (3.0 * load_n / (4.0 * e_star_pa(p) * SPHERE_RADIUS_M.sqrt())).powf(2.0 / 3.0)
}

/// The period of small normal oscillations of the pod sphere resting on the floor at overlap
/// `alpha_m` (m), s: 2π√(m/k) with the tangent stiffness k = 2E*a, a = √(Rα).
pub fn resting_period_s(p: &ModelParams, alpha_m: f64) -> f64 {
    let k = 2.0 * e_star_pa(p) * (SPHERE_RADIUS_M * alpha_m).sqrt();
    2.0 * std::f64::consts::PI * (mass_kg() / k).sqrt()
}

/// Hertz contact duration, s: t_c = 2.868·(m²/(R·E*²·v))^{1/5} (Johnson 1985, §11.1).
pub fn hertz_contact_time_s(p: &ModelParams, v: f64) -> f64 {
    let m = mass_kg();
    let es = e_star_pa(p);
    2.868 * (m * m / (SPHERE_RADIUS_M * es * es * v)).powf(0.2)
}

/// One cheap test of a pod sphere (one rig file each).
#[derive(Debug, Clone, Copy)]
pub struct SingleSphereTest {
    /// The rig's name.
    pub name: &'static str,
    /// What it measures, in words.
    pub about: &'static str,
    /// The quantity.
    pub quantity: Quantity,
    /// The condition it is measured at (one number).
    pub condition: ConditionKey,
    /// The parameters that can act in it ([`PARAMETERS`] or
    /// [`PARAMETERS_WITHOUT_ROLLING`]); it reads all of [`ModelParams`].
    pub parameters: &'static [RigParameter],
    /// Simulates the quantity at a condition.
    pub simulate: fn(f64, &ModelParams) -> Result<f64, RigError>,
}

impl SingleSphereTest {
    /// The catalogue entry of this test's rig, which `build` builds (each rig file passes a
    /// builder naming its own test: a builder is a plain function and cannot carry it).
    pub const fn kind(&'static self, build: BuildRig) -> RigKind {
        RigKind {
            name: self.name,
            about: self.about,
            world: WorldKind::Fixed,
            random: false,
            quantities: std::slice::from_ref(&self.quantity),
            conditions: std::slice::from_ref(&self.condition),
            parameters: self.parameters,
            build,
        }
    }

    /// Simulates the quantity at `condition` with parameters `p`, after checking both.
    pub fn observe(&self, condition: f64, p: &ModelParams) -> Result<f64, RigError> {
        self.condition
            .check(condition)
            .map_err(|e| RigError(format!("{} condition: {e}", self.name)))?;
        p.validate().map_err(RigError)?;
        (self.simulate)(condition, p)
            .map_err(|e| RigError(format!("simulating {} at {condition}: {e}", self.name)))
    }
}

/// A single-sphere test as a rig: the condition's one value in, the quantity out.
/// Deterministic (no random placement): a replicate is the same run.
#[derive(Debug, Clone, Copy)]
pub struct SingleSphereRig {
    /// The test.
    pub test: &'static SingleSphereTest,
}

impl SingleSphereRig {
    /// The condition's value in `request`.
    fn condition(&self, request: &RunRequest<'_>) -> Result<f64, RigError> {
        let key = self.test.condition.key;
        if let Some(other) = request.condition.keys().find(|k| *k != key) {
            return Err(RigError(format!(
                "the {} rig takes the condition {key}, not '{other}'",
                self.test.name
            )));
        }
        request.condition.get(key).copied().ok_or_else(|| {
            RigError(format!(
                "a {} run needs its condition {key} ({})",
                self.test.name, self.test.condition.label
            ))
        })
    }
}

impl Rig for SingleSphereRig {
    fn id(&self) -> String {
        format!("arachis-single-sphere-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        format!(
            "Arachis single pod sphere on a steel floor (fixed-point core; {})",
            self.test.about
        )
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        let condition = self.condition(request)?;
        let p = ModelParams::from_values(request.values)?;
        let mut spec = json!({ "rig": self.test.name, "parameters": p.values() });
        spec[self.test.condition.key] = json!(condition);
        Ok(spec)
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        let condition = self.condition(request)?;
        let p = ModelParams::from_values(request.values)?;
        let value = self.test.observe(condition, &p)?;
        Ok(Responses::from([(
            self.test.quantity.name.to_owned(),
            value,
        )]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> ModelParams {
        ModelParams {
            restitution: 0.5,
            youngs_modulus_pa: 8.43e6,
            viscoelastic_time_s: 0.0,
            cohesion_j_m3: 0.0,
            drag_coefficient: 0.0,
            plastic_fraction: 0.0,
            epsd_rolling_friction: 0.0,
        }
    }

    #[test]
    fn observables_match_theory_with_effects_off() {
        let p = base();
        // Free fall in vacuum: t = √(2h/g); kick–drift error below one step (0.05 ms).
        let t = super::super::fall::TEST.observe(1.0, &p).unwrap();
        let theory = (2.0 / GRAVITY_M_S2).sqrt() * 1e3;
        assert!((t - theory).abs() < 0.06, "{t} vs {theory}");
        // Hertz overlap under load: α = (3F/(4E*√R))^{2/3}, within 0.5 %.
        let f = 0.01;
        let alpha = super::super::press::TEST.observe(f, &p).unwrap();
        let theory =
            (3.0 * f / (4.0 * e_star_pa(&p) * SPHERE_RADIUS_M.sqrt())).powf(2.0 / 3.0) * 1e6;
        assert!((alpha / theory - 1.0).abs() < 5e-3, "{alpha} vs {theory}");
        // Restitution is speed-independent without effects (within 1 %; the clip of the
        // attractive damping force raises the effective e a little, core tests/restitution).
        let e1 = super::super::rebound::TEST.observe(0.05, &p).unwrap();
        let e2 = super::super::rebound::TEST.observe(1.0, &p).unwrap();
        assert!(
            (e1 - e2).abs() < 0.01 && (e1 - 0.55).abs() < 0.02,
            "{e1} {e2}"
        );
    }

    #[test]
    fn unload_rests_on_the_hysteretic_unloading_curve() {
        // Peak load F: α_max = (3F/(4E*√R))^{2/3}. Under F/2 the sphere rests where
        // F/2 = F·((α − λα_max)/((1 − λ)α_max))^{3/2}, α = λα_max + (1 − λ)·2^{-2/3}·α_max;
        // within 0.5 % for λ = 0 (elastic) and λ = 0.3.
        let f = 0.01;
        let peak =
            (3.0 * f / (4.0 * e_star_pa(&base()) * SPHERE_RADIUS_M.sqrt())).powf(2.0 / 3.0) * 1e6;
        for lambda in [0.0, 0.3] {
            let p = ModelParams {
                plastic_fraction: lambda,
                ..base()
            };
            let alpha = super::super::unload::TEST.observe(f, &p).unwrap();
            let theory = peak
                * (lambda + (1.0 - lambda) * super::super::unload::UNLOAD_FRACTION.powf(2.0 / 3.0));
            assert!(
                (alpha / theory - 1.0).abs() < 5e-3,
                "λ {lambda}: {alpha} vs {theory} um"
            );
        }
    }

    #[test]
    fn only_the_rolling_effects_are_left_out_of_the_non_rolling_rigs() {
        let left_out = &PARAMETERS[PARAMETERS_WITHOUT_ROLLING.len()..];
        let names: Vec<&str> = left_out.iter().map(|p| p.name).collect();
        assert_eq!(names, ["epsd_rolling"]);
    }

    #[test]
    fn bad_conditions_are_refused() {
        assert!(super::super::fall::TEST.observe(-1.0, &base()).is_err());
        assert!(super::super::press::TEST
            .observe(f64::NAN, &base())
            .is_err());
    }
}
