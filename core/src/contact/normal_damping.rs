//! Normal viscous damping, seed 000 eq. (4): Fn_d = −2√(5/6)·β·√(Sn·m*)·vn with Sn = 2E*a and
//! β = ln e/√(ln²e + π²). Since Sn·m* = 2E*·(a·m*), the pair constant 2√(5/6)(−β)√(2E*) is
//! precomputed and multiplied by the per-contact √(a·m*).

use super::{
    beta_from_restitution, ContactForce, ContactKinematics, ContactState, ContactTerm,
    DAMPING_PREFACTOR,
};
use crate::num::Scalar;

/// Normal damping. Off value: `on = false` (equivalently e = 1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NormalDamping<S> {
    /// Whether the term is active.
    pub on: bool,
    /// 2√(5/6)·(−β)·√(2E*), √MPa: the force is −coef·√(a m*)·vn, N.
    pub coef: S,
}

impl<S: Scalar> NormalDamping<S> {
    /// Build from restitution e ∈ (0, 1] and E*, MPa.
    pub fn new(restitution: f64, e_star_mpa: f64) -> Self {
        let beta = beta_from_restitution(restitution);
        NormalDamping {
            on: beta != 0.0,
            coef: S::from_f64(DAMPING_PREFACTOR * -beta * libm::sqrt(2.0 * e_star_mpa)),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for NormalDamping<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            out.normal -= self.coef * k.sqrt_a_mstar * k.vn;
        }
    }
}
