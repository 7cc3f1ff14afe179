//! Elastic–plastic spring–dashpot (EPSD) rolling resistance, model type C of Ai, Chen, Rotter
//! & Ooi, "Assessment of rolling resistance models in discrete element simulations", Powder
//! Technology 206 (2011) 269–282, eqs. (12)–(16):
//!
//! - spring: M_k = −k_r·θr, with θr the accumulated relative rolling rotation of i against j
//!   (the tangent-plane part of ∫(ωi − ωj)dt, kept in the contact history) and
//!   k_r = 2.25·k_n·μr²·R*² (eq. 13), k_n the normal contact stiffness; here the Hertz tangent
//!   stiffness k_n = 2E*·a (seed 000 eq. (4)'s Sn), so k_r = 4.5·E*·a·μr²·R*²;
//! - limit: |M_k| ≤ M_m = μr·R*·Fn (eq. 15), Fn the clipped normal force; beyond it the
//!   contact rolls (fully mobilised) and θr is rescaled so that k_r|θr| = M_m, as the Mindlin
//!   history is rescaled at the Coulomb limit;
//! - dashpot: M_d = −C_r·ω_r with C_r = η_r·2√(I_r·k_r) (eq. 14), η_r the rolling damping
//!   ratio, I_r the equivalent rolling inertia of [`ContactKinematics::rolling_inertia`],
//!   ω_r the tangent-plane part of ωi − ωj; as in Ai et al. with f = 0, no damping while
//!   fully mobilised (eq. 16).
//!
//! [`ContactForce::rolling_torque`] holds the torque on j, k_r·θr + C_r·ω_r; i receives the
//! opposite, which resists its relative rotation. The pair is equal and opposite, so unlike
//! CDT the law conserves angular momentum. Ai et al. update M_k incrementally (ΔM = −k_r·Δθ); keeping θr instead gives the
//! same torque while k_r is constant and a path-independent one when Fn (so a) changes.
//!
//! Against CDT ([`super::RollingCdt`]): above the limit both give a torque of magnitude
//! μr·Fn·R (CDT with the lever R − α/2, EPSD with R*); below it CDT only stops rotation, EPSD
//! holds a static rotation θr = M/k_r and can spring back.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// 2.25·2 = 4.5: Ai et al. eq. (13) with the Hertz tangent stiffness k_n = 2E*a.
const STIFFNESS_FACTOR: f64 = 4.5;

/// EPSD rolling resistance. Off value: μr = 0 (`on = false`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollingEpsd<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Rolling friction coefficient μr (≥ 0), dimensionless.
    pub mu_r: S,
    /// 4.5·E*·μr², MPa: k_r = this·a·R*², N·mm/rad.
    pub stiffness_coef: S,
    /// 2·η_r (η_r ≥ 0, the rolling viscous damping ratio): C_r = this·√(I_r·k_r).
    pub two_damping_ratio: S,
}

impl<S: Scalar> RollingEpsd<S> {
    /// Build from μr (≥ 0), the damping ratio η_r (≥ 0) and E*, MPa.
    pub fn new(mu_r: f64, damping_ratio: f64, e_star_mpa: f64) -> Self {
        RollingEpsd {
            on: mu_r > 0.0,
            mu_r: S::from_f64(mu_r),
            stiffness_coef: S::from_f64(STIFFNESS_FACTOR * e_star_mpa * mu_r * mu_r),
            two_damping_ratio: S::from_f64(2.0 * damping_ratio),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for RollingEpsd<S> {
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
        let wr = k.w_rel.in_plane_of(n);
        let th = state.roll_angle;
        let th = th.in_plane_of(n) + wr.scale(k.dt);
        let kr = self.stiffness_coef * k.contact_radius * (k.r_star * k.r_star);
        let limit = self.mu_r * k.r_star * out.normal;
        // |θr| through the exact power-of-two normalisation: θr is ~1e-3 rad, whose square
        // would keep only a few thousand raw units in Q32.32.
        let (spring, th) = match th.normalize_with_len() {
            None => (crate::num::Vec3::ZERO, th),
            Some((u, len)) => {
                let m = kr * len;
                if m > limit {
                    // Fully mobilised: torque at the limit, θr rescaled onto it, no dashpot.
                    let th = if kr > S::ZERO {
                        u.scale(limit / kr)
                    } else {
                        crate::num::Vec3::ZERO
                    };
                    state.roll_angle = th;
                    out.rolling_torque += u.scale(limit);
                    return;
                }
                (u.scale(m), th)
            }
        };
        state.roll_angle = th;
        let c_r = self.two_damping_ratio * (k.rolling_inertia * kr).sqrt();
        out.rolling_torque += spring + wr.scale(c_r);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Fx, Vec3};

    fn kin(w_rel_y: f64) -> ContactKinematics<Fx> {
        ContactKinematics {
            dt: Fx::from_f64(1e-2),
            lever_i: Fx::from_f64(4.0),
            r_star: Fx::from_f64(4.0),
            // A twisting part along n, which the rolling term must ignore.
            w_rel: Vec3::new(Fx::ZERO, Fx::from_f64(w_rel_y), Fx::from_f64(0.3)),
            rolling_inertia: Fx::from_f64(6.0),
            ..crate::contact::test_kinematics(0.005, 0.02f64.sqrt())
        }
    }

    #[test]
    fn spring_then_limit_then_rescaled_history() {
        // E* 10 MPa, μr 0.1, a = √0.02 mm, R* 4 mm: k_r = 4.5·10·0.01·a·16 = 1.01823 N·mm/rad.
        // Fn 0.01 N: M_m = 0.1·4·0.01 = 4e-3 N·mm. η_r 0 (no dashpot).
        let t = RollingEpsd::<Fx>::new(0.1, 0.0, 10.0);
        let kr = 4.5 * 10.0 * 0.01 * 0.02f64.sqrt() * 16.0;
        let mut st = ContactState::default();
        // One step at ω 0.1 rad/ms, dt 0.01 ms: θ = 1e-3 rad, torque on j = k_r·θ along +y.
        let mut out = ContactForce {
            normal: Fx::from_f64(0.01),
            ..ContactForce::default()
        };
        t.apply(&kin(0.1), &mut st, &mut out);
        assert!((st.roll_angle.y.to_f64() - 1e-3).abs() < 1e-9);
        assert_eq!(st.roll_angle.z, Fx::ZERO);
        let m = out.rolling_torque.y.to_f64();
        assert!((m / (kr * 1e-3) - 1.0).abs() < 1e-6, "{m}");
        // Ten more steps: k_r·θ = 0.0112 > M_m: torque capped at 4e-3, θ = M_m/k_r.
        for _ in 0..10 {
            out = ContactForce {
                normal: Fx::from_f64(0.01),
                ..ContactForce::default()
            };
            t.apply(&kin(0.1), &mut st, &mut out);
        }
        assert!((out.rolling_torque.y.to_f64() - 4e-3).abs() < 1e-9);
        assert!((st.roll_angle.y.to_f64() - 4e-3 / kr).abs() < 1e-8);
        // Reverse: the spring unloads elastically from the limit (no jump to −M_m).
        out = ContactForce {
            normal: Fx::from_f64(0.01),
            ..ContactForce::default()
        };
        t.apply(&kin(-0.1), &mut st, &mut out);
        let expected = 4e-3 - kr * 1e-3;
        assert!((out.rolling_torque.y.to_f64() - expected).abs() < 1e-8);
    }

    #[test]
    fn dashpot_is_critical_fraction_of_rolling_inertia() {
        // η_r 0.5: C_r = 2·0.5·√(I_r·k_r), I_r 6 g·mm²; torque = k_r·θ + C_r·ω.
        let t = RollingEpsd::<Fx>::new(0.1, 0.5, 10.0);
        let kr = 4.5 * 10.0 * 0.01 * 0.02f64.sqrt() * 16.0;
        let mut st = ContactState::default();
        let mut out = ContactForce {
            normal: Fx::from_f64(1.0),
            ..ContactForce::default()
        };
        t.apply(&kin(0.1), &mut st, &mut out);
        let expected = kr * 1e-3 + (6.0 * kr).sqrt() * 0.1;
        assert!((out.rolling_torque.y.to_f64() / expected - 1.0).abs() < 1e-6);
        // Off value: nothing, no history.
        let mut st = ContactState::default();
        let mut out = ContactForce::default();
        RollingEpsd::<Fx>::new(0.0, 0.5, 10.0).apply(&kin(0.1), &mut st, &mut out);
        assert_eq!(out.rolling_torque, Vec3::ZERO);
        assert_eq!(st, ContactState::default());
    }
}
