//! Tangential viscous damping, seed 000 eq. (6): Ft_d = −2√(5/6)·β·√(St·m*)·vt with
//! St = 8G*a, so the pair constant 2√(5/6)(−β)√(8G*) multiplies the per-contact √(a·m*).

use super::{
    beta_from_restitution, ContactForce, ContactKinematics, ContactState, ContactTerm,
    DAMPING_PREFACTOR,
};
use crate::num::Scalar;

/// Tangential damping. Off value: `on = false` (equivalently e = 1).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TangentialDamping<S> {
    /// Whether the term is active.
    pub on: bool,
    /// 2√(5/6)·(−β)·√(8G*), √MPa: the force is −coef·√(a m*)·vt, N.
    pub coef: S,
}

impl<S: Scalar> TangentialDamping<S> {
    /// Build from restitution e ∈ (0, 1] and G*, MPa.
    pub fn new(restitution: f64, g_star_mpa: f64) -> Self {
        let beta = beta_from_restitution(restitution);
        TangentialDamping {
            on: beta != 0.0,
            coef: S::from_f64(DAMPING_PREFACTOR * -beta * libm::sqrt(8.0 * g_star_mpa)),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for TangentialDamping<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            out.tangential -= k.vt.scale(self.coef * k.sqrt_a_mstar);
        }
    }
}
