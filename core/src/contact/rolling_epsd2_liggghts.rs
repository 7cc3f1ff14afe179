//! Rolling resistance in LIGGGHTS 3.8's `rolling_friction epsd2` (`src/rolling_model_epsd2.h`,
//! `surfacesIntersect` and `calcRollTorque`): an elastic–plastic spring on the relative spin,
//! kept as a torque in the contact history and updated incrementally,
//!
//! M ← M_old + k_r·dt·ω_t,  k_r = k_t·R*²,  then |M| ≤ μr·|Fn|·R* (M scaled onto the limit),
//!
//! with ω_t the part of ω_i − ω_j in the tangent plane (LIGGGHTS' default `torsionTorque off`),
//! k_t = 8G*·a the tangential stiffness of the Hertz–Mindlin pair (seed 000 eq. (5)'s St,
//! LIGGGHTS' `sidata.kt`), R* = R_iR_j/(R_i + R_j) (against a wall: R_i, and ω_t from ω_i), and
//! Fn the total normal force after the clip (elastic plus damping, LIGGGHTS' `sidata.Fn` with
//! `limitForce on`). The torque on j is +M and on i −M, so the pair conserves angular momentum.
//! There is no dashpot, and the stored torque is neither rotated nor projected when the
//! contact turns: it is reset only when the contact opens. Units: torques in N·mm, k_r in
//! N·mm/rad, spins in rad/ms, dt in ms.
//!
//! Against the core's EPSD effect ([`super::RollingEpsd`], Ai et al. 2011 type C) the limit is
//! the same, but the spring is k_t·R*² instead of 2.25·(2E*a)·μr²·R*², it carries no dashpot,
//! and it keeps a torque rather than an angle (the same while a is constant; LIGGGHTS' form
//! does not unload when the overlap falls). `docs/conventions.md` compares the two.
//!
//! ```
//! use arachis_core::contact::RollingEpsd2Liggghts;
//! let t = RollingEpsd2Liggghts::<f64>::new(0.3, 8.0);
//! assert!(t.on);
//! assert_eq!(t.eight_g_star, 64.0);
//! assert!(!RollingEpsd2Liggghts::<f64>::new(0.0, 8.0).on);
//! ```

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Hertz–Mindlin tangential stiffness factor: k_t = 8G*·a (seed 000 eq. (5)).
const TANGENTIAL_STIFFNESS_FACTOR: f64 = 8.0;

/// LIGGGHTS-convention EPSD2 rolling resistance. Off value: `on = false` (equivalently μr = 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollingEpsd2Liggghts<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Rolling friction coefficient μr (≥ 0), dimensionless.
    pub mu_r: S,
    /// 8·G*, MPa: k_r = this·a·R*², N·mm/rad.
    pub eight_g_star: S,
}

impl<S: Scalar> RollingEpsd2Liggghts<S> {
    /// Build from μr and G*, MPa.
    pub fn new(mu_r: f64, g_star_mpa: f64) -> Self {
        RollingEpsd2Liggghts {
            on: mu_r > 0.0,
            mu_r: S::from_f64(mu_r),
            eight_g_star: S::from_f64(TANGENTIAL_STIFFNESS_FACTOR * g_star_mpa),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for RollingEpsd2Liggghts<S> {
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
        let w_t = k.w_rel.in_plane_of(k.normal);
        let k_r = self.eight_g_star * k.contact_radius * (k.r_star * k.r_star);
        let mut torque = state.roll_torque + w_t.scale(k.dt * k_r);
        let limit = self.mu_r * out.normal.abs() * k.r_star;
        if let Some((unit, len)) = torque.normalize_with_len() {
            if len > limit {
                torque = unit.scale(limit);
            }
        }
        state.roll_torque = torque;
        out.rolling_torque += torque;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Fx, Vec3};

    /// R* 4 mm, dt 0.01 ms, a = √0.02 mm, normal +z; spin (0, w_y, 0.3) rad/ms with a twist.
    fn kin(w_y: f64) -> ContactKinematics<Fx> {
        ContactKinematics {
            dt: Fx::from_f64(1e-2),
            r_star: Fx::from_f64(4.0),
            w_rel: Vec3::new(Fx::ZERO, Fx::from_f64(w_y), Fx::from_f64(0.3)),
            ..crate::contact::test_kinematics(0.005, 0.02f64.sqrt())
        }
    }

    fn force(normal: f64) -> ContactForce<Fx> {
        ContactForce {
            normal: Fx::from_f64(normal),
            ..ContactForce::default()
        }
    }

    #[test]
    fn increments_by_kt_r_star_squared_then_caps_and_unloads_from_the_cap() {
        // G* 1 MPa: k_r = 8·√0.02·16 = 18.1019 N·mm/rad. Fn 0.01 N, μr 0.1, R* 4:
        // limit 4e-3 N·mm. One step at ω 0.01 rad/ms: ΔM = k_r·1e-4 = 1.81e-3 N·mm along +y.
        let t = RollingEpsd2Liggghts::<Fx>::new(0.1, 1.0);
        let k_r = 8.0 * 0.02f64.sqrt() * 16.0;
        let mut st = ContactState::default();
        let mut out = force(0.01);
        t.apply(&kin(0.01), &mut st, &mut out);
        let step = k_r * 1e-4;
        assert!((out.rolling_torque.y.to_f64() / step - 1.0).abs() < 1e-6);
        assert_eq!(out.rolling_torque.x, Fx::ZERO);
        assert_eq!(out.rolling_torque.z, Fx::ZERO, "the twist must not enter");
        assert_eq!(st.roll_torque, out.rolling_torque);
        // Two more steps: 5.43e-3 > 4e-3, so the torque (and the history) sit at the limit.
        for _ in 0..2 {
            out = force(0.01);
            t.apply(&kin(0.01), &mut st, &mut out);
        }
        assert!((out.rolling_torque.y.to_f64() - 4e-3).abs() < 1e-9);
        assert_eq!(st.roll_torque, out.rolling_torque);
        // Reverse spin: elastic unloading from the limit, no jump to −limit.
        out = force(0.01);
        t.apply(&kin(-0.01), &mut st, &mut out);
        assert!((out.rolling_torque.y.to_f64() - (4e-3 - step)).abs() < 1e-8);
    }

    #[test]
    fn off_value_and_no_normal_force_give_no_torque() {
        let mut st = ContactState::default();
        let mut out = force(1.0);
        RollingEpsd2Liggghts::<Fx>::new(0.0, 1.0).apply(&kin(1.0), &mut st, &mut out);
        assert_eq!(out.rolling_torque, Vec3::ZERO);
        assert_eq!(st, ContactState::default());
        // Fn = 0 (a contact whose damping cancels its spring): the limit is zero.
        let t = RollingEpsd2Liggghts::<Fx>::new(0.1, 1.0);
        let mut out = force(0.0);
        t.apply(&kin(1.0), &mut st, &mut out);
        assert_eq!(out.rolling_torque, Vec3::ZERO);
    }
}
