//! Rolling friction, EDEM's constant directional torque (CDT), seed 000 eq. (7):
//! T_i = −μr·Fn·R_i·ω̂_i, with R_i the distance from body i's centre of mass to the contact
//! point and ω̂_i the unit angular velocity of body i (not the relative ω: this is EDEM's form,
//! not LIGGGHTS').
//!
//! The term only accumulates the magnitude μr·Fn·R_i per body; the integrator applies it along
//! −ω̂_i and caps it so that it never reverses ω within a step (a constant torque would
//! otherwise chatter around ω = 0, DESIGN §2).
//!
//! Because each body's torque follows its own ω̂, the pair of torques is not equal and
//! opposite: this law dissipates angular momentum as well as energy (as in EDEM).

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// CDT rolling friction. Off value: `on = false` (equivalently μr = 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollingCdt<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Rolling friction coefficient μr (≥ 0), dimensionless.
    pub mu_r: S,
}

impl<S: Scalar> RollingCdt<S> {
    /// Build from μr.
    pub fn new(mu_r: f64) -> Self {
        RollingCdt {
            on: mu_r > 0.0,
            mu_r: S::from_f64(mu_r),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for RollingCdt<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            let t = self.mu_r * out.normal;
            out.roll_i += t * k.lever_i;
            out.roll_j += t * k.lever_j;
        }
    }
}
