//! The rebound rig: a pod sphere dropped on a steel floor. Condition: the drop height, m
//! (impact speed √(2gh)); observable: the rebound/impact speed ratio. Responds to the
//! restitution and to viscoelastic damping (restitution falling with impact speed). The run
//! starts at first touch with the impact speed (the free flight before it is not simulated).

use arachis_core::prelude::*;

use super::kind::{ConditionKey, Quantity, RigKind};
use super::single_sphere::*;
use crate::calibration::RigError;
use crate::limits::Limits;

/// Time steps per Hertz contact duration.
const STEPS_PER_CONTACT: f64 = 100.0;

/// This rig's test.
pub const TEST: SingleSphereTest = SingleSphereTest {
    name: "rebound",
    about: "drop on the floor; rebound/impact speed ratio against drop height",
    quantity: Quantity {
        name: "rebound_ratio",
        unit: "-",
        label: "rebound/impact speed ratio",
    },
    condition: ConditionKey::new("drop_height_m", "drop height, m", Limits::Positive)
        .within((0.005, 3.0), (0.02, 2.0)),
    parameters: PARAMETERS_WITHOUT_ROLLING,
    simulate,
};

/// This rig in the catalogue.
pub const KIND: RigKind = TEST.kind(|_, _| Ok(Box::new(SingleSphereRig { test: &TEST })));

/// The rebound/impact speed ratio after a drop from `height_m` (m).
fn simulate(height_m: f64, p: &ModelParams) -> Result<f64, RigError> {
    let v = (2.0 * GRAVITY_M_S2 * height_m).sqrt();
    let mut a = one_sphere_arena();
    // Start 0.1 µm above the floor so the first step is contact-free.
    let mut w = floor_world(&mut a, p, p.restitution, SPHERE_RADIUS_M + 1e-7, -v)?;
    let dt = (hertz_contact_time_s(p, v) / STEPS_PER_CONTACT).min(0.9 * w.max_timestep_s());
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
    Err(RigError(format!(
        "rebound did not finish in {MAX_STEPS} steps"
    )))
}
