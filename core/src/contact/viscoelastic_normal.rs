//! Viscoelastic normal damping (velocity-dependent restitution), Brilliantov, Spahn, Hertzsch &
//! Pöschel, Phys. Rev. E 53, 5382 (1996), eq. (21):
//! F = (2Y√R*)/(3(1−ν²))·(ξ^{3/2} + A·√ξ·ξ̇). The first part is the Hertz force (4/3)E*·a·ξ,
//! so the dissipative part is Fn_v = (4/3)·E*·A·a·ξ̇ = −(4/3)·E*·A·a·vn, with a = √(R*ξ) and the
//! material's dissipative relaxation time A (s).
//!
//! Unlike the constant-e damping of seed 000 eq. (4), this law gives a restitution that falls
//! with impact speed: e ≈ 1 − 1.153·β·v^{1/5} + … with β = (3/2)·A·ρ^{2/5},
//! ρ = (4/3)E*√R*/m* (Schwager & Pöschel, Phys. Rev. E 78, 051304 (2008), eq. (31)).
//! It runs before the clip, as part of the total normal force.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Seconds to internal milliseconds.
const MS_PER_S: f64 = 1.0e3;

/// Viscoelastic normal damping. Off value: relaxation time A = 0 (`on = false`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ViscoelasticNormal<S> {
    /// Whether the term is active.
    pub on: bool,
    /// (4/3)·E*·A, MPa·ms = N·ms/mm²: the force is −coef·a·vn, N.
    pub coef: S,
}

impl<S: Scalar> ViscoelasticNormal<S> {
    /// Build from the dissipative relaxation time A (s, ≥ 0) and E* (MPa).
    pub fn new(relaxation_time_s: f64, e_star_mpa: f64) -> Self {
        ViscoelasticNormal {
            on: relaxation_time_s > 0.0,
            coef: S::from_f64(4.0 / 3.0 * e_star_mpa * relaxation_time_s * MS_PER_S),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for ViscoelasticNormal<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            out.normal -= self.coef * (k.contact_radius * k.vn);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;

    fn kin(a: f64, vn: f64) -> ContactKinematics<Fx> {
        ContactKinematics {
            vn: Fx::from_f64(vn),
            ..crate::contact::test_kinematics(0.01, a)
        }
    }

    #[test]
    fn force_matches_brilliantov_dissipative_part() {
        // E* 10 MPa, A 1e-5 s, a 0.2 mm, approaching at 2 m/s:
        // F = (4/3)·10·(1e-5·1e3)·0.2·2 = 0.053333 N (repulsive).
        let t = ViscoelasticNormal::<Fx>::new(1e-5, 10.0);
        let mut out = ContactForce::default();
        t.apply(&kin(0.2, -2.0), &mut ContactState::default(), &mut out);
        assert!((out.normal.to_f64() - 0.053_333_3).abs() < 1e-6);
        let off = ViscoelasticNormal::<Fx>::new(0.0, 10.0);
        let mut out = ContactForce::default();
        off.apply(&kin(0.2, -2.0), &mut ContactState::default(), &mut out);
        assert_eq!(out.normal, Fx::ZERO);
    }
}
