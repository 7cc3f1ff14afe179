//! Rolling friction in LIGGGHTS 3.8's convention (`rolling_friction cdt`,
//! `src/rolling_model_cdt.h`, `surfacesIntersect`):
//!
//! T_j = −T_i = μr·F_el·R*·(ŵ − (ŵ·n̂)n̂),  ŵ = (ω_i − ω_j)/|ω_i − ω_j|,
//!
//! with F_el = (4/3)E*·a·α the elastic part of the normal force only (LIGGGHTS' `kn·deltan`),
//! R* = R_iR_j/(R_i + R_j) and, against a wall, R* = R_i and ŵ = ω̂_i. The part of the torque
//! along the normal (torsion) is removed (LIGGGHTS' default `torsionTorque off`).
//!
//! Unlike EDEM's form ([`super::RollingCdt`], seed 000 eq. (7)) the two torques are equal and
//! opposite, so a pair conserves angular momentum; and nothing stops the torque from reversing
//! the relative spin within a step: near ω_i = ω_j it chatters by μr·F_el·R*·dt/I per step, as
//! LIGGGHTS does.
//!
//! ```
//! use arachis_core::contact::RollingCdtLiggghts;
//! let t = RollingCdtLiggghts::<f64>::new(0.3, 5.0);
//! assert!(t.on);
//! assert!(!RollingCdtLiggghts::<f64>::new(0.0, 5.0).on);
//! ```

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// LIGGGHTS-convention CDT rolling friction. Off value: `on = false` (equivalently μr = 0).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RollingCdtLiggghts<S> {
    /// Whether the term is active.
    pub on: bool,
    /// Rolling friction coefficient μr (≥ 0), dimensionless.
    pub mu_r: S,
    /// (4/3)·E*, MPa: the elastic normal force F_el = (4/3)E*·a·α is this term's own, so that
    /// damping and the clip do not enter the torque (LIGGGHTS' `kn·deltan`).
    pub four_thirds_e_star: S,
}

impl<S: Scalar> RollingCdtLiggghts<S> {
    /// Build from μr and E*, MPa.
    pub fn new(mu_r: f64, e_star_mpa: f64) -> Self {
        RollingCdtLiggghts {
            on: mu_r > 0.0,
            mu_r: S::from_f64(mu_r),
            four_thirds_e_star: S::from_f64(4.0 / 3.0 * e_star_mpa),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for RollingCdtLiggghts<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if !self.on {
            return;
        }
        let Some((w_hat, _)) = k.w_rel.normalize_with_len() else {
            return;
        };
        let rolling = w_hat.in_plane_of(k.normal);
        let elastic = self.four_thirds_e_star * (k.contact_radius * k.overlap);
        out.rolling_torque += rolling.scale(self.mu_r * elastic * k.r_star);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::{Fx, Vec3};

    fn kin(w: [f64; 3]) -> ContactKinematics<Fx> {
        ContactKinematics {
            r_star: Fx::from_f64(2.0),
            w_rel: Vec3::new(Fx::from_f64(w[0]), Fx::from_f64(w[1]), Fx::from_f64(w[2])),
            ..crate::contact::test_kinematics(0.01, 0.02f64.sqrt())
        }
    }

    #[test]
    fn torque_is_mu_r_elastic_force_r_star_along_relative_spin_without_torsion() {
        // E* 6 MPa: F_el = 8·√0.02·0.01 N; μr 0.3, R* 2 mm. The spin has a twisting part
        // along n = +z (0.7), which must not enter: the torque lies along +y alone, with the
        // full magnitude μr·F_el·R* (the unit vector is taken before the normal part is removed,
        // so the magnitude is μr·F_el·R*·|ŵ_t|).
        let t = RollingCdtLiggghts::<Fx>::new(0.3, 6.0);
        let mut out = ContactForce {
            // A damping part in the normal force, which the torque must ignore.
            normal: Fx::from_f64(5.0),
            ..ContactForce::default()
        };
        t.apply(
            &kin([0.0, 0.24, 0.07]),
            &mut ContactState::default(),
            &mut out,
        );
        let elastic = 8.0 * 0.02f64.sqrt() * 0.01;
        let w_t = 0.24 / (0.24f64 * 0.24 + 0.07 * 0.07).sqrt();
        let expected = 0.3 * elastic * 2.0 * w_t;
        let m = out.rolling_torque;
        assert!((m.y.to_f64() / expected - 1.0).abs() < 1e-6, "{m:?}");
        assert_eq!(m.x, Fx::ZERO);
        assert!(m.z.to_f64().abs() < 1e-9);
        // No relative spin: no torque; off value: nothing.
        let mut out = ContactForce::default();
        t.apply(&kin([0.0; 3]), &mut ContactState::default(), &mut out);
        assert_eq!(out.rolling_torque, Vec3::ZERO);
        RollingCdtLiggghts::<Fx>::new(0.0, 6.0).apply(
            &kin([0.0, 1.0, 0.0]),
            &mut ContactState::default(),
            &mut out,
        );
        assert_eq!(out.rolling_torque, Vec3::ZERO);
    }
}
