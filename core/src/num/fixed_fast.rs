//! [`FxFast`]: Q32.32 with the bits of [`Fx`] but without overflow checks, and with fast
//! deterministic roots, for the fused contact kernel ([`crate::contact::fused`]).
//!
//! Each operation of [`Fx`] tests its operands for the overflow poison and its result for
//! the range, so that any overflow is reported (DESIGN §4). The fused kernel instead checks a
//! few magnitudes of each contact against an *envelope* ([`Envelope::within`]) inside which
//! no operation can overflow, and falls back to the checked path for a contact outside it: the
//! rule "overflow is never silent" holds, at a few comparisons per contact instead of one per
//! operation. Inside the envelope sums, differences and products are the same bits as
//! [`Fx`]'s.
//!
//! The square root is not: [`Scalar::sqrt`] is X·(1/√X) on the normalised mantissa, from
//! [`Fx`]'s reciprocal root (a 9-bit table and three Newton steps, ≥ 58 correct bits), rounded
//! once, instead of the
//! correctly rounded root with its exact fix-up; it lies within a unit or two of it. It is a
//! fixed sequence of integer operations, so it gives the same bits on every machine.
//!
//! ```
//! use arachis_core::num::{Envelope, Fx, FxFast, Scalar};
//! let x = FxFast::from_f64(2.0);
//! assert!((x.sqrt().to_f64() - 2f64.sqrt()).abs() < 1e-9);
//! assert!((x.rsqrt().to_f64() - 0.5f64.sqrt()).abs() < 1e-9);
//! assert_eq!((x * x).raw(), (Fx::from_f64(2.0) * Fx::from_f64(2.0)).raw());
//! assert!(x.within(2) && !x.within(1));
//! ```

use super::fixed::FRAC_BITS;
use super::scalar::Scalar;
use super::{Fx, Vec3};
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Magnitude tests for the fused kernel's envelope.
pub trait Envelope: Scalar {
    /// `|self| < 2^log2` (false for NaN, ∞ and the overflow poison); `log2` ≤ 30.
    fn within(self, log2: i32) -> bool;
    /// A square root to about 2^-28 relative (0 for x ≤ 0): enough for a stiffness, cheaper
    /// than [`Scalar::sqrt`] in fixed point.
    fn sqrt_coarse(self) -> Self {
        self.sqrt()
    }
    /// The product, and whether it is `within(log2)`. The test sees the exact product even
    /// where the operands are large enough for the product to leave the range.
    fn mul_within(self, o: Self, log2: i32) -> (Self, bool) {
        let p = self * o;
        (p, p.within(log2))
    }
    /// A magnitude at least the largest |component| of `v` and less than twice it, for one
    /// [`Envelope::within`] test of all three components.
    fn magnitude3(v: Vec3<Self>) -> Self {
        v.x.abs().max(v.y.abs()).max(v.z.abs())
    }
    /// The unit vector along `v` to about 2^-28 (`None` for the zero vector).
    fn unit3(v: Vec3<Self>) -> Option<Vec3<Self>> {
        v.normalize_with_len().map(|(u, _)| u)
    }
}

impl Envelope for f64 {
    #[inline(always)]
    fn within(self, log2: i32) -> bool {
        self.abs() < (1u64 << log2) as f64
    }
}

impl Envelope for Fx {
    #[inline(always)]
    fn within(self, log2: i32) -> bool {
        self.raw().unsigned_abs() < 1u64 << (FRAC_BITS as i32 + log2)
    }
}

/// Unchecked Q32.32 (see the module docs).
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default, Debug)]
#[repr(transparent)]
pub struct FxFast(i64);

/// Entries of [`RSQRT_TABLE_FINE`]: one per top-10-bit value 256..=1023 of a normalised input.
const RSQRT_TABLE_FINE_LEN: usize = 768;

/// 1/√X at the midpoints of X ∈ [¼, 1) in 768 bins, in units of 2^-30 (≤ 2^31, fits `u32`):
/// entry i = ⌊√(2^71 / (2(i + 256) + 1))⌋ = 2^30/√((2(i + 256) + 1)/2048), rounded down. Built
/// at compile time with integer arithmetic only. Its relative error is below 2^-10, so two
/// Newton steps give 38 correct bits.
const RSQRT_TABLE_FINE: [u32; RSQRT_TABLE_FINE_LEN] = {
    let mut t = [0u32; RSQRT_TABLE_FINE_LEN];
    let mut i = 0;
    while i < RSQRT_TABLE_FINE_LEN {
        let idx = i as u128 + 256;
        t[i] = ((1u128 << 71) / (2 * idx + 1)).isqrt() as u32;
        i += 1;
    }
    t
};

/// Q2.62 reciprocal square root Y = 1/√X of X = x/2^64 ∈ [¼, 1) (x ≥ 2^62): the 10-bit table
/// value and two Newton steps Y ← Y(3 − XY²)/2 (≥ 38 correct bits), integer multiplications
/// only.
#[inline(always)]
fn rsqrt_q62_fast(x: u64) -> u64 {
    let mut y = (RSQRT_TABLE_FINE[(x >> 54) as usize - 256] as u64) << 32;
    for _ in 0..2 {
        let y2 = (y as u128 * y as u128) >> 62;
        let t = (x as u128 * y2) >> 64;
        let f = (3u128 << 62).saturating_sub(t);
        y = ((y as u128 * f) >> 63) as u64;
    }
    y
}

/// Q30 reciprocal square root 1/√X of X = x/2^64 ∈ [¼, 1) (x ≥ 2^62; result ≤ 2^31): the
/// 10-bit table value and two Newton steps Y ← Y(3 − XY²)/2 in 64-bit products, good to about
/// 2^-28.
#[inline(always)]
pub(crate) fn rsqrt_q30(x: u64) -> u64 {
    let x32 = x >> 32;
    let mut y = RSQRT_TABLE_FINE[(x >> 54) as usize - 256] as u64;
    for _ in 0..2 {
        let y2 = (y * y) >> 30;
        let t = (x32 * y2) >> 32;
        y = (y * (3u64 << 30).saturating_sub(t)) >> 31;
    }
    y
}

/// Half a unit of the last place of a Q64.64 product, for rounding to nearest.
const ROUND_HALF: i128 = 1 << (FRAC_BITS - 1);

impl FxFast {
    /// From raw Q32.32 bits.
    #[inline(always)]
    pub const fn from_raw(raw: i64) -> Self {
        FxFast(raw)
    }
    /// Raw Q32.32 bits.
    #[inline(always)]
    pub const fn raw(self) -> i64 {
        self.0
    }
    #[inline(always)]
    fn round(p: i128) -> FxFast {
        FxFast(((p + ROUND_HALF) >> FRAC_BITS) as i64)
    }
}

impl From<Fx> for FxFast {
    #[inline(always)]
    fn from(x: Fx) -> Self {
        FxFast(x.raw())
    }
}

impl From<FxFast> for Fx {
    #[inline(always)]
    fn from(x: FxFast) -> Self {
        Fx::from_raw(x.0)
    }
}

impl Envelope for FxFast {
    #[inline(always)]
    fn within(self, log2: i32) -> bool {
        self.0.unsigned_abs() < 1u64 << (FRAC_BITS as i32 + log2)
    }
    /// From the top 32 bits of the normalised mantissa, the 10-bit table and two Newton steps
    /// in 64-bit products.
    #[inline(always)]
    fn sqrt_coarse(self) -> Self {
        if self.0 <= 0 {
            return FxFast(0);
        }
        // raw·4^(e/2) = X·2^64 with X = x32/2^32 ∈ [¼, 1); Y = 1/√X and √X = X·Y in Q30.
        let e = self.0.leading_zeros() & !1;
        let x = (self.0 as u64) << e;
        let y = rsqrt_q30(x);
        let root_x = ((x >> 32) * y) >> 32;
        // √(raw·2^32) = √X·2^(48 − e/2), so raw_out = root_x·2^(18 − e/2).
        let half = e / 2;
        FxFast(if half <= 18 {
            (root_x << (18 - half)) as i64
        } else {
            let s = half - 18;
            (((root_x >> (s - 1)) + 1) >> 1) as i64
        })
    }
    /// |x| | |y| | |z| on the raw bits: below twice the largest magnitude, and below 2^k
    /// exactly when every component is.
    #[inline(always)]
    fn magnitude3(v: Vec3<Self>) -> Self {
        FxFast(
            (v.x.0.unsigned_abs() | v.y.0.unsigned_abs() | v.z.0.unsigned_abs())
                .min(i64::MAX as u64) as i64,
        )
    }
    /// Scale `v` exactly (a shift) so that its largest component lies in [2^30, 2^31) raw,
    /// then multiply by the reciprocal root of its squared length ([`rsqrt_q30`]): integer
    /// multiplications only, no division.
    #[inline(always)]
    fn unit3(v: Vec3<Self>) -> Option<Vec3<Self>> {
        let m = v.x.0.unsigned_abs() | v.y.0.unsigned_abs() | v.z.0.unsigned_abs();
        if m == 0 {
            return None;
        }
        // Bring the largest magnitude to [2^30, 2^31): a left shift is exact; a right shift
        // (|v| ≥ 2^-1 raw … only for huge vectors) rounds, which a unit vector does not mind.
        let lz = m.leading_zeros() as i32;
        let scale = |x: i64| -> i64 {
            let k = lz - 33;
            if k >= 0 {
                x << k
            } else {
                let s = (-k) as u32;
                (x + (1 << (s - 1))) >> s
            }
        };
        let u = [scale(v.x.0), scale(v.y.0), scale(v.z.0)];
        // q < 3·2^62 < 2^64 and q ≥ 2^60 (one component ≥ 2^30 after rounding).
        let q = u
            .iter()
            .map(|&c| (c * c) as u64)
            .fold(0u64, u64::wrapping_add);
        let e = q.leading_zeros() & !1; // 0 or 2 (q ≥ 2^60)
        let y = rsqrt_q30(q << e); // 1/√(q·2^e/2^64) in Q30
                                   // û = u/√q = u·y·2^(e/2 − 62); in Q32.32: u·y >> (30 − e/2). u·y < 2^31·2^31.
        let sh = 30 - e / 2;
        let unit = |c: i64| FxFast((c * y as i64 + (1 << (sh - 1))) >> sh);
        Some(Vec3::new(unit(u[0]), unit(u[1]), unit(u[2])))
    }
    #[inline(always)]
    fn mul_within(self, o: Self, log2: i32) -> (Self, bool) {
        // Both raw operands are below 2^63, so the 128-bit product and its rounding are exact.
        let q = (self.0 as i128 * o.0 as i128 + ROUND_HALF) >> FRAC_BITS;
        (
            FxFast(q as i64),
            q.unsigned_abs() < 1u128 << (FRAC_BITS as i32 + log2),
        )
    }
}

impl Add for FxFast {
    type Output = FxFast;
    #[inline(always)]
    fn add(self, o: FxFast) -> FxFast {
        FxFast(self.0.wrapping_add(o.0))
    }
}
impl Sub for FxFast {
    type Output = FxFast;
    #[inline(always)]
    fn sub(self, o: FxFast) -> FxFast {
        FxFast(self.0.wrapping_sub(o.0))
    }
}
impl Neg for FxFast {
    type Output = FxFast;
    #[inline(always)]
    fn neg(self) -> FxFast {
        FxFast(self.0.wrapping_neg())
    }
}
impl Mul for FxFast {
    type Output = FxFast;
    /// Round-to-nearest (ties toward +∞) product, as [`Fx`]'s.
    #[inline(always)]
    fn mul(self, o: FxFast) -> FxFast {
        FxFast::round(self.0 as i128 * o.0 as i128)
    }
}
impl Div for FxFast {
    type Output = FxFast;
    /// [`Fx`]'s division (exact, rounded to nearest; rare in the kernel).
    #[inline]
    fn div(self, o: FxFast) -> FxFast {
        (Fx::from(self) / Fx::from(o)).into()
    }
}
impl AddAssign for FxFast {
    #[inline(always)]
    fn add_assign(&mut self, o: FxFast) {
        *self = *self + o;
    }
}
impl SubAssign for FxFast {
    #[inline(always)]
    fn sub_assign(&mut self, o: FxFast) {
        *self = *self - o;
    }
}

impl Scalar for FxFast {
    type Sum = i64;
    type SumWraps = i32;
    type Fast = FxFast;
    const ZERO: Self = FxFast(0);
    const ONE: Self = FxFast(1 << FRAC_BITS);
    const HALF: Self = FxFast(1 << (FRAC_BITS - 1));
    const NAME: &'static str = "fixed-fast";

    #[inline(always)]
    fn to_fast(self) -> FxFast {
        self
    }
    #[inline(always)]
    fn from_fast(x: FxFast) -> Self {
        x
    }
    // The sums are Fx's, on the same raw integers.
    #[inline(always)]
    fn sum_add(sum: &mut i64, wraps: &mut i32, x: Self) {
        Fx::sum_add(sum, wraps, x.into());
    }
    #[inline(always)]
    fn sum_sub(sum: &mut i64, wraps: &mut i32, x: Self) {
        Fx::sum_sub(sum, wraps, x.into());
    }
    #[inline(always)]
    fn sum_merge(sum: &mut i64, wraps: &mut i32, other: i64, other_wraps: i32) {
        Fx::sum_merge(sum, wraps, other, other_wraps);
    }
    #[inline(always)]
    fn sum_value(sum: i64, wraps: i32) -> Self {
        Fx::sum_value(sum, wraps).into()
    }
    #[inline(always)]
    fn sums_in_range(wraps: &[i32; 7]) -> bool {
        Fx::sums_in_range(wraps)
    }
    #[inline(always)]
    fn sum_low(sum: i64) -> Self {
        Fx::sum_low(sum).into()
    }
    fn from_f64(x: f64) -> Self {
        Fx::from_f64(x).into()
    }
    fn to_f64(self) -> f64 {
        Fx::from(self).to_f64()
    }
    /// √X = X·(1/√X) on the normalised mantissa (module docs), rounded once; 0 for x ≤ 0.
    #[inline(always)]
    fn sqrt(self) -> Self {
        if self.0 <= 0 {
            return FxFast(0);
        }
        // raw·4^(e/2) = X·2^64; √(raw·2^32) = √X·2^(48 − e/2), and x·y >> 64 is √X in Q2.62.
        let e = self.0.leading_zeros() & !1;
        let x = (self.0 as u64) << e;
        let y = rsqrt_q62_fast(x);
        let root_x = ((x as u128 * y as u128) >> 64) as u64;
        let sh = 14 + e / 2;
        FxFast(((root_x >> (sh - 1)) + 1) as i64 >> 1)
    }
    #[inline(always)]
    fn is_valid(self) -> bool {
        Fx::from(self).is_valid()
    }
    fn to_bits(self) -> u64 {
        self.0 as u64
    }
    #[inline(always)]
    fn from_bits(bits: u64) -> Self {
        FxFast(bits as i64)
    }
    #[inline(always)]
    fn mul_int(self, k: i32) -> Self {
        FxFast(self.0.wrapping_mul(k as i64))
    }
    fn floor_i64(self) -> i64 {
        self.0 >> FRAC_BITS
    }
    /// 1/√x from [`rsqrt_q62_fast`]; 0 for x ≤ 0.
    #[inline(always)]
    fn rsqrt(self) -> Self {
        if self.0 <= 0 {
            return FxFast(0);
        }
        // As `Fx::rsqrt`: raw·4^(e/2) = X·2^64, X ∈ [¼, 1), raw_out = Y·2^(16 + e/2).
        let e = self.0.leading_zeros() & !1;
        let y = rsqrt_q62_fast((self.0 as u64) << e);
        let sh = 46 - e / 2;
        FxFast(((y >> (sh - 1)) + 1) as i64 >> 1)
    }
    /// (√x, 1/√x) from one reciprocal root: the pair [`Scalar::sqrt`] and [`Scalar::rsqrt`]
    /// give, at the cost of one.
    #[inline(always)]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        if self.0 <= 0 {
            return (FxFast(0), FxFast(0));
        }
        let e = self.0.leading_zeros() & !1;
        let x = (self.0 as u64) << e;
        let y = rsqrt_q62_fast(x);
        let root_x = ((x as u128 * y as u128) >> 64) as u64;
        let (sh_r, sh_s) = (46 - e / 2, 14 + e / 2);
        (
            FxFast(((root_x >> (sh_s - 1)) + 1) as i64 >> 1),
            FxFast(((y >> (sh_r - 1)) + 1) as i64 >> 1),
        )
    }
    #[inline(always)]
    fn log2_floor(self) -> i32 {
        if self.0 == 0 {
            return 0;
        }
        63 - self.0.unsigned_abs().leading_zeros() as i32 - FRAC_BITS as i32
    }
    /// x·2^k: a left shift (unchecked) or a right shift rounded to nearest, as [`Fx`]'s.
    #[inline(always)]
    fn mul_pow2(self, k: i32) -> Self {
        if k >= 0 {
            FxFast(self.0.wrapping_shl(k as u32))
        } else {
            let s = (-k).min(64) as u32;
            FxFast(((self.0 as i128 + (1i128 << (s - 1))) >> s) as i64)
        }
    }
    #[inline(always)]
    fn dot3(a: Self, b: Self, c: Self, d: Self, e: Self, f: Self) -> Self {
        FxFast::round(
            a.0 as i128 * b.0 as i128 + c.0 as i128 * d.0 as i128 + e.0 as i128 * f.0 as i128,
        )
    }
    #[inline(always)]
    fn mul_sub(a: Self, b: Self, c: Self, d: Self) -> Self {
        FxFast::round(a.0 as i128 * b.0 as i128 - c.0 as i128 * d.0 as i128)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Inside the range, sums, products, dot products and cross terms are Fx's bits.
    #[test]
    fn arithmetic_matches_fx_inside_the_range() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..100_000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Values up to ±2^14 (raw 2^46): products and sums of three stay inside the range.
            let a = (x as i64) >> 17;
            let b = (x.rotate_left(23) as i64) >> 17;
            let (fa, fb) = (Fx::from_raw(a), Fx::from_raw(b));
            let (qa, qb) = (FxFast(a), FxFast(b));
            assert_eq!((qa * qb).raw(), (fa * fb).raw());
            assert_eq!((qa + qb).raw(), (fa + fb).raw());
            assert_eq!((qa - qb).raw(), (fa - fb).raw());
            assert_eq!(
                FxFast::dot3(qa, qb, qb, qa, qa, qa).raw(),
                Fx::dot3(fa, fb, fb, fa, fa, fa).raw()
            );
            assert_eq!(
                FxFast::mul_sub(qa, qb, qb, qb).raw(),
                Fx::mul_sub(fa, fb, fb, fb).raw()
            );
            // A product far outside the range is seen as such, not wrapped back inside.
            let big = FxFast::from_raw(a << 16);
            let (_, inside) = big.mul_within(big, 30);
            assert_eq!(
                inside,
                (Fx::from_raw(a << 16) * Fx::from_raw(a << 16)).within(30)
            );
        }
    }

    /// Both roots are within a few units of the last place (and 2^-37 relative) of Fx's
    /// correctly rounded ones, over 60 binary decades.
    #[test]
    fn fast_roots_are_accurate() {
        let mut v = 1e-9;
        while v < 1e9 {
            // (1e-9 … 1e9: 60 binary decades.)
            for k in 0..37 {
                let x = v * (1.0 + k as f64 / 37.0);
                let q = FxFast::from_f64(x);
                assert_eq!(q.sqrt_rsqrt(), (q.sqrt(), q.rsqrt()));
                let close = |got: i64, exact: i64| (got - exact).abs() <= 2 + (exact.abs() >> 37);
                let r = Fx::from(q).rsqrt().raw();
                assert!(
                    close(q.rsqrt().raw(), r),
                    "rsqrt {x}: {:?} vs {r}",
                    q.rsqrt()
                );
                let s = Fx::from(q).sqrt().raw();
                assert!(close(q.sqrt().raw(), s), "sqrt {x}: {:?} vs {s}", q.sqrt());
            }
            v *= 2.0;
        }
    }
}
