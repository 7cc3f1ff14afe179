//! Breakage criterion (seed 001 §2.4.1 as read in [`super`]; Potyondy & Cundall eq. (12)):
//!
//! ```text
//! σmax = −Fn/A + 2|Mb|·Rb/J ≥ σc     or     τmax = |Ft|/A + |Mt|·Rb/J ≥ τc
//! ```
//!
//! Fn > 0 is compression, so tension raises σmax. 2Rb/J = Rb/I is precomputed per set.

use super::arena::Bond;
use super::params::BondParams;
use crate::num::{Scalar, Vec3};

/// What a rounded Q32.32 length can exceed the L1 length of its vector by, raw units:
/// √(1.5·2^32) + ½ < 2^17 ([`Stresses::surely_holds`]).
const ROOT_SLACK: u64 = 1 << 17;
/// L1 lengths below 2^14 (N or N·mm) keep |v|² below 2^28, far inside the range, raw.
const LENGTH_RAW: u64 = 1 << (32 + 14);
/// Stress terms below 2^30 MPa, raw: two of them sum inside the range.
const TERM_RAW: u128 = 1 << (32 + 30);

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

    /// The criterion of [`BreakCriterion::code`] (any code above 1 is `Both`).
    pub fn from_code(code: u8) -> Self {
        match code {
            0 => BreakCriterion::Normal,
            1 => BreakCriterion::Tangential,
            _ => BreakCriterion::Both,
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

    /// Whether `bond` surely holds under `p`: an upper bound of each stress, formed without
    /// the two roots of [`Stresses::of`], lies below its strength. Then
    /// [`Stresses::criterion`] is `None` and both stresses are in range, so a caller may skip
    /// [`Stresses::of`] and get the same decision. `false` means "compute them" (always in
    /// floating point, whose roundings the bounds do not cover).
    ///
    /// In raw Q32.32 units: a length |v| = round(√round(v·v)) is at most |x| + |y| + |z| plus
    /// [`ROOT_SLACK`] (the rounded square adds at most half a unit, whose root is below 2^16,
    /// and the rounded root half a unit more); a product with a factor ≥ 0 rounds
    /// monotonically, so bounding the other factor bounds it; the two products without a
    /// root are formed exactly as `Fx` rounds them. Vectors of L1 length 2^14 (N, N·mm) or
    /// more, and terms of 2^30 MPa or more, take the exact path, which also reports any
    /// overflow.
    #[inline(always)]
    pub fn surely_holds(bond: &Bond<S>, p: &BondParams<S>) -> bool {
        if !S::Q32_32 {
            return false;
        }
        let raw = |x: S| x.to_bits() as i64;
        // The overflow poison, i64::MIN, has an L1 length beyond the bound.
        let l1 = |v: Vec3<S>| {
            let a = |x: S| raw(x).unsigned_abs();
            a(v.x).saturating_add(a(v.y)).saturating_add(a(v.z))
        };
        // One widening multiply each: Fx's rounded product.
        let product = |a: i64, b: i64| (a as i128 * b as i128 + (1 << 31)) >> 32;
        let (mb, ft) = (l1(bond.bending_moment), l1(bond.tangential_force));
        let scalars_valid = bond.normal_force.is_valid()
            & bond.twisting_moment.is_valid()
            & p.inv_area.is_valid()
            & p.rb_over_inertia.is_valid()
            & p.rb_over_polar.is_valid();
        let (inv_area, k_bend) = (raw(p.inv_area), raw(p.rb_over_inertia));
        if !(scalars_valid
            & (mb < LENGTH_RAW)
            & (ft < LENGTH_RAW)
            & (inv_area >= 0)
            & (k_bend >= 0))
        {
            return false;
        }
        let slack = |l: u64| (l + ROOT_SLACK) as i64;
        let terms = [
            product(-raw(bond.normal_force), inv_area),
            product(slack(mb), k_bend),
            product(slack(ft), inv_area),
            product(raw(bond.twisting_moment).abs(), raw(p.rb_over_polar)),
        ];
        // Terms inside ±2^30 MPa: every product and sum of the exact path stays in range.
        terms.iter().all(|t| t.unsigned_abs() < TERM_RAW)
            & (terms[0] + terms[1] < raw(p.normal_strength) as i128)
            & (terms[2] + terms[3] < raw(p.tangential_strength) as i128)
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
    use crate::contact::fused::random_contacts::Stream;
    use crate::num::Fx;

    fn params() -> BondParams<f64> {
        params_in()
    }

    fn params_in<S: Scalar>() -> BondParams<S> {
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

    /// A raw Q32.32 value of any magnitude up to `2^(32 + top)`, either sign.
    fn value(x: u64, top: u32) -> Fx {
        let bits = (x >> 58) as u32 % (33 + top); // magnitude below 2^bits raw
        let raw = ((x >> 1) & ((1u64 << bits) - 1)) as i64;
        Fx::from_raw(if x & 1 == 0 { raw } else { -raw })
    }

    #[test]
    fn a_bond_that_surely_holds_does_hold_with_stresses_in_range() {
        let mut stream = Stream(0x2545_F491_4F6C_DD1D);
        let mut next = || stream.bits();
        let base = params_in::<Fx>();
        let (mut sure, mut near) = (0u32, 0u32);
        for i in 0..300_000 {
            let top = (next() % 20) as u32; // magnitudes from 2^-32 to 2^19
            let v = |x: u64, y: u64, z: u64| Vec3::new(value(x, top), value(y, top), value(z, top));
            let mut b = Bond::<Fx> {
                normal_force: value(next(), top),
                twisting_moment: value(next(), top),
                tangential_force: v(next(), next(), next()),
                bending_moment: v(next(), next(), next()),
                ..Bond::default()
            };
            if i % 3 == 0 {
                // Along one axis, where the L1 length is the length: the bound is tight.
                b.bending_moment.y = Fx::ZERO;
                b.bending_moment.z = Fx::ZERO;
                b.tangential_force.x = Fx::ZERO;
                b.tangential_force.y = Fx::ZERO;
            }
            // Strengths a random distance (2^0 to 2^40 raw) above or below the stresses.
            let exact = Stresses::of(&b, &base);
            let shifted = |s: Fx, x: u64| {
                let d = ((x >> 8) & ((1u64 << (x % 41)) - 1)) as i64;
                Fx::from_raw(s.raw().saturating_add(if x & 128 == 0 { d } else { -d }))
            };
            let p = BondParams {
                normal_strength: shifted(exact.sigma_max, next()),
                tangential_strength: shifted(exact.tau_max, next()),
                ..base
            };
            if Stresses::surely_holds(&b, &p) {
                sure += 1;
                assert!(
                    exact.sigma_max.is_valid() && exact.tau_max.is_valid(),
                    "{b:?}"
                );
                assert_eq!(exact.criterion(&p), None, "{b:?} {p:?}");
                // Within 0.1 % of a strength: the bound is tight where it matters.
                let close = |s: Fx, c: Fx| (c - s).to_f64() < 1e-3 * c.to_f64().abs();
                near += (close(exact.sigma_max, p.normal_strength)
                    | close(exact.tau_max, p.tangential_strength)) as u32;
            }
        }
        assert!(sure > 10_000, "{sure}");
        assert!(near > 1_000, "{near}");
    }

    #[test]
    fn a_short_vector_whose_rounded_length_exceeds_its_l1_length_is_not_sure() {
        // |Mb| = 46 341 raw: its rounded square is one raw unit, whose rounded root is
        // 65 536 raw, above the L1 length; σ = |Mb|·1 then reaches a strength of 50 000 raw.
        let p = BondParams::<Fx> {
            rb_over_inertia: Fx::ONE,
            normal_strength: Fx::from_raw(50_000),
            tangential_strength: Fx::ONE,
            ..params_in::<Fx>()
        };
        let b = Bond::<Fx> {
            bending_moment: Vec3::new(Fx::from_raw(46_341), Fx::ZERO, Fx::ZERO),
            ..Bond::default()
        };
        assert_eq!(Stresses::of(&b, &p).sigma_max, Fx::from_raw(65_536));
        assert_eq!(
            Stresses::of(&b, &p).criterion(&p),
            Some(BreakCriterion::Normal)
        );
        assert!(!Stresses::surely_holds(&b, &p));
    }

    #[test]
    fn a_bond_exactly_at_its_strength_is_not_sure() {
        // Tension only, no bending lever: the bound of σ is σ itself.
        let p = BondParams::<Fx> {
            rb_over_inertia: Fx::ZERO,
            ..params_in::<Fx>()
        };
        let b = Bond::<Fx> {
            normal_force: Fx::from_f64(-2.5),
            ..Bond::default()
        };
        let at = BondParams {
            normal_strength: Stresses::of(&b, &p).sigma_max,
            ..p
        };
        assert_eq!(
            Stresses::of(&b, &at).criterion(&at),
            Some(BreakCriterion::Normal)
        );
        assert!(!Stresses::surely_holds(&b, &at));
        let above = BondParams {
            normal_strength: at.normal_strength + Fx::from_raw(1),
            ..p
        };
        assert!(Stresses::surely_holds(&b, &above));
    }
}
