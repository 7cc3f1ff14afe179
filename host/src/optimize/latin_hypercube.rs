//! Deterministic Latin-hypercube starting points in the coded box [−1, 1]^k.
//!
//! Each axis is cut into n equal slices and every slice is used exactly once per axis; the
//! slices are paired across axes by permutations shuffled from a fixed seed, and each point
//! sits at the middle of its cell. The same seed always gives the same points, so an
//! optimisation is reproducible run to run.
//!
//! ```
//! let pts = arachis::optimize::latin_hypercube(5, 2, 7);
//! assert_eq!(pts.len(), 5);
//! // Each of the 5 slices of each axis holds exactly one point, at the slice's middle.
//! for axis in 0..2 {
//!     let mut slices: Vec<i64> =
//!         pts.iter().map(|p| ((p[axis] + 1.0) * 2.5 - 0.5).round() as i64).collect();
//!     slices.sort();
//!     assert_eq!(slices, vec![0, 1, 2, 3, 4]);
//! }
//! ```

/// SplitMix64 (Steele, Lea & Flood 2014), a few lines of integer mixing used only to shuffle
/// the hypercube's slices reproducibly; it is not an optimiser or a special function, and
/// pulling in a random-number crate for it would add a dependency for nothing.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform integer in 0..n (n > 0); the modulo bias is irrelevant for shuffling starts.
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// `n` points in [−1, 1]^`dims`, a centred Latin hypercube shuffled from `seed`.
pub fn latin_hypercube(n: usize, dims: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut rng = SplitMix64(seed);
    let mut points = vec![vec![0.0; dims]; n];
    for d in 0..dims {
        let mut slices: Vec<usize> = (0..n).collect();
        // Fisher–Yates shuffle.
        for i in (1..n).rev() {
            let j = rng.below(i + 1);
            slices.swap(i, j);
        }
        for (p, s) in points.iter_mut().zip(slices) {
            p[d] = -1.0 + 2.0 * (s as f64 + 0.5) / n as f64;
        }
    }
    points
}
