//! [`BodyForce`]: the force, torque and rolling-resistance sums one step gathers on a body
//! from its contacts, bonds and air drag (gravity excluded: the integrator applies it as the
//! acceleration g itself).
//!
//! The sums live apart from [`super::Body`], in an arena of their own, so that the contact
//! stage can read every body's motion while each part of a threaded step writes only its own
//! accumulator arena. In fixed point each sum is exact ([`crate::num::exact_sum`]: 64 bits
//! and a count of wraps, the integer a 128-bit sum holds), so the total does not depend on
//! the order of the contacts or on how many threads shared them.
//!
//! ```
//! use arachis_core::body::BodyForce;
//! use arachis_core::num::{Fx, Scalar, Vec3};
//! let mut a = BodyForce::<Fx>::default();
//! a.add_force(Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO));
//! let mut b = BodyForce::<Fx>::default();
//! b.sub_force(Vec3::new(Fx::HALF, Fx::ZERO, Fx::ZERO));
//! a.merge(&b);
//! assert_eq!(a.force().x, Fx::HALF);
//! ```

use crate::num::{Scalar, Vec3};

/// Sums of one body's loads in the current step (N, N·mm).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct BodyForce<S: Scalar> {
    /// Force, N, per component.
    pub force: [S::Sum; 3],
    /// Torque about the centre of mass, N·mm, world frame, per component.
    pub torque: [S::Sum; 3],
    /// Rolling-resistance torque magnitude, N·mm, applied along −ω̂ by the integrator.
    pub roll: S::Sum,
    /// What keeps each sum exact ([`Scalar::SumWraps`]): force x, y, z, torque x, y, z, roll.
    /// Kept together, apart from the sums, so that the sums' reads and clears stay dense.
    pub wraps: [S::SumWraps; 7],
}

/// Index of the first force component in [`BodyForce::wraps`].
const FORCE: usize = 0;
/// Index of the first torque component in [`BodyForce::wraps`].
const TORQUE: usize = 3;
/// Index of the rolling-resistance magnitude in [`BodyForce::wraps`].
const ROLL: usize = 6;

#[inline(always)]
fn add3<S: Scalar, const FIRST: usize>(
    sum: &mut [S::Sum; 3],
    wraps: &mut [S::SumWraps; 7],
    v: Vec3<S>,
) {
    S::sum_add(&mut sum[0], &mut wraps[FIRST], v.x);
    S::sum_add(&mut sum[1], &mut wraps[FIRST + 1], v.y);
    S::sum_add(&mut sum[2], &mut wraps[FIRST + 2], v.z);
}

#[inline(always)]
fn value3<S: Scalar, const FIRST: usize>(sum: &[S::Sum; 3], wraps: &[S::SumWraps; 7]) -> Vec3<S> {
    Vec3::new(
        S::sum_value(sum[0], wraps[FIRST]),
        S::sum_value(sum[1], wraps[FIRST + 1]),
        S::sum_value(sum[2], wraps[FIRST + 2]),
    )
}

impl<S: Scalar> BodyForce<S> {
    /// Add a force, N.
    #[inline(always)]
    pub fn add_force(&mut self, f: Vec3<S>) {
        add3::<S, FORCE>(&mut self.force, &mut self.wraps, f);
    }
    /// Subtract a force, N.
    #[inline(always)]
    pub fn sub_force(&mut self, f: Vec3<S>) {
        let w = &mut self.wraps;
        S::sum_sub(&mut self.force[0], &mut w[FORCE], f.x);
        S::sum_sub(&mut self.force[1], &mut w[FORCE + 1], f.y);
        S::sum_sub(&mut self.force[2], &mut w[FORCE + 2], f.z);
    }
    /// Add a torque, N·mm.
    #[inline(always)]
    pub fn add_torque(&mut self, t: Vec3<S>) {
        add3::<S, TORQUE>(&mut self.torque, &mut self.wraps, t);
    }
    /// Add a rolling-resistance torque magnitude, N·mm.
    #[inline(always)]
    pub fn add_roll(&mut self, r: S) {
        S::sum_add(&mut self.roll, &mut self.wraps[ROLL], r);
    }
    /// Add another accumulator (another thread's share of this body).
    #[inline(always)]
    pub fn merge(&mut self, o: &Self) {
        let w = &mut self.wraps;
        for k in 0..3 {
            let f = FORCE + k;
            S::sum_merge(&mut self.force[k], &mut w[f], o.force[k], o.wraps[f]);
            let t = TORQUE + k;
            S::sum_merge(&mut self.torque[k], &mut w[t], o.torque[k], o.wraps[t]);
        }
        S::sum_merge(&mut self.roll, &mut w[ROLL], o.roll, o.wraps[ROLL]);
    }
    /// The force sum, N (invalid components where it overflowed the scalar's range).
    #[inline(always)]
    pub fn force(&self) -> Vec3<S> {
        value3::<S, FORCE>(&self.force, &self.wraps)
    }
    /// The torque sum, N·mm.
    #[inline(always)]
    pub fn torque(&self) -> Vec3<S> {
        value3::<S, TORQUE>(&self.torque, &self.wraps)
    }
    /// The rolling-resistance torque magnitude, N·mm.
    #[inline(always)]
    pub fn roll(&self) -> S {
        S::sum_value(self.roll, self.wraps[ROLL])
    }
    /// The force, torque and rolling-resistance sums at once ([`Self::force`],
    /// [`Self::torque`], [`Self::roll`]): one test of every sum's range, then the sums as
    /// they are, unless a sum left the range (then each is read with its own test).
    #[inline(always)]
    pub fn values(&self) -> Loads<S> {
        if !S::sums_in_range(&self.wraps) {
            return Loads {
                force: self.force(),
                torque: self.torque(),
                roll: self.roll(),
            };
        }
        let v = |s: &[S::Sum; 3]| Vec3::new(S::sum_low(s[0]), S::sum_low(s[1]), S::sum_low(s[2]));
        Loads {
            force: v(&self.force),
            torque: v(&self.torque),
            roll: S::sum_low(self.roll),
        }
    }
}

/// A body's summed loads, read out of its accumulator ([`BodyForce::values`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Loads<S> {
    /// Force, N (invalid components where the sum overflowed).
    pub force: Vec3<S>,
    /// Torque about the centre of mass, N·mm.
    pub torque: Vec3<S>,
    /// Rolling-resistance torque magnitude, N·mm.
    pub roll: S,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;

    /// 2^30 N (or N·mm): three of them leave the fixed-point range (±2^31).
    fn big() -> Fx {
        Fx::from_f64(1_073_741_824.0)
    }

    /// A sum that leaves the range reads as invalid, in `values` as in `force`, and as valid
    /// again once it returns, exactly; the same when its terms arrive in two accumulators
    /// merged afterwards (two threads' shares), and the other sums stay readable meanwhile.
    #[test]
    fn a_sum_out_of_range_is_invalid_until_it_returns_in_any_split() {
        let out = Vec3::new(big(), Fx::ZERO, Fx::ZERO);
        let mut one = BodyForce::<Fx>::default();
        let (mut first, mut second) = (BodyForce::<Fx>::default(), BodyForce::<Fx>::default());
        for _ in 0..3 {
            one.add_force(out);
            first.add_force(out);
        }
        one.add_torque(Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO));
        second.add_torque(Vec3::new(Fx::ONE, Fx::ZERO, Fx::ZERO));
        first.merge(&second);
        for (name, sums) in [("one accumulator", one), ("two merged", first)] {
            let loads = sums.values();
            assert!(!loads.force.x.is_valid(), "{name}: 3·2^30 N read as valid");
            assert_eq!(loads.force.y, Fx::ZERO, "{name}");
            assert_eq!(
                loads.torque.x,
                Fx::ONE,
                "{name}: the torque sum is in range"
            );
            assert_eq!(
                sums.force().x.is_valid(),
                loads.force.x.is_valid(),
                "{name}"
            );
        }
        one.sub_force(out);
        one.sub_force(out);
        let loads = one.values();
        assert_eq!(loads.force.x, big(), "back in range, exactly");
        assert_eq!(
            loads,
            Loads {
                force: one.force(),
                torque: one.torque(),
                roll: one.roll()
            }
        );
    }
}
