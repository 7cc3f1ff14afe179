//! Coulomb friction limit (DESIGN §2): |Ft| ≤ μs·Fn, with Fn the clipped total normal force.
//!
//! When the tangential force exceeds the limit it is scaled back onto the limit, and if the
//! spring alone exceeds it (St|δt| > μs·Fn) the history is rescaled so that St|δt| = μs·Fn: the
//! contact slides and does not store more elastic energy than friction can hold.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Coulomb limit. Off value: `on = false` (no limit, i.e. μs = ∞; only sensible with the
/// tangential spring also off).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CoulombLimit<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Sliding friction coefficient μs (≥ 0).
    pub mu: S,
}

impl<S: Scalar> CoulombLimit<S> {
    /// Build from μs.
    pub fn new(mu: f64) -> Self {
        CoulombLimit {
            on: true,
            mu: S::from_f64(mu),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for CoulombLimit<S> {
    #[inline(always)]
    fn apply(
        &self,
        _: &ContactKinematics<S>,
        state: &mut ContactState<S>,
        out: &mut ContactForce<S>,
    ) {
        if !self.on {
            return;
        }
        let limit = self.mu * out.normal;
        let f2 = out.tangential.norm2();
        if f2 <= limit * limit {
            return;
        }
        if limit <= S::ZERO {
            out.tangential = crate::num::Vec3::ZERO;
            state.delta = crate::num::Vec3::ZERO;
            return;
        }
        let f = f2.sqrt();
        out.tangential = out.tangential.scale(limit / f);
        let spring = out.tangential_stiffness * state.delta.norm();
        if spring > limit {
            state.delta = state.delta.scale(limit / spring);
        }
    }
}
