//! Hysteretic (plastic) normal contact, after Walton & Braun (J. Rheol. 30, 949 (1986)):
//! loading and unloading follow different curves, with the maximum overlap α_max of the
//! contact kept in its history. Here loading is Hertz (so the off value is exactly the plain
//! law) and unloading is a Hertz curve from the peak down to a plastic set α_p = λ·α_max:
//!
//!   F = F_max·((α − α_p)/(α_max − α_p))^{3/2} for α < α_max,  F_max = (4/3)E*·√R*·α_max^{3/2},
//!
//! with the plastic fraction λ ∈ [0, 1). The energy returned is (1 − λ) times the energy
//! stored ((2/5)F_max·(α_max − α_p) against (2/5)F_max·α_max), so with no other damping the
//! restitution is e = √(1 − λ), independent of impact speed — the hysteresis loop of a
//! compression test (seed 001's loading/unloading cycle) in its simplest form.
//!
//! The term runs right after [`super::HertzNormal`] and replaces its force while unloading.
//! A contact's history keeps α_max while the contact lasts (it is reset when the contact
//! ends).

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Hysteretic normal contact. Off value: λ = 0 (`on = false`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct HystereticNormal<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Plastic fraction λ ∈ [0, 1): the plastic set is λ·α_max.
    pub plastic_fraction: S,
    /// (4/3)·E*, MPa (as the Hertz term).
    pub four_thirds_e_star: S,
}

impl<S: Scalar> HystereticNormal<S> {
    /// Build from the plastic fraction λ ∈ [0, 1) and E*, MPa.
    pub fn new(plastic_fraction: f64, e_star_mpa: f64) -> Self {
        HystereticNormal {
            on: plastic_fraction > 0.0,
            plastic_fraction: S::from_f64(plastic_fraction),
            four_thirds_e_star: S::from_f64(4.0 / 3.0 * e_star_mpa),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for HystereticNormal<S> {
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
        let alpha = k.overlap;
        if alpha >= state.max_overlap {
            // Loading: Hertz (already added by the Hertz term); remember the peak.
            state.max_overlap = alpha;
            return;
        }
        let am = state.max_overlap;
        let ap = self.plastic_fraction * am;
        // Unloading: remove the Hertz force and add the unloading curve.
        let hertz = self.four_thirds_e_star * (k.contact_radius * alpha);
        let mut unload = S::ZERO;
        if alpha > ap {
            // a_max = a·√(α_max/α), so F_max = (4/3)E*·a_max·α_max.
            let a_max = k.contact_radius * (am / alpha).sqrt();
            let f_max = self.four_thirds_e_star * (a_max * am);
            let x = (alpha - ap) / (am - ap);
            unload = f_max * (x * x.sqrt());
        }
        out.normal += unload - hertz;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;

    fn kin(r: f64, alpha: f64) -> ContactKinematics<Fx> {
        ContactKinematics {
            contact_radius: Fx::from_f64(r * alpha).sqrt(),
            ..crate::contact::test_kinematics(alpha, 0.0)
        }
    }

    #[test]
    fn unloading_follows_the_shifted_hertz_curve() {
        // E* 10 MPa, R* 4 mm, peak 0.01 mm, λ 0.4: α_p = 0.004 mm. At α = 0.007 mm:
        // F_max = (4/3)·10·2·0.01^{1.5} = 0.0266667 N, F = F_max·(0.5)^{1.5} = 0.0094281 N.
        let (r, es) = (4.0, 10.0);
        let t = HystereticNormal::<Fx>::new(0.4, es);
        let hertz = |a: f64| 4.0 / 3.0 * es * r.sqrt() * a.powf(1.5);
        let mut st = ContactState::default();
        let mut out = ContactForce {
            normal: Fx::from_f64(hertz(0.01)),
            ..ContactForce::default()
        };
        t.apply(&kin(r, 0.01), &mut st, &mut out);
        assert_eq!(st.max_overlap, Fx::from_f64(0.01));
        assert!((out.normal.to_f64() - hertz(0.01)).abs() < 1e-8);
        let mut out = ContactForce {
            normal: Fx::from_f64(hertz(0.007)),
            ..ContactForce::default()
        };
        t.apply(&kin(r, 0.007), &mut st, &mut out);
        assert!(
            (out.normal.to_f64() - 0.009_428_1).abs() < 2e-6,
            "{}",
            out.normal.to_f64()
        );
        // Below the plastic set: no force at all.
        let mut out = ContactForce {
            normal: Fx::from_f64(hertz(0.003)),
            ..ContactForce::default()
        };
        t.apply(&kin(r, 0.003), &mut st, &mut out);
        assert!(out.normal.to_f64().abs() < 1e-8);
    }
}
