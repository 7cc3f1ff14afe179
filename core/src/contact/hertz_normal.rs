//! Hertz elastic normal force, seed 000 eq. (3) in the form of DESIGN §2:
//! Fn = (4/3)·E*·a·α with a = √(R*α). Computing `a` once avoids α^1.5, which loses precision at
//! tiny overlaps in fixed point.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Hertz normal spring. Off value: `on = false` (no elastic normal force).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HertzNormal<S> {
    /// Whether the term is active.
    pub on: bool,
    /// (4/3)·E*, MPa, with 1/E* = (1−νi²)/Ei + (1−νj²)/Ej (DESIGN §2).
    pub four_thirds_e_star: S,
}

impl<S: Scalar> HertzNormal<S> {
    /// Build from E*, MPa.
    pub fn new(e_star_mpa: f64) -> Self {
        HertzNormal {
            on: true,
            four_thirds_e_star: S::from_f64(4.0 / 3.0 * e_star_mpa),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for HertzNormal<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            out.normal += self.four_thirds_e_star * (k.contact_radius * k.overlap);
        }
    }
}
