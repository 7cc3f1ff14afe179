//! The [`Scalar`] trait: the arithmetic the stepper needs, implemented by [`Fx`](super::Fx)
//! (Q32.32 fixed point) and by `f64` (reference).
//!
//! Invalid values: both implementations have an "invalid" state that propagates through
//! arithmetic like a NaN: `f64` uses NaN/±∞, [`Fx`](super::Fx) uses a poison value produced by
//! any overflowing operation. The stepper checks [`Scalar::is_valid`] once per contact and once
//! per body, so overflow is reported as a typed error and is never silent (DESIGN §4).

use core::fmt::Debug;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Arithmetic used by the stepper. Implemented by [`Fx`](super::Fx) and `f64`.
pub trait Scalar:
    Copy
    + Debug
    + PartialEq
    + PartialOrd
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + Send
    + Sync
    + 'static
{
    /// An accumulator for sums of many values: contact forces are summed in it, in any order
    /// and split over any number of threads. Fixed point: the raw sum in 128 bits, which is
    /// exact and associative, so the total does not depend on the order of the terms or on how
    /// they were split between threads (DESIGN §5). `f64`: an `f64`, whose sum depends on the
    /// order, as in every floating-point engine.
    type Sum: Copy + Debug + Default + PartialEq + Send + Sync + 'static;
    /// What an accumulator keeps beside each [`Scalar::Sum`] to stay exact. Fixed point:
    /// how many times the 64-bit sum wrapped ([`crate::num::exact_sum`]); `f64`: nothing.
    type SumWraps: Copy + Debug + Default + PartialEq + Send + Sync + 'static;
    /// The same numbers with unchecked arithmetic and fast roots, for the fused contact
    /// kernel inside its overflow envelope ([`super::FxFast`] for fixed point; `f64` itself).
    type Fast: super::Envelope;

    /// Additive identity.
    const ZERO: Self;
    /// Multiplicative identity.
    const ONE: Self;
    /// One half (exact in both implementations).
    const HALF: Self;
    /// Short name for messages and dumps ("fixed" or "f64").
    const NAME: &'static str;
    /// Whether the raw bits ([`Scalar::to_bits`]) are a Q32.32 integer (fixed point). Fixed
    /// point then takes the narrow integer kernels (e.g. [`crate::contact::fused`]) and
    /// [`super::Vec3::normalize_with_len`] scales short vectors before normalising them;
    /// floating point keeps its precision anyway.
    const Q32_32: bool = true;

    /// The value as [`Scalar::Fast`] (the same bits).
    fn to_fast(self) -> Self::Fast;
    /// A [`Scalar::Fast`] value back (the same bits).
    fn from_fast(x: Self::Fast) -> Self;
    /// Add a valid value to an accumulator (its sum and wraps).
    fn sum_add(sum: &mut Self::Sum, wraps: &mut Self::SumWraps, x: Self);
    /// Subtract a valid value from an accumulator.
    fn sum_sub(sum: &mut Self::Sum, wraps: &mut Self::SumWraps, x: Self);
    /// Add another accumulator.
    fn sum_merge(
        sum: &mut Self::Sum,
        wraps: &mut Self::SumWraps,
        other: Self::Sum,
        other_wraps: Self::SumWraps,
    );
    /// The accumulated value; invalid when it does not fit the scalar's range.
    fn sum_value(sum: Self::Sum, wraps: Self::SumWraps) -> Self;
    /// Whether every sum whose wraps these are lies in the scalar's range.
    fn sums_in_range(wraps: &[Self::SumWraps; 7]) -> bool;
    /// The value of a sum known to lie in the range ([`Scalar::sums_in_range`]).
    fn sum_low(sum: Self::Sum) -> Self;

    /// Quantise an `f64` (set-up only). Fixed point rounds to nearest; out-of-range or
    /// non-finite input gives the invalid value.
    fn from_f64(x: f64) -> Self;
    /// Convert to `f64` (for reports, dumps and tests; never used while stepping).
    fn to_f64(self) -> f64;
    /// Square root. Fixed point: deterministic integer square root, rounded to nearest.
    /// Negative input gives the invalid value.
    fn sqrt(self) -> Self;
    /// `false` for NaN/∞ (`f64`) or the overflow poison ([`Fx`](super::Fx)).
    fn is_valid(self) -> bool;
    /// Raw bits for the digest (`f64::to_bits` or the Q32.32 raw integer).
    fn to_bits(self) -> u64;
    /// The value with these raw bits (the inverse of [`Scalar::to_bits`]).
    fn from_bits(bits: u64) -> Self;
    /// Multiply by a small integer exactly (used for constant factors such as 2).
    fn mul_int(self, k: i32) -> Self;
    /// Floor to an integer, saturating at the `i64` range (grid binning).
    fn floor_i64(self) -> i64;
    /// Reciprocal square root 1/√x for x > 0 (invalid for x ≤ 0). Fixed point: integer-only
    /// Newton iteration, within one unit of the last place (deterministic, not always the
    /// correctly rounded value); it replaces a square root plus a division.
    fn rsqrt(self) -> Self;
    /// (√x, 1/√x) for x > 0, bit for bit [`Scalar::sqrt`] and [`Scalar::rsqrt`]; fixed point
    /// shares the reciprocal root between both (the root is then corrected exactly), which
    /// saves a 128-bit integer square root per sphere contact.
    #[inline(always)]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        (self.sqrt(), self.rsqrt())
    }
    /// ⌊log₂|x|⌋ for x ≠ 0 (0 for x = 0 or invalid x).
    fn log2_floor(self) -> i32;
    /// x·2^k, exact when the result is representable (fixed point rounds right shifts to
    /// nearest and poisons on overflow).
    fn mul_pow2(self, k: i32) -> Self;

    /// a·b + c·d + e·f with a single rounding in fixed point (exact products summed in 128 bits).
    #[inline(always)]
    fn dot3(a: Self, b: Self, c: Self, d: Self, e: Self, f: Self) -> Self {
        a * b + c * d + e * f
    }
    /// a·b − c·d with a single rounding in fixed point.
    #[inline(always)]
    fn mul_sub(a: Self, b: Self, c: Self, d: Self) -> Self {
        a * b - c * d
    }

    /// Absolute value.
    #[inline]
    fn abs(self) -> Self {
        if self < Self::ZERO {
            -self
        } else {
            self
        }
    }
    /// Larger of two values.
    #[inline]
    fn max(self, other: Self) -> Self {
        if self > other {
            self
        } else {
            other
        }
    }
    /// Smaller of two values.
    #[inline]
    fn min(self, other: Self) -> Self {
        if self < other {
            self
        } else {
            other
        }
    }
}

impl Scalar for f64 {
    type Sum = f64;
    type SumWraps = ();
    type Fast = f64;
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    const HALF: Self = 0.5;
    const NAME: &'static str = "f64";
    const Q32_32: bool = false;

    #[inline(always)]
    fn to_fast(self) -> f64 {
        self
    }
    #[inline(always)]
    fn from_fast(x: f64) -> f64 {
        x
    }
    #[inline(always)]
    fn sum_add(sum: &mut f64, _: &mut (), x: f64) {
        *sum += x;
    }
    #[inline(always)]
    fn sum_sub(sum: &mut f64, _: &mut (), x: f64) {
        *sum -= x;
    }
    #[inline(always)]
    fn sum_merge(sum: &mut f64, _: &mut (), other: f64, _: ()) {
        *sum += other;
    }
    #[inline(always)]
    fn sum_value(sum: f64, _: ()) -> f64 {
        sum
    }
    #[inline(always)]
    fn sums_in_range(_: &[(); 7]) -> bool {
        true
    }
    #[inline(always)]
    fn sum_low(sum: f64) -> f64 {
        sum
    }

    #[inline]
    fn from_f64(x: f64) -> Self {
        x
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self
    }
    #[inline]
    fn sqrt(self) -> Self {
        libm::sqrt(self)
    }
    #[inline]
    fn is_valid(self) -> bool {
        self.is_finite()
    }
    #[inline]
    fn to_bits(self) -> u64 {
        f64::to_bits(self)
    }
    #[inline(always)]
    fn from_bits(bits: u64) -> Self {
        f64::from_bits(bits)
    }
    #[inline]
    fn mul_int(self, k: i32) -> Self {
        self * f64::from(k)
    }
    #[inline]
    fn floor_i64(self) -> i64 {
        libm::floor(self) as i64
    }
    #[inline]
    fn rsqrt(self) -> Self {
        if self > 0.0 {
            1.0 / libm::sqrt(self)
        } else {
            f64::NAN
        }
    }
    #[inline]
    fn log2_floor(self) -> i32 {
        if self == 0.0 || !self.is_finite() {
            return 0;
        }
        libm::frexp(self).1 - 1
    }
    #[inline]
    fn mul_pow2(self, k: i32) -> Self {
        libm::scalbn(self, k)
    }
}
