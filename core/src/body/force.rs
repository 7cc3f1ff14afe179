//! [`BodyForce`]: the force, torque and rolling-resistance sums one step gathers on a body
//! from its contacts, bonds and air drag (gravity excluded: the integrator applies it as the
//! acceleration g itself).
//!
//! The sums live apart from [`super::Body`], in an arena of their own, so that the contact
//! stage can read every body's motion while each part of a threaded step writes only its own
//! accumulator arena. In fixed point a [`Scalar::Sum`] is an exact 128-bit integer sum, so
//! the total does not depend on the order of the contacts or on how many threads shared them.
//!
//! ```
//! use arachis_core::body::BodyForce;
//! use arachis_core::num::{Fx, Scalar, Vec3};
//! let mut a = BodyForce::<Fx>::default();
//! a.add_force(Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO));
//! let mut b = BodyForce::<Fx>::default();
//! b.sub_force(Vec3::new(Fx::HALF, Fx::ZERO, Fx::ZERO));
//! a.merge(&b);
//! assert_eq!(a.force().x, Fx::HALF);
//! ```

use crate::num::{Scalar, Vec3};

/// Sums of one body's loads in the current step (N, N·mm).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BodyForce<S: Scalar> {
    /// Force, N, per component.
    pub force: [S::Sum; 3],
    /// Torque about the centre of mass, N·mm, world frame, per component.
    pub torque: [S::Sum; 3],
    /// Rolling-resistance torque magnitude, N·mm, applied along −ω̂ by the integrator.
    pub roll: S::Sum,
}

#[inline(always)]
fn add3<S: Scalar>(sum: &mut [S::Sum; 3], v: Vec3<S>) {
    S::sum_add(&mut sum[0], v.x);
    S::sum_add(&mut sum[1], v.y);
    S::sum_add(&mut sum[2], v.z);
}

#[inline(always)]
fn value3<S: Scalar>(sum: &[S::Sum; 3]) -> Vec3<S> {
    Vec3::new(
        S::sum_value(sum[0]),
        S::sum_value(sum[1]),
        S::sum_value(sum[2]),
    )
}

impl<S: Scalar> BodyForce<S> {
    /// Add a force, N.
    #[inline(always)]
    pub fn add_force(&mut self, f: Vec3<S>) {
        add3(&mut self.force, f);
    }
    /// Subtract a force, N.
    #[inline(always)]
    pub fn sub_force(&mut self, f: Vec3<S>) {
        S::sum_sub(&mut self.force[0], f.x);
        S::sum_sub(&mut self.force[1], f.y);
        S::sum_sub(&mut self.force[2], f.z);
    }
    /// Add a torque, N·mm.
    #[inline(always)]
    pub fn add_torque(&mut self, t: Vec3<S>) {
        add3(&mut self.torque, t);
    }
    /// Add a rolling-resistance torque magnitude, N·mm.
    #[inline(always)]
    pub fn add_roll(&mut self, r: S) {
        S::sum_add(&mut self.roll, r);
    }
    /// Add another accumulator (another thread's share of this body).
    #[inline(always)]
    pub fn merge(&mut self, o: &Self) {
        for k in 0..3 {
            S::sum_merge(&mut self.force[k], o.force[k]);
            S::sum_merge(&mut self.torque[k], o.torque[k]);
        }
        S::sum_merge(&mut self.roll, o.roll);
    }
    /// The force sum, N (invalid components where it overflowed the scalar's range).
    #[inline(always)]
    pub fn force(&self) -> Vec3<S> {
        value3(&self.force)
    }
    /// The torque sum, N·mm.
    #[inline(always)]
    pub fn torque(&self) -> Vec3<S> {
        value3(&self.torque)
    }
    /// The rolling-resistance torque magnitude, N·mm.
    #[inline(always)]
    pub fn roll(&self) -> S {
        S::sum_value(self.roll)
    }
}
