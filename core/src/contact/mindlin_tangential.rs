//! Mindlin tangential spring with history, seed 000 eq. (5) as in DESIGN §2:
//! Ft = −St·δt, St = 8G*a, where δt is the accumulated tangential displacement.
//!
//! Each step the stored δt is first projected onto the current tangent plane
//! (δt ← δt − (δt·n)n, which drops the part that rotated out of the plane; the length is not
//! restored), then the increment vt·dt is added.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Mindlin no-slip tangential spring. Off value: `on = false` (no tangential force, no history).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MindlinTangential<S> {
    /// Whether the term is active.
    pub on: bool,
    /// 8·G*, MPa, with 1/G* = 2(2−νi)(1+νi)/Ei + 2(2−νj)(1+νj)/Ej (DESIGN §2).
    pub eight_g_star: S,
}

impl<S: Scalar> MindlinTangential<S> {
    /// Build from G*, MPa.
    pub fn new(g_star_mpa: f64) -> Self {
        MindlinTangential {
            on: true,
            eight_g_star: S::from_f64(8.0 * g_star_mpa),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for MindlinTangential<S> {
    #[inline(always)]
    fn apply(
        &self,
        k: &ContactKinematics<S>,
        state: &mut ContactState<S>,
        out: &mut ContactForce<S>,
    ) {
        if !self.on {
            return;
        }
        let n = k.normal;
        let d = state.delta;
        let d = d.in_plane_of(n) + k.vt.scale(k.dt);
        state.delta = d;
        let st = self.eight_g_star * k.contact_radius;
        out.tangential_stiffness = st;
        out.tangential -= d.scale(st);
    }
}
