//! The fall rig: a pod sphere falling freely from rest. Condition: the fall height, m;
//! observable: the fall time, ms. Responds to air drag. The floor lies far below: the sphere
//! never reaches it.

use arachis_core::prelude::*;

use super::kind::{ConditionKey, Quantity, RigKind};
use super::single_sphere::*;
use crate::calibration::RigError;
use crate::limits::Limits;

/// Time step, s (below the Rayleigh bound of the pod sphere, 7.5e-5 s).
const DT_S: f64 = 5.0e-5;

/// This rig's test.
pub const TEST: SingleSphereTest = SingleSphereTest {
    name: "fall",
    about: "free fall; fall time against height",
    quantity: Quantity {
        name: "fall_time",
        unit: "ms",
        label: "fall time, ms",
    },
    condition: ConditionKey::new("fall_height_m", "fall height, m", Limits::Positive)
        .within((0.05, 5.0), (0.1, 3.0)),
    parameters: PARAMETERS_WITHOUT_ROLLING,
    simulate,
};

/// This rig in the catalogue.
pub const KIND: RigKind = TEST.kind(|_, _| Ok(Box::new(SingleSphereRig { test: &TEST })));

/// The time (ms) to fall `height_m` (m) from rest.
fn simulate(height_m: f64, p: &ModelParams) -> Result<f64, RigError> {
    let mut a = one_sphere_arena();
    // The floor sits far below; the sphere never reaches it.
    let z0 = SPHERE_RADIUS_M + height_m + 1.0;
    let mut w = floor_world(&mut a, p, p.restitution, z0, 0.0)?;
    w.set_gravity_m_s2([0.0, 0.0, -GRAVITY_M_S2])
        .map_err(core_err)?;
    let dt = DT_S.min(0.9 * w.max_timestep_s());
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
    Err(RigError(format!(
        "fall did not finish in {MAX_STEPS} steps"
    )))
}
