//! The cheap experiments of the diagnosis loop: one pod sphere (R 4 mm, seed 000 §3.1 pod
//! material with the calibrated Young's modulus) and, where needed, a steel floor, simulated
//! by the fixed-point core in a few hundred to a few thousand steps.
//!
//! | kind | condition | observable | responds to |
//! |---|---|---|---|
//! | `rebound` | drop height, m (impact speed √(2gh)) | rebound/impact speed ratio, - | restitution, viscoelastic |
//! | `press` | static load on the sphere, N | resting overlap on the floor, µm | Young's modulus, cohesion |
//! | `fall` | drop height, m | free-fall time, ms | drag |
//! | `unload` | peak load, N | resting overlap after unloading to half the peak, µm | Young's modulus, cohesion, hysteretic |
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

use anyhow::{bail, Context, Result};
use arachis_core::effects::{EffectSpec, AIR_DENSITY_20C_KG_M3};
use arachis_core::prelude::*;
use serde::{Deserialize, Serialize};

use super::params::ModelParams;
use crate::arena::OwnedStorage;

/// Sphere radius, m.
pub const SPHERE_RADIUS_M: f64 = 0.004;
/// Pod density, kg/m³ (seed 000 §3.1).
pub const POD_DENSITY_KG_M3: f64 = 582.36;
/// Pod Poisson's ratio (seed 000 §3.1).
pub const POD_POISSON: f64 = 0.386;
/// Standard gravity, m/s².
pub const GRAVITY_M_S2: f64 = 9.806_65;
/// Restitution used only to settle the press test (quasi-static: it does not change the
/// resting overlap, only how fast the sphere gets there).
pub const PRESS_SETTLING_RESTITUTION: f64 = 0.2;
/// Time steps per Hertz contact duration in the rebound run.
const REBOUND_STEPS_PER_CONTACT: f64 = 100.0;
/// Time steps per small-oscillation period in the press run, and periods simulated.
const PRESS_STEPS_PER_PERIOD: f64 = 30.0;
const PRESS_PERIODS: f64 = 25.0;
/// The unload run's final load as a fraction of its peak.
pub const UNLOAD_FRACTION: f64 = 0.5;
/// Time step of the fall run, s (below the Rayleigh bound of the pod sphere, 7.5e-5 s).
const FALL_DT_S: f64 = 5.0e-5;
/// Step limit guarding every run.
const MAX_STEPS: u64 = 2_000_000;

/// Steel (DESIGN §8) for the floor.
const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};

/// Experiment kinds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExperimentKind {
    /// Drop-and-rebound: condition drop height (m), observable rebound/impact speed ratio.
    Rebound,
    /// Static press: condition load (N), observable resting overlap (µm).
    Press,
    /// Free fall: condition height (m), observable fall time (ms).
    Fall,
    /// Load then unload to half: condition peak load (N), observable resting overlap (µm).
    Unload,
}

impl ExperimentKind {
    /// All kinds.
    pub const ALL: [ExperimentKind; 4] = [Self::Rebound, Self::Press, Self::Fall, Self::Unload];

    /// Name in study files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Rebound => "rebound",
            Self::Press => "press",
            Self::Fall => "fall",
            Self::Unload => "unload",
        }
    }
    /// Condition label with unit.
    pub fn condition_label(self) -> &'static str {
        match self {
            Self::Rebound => "drop height, m",
            Self::Press => "load, N",
            Self::Fall => "fall height, m",
            Self::Unload => "peak load, N",
        }
    }
    /// Observable label with unit.
    pub fn observable_label(self) -> &'static str {
        match self {
            Self::Rebound => "rebound/impact speed ratio",
            Self::Press => "resting overlap, um",
            Self::Fall => "fall time, ms",
            Self::Unload => "overlap after unloading to half, um",
        }
    }
    /// Valid condition range (inclusive), in the condition's unit.
    pub fn condition_range(self) -> (f64, f64) {
        match self {
            Self::Rebound => (0.005, 3.0),
            Self::Press => (5.0e-4, 0.5),
            Self::Fall => (0.05, 5.0),
            Self::Unload => (5.0e-4, 0.5),
        }
    }

    /// Simulate the observable at `condition` with parameters `p`.
    pub fn simulate(self, condition: f64, p: &ModelParams) -> Result<f64> {
        let (lo, hi) = self.condition_range();
        if !(condition >= lo && condition <= hi) {
            bail!(
                "{} condition {condition} outside [{lo}, {hi}] ({})",
                self.name(),
                self.condition_label()
            );
        }
        p.validate()?;
        let r = match self {
            Self::Rebound => rebound(condition, p),
            Self::Press => press(condition, p, 1.0),
            Self::Unload => press(condition, p, UNLOAD_FRACTION),
            Self::Fall => fall(condition, p),
        };
        r.with_context(|| format!("simulating {} at {condition}", self.name()))
    }
}

fn pod(p: &ModelParams) -> MaterialSpec {
    MaterialSpec {
        youngs_modulus_pa: p.youngs_modulus_pa,
        poisson: POD_POISSON,
        density_kg_m3: POD_DENSITY_KG_M3,
    }
}

fn mass_kg() -> f64 {
    4.0 / 3.0 * std::f64::consts::PI * SPHERE_RADIUS_M.powi(3) * POD_DENSITY_KG_M3
}

fn e_star_pa(p: &ModelParams) -> f64 {
    let part = |m: &MaterialSpec| (1.0 - m.poisson * m.poisson) / m.youngs_modulus_pa;
    1.0 / (part(&pod(p)) + part(&STEEL))
}

/// Storage for the one-sphere worlds of these experiments.
fn one_sphere_arena() -> OwnedStorage<Fx> {
    OwnedStorage::new(StorageLengths::for_spheres(1, 1).with_effects())
}

/// Core errors (set-up or step) as `anyhow` errors with their message.
fn core_err(e: impl std::fmt::Display) -> anyhow::Error {
    anyhow::anyhow!("core: {e}")
}

/// A pod sphere over a steel floor (z = 0), normal terms only, effects from `p`.
fn floor_world<'a>(
    a: &'a mut OwnedStorage<Fx>,
    p: &ModelParams,
    restitution: f64,
    z_m: f64,
    vz_m_s: f64,
) -> Result<World<'a, Fx>> {
    let mut w = World::new(a.storage()).map_err(core_err)?;
    let pod_id = w.add_material(pod(p)).map_err(core_err)?;
    let steel = w.add_material(STEEL).map_err(core_err)?;
    let spec = PairSpec {
        restitution,
        friction: 0.0,
        rolling_friction: 0.0,
        terms: TermSwitches {
            mindlin_tangential: false,
            tangential_damping: false,
            coulomb_limit: false,
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
    let mut s = SphereSpec::at_rest(pod_id, SPHERE_RADIUS_M, [0.0, 0.0, z_m]);
    s.velocity_m_s = [0.0, 0.0, vz_m_s];
    w.add_sphere(s).map_err(core_err)?;
    Ok(w)
}

/// Hertz contact duration, s: t_c = 2.868·(m²/(R·E*²·v))^{1/5} (Johnson 1985, §11.1).
fn hertz_contact_time_s(p: &ModelParams, v: f64) -> f64 {
    let m = mass_kg();
    let es = e_star_pa(p);
    2.868 * (m * m / (SPHERE_RADIUS_M * es * es * v)).powf(0.2)
}

fn rebound(height_m: f64, p: &ModelParams) -> Result<f64> {
    let v = (2.0 * GRAVITY_M_S2 * height_m).sqrt();
    let mut a = one_sphere_arena();
    // Start 0.1 µm above the floor so the first step is contact-free.
    let mut w =
        floor_world(&mut a, p, p.restitution, SPHERE_RADIUS_M + 1e-7, -v).map_err(core_err)?;
    let dt = (hertz_contact_time_s(p, v) / REBOUND_STEPS_PER_CONTACT).min(0.9 * w.max_timestep_s());
    w.set_timestep_s(dt).map_err(core_err)?;
    let mut touched = false;
    for _ in 0..MAX_STEPS {
        w.step().map_err(core_err)?;
        let f = w.walls()[0].force.norm().to_f64();
        if f != 0.0 {
            touched = true;
        } else if touched {
            return Ok(w.body(BodyId(0)).velocity.z.to_f64() / v);
        }
    }
    bail!("rebound did not finish in {MAX_STEPS} steps")
}

/// Start at rest at the Hertz overlap of `load_n` (N) and settle under `fraction`·`load_n`.
fn press(load_n: f64, p: &ModelParams, fraction: f64) -> Result<f64> {
    let m = mass_kg();
    let es = e_star_pa(p);
    let r = SPHERE_RADIUS_M;
    // Start at the Hertz overlap of the load, at rest.
    let alpha0 = (3.0 * load_n / (4.0 * es * r.sqrt())).powf(2.0 / 3.0);
    let mut a = one_sphere_arena();
    let mut w =
        floor_world(&mut a, p, PRESS_SETTLING_RESTITUTION, r - alpha0, 0.0).map_err(core_err)?;
    w.set_gravity_m_s2([0.0, 0.0, -fraction * load_n / m])
        .map_err(core_err)?;
    // Small-oscillation period with the tangent stiffness 2E*a, a = √(Rα).
    let k = 2.0 * es * (r * alpha0).sqrt();
    let period = 2.0 * std::f64::consts::PI * (m / k).sqrt();
    let dt = (period / PRESS_STEPS_PER_PERIOD).min(0.9 * w.max_timestep_s());
    w.set_timestep_s(dt).map_err(core_err)?;
    let n = ((PRESS_PERIODS * period / dt) as u64).min(MAX_STEPS);
    w.run(n).map_err(core_err)?;
    let z_mm = w.body(BodyId(0)).position.z.to_f64();
    Ok((r * 1e3 - z_mm) * 1e3)
}

fn fall(height_m: f64, p: &ModelParams) -> Result<f64> {
    let mut a = one_sphere_arena();
    // The floor sits far below; the sphere never reaches it.
    let z0 = SPHERE_RADIUS_M + height_m + 1.0;
    let mut w = floor_world(&mut a, p, p.restitution, z0, 0.0).map_err(core_err)?;
    w.set_gravity_m_s2([0.0, 0.0, -GRAVITY_M_S2])
        .map_err(core_err)?;
    let dt = FALL_DT_S.min(0.9 * w.max_timestep_s());
    w.set_timestep_s(dt).map_err(core_err)?;
    let target_mm = (z0 - height_m) * 1e3;
    let mut z_prev = z0 * 1e3;
    for i in 0..MAX_STEPS {
        w.step().map_err(core_err)?;
        let z = w.body(BodyId(0)).position.z.to_f64();
        if z <= target_mm {
            // Linear interpolation inside the step that crossed the target height.
            let frac = (z_prev - target_mm) / (z_prev - z);
            return Ok((i as f64 + frac) * dt * 1e3);
        }
        z_prev = z;
    }
    bail!("fall did not finish in {MAX_STEPS} steps")
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
        }
    }

    #[test]
    fn observables_match_theory_with_effects_off() {
        let p = base();
        // Free fall in vacuum: t = √(2h/g); kick–drift error below one step (0.05 ms).
        let t = ExperimentKind::Fall.simulate(1.0, &p).unwrap();
        let theory = (2.0 / GRAVITY_M_S2).sqrt() * 1e3;
        assert!((t - theory).abs() < 0.06, "{t} vs {theory}");
        // Hertz overlap under load: α = (3F/(4E*√R))^{2/3}, within 0.5 %.
        let f = 0.01;
        let alpha = ExperimentKind::Press.simulate(f, &p).unwrap();
        let theory =
            (3.0 * f / (4.0 * e_star_pa(&p) * SPHERE_RADIUS_M.sqrt())).powf(2.0 / 3.0) * 1e6;
        assert!((alpha / theory - 1.0).abs() < 5e-3, "{alpha} vs {theory}");
        // Restitution is speed-independent without effects (within 1 %; the clip of the
        // attractive damping force raises the effective e a little, core tests/restitution).
        let e1 = ExperimentKind::Rebound.simulate(0.05, &p).unwrap();
        let e2 = ExperimentKind::Rebound.simulate(1.0, &p).unwrap();
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
            let alpha = ExperimentKind::Unload.simulate(f, &p).unwrap();
            let theory = peak * (lambda + (1.0 - lambda) * UNLOAD_FRACTION.powf(2.0 / 3.0));
            assert!(
                (alpha / theory - 1.0).abs() < 5e-3,
                "λ {lambda}: {alpha} vs {theory} um"
            );
        }
    }

    #[test]
    fn bad_conditions_are_refused() {
        assert!(ExperimentKind::Fall.simulate(-1.0, &base()).is_err());
        assert!(ExperimentKind::Press.simulate(f64::NAN, &base()).is_err());
    }
}
