//! Kinematic bodies: bodies that move only with their prescribed velocity and angular
//! velocity, whatever forces act on them (a clamp, a gripper pulling at constant speed).
//! Setting the inverse mass and inverse inertia to zero makes the integrator's kick vanish
//! exactly; the one special case is gravity, which the integrator adds as an acceleration
//! (fuzz finding F3) and skips for a body whose inverse mass is zero. The force and torque accumulators still show what
//! the rest of the world exerts on the body (gravity included), which is how a test reads the
//! reaction force of a clamp or the pull of a gripper.

use crate::error::SetupError;
use crate::num::{Scalar, Vec3};
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    /// Make body `id` kinematic (see the module docs); keep its velocities with
    /// [`World::set_body_velocity`]. Irreversible.
    pub fn set_body_kinematic(&mut self, id: crate::body::BodyId) -> Result<(), SetupError> {
        if id.0 >= self.n_bodies {
            return Err(SetupError::UnknownId { id: id.0 });
        }
        let b = &mut self.bodies[id.0 as usize];
        b.inv_mass = S::ZERO;
        b.inv_inertia = Vec3::ZERO;
        Ok(())
    }
}
