//! Exact sums of raw Q32.32 values in 64 bits and a count of wraps: the fixed-point
//! [`crate::num::Scalar::Sum`] and [`crate::num::Scalar::SumWraps`].
//!
//! The contact stage adds every contact's loads into per-body accumulators, in an order that
//! depends on how the step was split between threads. An exact integer sum is associative, so
//! the total does not depend on that order (DESIGN §5). A 128-bit sum is exact, but every
//! addition then carries into the high word, every read tests the high word and every clear
//! writes it. Here a term is added to the 64-bit low word alone; the processor's overflow flag
//! says when the signed sum left the 64-bit range, and a cold branch, taken only then, counts
//! the wrap in a 32-bit counter kept beside it (an accumulator keeps its seven counters
//! together, so a body's accumulator takes 88 bytes instead of 112). The pair (low, wraps)
//! stands for low + wraps·2^64, the integer the 128-bit sum held, and is unique for it: every
//! order and every split still gives the same bits. A sum whose wraps are not zero lies outside the
//! 64-bit range and reads as out of range, as the 128-bit sum did. The counter cannot
//! overflow: each term moves it by at most one, and no step adds 2^31 terms to one body.
//!
//! ```
//! use arachis_core::num::exact_sum::{add, sub, value};
//! let (mut low, mut wraps) = (0i64, 0i32);
//! add(&mut low, &mut wraps, i64::MAX);
//! add(&mut low, &mut wraps, 1); // wraps once …
//! assert_eq!(value(low, wraps), None);
//! sub(&mut low, &mut wraps, 2); // … and back: the sum is exact.
//! assert_eq!(value(low, wraps), Some(i64::MAX - 1));
//! ```

/// Add `x` to the sum `low` + `wraps`·2^64.
#[inline(always)]
pub fn add(low: &mut i64, wraps: &mut i32, x: i64) {
    let (sum, wrapped) = low.overflowing_add(x);
    *low = sum;
    if wrapped {
        // A signed addition overflows only when both terms have the sign of x.
        count_wrap(wraps, x < 0);
    }
}

/// Subtract `x` from the sum `low` + `wraps`·2^64.
#[inline(always)]
pub fn sub(low: &mut i64, wraps: &mut i32, x: i64) {
    let (sum, wrapped) = low.overflowing_sub(x);
    *low = sum;
    if wrapped {
        // low − x overflows downwards only for a positive x.
        count_wrap(wraps, x > 0);
    }
}

/// Add the sum `other` + `other_wraps`·2^64.
#[inline(always)]
pub fn merge(low: &mut i64, wraps: &mut i32, other: i64, other_wraps: i32) {
    *wraps += other_wraps;
    add(low, wraps, other);
}

/// The sum, or `None` when it lies outside the 64-bit range.
#[inline(always)]
pub fn value(low: i64, wraps: i32) -> Option<i64> {
    (wraps == 0).then_some(low)
}

/// Whether none of the sums with these wraps left the 64-bit range (one test for all).
#[inline(always)]
pub fn none_wrapped(wraps: &[i32]) -> bool {
    wraps.iter().fold(0, |any, &w| any | w) == 0
}

/// One wrap, downwards or upwards. Out of line: no sum of contact loads comes near 2^63 raw
/// (2^31 N), so a run that does not overflow never takes it.
#[cold]
#[inline(never)]
fn count_wrap(wraps: &mut i32, downwards: bool) {
    *wraps += if downwards { -1 } else { 1 };
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sum as a pair.
    #[derive(Clone, Copy, Debug, Default, PartialEq)]
    struct Pair(i64, i32);

    impl Pair {
        fn add(&mut self, x: i64) {
            add(&mut self.0, &mut self.1, x);
        }
        fn sub(&mut self, x: i64) {
            sub(&mut self.0, &mut self.1, x);
        }
        fn merge(&mut self, o: Pair) {
            merge(&mut self.0, &mut self.1, o.0, o.1);
        }
    }

    /// Sums of terms near the ends of the range against `i128` arithmetic, added in order, in
    /// reverse, split in two merged halves and subtracted as negatives: the same value and the
    /// same pair every way.
    #[test]
    fn sums_as_the_128_bit_integers_do_in_any_order_and_split() {
        let mut x = 0x9E37_79B9_7F4A_7C15u64;
        let mut wrapped = 0;
        for trial in 0..2_000 {
            let n = 1 + trial % 17;
            let terms: alloc::vec::Vec<i64> = (0..n)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    // Half the terms near ±2^63, the rest small.
                    if x & 1 == 0 {
                        x as i64
                    } else {
                        (x as i64) >> 40
                    }
                })
                .collect();
            let exact: i128 = terms.iter().map(|&t| t as i128).sum();
            let want = i64::try_from(exact).ok();
            let mut forward = Pair::default();
            terms.iter().for_each(|&t| forward.add(t));
            wrapped += usize::from(forward.1 != 0);
            let mut backward = Pair::default();
            terms.iter().rev().for_each(|&t| backward.add(t));
            let (a, b) = terms.split_at(n / 2);
            let (mut split, mut second) = (Pair::default(), Pair::default());
            a.iter().for_each(|&t| split.add(t));
            b.iter().for_each(|&t| second.add(t));
            split.merge(second);
            for (name, s) in [
                ("forward", forward),
                ("backward", backward),
                ("split", split),
            ] {
                assert_eq!(value(s.0, s.1), want, "{name}, terms {terms:?}");
                assert_eq!(s, forward, "{name}: not the same pair, terms {terms:?}");
            }
            // Subtracting −t adds t, but for t = i64::MIN, whose negation wraps.
            if !terms.contains(&i64::MIN) {
                let mut negated = Pair::default();
                terms.iter().for_each(|&t| negated.sub(-t));
                assert_eq!(negated, forward, "subtraction, terms {terms:?}");
            }
        }
        assert!(wrapped > 500, "only {wrapped} sums left the range");
    }

    #[test]
    fn a_sum_past_either_end_reads_as_out_of_range_until_it_returns() {
        let mut s = Pair::default();
        s.sub(i64::MAX);
        s.sub(2);
        assert_eq!(value(s.0, s.1), None, "below −2^63");
        s.add(1);
        assert_eq!(value(s.0, s.1), Some(i64::MIN));
    }
}
