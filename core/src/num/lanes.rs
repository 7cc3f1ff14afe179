//! Lane arithmetic for the narrow contact kernel ([`crate::contact::lanes`]): [`LANES`]
//! contacts at a time, each quantity an array of `i64` (structure of arrays), so that the
//! compiler can turn every operation into one vector instruction.
//!
//! Two kinds of numbers:
//! - **Narrow fixed point**: a value of known range in a format Q.f chosen so that its raw
//!   integer lies below 2^31. A product of two such values is exact in 64 bits (one
//!   `vpmuldq` per four or eight lanes) and is brought back to a format by a rounded
//!   arithmetic shift ([`shr_round`]). Sums are exact in 64 bits.
//! - **Block values** ([`Soft`]): x = m·2^e with a 31-bit significand |m| ∈ [2^30, 2^31) (or
//!   m = 0 and e = [`ZERO_EXP`]), for the few quantities whose size spans decades (contact
//!   radius, stiffness, the normal force): an integer floating point, every operation
//!   rounded to nearest to 31 bits (relative error at most 2^-31 per operation).
//!
//! Everything is integer arithmetic and every function is exact as written, so a vectorised
//! build gives the same bits as the portable one (DESIGN §5).
//!
//! ```
//! use arachis_core::num::lanes::{shr_round, Soft, LANES};
//! // 3 × 5 in block values, back to Q.32 fixed point.
//! let three = Soft::from_fixed(&[3 << 32; LANES], 32);
//! let five = Soft::from_fixed(&[5 << 32; LANES], 32);
//! assert_eq!(three.mul(&five).to_fixed(32).0[0], 15 << 32);
//! assert_eq!(shr_round(-3, 1), -1); // −1.5 rounds up to −1
//! ```

// Lane code indexes structure-of-arrays fields by the lane number on purpose: one loop per
// operation over every lane is what the compiler turns into one vector instruction.
#![allow(clippy::needless_range_loop)]

/// Contacts evaluated together.
pub const LANES: usize = 16;

/// One `i64` per lane.
pub type Lanes = [i64; LANES];

/// One flag per lane.
pub type Mask = [bool; LANES];

/// The exponent of a zero block value: far below any real one, so that aligning a zero for a
/// sum shifts it out and a product with zero stays zero.
pub const ZERO_EXP: i64 = -(1 << 40);

/// Largest left shift a conversion to fixed point may take: a significand below 2^31 shifted
/// by at most 31 stays below 2^62.
const MAX_LEFT_SHIFT: i64 = 31;

/// `[e(0), …, e(LANES − 1)]` for an expression in the lane index: `lanes!(|l| a[l] + b[l])`.
/// A macro, not a function taking a closure, because a closure is compiled on its own,
/// without the instruction sets of the vectorised build it is called from.
#[macro_export]
#[doc(hidden)]
macro_rules! lanes {
    (|$l:ident| $e:expr) => {{
        let mut out = [0i64; $crate::num::lanes::LANES];
        for $l in 0..$crate::num::lanes::LANES {
            out[$l] = $e;
        }
        out
    }};
}

/// [`lanes!`] for a mask.
#[macro_export]
#[doc(hidden)]
macro_rules! mask {
    (|$l:ident| $e:expr) => {{
        let mut out = [false; $crate::num::lanes::LANES];
        for $l in 0..$crate::num::lanes::LANES {
            out[$l] = $e;
        }
        out
    }};
}

/// `[e(0), e(1), e(2)]` for an expression in the component index.
#[macro_export]
#[doc(hidden)]
macro_rules! xyz {
    (|$k:ident| $e:expr) => {
        [
            {
                let $k = 0;
                $e
            },
            {
                let $k = 1;
                $e
            },
            {
                let $k = 2;
                $e
            },
        ]
    };
}

/// `e(0) + e(1) + e(2)` for an expression in the component index.
#[macro_export]
#[doc(hidden)]
macro_rules! sum3 {
    (|$k:ident| $e:expr) => {{
        let [a, b, c]: [i64; 3] = $crate::xyz!(|$k| $e);
        a.wrapping_add(b).wrapping_add(c)
    }};
}

/// (x + 2^(s−1)) >> s, rounded to nearest (ties up), for 0 ≤ s ≤ 63 (s is clamped there);
/// |x| < 2^62.
///
/// Lane arithmetic wraps instead of panicking: a lane outside the kernel's envelope computes
/// garbage that is thrown away, and must do so the same way in debug and release builds. A
/// lane inside it never wraps (the bounds of [`crate::contact::lanes`]).
#[inline(always)]
pub fn shr_round(x: i64, s: i64) -> i64 {
    let s = s.clamp(0, 63) as u32;
    let half = ((1u64 << s) >> 1) as i64;
    x.wrapping_add(half) >> s
}

/// a·b of two narrow values, |a|, |b| < 2^31: a 32 × 32 → 64-bit product (`vpmuldq`). Only
/// the low 32 bits of each operand are read, so the caller's bounds must hold (the kernel's
/// envelope; `tests::narrow_products_see_every_bit` checks it).
#[inline(always)]
pub fn mul32(a: i64, b: i64) -> i64 {
    #[cfg(test)]
    check_narrow(a, b);
    (a as i32 as i64) * (b as i32 as i64)
}

/// In tests: record a product whose operand does not fit 32 bits (it would be truncated).
#[cfg(test)]
fn check_narrow(a: i64, b: i64) {
    if a as i32 as i64 != a || b as i32 as i64 != b {
        WIDE_OPERANDS.with(|w| w.set(w.get() + 1));
    }
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
std::thread_local! {
    /// Products with an operand wider than 32 bits since the last [`take_wide_operands`].
    static WIDE_OPERANDS: core::cell::Cell<u64> = const { core::cell::Cell::new(0) };
}

/// In tests: the number of truncated products since the last call.
#[cfg(test)]
pub(crate) fn take_wide_operands() -> u64 {
    WIDE_OPERANDS.with(|w| w.replace(0))
}

/// (a·b − c·d) of narrow values, rounded and shifted right by s.
#[inline(always)]
pub fn mul_sub_shr(a: i64, b: i64, c: i64, d: i64, s: i64) -> i64 {
    shr_round(mul32(a, b).wrapping_sub(mul32(c, d)), s)
}

/// Bits of |x| (0 for x = 0).
#[inline(always)]
pub fn bit_length(x: i64) -> i64 {
    64 - x.unsigned_abs().leading_zeros() as i64
}

/// x·2^e as a block value (m, e'): m rounded to 31 significant bits; |x| < 2^63.
#[inline(always)]
pub fn normalise(x: i64, e: i64) -> (i64, i64) {
    let ax = x.unsigned_abs();
    let s = 64 - ax.leading_zeros() as i64 - 31;
    let right = s.max(0) as u32;
    let left = (-s).max(0) as u32;
    let m = ((ax + ((1u64 << right) >> 1)) >> right) << left;
    // Rounding up may reach 2^31: one more halving (exact, m is even then).
    let carry = (m >> 31) as u32;
    let m = (m >> carry) as i64;
    let e = e + s + carry as i64;
    if ax == 0 {
        (0, ZERO_EXP)
    } else if x < 0 {
        (-m, e)
    } else {
        (m, e)
    }
}

/// Q30 reciprocal square root of X = x/2^64 ∈ [¼, 1) (x ≥ 2^62), good to about 2^-29: a
/// chord of 1/√X on [¼, ½) or [½, 1) (within 4.6 % of it) and three Newton steps
/// Y ← Y(3 − XY²)/2, in 64-bit products of 32-bit values. No table, so that a vector unit
/// takes eight lanes at once instead of looking up each.
#[inline(always)]
pub fn rsqrt_q30_seeded(x: u64) -> u64 {
    let x32 = x >> 32;
    let upper = x32 >> 31; // X ≥ ½
    let (a, b) = if upper == 1 {
        (CHORD_UPPER_A, CHORD_UPPER_B)
    } else {
        (CHORD_LOWER_A, CHORD_LOWER_B)
    };
    // Every factor below is below 2^32, so each product is one 32 × 32 → 64-bit multiply
    // (`vpmuludq`, 5 cycles, where a 64-bit `vpmullq` takes 15).
    let mut y = a - (mul_u32(b, x32) >> 32);
    for _ in 0..3 {
        let y2 = (mul_u32(y, y) >> 30).min(u32::MAX as u64);
        let t = mul_u32(x32, y2) >> 32;
        y = mul_u32(y, (3u64 << 30).saturating_sub(t)) >> 31;
    }
    y
}

/// a·b of two values below 2^32, as one 32 × 32 → 64-bit multiply.
#[inline(always)]
fn mul_u32(a: u64, b: u64) -> u64 {
    (a as u32 as u64) * (b as u32 as u64)
}

/// The chord of 1/√X through X = ¼ and ½: intercept 2 + (2 − √2) = 2.585786 in Q30 …
const CHORD_LOWER_A: u64 = 2_776_467_046;
/// … and slope 4(2 − √2) = 2.343146 (subtracted).
const CHORD_LOWER_B: u64 = 2_515_933_592;
/// The chord through X = ½ and 1: intercept 2√2 − 1 = 1.828427 …
const CHORD_UPPER_A: u64 = 1_963_258_676;
/// … and slope 2(√2 − 1) = 0.828427.
const CHORD_UPPER_B: u64 = 889_516_852;

/// Block values, one per lane (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Soft {
    /// Significands, |m| ∈ [2^30, 2^31) or 0.
    pub m: Lanes,
    /// Exponents (value = m·2^e).
    pub e: Lanes,
}

impl Soft {
    /// Zero in every lane.
    pub const ZERO: Soft = Soft {
        m: [0; LANES],
        e: [ZERO_EXP; LANES],
    };

    /// Q.`frac` fixed-point raw values (|x| < 2^63) as block values.
    #[inline(always)]
    pub fn from_fixed(x: &Lanes, frac: i64) -> Soft {
        let mut out = Soft::ZERO;
        for l in 0..LANES {
            (out.m[l], out.e[l]) = normalise(x[l], -frac);
        }
        out
    }

    /// The same value in every lane.
    #[inline(always)]
    pub fn splat(x: i64, frac: i64) -> Soft {
        Soft::from_fixed(&[x; LANES], frac)
    }

    /// Q.`frac` raw values, rounded to nearest, and per lane whether the value fits: below
    /// 2^62 raw, left shifts of at most 31 (a lane that does not fit holds garbage).
    #[inline(always)]
    pub fn to_fixed(&self, frac: i64) -> (Lanes, Mask) {
        let mut out = [0; LANES];
        let mut fits = [true; LANES];
        for l in 0..LANES {
            let t = self.e[l] + frac;
            let left = t.clamp(0, MAX_LEFT_SHIFT) as u32;
            out[l] = shr_round(self.m[l], -t) << left;
            fits[l] = t <= MAX_LEFT_SHIFT || self.m[l] == 0;
        }
        (out, fits)
    }

    /// Whether |x| < 2^bits in every lane (tested on the exponent: |x| < 2^(e + 31), so the
    /// test is conservative by less than a factor 2).
    #[inline(always)]
    pub fn below(&self, bits: i64) -> Mask {
        mask!(|l| self.m[l] == 0 || self.e[l] + 31 <= bits)
    }

    /// Whether x > 0.
    #[inline(always)]
    pub fn positive(&self) -> Mask {
        mask!(|l| self.m[l] > 0)
    }

    /// a·b.
    #[inline(always)]
    pub fn mul(&self, b: &Soft) -> Soft {
        let mut out = Soft::ZERO;
        for l in 0..LANES {
            // |p| ∈ [2^60, 2^62) (or 0): the significand is p >> 30 or p >> 31, rounded.
            let p = mul32(self.m[l], b.m[l]);
            let ap = p.unsigned_abs();
            let s = 30 + (ap >> 61) as u32;
            let m = (ap + (1 << (s - 1))) >> s;
            let carry = (m >> 31) as u32;
            let m = (m >> carry) as i64;
            let e = self.e[l] + b.e[l] + (s + carry) as i64;
            (out.m[l], out.e[l]) = if p == 0 {
                (0, ZERO_EXP)
            } else if p < 0 {
                (-m, e)
            } else {
                (m, e)
            };
        }
        out
    }

    /// a·x for a narrow Q.`frac` fixed-point x (|x| < 2^31).
    #[inline(always)]
    pub fn mul_fixed(&self, x: &Lanes, frac: i64) -> Soft {
        let mut out = Soft::ZERO;
        for l in 0..LANES {
            (out.m[l], out.e[l]) = normalise(mul32(self.m[l], x[l]), self.e[l] - frac);
        }
        out
    }

    /// a·x for a narrow Q.`x_frac` fixed-point x (|x| < 2^31), in Q.`frac` (a lane whose
    /// result would need a left shift, far outside any bound of the kernel, gives 0 and
    /// `false`).
    #[inline(always)]
    pub fn times_fixed(&self, x: &Lanes, x_frac: i64, frac: i64) -> (Lanes, Mask) {
        self.times_fixed_lanes(x, &[x_frac; LANES], frac)
    }

    /// [`Soft::times_fixed`] with a format per lane.
    #[inline(always)]
    pub fn times_fixed_lanes(&self, x: &Lanes, x_frac: &Lanes, frac: i64) -> (Lanes, Mask) {
        let mut out = [0; LANES];
        let mut fits = [true; LANES];
        for l in 0..LANES {
            let s = x_frac[l] - frac - self.e[l];
            out[l] = if s >= 0 {
                shr_round(mul32(self.m[l], x[l]), s)
            } else {
                0
            };
            fits[l] = s >= 0 || self.m[l] == 0 || x[l] == 0;
        }
        (out, fits)
    }

    /// a + b.
    #[inline(always)]
    pub fn add(&self, b: &Soft) -> Soft {
        let mut out = Soft::ZERO;
        for l in 0..LANES {
            let e = self.e[l].max(b.e[l]);
            // With 31 guard bits: each term below 2^62, the sum below 2^63.
            let xa = shr_round(self.m[l] << 31, e - self.e[l]);
            let xb = shr_round(b.m[l] << 31, e - b.e[l]);
            (out.m[l], out.e[l]) = normalise(xa.wrapping_add(xb), e - 31);
        }
        out
    }

    /// −a.
    #[inline(always)]
    pub fn neg(&self) -> Soft {
        Soft {
            m: lanes!(|l| -self.m[l]),
            e: self.e,
        }
    }

    /// a − b.
    #[inline(always)]
    pub fn sub(&self, b: &Soft) -> Soft {
        self.add(&b.neg())
    }

    /// a·2^k with k per lane.
    #[inline(always)]
    pub fn mul_pow_lanes(&self, k: &Lanes) -> Soft {
        Soft {
            m: self.m,
            e: lanes!(|l| if self.m[l] == 0 {
                ZERO_EXP
            } else {
                self.e[l] + k[l]
            }),
        }
    }

    /// 1/√a for a > 0, good to about 2^-28 ([`rsqrt_q30`]); lanes with a ≤ 0 give garbage.
    #[inline(always)]
    pub fn rsqrt(&self) -> Soft {
        let mut out = Soft::ZERO;
        for l in 0..LANES {
            let odd = self.e[l] & 1;
            // m·2^odd ∈ [2^30, 2^32) with an even exponent.
            let m = (self.m[l].max(1 << 30) as u64) << odd;
            let e = self.e[l] - odd;
            // y ≈ 2^30/√(m/2^32) = 2^46/√m.
            let y = rsqrt_q30_seeded(m << 32) as i64;
            (out.m[l], out.e[l]) = normalise(y, -46 - (e >> 1));
        }
        out
    }

    /// √a for a ≥ 0 (0 for a = 0).
    #[inline(always)]
    pub fn sqrt(&self) -> Soft {
        self.mul(&self.rsqrt())
    }

    /// Per lane, `when` ? a : b.
    #[inline(always)]
    pub fn select(when: &Mask, a: &Soft, b: &Soft) -> Soft {
        Soft {
            m: lanes!(|l| if when[l] { a.m[l] } else { b.m[l] }),
            e: lanes!(|l| if when[l] { a.e[l] } else { b.e[l] }),
        }
    }

    /// Whether a > b, for a, b ≥ 0 (normalised significands compare with their exponents).
    #[inline(always)]
    pub fn greater(&self, b: &Soft) -> Mask {
        mask!(|l| self.e[l] > b.e[l] || (self.e[l] == b.e[l] && self.m[l] > b.m[l]))
    }
}

/// Whether any lane is set. The kernel skips work that no lane of a batch needs (sliding,
/// clump levers): every build takes the same branch, so the bits stay the same.
#[inline(always)]
pub fn any(m: &Mask) -> bool {
    let mut a = false;
    for l in 0..LANES {
        a |= m[l];
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(s: &Soft, l: usize) -> f64 {
        s.m[l] as f64 * libm::exp2(s.e[l] as f64)
    }

    /// A deterministic stream of `i64`s.
    fn stream(mut x: u64) -> impl FnMut() -> u64 {
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            x
        }
    }

    #[test]
    fn normalise_keeps_31_bits_rounded_to_nearest() {
        let mut next = stream(0x9E37_79B9_7F4A_7C15);
        for _ in 0..100_000 {
            let bits = (next() % 62) as u32 + 1;
            let x = (next() >> (64 - bits)) as i64 * if next() & 1 == 0 { 1 } else { -1 };
            let (m, e) = normalise(x, 0);
            if x == 0 {
                assert_eq!((m, e), (0, ZERO_EXP));
                continue;
            }
            assert!((1 << 30..1 << 31).contains(&m.abs()), "{x}: {m}");
            // Exact below 2^31, else within half a unit of the last kept place.
            let back = (m as i128 * (1i128 << e.max(0))) >> (-e).max(0);
            let err = (back - x as i128).abs();
            assert!(2 * err <= 1i128 << e.max(0), "{x}: {m}·2^{e}");
            assert_eq!(m.signum(), x.signum());
        }
    }

    /// Every operation against f64, within its rounding (2^-31 relative per rounding, 2^-27 for
    /// the reciprocal root).
    #[test]
    fn operations_agree_with_f64() {
        let mut next = stream(0xD1B5_4A32_D192_ED03);
        for _ in 0..20_000 {
            let mut raw = || {
                let bits = (next() % 60) as u32 + 1;
                (next() >> (64 - bits)) as i64 * if next() & 1 == 0 { 1 } else { -1 }
            };
            let mut xa: Lanes = [0; LANES];
            let mut xb: Lanes = [0; LANES];
            for l in 0..LANES {
                xa[l] = raw();
                xb[l] = raw();
            }
            let (a, b) = (Soft::from_fixed(&xa, 32), Soft::from_fixed(&xb, 20));
            let (sum, prod) = (a.add(&b), a.mul(&b));
            let root = a.mul(&a).sqrt();
            for l in 0..LANES {
                let (fa, fb) = (xa[l] as f64 / 2f64.powi(32), xb[l] as f64 / 2f64.powi(20));
                let tol = |want: f64, k: f64| k * 2f64.powi(-31) * want.abs();
                let mag = fa.abs().max(fb.abs());
                // Two rounded inputs and the rounded sum (at most twice the larger input).
                assert!((value(&sum, l) - (fa + fb)).abs() <= tol(mag, 4.0));
                assert!((value(&prod, l) - fa * fb).abs() <= tol(fa * fb, 3.0));
                assert!((value(&root, l) - fa.abs()).abs() <= tol(fa, 40.0));
            }
        }
    }

    #[test]
    fn zero_is_absorbed_and_stays_zero() {
        let x = Soft::splat(7 << 20, 20);
        assert_eq!(Soft::ZERO.add(&x), x);
        assert_eq!(x.add(&Soft::ZERO), x);
        assert_eq!(x.mul(&Soft::ZERO).m, [0; LANES]);
        assert_eq!(Soft::ZERO.sqrt().m, [0; LANES]);
        assert_eq!(x.sub(&x), Soft::ZERO);
    }

    #[test]
    fn conversion_to_fixed_rounds_and_reports_range() {
        let x = Soft::splat(-(5 << 31) - 1, 32); // −2.5 − 2^-32
        let (v, fits) = x.to_fixed(1);
        assert_eq!(v[0], -5);
        assert!(fits[0]);
        let big = Soft::splat(1 << 40, 0);
        assert!(!big.to_fixed(32).1[0]);
        assert_eq!(big.below(41), [true; LANES]);
        assert_eq!(big.below(40), [false; LANES]);
    }

    #[test]
    fn seeded_root_is_good_to_2_pow_minus_29() {
        let mut next = stream(0x6A09_E667_F3BC_C909);
        for _ in 0..200_000 {
            let x = next() | 1 << 62;
            let want = 2f64.powi(30) / libm::sqrt(x as f64 / 2f64.powi(64));
            let got = rsqrt_q30_seeded(x) as f64;
            assert!(
                (got - want).abs() <= want * 2f64.powi(-29),
                "{x}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn comparison_orders_non_negative_values() {
        let a = Soft::splat(3 << 30, 30);
        let b = Soft::splat(5 << 29, 30);
        assert_eq!(a.greater(&b), [true; LANES]);
        assert_eq!(b.greater(&a), [false; LANES]);
        assert_eq!(a.greater(&Soft::ZERO), [true; LANES]);
        assert_eq!(Soft::ZERO.greater(&a), [false; LANES]);
        assert_eq!(a.greater(&a), [false; LANES]);
    }
}
