//! [`Fx`]: Q32.32 fixed point as a newtype over the raw `i64`, with round-to-nearest
//! multiplication, overflow poisoning and a deterministic integer square root.
//!
//! Why a newtype rather than `fixed::types::I32F32` directly: the stepper needs
//! (1) multiplication rounded to nearest (`I32F32`'s `*` floors, a bias that accumulates over
//! ~1e6 steps, DESIGN §4), (2) overflow that neither wraps nor panics but *poisons* the result so
//! that one cheap validity check per contact and per body reports it, and (3) a deterministic
//! integer square root. The bit layout is exactly `I32F32`'s, so [`Fx::from_i32f32`] and
//! [`Fx::to_i32f32`] convert losslessly.
//!
//! Resolution 2⁻³² ≈ 2.3e-10, range ±2.1e9 (in the internal units of [`crate::units`]).
//!
//! ```
//! use arachis_core::num::{Fx, Scalar};
//! let a = Fx::from_f64(1.5);
//! let b = Fx::from_f64(2.0);
//! assert_eq!((a * b).to_f64(), 3.0);
//! assert_eq!(Fx::from_f64(9.0).sqrt().to_f64(), 3.0);
//! // Overflow poisons instead of wrapping:
//! let big = Fx::from_f64(2.0e9);
//! assert!(!(big * big).is_valid());
//! ```

use super::exact_sum;
use super::scalar::Scalar;
use core::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

/// Number of fractional bits.
pub const FRAC_BITS: u32 = 32;
/// Raw value of 1.0.
const ONE_RAW: i64 = 1 << FRAC_BITS;
/// Raw poison value: the result of any overflowing operation; it propagates like a NaN.
const POISON: i64 = i64::MIN;

/// Q32.32 fixed-point number (raw `i64`, value = raw / 2³²). See the module docs.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default)]
#[repr(transparent)]
pub struct Fx(i64);

impl Fx {
    /// The overflow poison.
    pub const POISON: Fx = Fx(POISON);
    /// Largest representable value.
    pub const MAX: Fx = Fx(i64::MAX);

    /// From raw Q32.32 bits.
    #[inline]
    pub const fn from_raw(raw: i64) -> Self {
        Fx(raw)
    }
    /// Raw Q32.32 bits.
    #[inline]
    pub const fn raw(self) -> i64 {
        self.0
    }
    /// From an integer (exact when |i| < 2³¹).
    #[inline]
    pub const fn from_int(i: i32) -> Self {
        Fx((i as i64) << FRAC_BITS)
    }
    /// Lossless conversion from the `fixed` crate's `I32F32` (same bit layout).
    #[inline]
    pub fn from_i32f32(x: fixed::types::I32F32) -> Self {
        Fx(x.to_bits())
    }
    /// Lossless conversion to the `fixed` crate's `I32F32`.
    #[inline]
    pub fn to_i32f32(self) -> fixed::types::I32F32 {
        fixed::types::I32F32::from_bits(self.0)
    }
    /// A Q64.64 product (or sum of products) rounded to nearest Q32.32, poisoned unless it fits.
    /// With q = p + 2^31, the result q >> 32 fits an i64 iff the high word h = q >> 64 fits an
    /// i32: the same test as [`Fx::check`] on the shifted value, in two instructions.
    #[inline(always)]
    fn round_product(p: i128) -> Fx {
        let q = p.wrapping_add(1i128 << (FRAC_BITS - 1));
        let high = (q >> 64) as i64;
        if high != high as i32 as i64 {
            return poisoned();
        }
        Fx((q >> FRAC_BITS) as i64)
    }
    #[inline(always)]
    fn check(r: i128) -> Fx {
        // r fits an i64 iff bits 63..127 are all equal (a result equal to POISON is POISON).
        let lo = r as i64;
        if lo as i128 != r {
            return poisoned();
        }
        Fx(lo)
    }
}

/// The poison, returned from a cold function so that the overflow tests compile to branches
/// the processor predicts as not taken, rather than to conditional moves: a conditional move
/// puts each test on the value's dependency chain, a branch takes it off.
#[cold]
#[inline(never)]
fn poisoned() -> Fx {
    Fx::POISON
}

impl core::fmt::Debug for Fx {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.0 == POISON {
            write!(f, "Fx(POISON)")
        } else {
            write!(f, "Fx({})", self.to_f64())
        }
    }
}

impl Add for Fx {
    type Output = Fx;
    #[inline(always)]
    fn add(self, rhs: Fx) -> Fx {
        let (r, o) = self.0.overflowing_add(rhs.0);
        if o | (self.0 == POISON) | (rhs.0 == POISON) {
            return poisoned();
        }
        Fx(r)
    }
}
impl Sub for Fx {
    type Output = Fx;
    #[inline(always)]
    fn sub(self, rhs: Fx) -> Fx {
        let (r, o) = self.0.overflowing_sub(rhs.0);
        // A result equal to POISON is POISON already.
        if o | (self.0 == POISON) | (rhs.0 == POISON) {
            return poisoned();
        }
        Fx(r)
    }
}
impl Neg for Fx {
    type Output = Fx;
    #[inline(always)]
    fn neg(self) -> Fx {
        // -POISON would overflow; POISON stays POISON.
        Fx(self.0.checked_neg().unwrap_or(POISON))
    }
}
impl Mul for Fx {
    type Output = Fx;
    /// Round-to-nearest (ties toward +∞) product, poisoned on overflow.
    #[inline(always)]
    fn mul(self, rhs: Fx) -> Fx {
        if (self.0 == POISON) | (rhs.0 == POISON) {
            return poisoned();
        }
        let p = (self.0 as i128) * (rhs.0 as i128);
        Fx::round_product(p)
    }
}
impl Div for Fx {
    type Output = Fx;
    /// Quotient rounded to nearest (ties away from zero); division by zero poisons.
    #[inline]
    fn div(self, rhs: Fx) -> Fx {
        if (self.0 == POISON) | (rhs.0 == POISON) | (rhs.0 == 0) {
            return Fx::POISON;
        }
        let neg = (self.0 < 0) != (rhs.0 < 0);
        let un = (self.0.unsigned_abs() as u128) << FRAC_BITS;
        let ud = rhs.0.unsigned_abs() as u128;
        // Quotients of 2^63 or more overflow; checking first keeps t·ud < 2^127 below.
        if un >= ud << 63 {
            return Fx::POISON;
        }
        let (t, rem) = udivrem(un, ud);
        let q = t + (2 * rem >= ud) as u128;
        Fx::check(if neg { -(q as i128) } else { q as i128 })
    }
}

/// Exact truncated quotient and remainder of `un / ud` (requires `un < ud · 2^63`), by
/// integer division. (An `f64`-estimate variant was measured slower: 42 ns against 18–20 ns
/// for the 128-bit integer division on this machine, so division is integer-only.)
///
/// On x86-64, a divisor below 2^64 with a quotient below 2^64 (every `Fx` division) takes
/// the processor's 128-by-64-bit `div` ([`div_wide`]) instead of the library's general
/// 128-bit division, a call that was 5 % of the host's scenario tests (the checked contact
/// terms divide for R*, m* and the Coulomb limit). Both are exact, so the bits are the same.
#[inline(always)]
pub fn udivrem(un: u128, ud: u128) -> (u128, u128) {
    #[cfg(target_arch = "x86_64")]
    if ud >> 64 == 0 && (un >> 64) < ud {
        let (q, r) = div_wide(un, ud as u64);
        return (q as u128, r as u128);
    }
    let t = un / ud;
    (t, un - t * ud)
}

/// Quotient and remainder of `un / d` by one `div` instruction; requires `un >> 64 < d`
/// (so that d ≠ 0 and the quotient fits 64 bits, the two cases in which `div` faults).
#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn div_wide(un: u128, d: u64) -> (u64, u64) {
    let (q, r): (u64, u64);
    // SAFETY: `div` divides rdx:rax by `d`, leaving the quotient in rax and the remainder in
    // rdx; it touches no memory, and the caller's bound rules out both faults.
    unsafe {
        core::arch::asm!(
            "div {d}",
            d = in(reg) d,
            inout("rax") un as u64 => q,
            inout("rdx") (un >> 64) as u64 => r,
            options(pure, nomem, nostack),
        );
    }
    (q, r)
}

impl AddAssign for Fx {
    #[inline(always)]
    fn add_assign(&mut self, rhs: Fx) {
        *self = *self + rhs;
    }
}
impl SubAssign for Fx {
    #[inline(always)]
    fn sub_assign(&mut self, rhs: Fx) {
        *self = *self - rhs;
    }
}

/// Integer square root of a `u128`, rounded to nearest: the unique r with
/// (r − ½)² ≤ v < (r + ½)².
///
/// By default the root is integer-only (stepping is integer-only, DESIGN §5): the
/// multiplication-only [`isqrt_round_u64`] below 2^64, [`isqrt_round_wide`] from 2^64 to
/// 2^[`WIDE_ROOT_BITS`], and `core`'s `isqrt` above.
/// With the `float-estimate` feature an `f64` estimate is corrected to the exact integer root
/// with integer multiply-and-compare, so the result does not depend on the estimate. Tests
/// check both agree.
#[inline]
pub fn isqrt_round_u128(v: u128) -> u128 {
    #[cfg(not(feature = "float-estimate"))]
    {
        if v <= u64::MAX as u128 {
            return isqrt_round_u64(v as u64) as u128;
        }
        if v >> WIDE_ROOT_BITS == 0 {
            return isqrt_round_wide(v);
        }
    }
    round_floor_root(v, isqrt_floor_u128(v))
}

/// [`isqrt_round_wide`] takes v below 2^WIDE_ROOT_BITS, so that its guess stays below 2^60,
/// inside the branch-free finish of [`round_root_from_guess`].
#[cfg_attr(feature = "float-estimate", allow(dead_code))]
const WIDE_ROOT_BITS: u32 = 2 * NEAREST_ROOT_GUESS_BITS;

/// [`isqrt_round_u128`] for 2^64 ≤ v < 2^[`WIDE_ROOT_BITS`] with multiplications only. Every
/// `Fx` root of a value of 1 or more lands here (v = raw·2^32), among them each bond's length
/// and each checked contact's distance; `core`'s `isqrt` took a chain of 128-bit divisions.
///
/// With the top 64 bits x ∈ [2^62, 2^64) of v·4^h, X = x/2^64: [`rsqrt_q62`] gives
/// Y ≈ 2^62/√X to about 2^-60, so √(x·2^64) = x·Y/2^62 and √v ≈ x·Y/2^(62 + h), within a
/// fraction of a unit for v < 2^120 (the 64 dropped low bits change the root by less than
/// 2^-32 of it). [`round_root_from_guess`] finishes exactly, so the result never depends on
/// the estimate.
#[inline(always)]
#[cfg_attr(feature = "float-estimate", allow(dead_code))]
fn isqrt_round_wide(v: u128) -> u128 {
    round_root_from_guess(v, wide_root_guess(v))
}

/// The estimate of [`isqrt_round_wide`]: x·Y/2^(62 + h).
#[inline(always)]
#[cfg_attr(feature = "float-estimate", allow(dead_code))]
fn wide_root_guess(v: u128) -> u128 {
    let h = v.leading_zeros() / 2;
    let x = ((v << (2 * h)) >> 64) as u64;
    (x as u128 * rsqrt_q62(x) as u128) >> (62 + h)
}

/// The rounded root from the floor root r = ⌊√v⌋: (r + ½)² = r² + r + ¼, so round up when
/// v − r² > r.
#[inline(always)]
fn round_floor_root(v: u128, r: u128) -> u128 {
    if v - r * r > r {
        r + 1
    } else {
        r
    }
}

/// The rounded root of [`isqrt_round_u128`] from a guess `r < 2^63` that is usually within
/// two units of it (see [`nearest_root`]); any other guess takes the exact stepping of
/// [`round_root_from_far_guess`], so the result never depends on the guess.
#[inline(always)]
fn round_root_from_guess(v: u128, r: u128) -> u128 {
    if r >> NEAREST_ROOT_GUESS_BITS != 0 {
        return round_root_from_far_guess(v, r);
    }
    // |v − r²| < 2^127 for r < 2^63 and v < 2^126, so the wrapped difference is exact; a
    // residual beyond the i64 range is far from any guess within two units.
    let d = v.wrapping_sub(r.wrapping_mul(r)) as i128;
    let d = d.clamp(i64::MIN as i128, i64::MAX as i128) as i64;
    match nearest_root(d, r as i64) {
        Some(root) => root as u128,
        None => round_root_from_far_guess(v, r),
    }
}

/// Guesses below 2^60 keep the bounds 5r + 6 of [`nearest_root`] inside i64.
const NEAREST_ROOT_GUESS_BITS: u32 = 60;

/// The rounded root r' of v from a guess 0 ≤ r < 2^60 and its residual d = v − r², if r' is
/// within two units of r. The rounded root is the r' with r'² − r' < v ≤ r'² + r', so it is
/// r + 1 for r < d ≤ 3r + 2, r + 2 for 3r + 2 < d ≤ 5r + 6, and likewise below: exact integer
/// comparisons, made without branches, because a guess's last unit is random and a branch on
/// it is mispredicted often.
#[inline(always)]
pub(crate) fn nearest_root(d: i64, r: i64) -> Option<i64> {
    if d <= 6 - 5 * r || d > 5 * r + 6 {
        return None;
    }
    let up = (d > r) as i64 + (d > 3 * r + 2) as i64;
    let down = (d <= -r) as i64 + (d <= 2 - 3 * r) as i64;
    Some(r + up - down)
}

/// [`round_root_from_guess`] for a guess more than two units off (or r < 2): stepped down
/// while r² > v and up while (r + 1)² ≤ v, then rounded.
#[cold]
#[inline(never)]
fn round_root_from_far_guess(v: u128, mut r: u128) -> u128 {
    while r * r > v {
        r -= 1;
    }
    while (r + 1) * (r + 1) <= v {
        r += 1;
    }
    round_floor_root(v, r)
}

/// ⌊√v⌋ for `v < 2^126`, exact.
#[inline(always)]
pub fn isqrt_floor_u128(v: u128) -> u128 {
    #[cfg(not(feature = "float-estimate"))]
    {
        if v <= u64::MAX as u128 {
            (v as u64).isqrt() as u128
        } else {
            v.isqrt()
        }
    }
    #[cfg(feature = "float-estimate")]
    {
        // v = raw·2^32 in Fx use; estimate √v = √(v/2^32)·2^16 with hardware conversions.
        let mut r = if v >> 64 == 0 {
            libm::sqrt(v as u64 as f64) as u64 as u128
        } else if v >> 96 == 0 {
            (libm::sqrt((v >> 32) as u64 as f64) * 65_536.0) as u64 as u128
        } else {
            libm::sqrt(v as f64) as u128
        };
        while r * r > v {
            r -= 1;
        }
        while (r + 1) * (r + 1) <= v {
            r += 1;
        }
        r
    }
}

/// Entries of [`RSQRT_TABLE`]: one per top-8-bit value 64..=255 of a normalised input.
const RSQRT_TABLE_LEN: usize = 192;

/// 1/√X at the midpoints of X ∈ [¼, 1) in 192 bins, in units of 2^-14 (≤ 2^15, fits `u16`):
/// entry i = ⌊√(2^37 / (2(i + 64) + 1))⌋, i.e. 2^14/√((2(i + 64) + 1)/512). Built at compile
/// time with integer arithmetic only.
const RSQRT_TABLE: [u16; RSQRT_TABLE_LEN] = {
    let mut t = [0u16; RSQRT_TABLE_LEN];
    let mut i = 0;
    while i < RSQRT_TABLE_LEN {
        let idx = i as u64 + 64;
        t[i] = ((1u64 << 37) / (2 * idx + 1)).isqrt() as u16;
        i += 1;
    }
    t
};

/// [`isqrt_round_u128`] for a `u64`, with multiplications and comparisons only (the `isqrt`
/// of `core` takes three hardware divisions, and this root is on every contact's path twice:
/// a = √(R*α) and √(a·m*), seed 000 eqs. (2), (4)).
///
/// With v = x/4^h, x ∈ [2^62, 2^64), X = x/2^64: the [`RSQRT_TABLE`] value t₀ ≈ 2^30/√X
/// (≈ 9 bits) and one Newton step t₁ = t₀(3 − X·t₀²)/2 (≈ 17 bits) give the guess
/// r ≈ x·t₁/2^62 >> h ≈ √v, and one residual step r ← r + (v − r²)/(2√v), with
/// 1/(2√v) = t₁·2^h/2^63, brings it within two units of the root (all but 31 of 5·10^7
/// random inputs above 2^32), which [`round_root_from_guess`] finishes exactly.
#[inline(always)]
#[cfg_attr(feature = "float-estimate", allow(dead_code))]
fn isqrt_round_u64(v: u64) -> u64 {
    if v == 0 {
        return 0;
    }
    let half = v.leading_zeros() / 2;
    let x = v << (2 * half);
    let t0 = (RSQRT_TABLE[(x >> 56) as usize - 64] as u64) << 16; // Q30, ≤ 2^31
    let t0_sq = (t0 * t0) >> 30; // Q30, ≤ 2^32
    let x_t0_sq = ((x >> 32) * t0_sq) >> 32; // X·t₀², Q30, < 3·2^30
    let t1 = (t0 * ((3u64 << 30) - x_t0_sq)) >> 31; // Q30, < 2^31

    // x·4t₁/2^64 = x·t₁/2^62 ≈ √x; shifted by h, ≈ √v (< 2^33).
    let r = (((x as u128 * (t1 << 2) as u128) >> 64) as u64 >> half) as i64;
    // |v − r²| < 2^50 here (r is within 2^-16 of √v) and < 2^36 after the step (within a few
    // units), so the wrapped difference is exact; its shift by h + 1 stays below 2^52.
    let residual = |r: i64| v.wrapping_sub((r as u64).wrapping_mul(r as u64)) as i64;
    let r = r + ((((residual(r) << (half + 1)) as i128 * t1 as i128) >> 64) as i64);
    // The finish of `round_root_from_guess`, in 64-bit arithmetic: calling that u128 function
    // measured 15 % slower in `contact_roots` (236 vs 205 ns).
    match nearest_root(residual(r), r) {
        Some(root) => root as u64,
        None => round_root_from_far_guess(v as u128, r.max(0) as u128) as u64,
    }
}

/// Q2.62 reciprocal square root Y = 1/√X of X = x/2^64 ∈ [¼, 1) (x ≥ 2^62), with integer
/// multiplications only: the table value (≈ 9 bits) refined by three Newton steps
/// Y ← Y(3 − XY²)/2 (9 → 17 → 34 → ≥ 60 bits; each step only moves Y towards 1/√X from
/// below, so Y ≤ 2 and no product overflows).
#[inline(always)]
fn rsqrt_q62(x: u64) -> u64 {
    let mut y = (RSQRT_TABLE[(x >> 56) as usize - 64] as u64) << 48;
    for _ in 0..3 {
        let y2 = (y as u128 * y as u128) >> 62;
        let t = (x as u128 * y2) >> 64;
        let f = (3u128 << 62).saturating_sub(t);
        y = ((y as u128 * f) >> 63) as u64;
    }
    y
}

impl Scalar for Fx {
    /// Raw Q32.32 values summed exactly: the sum's low 64 bits here and how many times it
    /// wrapped in [`Scalar::SumWraps`] ([`exact_sum`]), the integer a 128-bit sum holds.
    /// Integer addition is associative, so the sum does not depend on the order of its terms.
    type Sum = i64;
    type SumWraps = i32;
    type Fast = super::FxFast;
    const ZERO: Self = Fx(0);
    const ONE: Self = Fx(ONE_RAW);
    const HALF: Self = Fx(ONE_RAW / 2);
    const NAME: &'static str = "fixed";

    #[inline(always)]
    fn to_fast(self) -> super::FxFast {
        self.into()
    }
    #[inline(always)]
    fn from_fast(x: super::FxFast) -> Fx {
        x.into()
    }
    #[inline(always)]
    fn sum_add(sum: &mut i64, wraps: &mut i32, x: Fx) {
        exact_sum::add(sum, wraps, x.0);
    }
    #[inline(always)]
    fn sum_sub(sum: &mut i64, wraps: &mut i32, x: Fx) {
        exact_sum::sub(sum, wraps, x.0);
    }
    #[inline(always)]
    fn sum_merge(sum: &mut i64, wraps: &mut i32, other: i64, other_wraps: i32) {
        exact_sum::merge(sum, wraps, other, other_wraps);
    }
    #[inline(always)]
    fn sum_value(sum: i64, wraps: i32) -> Fx {
        match exact_sum::value(sum, wraps) {
            Some(v) => Fx(v),
            // A branch to the cold poison, not a conditional move (see `poisoned`).
            None => poisoned(),
        }
    }
    #[inline(always)]
    fn sums_in_range(wraps: &[i32; 7]) -> bool {
        exact_sum::none_wrapped(wraps)
    }
    #[inline(always)]
    fn sum_low(sum: i64) -> Fx {
        Fx(sum)
    }

    fn from_f64(x: f64) -> Self {
        let s = libm::round(x * ONE_RAW as f64);
        // 2^63 is exactly representable; anything at or beyond it (or NaN) poisons.
        if !(s > -9.223_372_036_854_775e18 && s < 9.223_372_036_854_775e18) {
            return Fx::POISON;
        }
        Fx(s as i64)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        if self.0 == POISON {
            f64::NAN
        } else {
            self.0 as f64 / ONE_RAW as f64
        }
    }
    #[inline]
    fn sqrt(self) -> Self {
        if self.0 < 0 {
            return Fx::POISON;
        }
        let v = (self.0 as u128) << FRAC_BITS;
        Fx(isqrt_round_u128(v) as i64)
    }
    #[inline(always)]
    fn is_valid(self) -> bool {
        self.0 != POISON
    }
    #[inline]
    fn to_bits(self) -> u64 {
        self.0 as u64
    }
    #[inline(always)]
    fn from_bits(bits: u64) -> Self {
        Fx(bits as i64)
    }
    #[inline]
    fn mul_int(self, k: i32) -> Self {
        if self.0 == POISON {
            return Fx::POISON;
        }
        Fx::check(self.0 as i128 * k as i128)
    }
    #[inline(always)]
    fn dot3(a: Self, b: Self, c: Self, d: Self, e: Self, f: Self) -> Self {
        let any_poison = (a.0 == POISON)
            | (b.0 == POISON)
            | (c.0 == POISON)
            | (d.0 == POISON)
            | (e.0 == POISON)
            | (f.0 == POISON);
        let p1 = a.0 as i128 * b.0 as i128;
        let p2 = c.0 as i128 * d.0 as i128;
        let p3 = e.0 as i128 * f.0 as i128;
        // |p| ≤ 2^126: the sum of three can exceed i128 only for operands near the range limits.
        let (s, o1) = p1.overflowing_add(p2);
        let (s, o2) = s.overflowing_add(p3);
        if any_poison | o1 | o2 {
            return poisoned();
        }
        Fx::round_product(s)
    }
    #[inline(always)]
    fn mul_sub(a: Self, b: Self, c: Self, d: Self) -> Self {
        let any_poison = (a.0 == POISON) | (b.0 == POISON) | (c.0 == POISON) | (d.0 == POISON);
        let p1 = a.0 as i128 * b.0 as i128;
        let p2 = c.0 as i128 * d.0 as i128;
        // |p1 − p2| ≤ 2^127 overflows only at exactly −2^63·−2^63 − …, excluded by POISON.
        let (s, o) = p1.overflowing_sub(p2);
        if any_poison | o {
            return poisoned();
        }
        Fx::round_product(s)
    }
    #[inline(always)]
    fn floor_i64(self) -> i64 {
        self.0 >> FRAC_BITS
    }
    /// raw_out = 2^48/√raw: with raw·4^(e/2) = X·2^64 (X ∈ [¼, 1)), 1/√raw = Y·2^(e/2 − 32),
    /// so raw_out = Y·2^(16 + e/2) = y_q62 >> (46 − e/2), rounded to nearest. Y carries ≥ 60
    /// correct bits and the result at most 48, so it is within one unit of 2^48/√raw.
    #[inline]
    fn rsqrt(self) -> Self {
        if self.0 <= 0 {
            return Fx::POISON;
        }
        let e = self.0.leading_zeros() & !1;
        let x = (self.0 as u64) << e;
        let y = rsqrt_q62(x);
        let sh = 46 - e / 2;
        Fx(((y >> (sh - 1)) + 1) as i64 >> 1)
    }
    /// One [`rsqrt_q62`] serves both: the reciprocal root exactly as [`Scalar::rsqrt`], and
    /// the root from √X = X·Y (x·y >> 64 is √X in Q2.62; √(raw·2³²) = √X·2^(48 − e/2), so
    /// shifting right by 14 + e/2 gives it to within a few units), then corrected exactly to
    /// the rounded integer root of [`Scalar::sqrt`].
    #[inline]
    fn sqrt_rsqrt(self) -> (Self, Self) {
        if self.0 <= 0 {
            return (self.sqrt(), self.rsqrt());
        }
        let e = self.0.leading_zeros() & !1;
        let x = (self.0 as u64) << e;
        let y = rsqrt_q62(x);
        let sh = 46 - e / 2;
        let rsqrt = Fx(((y >> (sh - 1)) + 1) as i64 >> 1);
        let sx = ((x as u128 * y as u128) >> 64) as u64;
        let guess = (sx >> (14 + e / 2)) as u128;
        let v = (self.0 as u128) << FRAC_BITS;
        (Fx(round_root_from_guess(v, guess) as i64), rsqrt)
    }
    #[inline]
    fn log2_floor(self) -> i32 {
        if self.0 == 0 || self.0 == POISON {
            return 0;
        }
        63 - self.0.unsigned_abs().leading_zeros() as i32 - FRAC_BITS as i32
    }
    #[inline]
    fn mul_pow2(self, k: i32) -> Self {
        if self.0 == POISON {
            return Fx::POISON;
        }
        if k >= 0 {
            if k >= 63 {
                return if self.0 == 0 { self } else { Fx::POISON };
            }
            Fx::check((self.0 as i128) << k)
        } else {
            let s = (-k).min(64) as u32;
            Fx(((self.0 as i128 + (1i128 << (s - 1))) >> s) as i64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Marsaglia's xorshift64: a cheap deterministic stream of test operands.
    fn xorshift(mut x: u64) -> u64 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    }

    #[test]
    fn mul_rounds_to_nearest() {
        // 2^-32 * 0.5 = 2^-33 → ties round up to 2^-32; 2^-32 * 0.25 → 0.
        let eps = Fx::from_raw(1);
        assert_eq!((eps * Fx::from_f64(0.5)).raw(), 1);
        assert_eq!((eps * Fx::from_f64(0.25)).raw(), 0);
        assert_eq!((Fx::from_raw(-1) * Fx::from_f64(0.25)).raw(), 0);
        assert_eq!((Fx::from_f64(-1.5) * Fx::from_f64(2.0)).to_f64(), -3.0);
    }

    #[test]
    fn round_product_matches_the_shift_then_check_definition() {
        // Reference: add ½ unit, shift, keep the result only if it fits an i64.
        let reference = |p: i128| match p.checked_add(1 << (FRAC_BITS - 1)) {
            Some(q) => Fx::check(q >> FRAC_BITS),
            None => Fx::POISON,
        };
        let unit = 1i128 << FRAC_BITS;
        let check = |p: i128| assert_eq!(Fx::round_product(p), reference(p), "{p}");
        for base in [0, i64::MAX as i128, i64::MIN as i128, i64::MAX as i128 + 1] {
            for d in -2..=2 {
                // Products whose rounded quotient is base + d, and the rounding ties around it.
                let q = (base + d) * unit;
                [q, q - unit / 2, q - unit / 2 - 1, q + unit / 2 - 1]
                    .into_iter()
                    .for_each(check);
            }
        }
        [i128::MAX, i128::MIN, i128::MAX - unit / 2, i128::MIN + 1]
            .into_iter()
            .for_each(check);
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let randoms = (0..200_000u32).map(|k| {
            x = xorshift(x);
            let a = (x as i64) >> (k % 64);
            let b = (x.rotate_left(29) as i64) >> ((k / 64) % 64);
            a as i128 * b as i128
        });
        randoms.for_each(check);
    }

    #[test]
    fn div_rounds_and_poisons() {
        assert_eq!((Fx::from_int(1) / Fx::from_int(4)).to_f64(), 0.25);
        assert_eq!((Fx::from_int(-7) / Fx::from_int(2)).to_f64(), -3.5);
        let third = Fx::from_int(1) / Fx::from_int(3);
        assert!((third.to_f64() - 1.0 / 3.0).abs() < 2.4e-10);
        assert!(!(Fx::ONE / Fx::ZERO).is_valid());
    }

    #[test]
    fn overflow_poisons_and_propagates() {
        let big = Fx::from_int(i32::MAX);
        assert!(!(big + big).is_valid());
        assert!(!(-big - big - big).is_valid());
        assert!(!(big * big).is_valid());
        let p = Fx::POISON;
        assert!(!(p * Fx::ZERO).is_valid());
        assert!(!(p + Fx::ONE).is_valid());
        assert!(!(-p).is_valid());
        assert!(!Fx::from_f64(f64::NAN).is_valid());
        assert!(!Fx::from_f64(3e9).is_valid());
    }

    #[test]
    fn fused_products_round_once() {
        let v = [1.25, -3.5, 0.000_123, 7.0, -0.5, 2.0];
        let f = v.map(Fx::from_f64);
        let exact = v[0] * v[1] + v[2] * v[3] + v[4] * v[5];
        let got = Fx::dot3(f[0], f[1], f[2], f[3], f[4], f[5]).to_f64();
        let q = f.map(|x| x.to_f64());
        let exact_q = q[0] * q[1] + q[2] * q[3] + q[4] * q[5];
        assert!(
            (got - exact_q).abs() <= 0.5 * 2f64.powi(-32) + 1e-15,
            "{got} {exact} {exact_q}"
        );
        let ms = Fx::mul_sub(f[0], f[1], f[2], f[3]).to_f64();
        assert!((ms - (q[0] * q[1] - q[2] * q[3])).abs() <= 0.5 * 2f64.powi(-32) + 1e-15);
        let big = Fx::from_int(i32::MAX);
        assert!(!Fx::dot3(big, big, big, big, big, big).is_valid());
        assert!(!Fx::mul_sub(big, big, -big, big).is_valid());
        assert!(!Fx::dot3(Fx::POISON, Fx::ZERO, Fx::ONE, Fx::ONE, Fx::ONE, Fx::ONE).is_valid());
    }

    #[test]
    fn fast_paths_match_integer_reference() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for k in 0..200_000u32 {
            x = xorshift(x);
            let v = ((x as u128) << (k % 63)) | (k as u128);
            assert_eq!(isqrt_floor_u128(v), v.isqrt(), "sqrt {v}");
            let d = ((x >> (k % 61)) | 1) as u128;
            let n = v % (d << 63);
            assert_eq!(udivrem(n, d), (n / d, n % d), "{n} / {d}");
            // The edge of the hardware division: a high word just below the divisor, and
            // divisors of 2^64 and more (the general division).
            let n = ((d - 1) << 64) | x as u128;
            assert_eq!(udivrem(n, d), (n / d, n % d), "{n} / {d}");
            let wide = (d << 64) | 1;
            let n = v | (1 << 127);
            assert_eq!(udivrem(n, wide), (n / wide, n % wide), "{n} / {wide}");
        }
    }

    #[test]
    fn wide_root_is_exact_at_squares_and_between() {
        // 2^64 ≤ v < 2^120 (the bond lengths and checked contact distances of `Fx::sqrt`):
        // k² − k, k², k² + k, k² + k + 1 around each power of two and 10^6 random roots
        // spread over every magnitude, against the rounded `core` isqrt.
        let mut cases = [1u128 << 64, (1u128 << WIDE_ROOT_BITS) - 1].to_vec();
        for b in 32..60u32 {
            for k in [(1u128 << b) - 1, 1u128 << b, (1u128 << b) + 1] {
                cases.extend([k * k - k, k * k, k * k + k, k * k + k + 1]);
            }
        }
        let mut x = 0x853c_49e6_748f_ea9bu64;
        for k in 0..1_000_000u32 {
            x = xorshift(x);
            let r = ((x >> (k % 28)) as u128 >> 4) | (1 << 32);
            x = xorshift(x);
            cases.push(r * r + (x as u128 % (2 * r + 1)));
        }
        for v in cases {
            if !(v >> 64 != 0 && v >> WIDE_ROOT_BITS == 0) {
                continue;
            }
            let exact = round_floor_root(v, v.isqrt());
            // The estimate lands on the branch-free finish (two units), not the stepping.
            assert!(wide_root_guess(v).abs_diff(exact) <= 2, "√{v}");
            assert_eq!(isqrt_round_wide(v), exact, "√{v}");
            assert_eq!(isqrt_round_u128(v), exact, "√{v}");
        }
    }

    #[test]
    fn u64_root_is_exact_at_squares_and_between() {
        // Every k² − k, k², k² + k, k² + k + 1 around each power of two (the rounding edges),
        // the largest inputs, and 10^6 random values spread over all magnitudes, against the
        // rounded `core` isqrt.
        let mut cases = [
            0u64,
            1,
            2,
            3,
            u64::MAX,
            u64::MAX - 1,
            1 << 62,
            (1 << 62) - 1,
        ]
        .to_vec();
        for b in 0..32u32 {
            for k in [(1u64 << b) - 1, 1u64 << b, (1u64 << b) + 1] {
                let sq = k * k;
                cases.extend([sq - k, sq, sq + k, sq + k + 1]);
            }
        }
        let mut x = 0xd1b5_4a32_d192_ed03u64;
        for k in 0..1_000_000u32 {
            x = xorshift(x);
            cases.push(x >> (k % 64));
        }
        for v in cases {
            let floor = v.isqrt() as u128;
            let rounded = round_floor_root(v as u128, floor) as u64;
            assert_eq!(isqrt_round_u64(v), rounded, "√{v}");
        }
    }

    #[test]
    fn root_from_any_guess_is_exact() {
        // Guesses 0..5 units either side of the rounded root (the branch-free ladder and both
        // of its edges), guesses 40 units off, and a guess at or above 2^60 (these three step).
        let mut x = 0x5851_f42d_4c95_7f2du64;
        for k in 0..20_000u32 {
            x = xorshift(x);
            let v = ((x as u128) << (k % 32)) | 1;
            // Also the rounding edges of a root n: v = n² − n rounds down, n² − n + 1 up, and
            // n² + n down, n² + n + 1 up.
            let n = (x >> 16) as u128 + 2;
            for v in [v, n * n - n, n * n - n + 1, n * n + n, n * n + n + 1] {
                let exact = round_floor_root(v, v.isqrt());
                for offset in -5i128..=5 {
                    let guess = (exact as i128 + offset).max(0) as u128;
                    assert_eq!(round_root_from_guess(v, guess), exact, "√{v} from {guess}");
                }
                for far in [exact + 40, exact.saturating_sub(40)] {
                    assert_eq!(round_root_from_guess(v, far), exact, "√{v} from {far}");
                }
            }
        }
        let v = 1u128 << 122;
        let exact = 1u128 << 61;
        assert_eq!(round_root_from_guess(v, exact + 3), exact);
    }

    #[test]
    fn rsqrt_within_one_unit() {
        // Against an exact integer reference: r = 2^48/√raw ⇔ r²·raw = 2^96.
        let mut x = 0x2545_f491_4f6c_dd1du64;
        for k in 0..100_000u32 {
            x = xorshift(x);
            let raw = ((x >> (k % 63)) | 1) as i64 & i64::MAX;
            let r = Fx::from_raw(raw).rsqrt().raw() as u128;
            let target = 1u128 << 96;
            // The true value lies in [r − 1, r + 1]: (r−1)²·raw ≤ 2^96 ≤ (r+1)²·raw.
            let lo = (r - 1)
                .checked_mul(r - 1)
                .and_then(|q| q.checked_mul(raw as u128));
            let hi = (r + 1)
                .checked_mul(r + 1)
                .and_then(|q| q.checked_mul(raw as u128));
            assert!(lo.is_none_or(|l| l <= target), "rsqrt({raw}) = {r} too big");
            assert!(
                hi.is_none_or(|h| h >= target),
                "rsqrt({raw}) = {r} too small"
            );
        }
        assert_eq!(Fx::from_int(4).rsqrt(), Fx::HALF);
        assert_eq!(Fx::from_f64(0.25).rsqrt(), Fx::from_int(2));
        assert!(!Fx::ZERO.rsqrt().is_valid());
        assert!(!Fx::from_int(-1).rsqrt().is_valid());
    }

    #[test]
    fn sqrt_rsqrt_matches_separate_calls() {
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        let edges = [
            0i64,
            1,
            2,
            3,
            1 << 32,
            (1 << 62) - 1,
            1 << 62,
            i64::MAX,
            -1,
            i64::MIN,
        ];
        let randoms = (0..200_000u32).map(|k| {
            x = xorshift(x);
            ((x >> (k % 63)) as i64) & i64::MAX
        });
        for raw in edges.into_iter().chain(randoms) {
            let a = Fx::from_raw(raw);
            let (s, r) = a.sqrt_rsqrt();
            assert_eq!(
                (s.raw(), r.raw()),
                (a.sqrt().raw(), a.rsqrt().raw()),
                "{raw}"
            );
        }
    }

    #[test]
    fn pow2_scaling_is_exact() {
        let a = Fx::from_f64(-0.375);
        assert_eq!(a.log2_floor(), -2);
        assert_eq!(a.mul_pow2(3).to_f64(), -3.0);
        assert_eq!(a.mul_pow2(-1).to_f64(), -0.1875);
        assert_eq!(Fx::from_raw(1).log2_floor(), -32);
        assert_eq!(Fx::from_raw(1).mul_pow2(31).to_f64(), 0.5);
        assert!(!Fx::ONE.mul_pow2(31).is_valid());
        assert_eq!(Fx::from_int(3).log2_floor(), 1);
    }

    #[test]
    fn sqrt_is_rounded() {
        for &x in &[0.0, 1e-9, 0.018, 1.0, 2.0, 64.0, 1e6, 2.0e9] {
            let q = Fx::from_f64(x);
            let s = q.sqrt().to_f64();
            assert!((s - q.to_f64().sqrt()).abs() <= 2.4e-10, "{x}: {s}");
        }
        assert!(!Fx::from_f64(-1.0).sqrt().is_valid());
    }
}
