//! Body forces: clear the accumulators and add gravity F = m·g (N), so that `Body::force`
//! reports the total force of the step. Later effects (air drag, buoyancy) belong here as
//! separate terms. The integrator takes gravity out again and applies it as the acceleration g
//! itself, exact for any mass (fuzz finding F3).

use crate::error::{Other, Stage, StepError};
use crate::num::{Scalar, Vec3};
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    pub(crate) fn apply_body_forces(&mut self) -> Result<(), StepError> {
        let g = self.gravity;
        for (i, b) in self.bodies[..self.n_bodies as usize].iter_mut().enumerate() {
            b.force = g.scale(b.mass);
            b.torque = Vec3::ZERO;
            b.roll_torque = S::ZERO;
            if !b.force.is_valid() {
                return Err(StepError::Overflow {
                    stage: Stage::BodyForces,
                    body: i as u32,
                    other: Other::None,
                });
            }
        }
        for w in self.walls.iter_mut() {
            w.force = Vec3::ZERO;
        }
        Ok(())
    }
}
