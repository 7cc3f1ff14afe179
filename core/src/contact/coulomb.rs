//! Coulomb friction limit (DESIGN §2): |Ft| ≤ μs·Fn, with Fn the clipped total normal force.
//!
//! When the tangential force exceeds the limit it is scaled back onto the limit, and if the
//! spring alone exceeds it (St|δt| > μs·Fn) the history is rescaled so that St|δt| = μs·Fn: the
//! contact slides and does not store more elastic energy than friction can hold.
//!
//! In LIGGGHTS' convention ([`crate::contact::FrictionConvention::Liggghts`],
//! `tangential_model_history.h`) only the spring is tested: if St|δt| > μs·Fn the force is the
//! spring scaled onto μs·Fn, without damping, and the history is rescaled to match; otherwise
//! the force is spring plus damping, which may exceed μs·Fn.

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
    /// LIGGGHTS' test: the spring alone against the limit, no damping while sliding.
    pub spring_only: bool,
}

impl<S: Scalar> CoulombLimit<S> {
    /// Build from μs.
    pub fn new(mu: f64) -> Self {
        CoulombLimit {
            on: true,
            mu: S::from_f64(mu),
            spring_only: false,
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
        if self.spring_only {
            return spring_limit(limit, state, out);
        }
        let f2 = out.tangential.norm2();
        let limit2 = limit * limit;
        if poisoned(out, [limit, f2, limit2]) {
            return;
        }
        if f2 <= limit2 {
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
        if poisoned(out, [spring]) {
            return;
        }
        if spring > limit {
            state.delta = state.delta.scale(limit / spring);
        }
    }
}

/// LIGGGHTS' Coulomb test: St|δt| against `limit` = μs·Fn; a sliding contact gets the spring
/// force −St·δt scaled onto the limit (its damping dropped) and the matching history.
#[inline(always)]
fn spring_limit<S: Scalar>(limit: S, state: &mut ContactState<S>, out: &mut ContactForce<S>) {
    let spring = out.tangential_stiffness * state.delta.norm();
    if poisoned(out, [limit, spring]) || spring <= limit {
        return;
    }
    let ratio = limit / spring;
    state.delta = state.delta.scale(ratio);
    out.tangential = state.delta.scale(-out.tangential_stiffness);
}

/// `true`, with the tangential force set to the offending value, when a quantity the limit
/// compares is not valid (an overflowed product): in fixed point the poison is the most
/// negative integer, which a comparison would take for a small number, turning an overflow
/// into a silently wrong force; carried in the force, it fails the step instead.
#[inline(always)]
fn poisoned<S: Scalar, const N: usize>(out: &mut ContactForce<S>, xs: [S; N]) -> bool {
    match xs.into_iter().find(|x| !x.is_valid()) {
        Some(p) => {
            out.tangential = crate::num::Vec3::new(p, p, p);
            true
        }
        None => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Fx, Vec3};

    /// A contact with St 1 N/mm, history δt = (0.1, 0, 0) mm (spring −0.1 N along x) and a
    /// damping part `damping_n` N along −x, under Fn 1 N. (A history of 0.1 mm keeps |δt|²
    /// exact to 2e-8 in Q32.32, so the tolerances below are 1e-8.)
    fn loaded(damping_n: f64) -> (ContactState<Fx>, ContactForce<Fx>) {
        let state = ContactState {
            delta: Vec3::new(Fx::from_f64(0.1), Fx::ZERO, Fx::ZERO),
            ..ContactState::default()
        };
        let out = ContactForce {
            normal: Fx::ONE,
            tangential_stiffness: Fx::ONE,
            tangential: Vec3::new(Fx::from_f64(-0.1 - damping_n), Fx::ZERO, Fx::ZERO),
            ..ContactForce::default()
        };
        (state, out)
    }

    fn limit(mu: f64, spring_only: bool) -> CoulombLimit<Fx> {
        CoulombLimit {
            spring_only,
            ..CoulombLimit::new(mu)
        }
    }

    fn apply(c: CoulombLimit<Fx>, damping_n: f64) -> (f64, f64) {
        let (mut st, mut out) = loaded(damping_n);
        let k = crate::contact::test_kinematics(0.01, 0.1);
        c.apply(&k, &mut st, &mut out);
        (out.tangential.x.to_f64(), st.delta.x.to_f64())
    }

    #[test]
    fn edem_caps_spring_plus_damping() {
        // μs 0.15: |spring + damping| = 0.2 N > 0.15 N → force −0.15 N; the spring (0.1 N) is
        // below the limit, so the history is kept.
        let (f, d) = apply(limit(0.15, false), 0.1);
        assert!((f + 0.15).abs() < 1e-8, "{f}");
        assert!((d - 0.1).abs() < 1e-8);
        // μs 0.05: the spring alone exceeds it: history rescaled to 0.05 mm.
        let (f, d) = apply(limit(0.05, false), 0.1);
        assert!((f + 0.05).abs() < 1e-8);
        assert!((d - 0.05).abs() < 1e-8);
    }

    #[test]
    fn liggghts_tests_the_spring_alone_and_drops_damping_when_sliding() {
        // μs 0.15: the spring (0.1 N) sticks, so spring + damping (0.2 N) passes unbounded.
        let (f, d) = apply(limit(0.15, true), 0.1);
        assert!((f + 0.2).abs() < 1e-8, "{f}");
        assert!((d - 0.1).abs() < 1e-8);
        // μs 0.05: sliding: the spring scaled onto 0.05 N, without the 0.1 N of damping.
        let (f, d) = apply(limit(0.05, true), 0.1);
        assert!((f + 0.05).abs() < 1e-8, "{f}");
        assert!((d - 0.05).abs() < 1e-8);
        // Fn 0: no force, no history.
        let (mut st, mut out) = loaded(0.1);
        out.normal = Fx::ZERO;
        let k = crate::contact::test_kinematics(0.01, 0.1);
        limit(0.5, true).apply(&k, &mut st, &mut out);
        assert_eq!(out.tangential, Vec3::ZERO);
        assert_eq!(st.delta, Vec3::ZERO);
    }
}
