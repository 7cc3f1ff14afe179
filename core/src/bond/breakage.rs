//! Breakage criterion (seed 001 §2.4.1 as read in [`super`]; Potyondy & Cundall eq. (12)):
//!
//! ```text
//! σmax = −Fn/A + 2|Mb|·Rb/J ≥ σc     or     τmax = |Ft|/A + |Mt|·Rb/J ≥ τc
//! ```
//!
//! Fn > 0 is compression, so tension raises σmax. 2Rb/J = Rb/I is precomputed per set.

use super::arena::Bond;
use super::params::BondParams;
use crate::num::Scalar;

/// Which stress reached its critical value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum BreakCriterion {
    /// σmax ≥ σc only.
    #[default]
    Normal,
    /// τmax ≥ τc only.
    Tangential,
    /// Both in the same step.
    Both,
}

impl BreakCriterion {
    /// Stable small integer for digests and files (0 normal, 1 tangential, 2 both).
    pub fn code(self) -> u8 {
        match self {
            BreakCriterion::Normal => 0,
            BreakCriterion::Tangential => 1,
            BreakCriterion::Both => 2,
        }
    }
}

/// The two governing stresses of a bond, MPa.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stresses<S> {
    /// σmax, MPa.
    pub sigma_max: S,
    /// τmax, MPa.
    pub tau_max: S,
}

impl<S: Scalar> Stresses<S> {
    /// The stresses of `bond` under the section constants of `p`.
    #[inline]
    pub fn of(bond: &Bond<S>, p: &BondParams<S>) -> Self {
        let sigma_max =
            -bond.normal_force * p.inv_area + bond.bending_moment.norm() * p.rb_over_inertia;
        let tau_max = bond.tangential_force.norm() * p.inv_area
            + bond.twisting_moment.abs() * p.rb_over_polar;
        Stresses { sigma_max, tau_max }
    }

    /// The criterion met, or `None` while the bond holds.
    #[inline]
    pub fn criterion(&self, p: &BondParams<S>) -> Option<BreakCriterion> {
        match (
            self.sigma_max >= p.normal_strength,
            self.tau_max >= p.tangential_strength,
        ) {
            (false, false) => None,
            (true, false) => Some(BreakCriterion::Normal),
            (false, true) => Some(BreakCriterion::Tangential),
            (true, true) => Some(BreakCriterion::Both),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bond::BondSetSpec;
    use crate::num::Vec3;

    fn params() -> BondParams<f64> {
        BondSetSpec {
            tag: 0,
            normal_stiffness_n_m3: 1e9,
            tangential_stiffness_n_m3: 1e9,
            normal_strength_pa: 1e6,
            tangential_strength_pa: 2e6,
            radius_m: 1e-3,
        }
        .validate()
        .unwrap()
    }

    #[test]
    fn tension_and_compression() {
        let p = params();
        let a = core::f64::consts::PI; // mm²
        let mut b = Bond::<f64> {
            normal_force: -a, // 1 MPa tension
            ..Bond::default()
        };
        let s = Stresses::of(&b, &p);
        assert!((s.sigma_max - 1.0).abs() < 1e-12);
        assert_eq!(s.criterion(&p), Some(BreakCriterion::Normal));
        b.normal_force = a; // compression never breaks by σ
        assert_eq!(Stresses::of(&b, &p).criterion(&p), None);
    }

    #[test]
    fn bending_uses_two_rb_over_j_and_twist_rb_over_j() {
        let p = params();
        let j = core::f64::consts::PI / 2.0; // Rb = 1 mm
        let mut b = Bond::<f64> {
            bending_moment: Vec3::new(0.25 * j, 0.0, 0.0), // σ = 2·0.25 = 0.5 MPa
            twisting_moment: -1.5 * j,                     // τ = 1.5 MPa
            ..Bond::default()
        };
        let s = Stresses::of(&b, &p);
        assert!((s.sigma_max - 0.5).abs() < 1e-12);
        assert!((s.tau_max - 1.5).abs() < 1e-12);
        assert_eq!(s.criterion(&p), None);
        b.twisting_moment = 2.0 * j;
        assert_eq!(
            Stresses::of(&b, &p).criterion(&p),
            Some(BreakCriterion::Tangential)
        );
    }
}
