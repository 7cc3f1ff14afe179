//! [`SplitMix64`]: a tiny integer-only pseudo-random generator for deterministic set-ups.
//!
//! SplitMix64 (Steele, Lea & Flood 2014, "Fast splittable pseudorandom number generators")
//! advances a 64-bit counter by the golden-ratio increment and scrambles it with two
//! xor-shift-multiply rounds. It is written here rather than taken from `rand` because the
//! core depends on `fixed`, `heapless` and `libm` only (issue 2), and because a set-up must
//! give the same numbers on every machine and in every profile: the generator uses only
//! wrapping integer arithmetic, and bounded draws use Lemire's multiply-shift with rejection
//! (integer, unbiased), never floating point.
//!
//! ```
//! use arachis_core::scenario::SplitMix64;
//! let mut a = SplitMix64::new(7);
//! let mut b = SplitMix64::new(7);
//! assert_eq!(a.next_u64(), b.next_u64());
//! let x = a.range_i64(-5, 5);
//! assert!((-5..=5).contains(&x));
//! ```

/// Golden-ratio increment of SplitMix64 (2⁶⁴/φ, odd).
const GOLDEN_GAMMA: u64 = 0x9e37_79b9_7f4a_7c15;
/// First scrambling multiplier of SplitMix64.
const MIX_MUL_1: u64 = 0xbf58_476d_1ce4_e5b9;
/// Second scrambling multiplier of SplitMix64.
const MIX_MUL_2: u64 = 0x94d0_49bb_1331_11eb;

/// SplitMix64 generator state. Equal seeds give equal sequences on every platform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    /// A generator started from `seed` (any value, zero included).
    pub const fn new(seed: u64) -> Self {
        SplitMix64 { state: seed }
    }

    /// Next 64 uniformly distributed bits.
    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN_GAMMA);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(MIX_MUL_1);
        z = (z ^ (z >> 27)).wrapping_mul(MIX_MUL_2);
        z ^ (z >> 31)
    }

    /// Uniform integer in `0..bound` (`bound` > 0), without modulo bias: Lemire's
    /// multiply-shift, redrawing the few values that would over-represent low results.
    pub fn below(&mut self, bound: u64) -> u64 {
        debug_assert!(bound > 0, "SplitMix64::below needs a positive bound");
        let bound = bound.max(1);
        // 2⁶⁴ mod bound: draws whose low product word falls below it are rejected.
        let threshold = bound.wrapping_neg() % bound;
        loop {
            let m = u128::from(self.next_u64()) * u128::from(bound);
            if (m as u64) >= threshold {
                return (m >> 64) as u64;
            }
        }
    }

    /// Uniform integer in the closed range `lo..=hi` (`lo ≤ hi`).
    pub fn range_i64(&mut self, lo: i64, hi: i64) -> i64 {
        debug_assert!(lo <= hi, "SplitMix64::range_i64 needs lo <= hi");
        let span = hi.abs_diff(lo).wrapping_add(1);
        if span == 0 {
            // The full 64-bit range.
            return self.next_u64() as i64;
        }
        lo.wrapping_add(self.below(span) as i64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_published_reference_sequence() {
        // First outputs of SplitMix64 seeded with 1234567, as printed by the reference C
        // implementation (Vigna, prng.di.unimi.it/splitmix64.c).
        let mut g = SplitMix64::new(1_234_567);
        assert_eq!(g.next_u64(), 6_457_827_717_110_365_317);
        assert_eq!(g.next_u64(), 3_203_168_211_198_807_973);
        assert_eq!(g.next_u64(), 9_817_491_932_198_370_423);
    }

    #[test]
    fn bounded_draws_stay_in_range_and_cover_it() {
        let mut g = SplitMix64::new(42);
        let mut seen = [false; 7];
        for _ in 0..1000 {
            let x = g.range_i64(-3, 3);
            assert!((-3..=3).contains(&x));
            seen[(x + 3) as usize] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn bounded_draws_are_roughly_uniform() {
        // 60 000 draws in 0..6: each face expects 10 000 with σ ≈ 91; allow 5σ.
        let mut g = SplitMix64::new(2024);
        let mut counts = [0u32; 6];
        for _ in 0..60_000 {
            counts[g.below(6) as usize] += 1;
        }
        for c in counts {
            assert!((9_545..=10_455).contains(&c), "{counts:?}");
        }
    }
}
