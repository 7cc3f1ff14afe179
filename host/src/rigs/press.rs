//! The press rig: a pod sphere pressed on a steel floor by a static load. Condition: the load,
//! N; observable: the resting overlap, µm. Responds to Young's modulus and cohesion. The
//! load acts as a body force (gravity scaled to F/m) and the sphere, started at rest at the
//! Hertz overlap of the load, settles with constant-e damping (e fixed at
//! [`SETTLING_RESTITUTION`]: the press is quasi-static, so e does not enter the result).

use arachis_core::prelude::*;

use super::kind::{ConditionKey, Quantity, RigKind};
use super::single_sphere::*;
use crate::calibration::RigError;
use crate::limits::Limits;

/// Restitution used only to settle the sphere (quasi-static: it does not change the resting
/// overlap, only how fast the sphere gets there).
pub const SETTLING_RESTITUTION: f64 = 0.2;
/// Time steps per small-oscillation period, and periods simulated.
const STEPS_PER_PERIOD: f64 = 30.0;
const PERIODS: f64 = 25.0;

/// This rig's test.
pub const TEST: SingleSphereTest = SingleSphereTest {
    name: "press",
    about: "static load on the floor; resting overlap against load",
    quantity: Quantity {
        name: "resting_overlap",
        unit: "um",
        label: "resting overlap, um",
    },
    condition: ConditionKey::new("load_n", "load, N", Limits::Positive)
        .within((5.0e-4, 0.5), (1.0e-3, 0.2)),
    parameters: PARAMETERS_WITHOUT_ROLLING,
    simulate,
};

/// This rig in the catalogue.
pub const KIND: RigKind = TEST.kind(|_, _| Ok(Box::new(SingleSphereRig { test: &TEST })));

/// The resting overlap (µm) under `load_n` (N).
fn simulate(load_n: f64, p: &ModelParams) -> Result<f64, RigError> {
    settle(load_n, p, 1.0)
}

/// Starts at rest at the Hertz overlap of `load_n` (N) and settles under
/// `fraction`·`load_n`; the resting overlap, µm.
pub fn settle(load_n: f64, p: &ModelParams, fraction: f64) -> Result<f64, RigError> {
    let r = SPHERE_RADIUS_M;
    // Start at the Hertz overlap of the load, at rest.
    let alpha0 = hertz_overlap_m(p, load_n);
    let mut a = one_sphere_arena();
    let mut w = floor_world(&mut a, p, SETTLING_RESTITUTION, r - alpha0, 0.0)?;
    w.set_gravity_m_s2([0.0, 0.0, -fraction * load_n / mass_kg()])
        .map_err(core_err)?;
    let period = resting_period_s(p, alpha0);
    let dt = (period / STEPS_PER_PERIOD).min(0.9 * w.max_timestep_s());
    w.set_timestep_s(dt).map_err(core_err)?;
    let n = ((PERIODS * period / dt) as u64).min(MAX_STEPS);
    w.run(n).map_err(core_err)?;
    let z_mm = w.body(BodyId(0)).position.z.to_f64();
    Ok((r * 1e3 - z_mm) * 1e3)
}
