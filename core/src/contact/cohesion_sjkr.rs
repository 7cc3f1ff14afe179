//! Simplified JKR cohesion (SJKR, as in LIGGGHTS `cohesion_model sjkr`): an attractive normal
//! force proportional to the contact area, Fc = k·A, with the cohesion energy density k (J/m³)
//! and A = π·a_g², where a_g is the radius of the circle in which the undeformed spheres
//! intersect. For small overlap a_g² = 2R*·α (+ O(α²)); LIGGGHTS evaluates the exact lens
//! formula, which equals this to first order in α. So Fc = 2π·k·R*·α = 2π·k·a² with the Hertz
//! contact radius a = √(R*α).
//!
//! Cohesion acts only while the bodies overlap (no neck, no pull-off hysteresis: the force
//! depends on α only, so it is conservative on its own). It runs **after** the clip and after
//! friction and rolling, so the Coulomb limit and rolling torque keep using the repulsive
//! normal force (LIGGGHTS adds cohesion the same way, after its normal model); the total
//! normal force may then be attractive.

use super::{ContactForce, ContactKinematics, ContactState, ContactTerm};
use crate::num::Scalar;

/// Pa (= J/m³) to N/mm².
const N_PER_MM2_PER_PA: f64 = 1.0e-6;

/// SJKR cohesion. Off value: k = 0 (`on = false`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CohesionSjkr<S> {
    /// Whether the term is active.
    pub on: bool,
    /// 2π·k, N/mm²: the attractive force is coef·a², N.
    pub coef: S,
}

impl<S: Scalar> CohesionSjkr<S> {
    /// Build from the cohesion energy density k, J/m³ (≥ 0).
    pub fn new(energy_density_j_m3: f64) -> Self {
        CohesionSjkr {
            on: energy_density_j_m3 > 0.0,
            coef: S::from_f64(2.0 * core::f64::consts::PI * energy_density_j_m3 * N_PER_MM2_PER_PA),
        }
    }
}

impl<S: Scalar> ContactTerm<S> for CohesionSjkr<S> {
    #[inline(always)]
    fn apply(&self, k: &ContactKinematics<S>, _: &mut ContactState<S>, out: &mut ContactForce<S>) {
        if self.on {
            out.normal -= self.coef * (k.contact_radius * k.contact_radius);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;

    #[test]
    fn force_is_energy_density_times_intersection_area() {
        // k 1e4 J/m³, R* 4 mm, α 5 µm: A = π·2·4·0.005 mm² = 0.12566 mm²,
        // Fc = 1e4·1e-6·0.12566 = 1.2566e-3 N (attractive).
        let (r, alpha) = (4.0, 0.005);
        let k = ContactKinematics {
            contact_radius: Fx::from_f64(r * alpha).sqrt(),
            ..crate::contact::test_kinematics(alpha, 0.0)
        };
        let mut out = ContactForce::default();
        CohesionSjkr::<Fx>::new(1e4).apply(&k, &mut ContactState::default(), &mut out);
        let expected = -1e4 * 1e-6 * core::f64::consts::PI * 2.0 * r * alpha;
        assert!((out.normal.to_f64() / expected - 1.0).abs() < 1e-5);
        let mut out = ContactForce::default();
        CohesionSjkr::<Fx>::new(0.0).apply(&k, &mut ContactState::default(), &mut out);
        assert_eq!(out.normal, Fx::ZERO);
    }
}
