//! The step pipeline (DESIGN §6), one module per stage:
//!
//! 1. [`body_forces`]: clear accumulators, add gravity (and later drag);
//! 2. [`neighbour_list`]: Verlet list with a skin, rebuilt from the [`broad_phase`] cell grid
//!    (counting sort, fixed order) only when a sphere may have moved by half the skin;
//! 3. [`narrow_phase`]: sphere–sphere and sphere–wall geometry, then the contact terms of
//!    [`crate::pair::PairParams`]; forces and torques accumulate into the bodies;
//! 4. [`bonds`]: bonded-particle loads, breakage and scheduled bond formation (between the
//!    narrow phase and integration);
//! 5. [`integration`]: symplectic Euler (kick–drift), the leapfrog form of velocity Verlet,
//!    with rolling friction applied so it never reverses ω; clumps through their quaternion;
//! 6. [`wall_motion`]: walls advance at their prescribed velocity.
//!
//! In fixed point, force accumulation is integer addition, so its result does not depend on
//! the order of contacts (DESIGN §5); the order is fixed anyway so the f64 reference is also
//! reproducible.

pub mod air_drag;
pub mod body_forces;
pub mod bonds;
pub mod broad_phase;
pub mod integration;
pub mod narrow_phase;
pub mod neighbour_list;
pub mod wall_motion;

use crate::error::StepError;
use crate::num::Scalar;
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    /// Advance the world by one time step.
    ///
    /// Errors: [`StepError::NoTimeStep`], [`StepError::TimeStepTooLarge`] (checked before any
    /// state changes), [`StepError::Overflow`] naming the stage and bodies,
    /// [`StepError::ContactCapacity`], [`StepError::UndefinedPair`]. After an error other than
    /// the time-step ones the state is partly advanced.
    pub fn step(&mut self) -> Result<(), StepError> {
        if self.dt_s == 0.0 {
            return Err(StepError::NoTimeStep);
        }
        let max_s = self.max_timestep_s();
        if self.dt_s > max_s {
            return Err(StepError::TimeStepTooLarge {
                dt_s: self.dt_s,
                max_s,
            });
        }
        self.apply_body_forces()?;
        if self.air_drag.on {
            self.apply_air_drag()?;
        }
        self.ensure_neighbour_list()?;
        self.contacts()?;
        self.bond_forces()?;
        self.integrate()?;
        self.move_walls()?;
        self.time += self.dt;
        self.steps += 1;
        Ok(())
    }

    /// Run `n` steps, stopping at the first error.
    pub fn run(&mut self, n: u64) -> Result<(), StepError> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }
}
