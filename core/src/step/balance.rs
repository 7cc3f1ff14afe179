//! Load balance of a threaded step: where to cut a stage into parts so that every part takes
//! about as long.
//!
//! A stage is cut into parts of about equal counts (list entries, spheres, bonds), but equal
//! counts are not equal work. On the DESIGN §8 bed on two threads, the part holding the
//! lower, denser half ran 7 % longer than the other in the contact stage and in integration;
//! on the shipped field (soil, plants, bonds) the parts of each stage differed by 10–14 %. A
//! thread that finishes first waits for the other at the end of every stage.
//!
//! A [`StageBalance`] keeps, for [`BINS`] equal runs of a stage's items (bodies or bonds),
//! how long a unit of count took there, relative to the stage's mean, from the times the
//! runner measured for each part ([`super::parts::Parallel::job_times`]). The next step
//! weighs each item's count by its run's factor ([`StageBalance::weights`]) and cuts where
//! the weight is shared equally. Each new measurement moves a factor a quarter of the way,
//! and at most by a factor of two, so that one slow step (a core taken by another program)
//! moves the cuts little. Forces are exact integer sums, so where the cuts fall never
//! changes a bit of the result, only how long each thread works. Floating-point sums depend
//! on their order, and so on the cuts: an `f64` step keeps its cuts by count, so that a run
//! on a given number of threads repeats itself.
//!
//! ```
//! use arachis_core::step::balance::StageBalance;
//! let mut balance = StageBalance::new();
//! let count_before = |i: usize| i as u64;
//! // Two parts of 50 items each; the first took three times as long.
//! for _ in 0..20 {
//!     balance.record(100, [(0..50, 50, 300), (50..100, 50, 100)].into_iter());
//! }
//! let w = balance.weights(100, &count_before);
//! // Items of the first half now weigh about three times as much.
//! assert!(w.before(50) > 2 * (w.before(100) - w.before(50)));
//! ```

use core::ops::Range;

/// Runs of items with a factor each.
pub const BINS: usize = 64;
/// Fraction bits of a factor: a run as fast as the stage's mean has `1 << FACTOR_SHIFT`.
const FACTOR_SHIFT: u32 = 16;
/// The factor of a run as fast as the mean (and of a run not measured yet).
const UNIT: u64 = 1 << FACTOR_SHIFT;
/// Each measurement moves a factor by 1/2^`SMOOTHING_SHIFT` of the way to its new value.
const SMOOTHING_SHIFT: u32 = 2;
/// Factors stay within [UNIT / FACTOR_RANGE, UNIT · FACTOR_RANGE].
const FACTOR_RANGE: u64 = 4;

/// The measured cost factors of one stage (module docs).
#[derive(Clone, Debug)]
pub struct StageBalance {
    /// Time per unit of count in each run, in `UNIT`s of the stage's mean.
    factor: [u64; BINS],
    /// The item count the factors were measured for (0: none measured).
    items: usize,
}

impl StageBalance {
    /// Nothing measured: every unit of count weighs the same.
    pub const fn new() -> Self {
        StageBalance {
            factor: [UNIT; BINS],
            items: 0,
        }
    }

    /// Note the parts of a stage over `items` items: (items, count, time) of each, with the
    /// time in any unit common to the parts. Parts without count or time say nothing.
    /// Factors measured for another item count are forgotten first.
    pub fn record(
        &mut self,
        items: usize,
        parts: impl Iterator<Item = (Range<usize>, u64, u64)> + Clone,
    ) {
        if items != self.items {
            *self = StageBalance::new();
            self.items = items;
        }
        let parts = parts.filter(|(_, c, t)| *c > 0 && *t > 0);
        let (count, time) = parts.clone().fold((0u128, 0u128), |(c, t), p| {
            (c + p.1 as u128, t + p.2 as u128)
        });
        if count == 0 || time == 0 {
            return;
        }
        for (range, c, t) in parts {
            // This part's time per unit of count over the stage's mean, in UNITs.
            let measured = (t as u128 * count * UNIT as u128 / (c as u128 * time)) as u64;
            for b in 0..BINS {
                let mid = (run_start(b, items) + run_start(b + 1, items)) / 2;
                if range.contains(&mid) {
                    let old = self.factor[b];
                    let new = measured.clamp(old / 2, old * 2);
                    let moved = old as i64 + ((new as i64 - old as i64) >> SMOOTHING_SHIFT);
                    self.factor[b] = (moved as u64).clamp(UNIT / FACTOR_RANGE, UNIT * FACTOR_RANGE);
                }
            }
        }
    }

    /// The weights of a stage over `items` items, where `count_before(i)` counts items
    /// `0..i` (non-decreasing in i): each run's count times its factor. Without factors
    /// measured for `items` items, the weight is the count itself, computed on demand (a
    /// one-part step measures nothing and pays nothing).
    pub fn weights<'c, F: Fn(usize) -> u64>(
        &self,
        items: usize,
        count_before: &'c F,
    ) -> Weights<'c, F> {
        let measured = items == self.items && items > 0;
        let mut before = [0u64; BINS + 1];
        if measured {
            for b in 0..BINS {
                let count =
                    count_before(run_start(b + 1, items)) - count_before(run_start(b, items));
                before[b + 1] = before[b] + count * self.factor[b];
            }
        }
        Weights {
            items,
            measured,
            before,
            factor: self.factor,
            count_before,
        }
    }
}

impl Default for StageBalance {
    fn default() -> Self {
        Self::new()
    }
}

/// The first item of run `b` of `items` items.
fn run_start(b: usize, items: usize) -> usize {
    b * items / BINS
}

/// A stage's weights for one step ([`StageBalance::weights`]).
pub struct Weights<'c, F> {
    items: usize,
    /// Whether the factors apply (else every unit of count weighs [`UNIT`]).
    measured: bool,
    /// The weight of the runs before each run.
    before: [u64; BINS + 1],
    factor: [u64; BINS],
    count_before: &'c F,
}

impl<F: Fn(usize) -> u64> Weights<'_, F> {
    /// The weight of items `0..i` (non-decreasing in i).
    pub fn before(&self, i: usize) -> u64 {
        let i = i.min(self.items);
        if !self.measured {
            return (self.count_before)(i) * UNIT;
        }
        let mut b = (i * BINS / self.items.max(1)).min(BINS);
        while b < BINS && run_start(b + 1, self.items) <= i {
            b += 1;
        }
        if b == BINS {
            return self.before[BINS];
        }
        let start = run_start(b, self.items);
        self.before[b] + ((self.count_before)(i) - (self.count_before)(start)) * self.factor[b]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_record_the_weight_is_the_count() {
        let balance = StageBalance::new();
        for items in [0, 1, 7, 64, 100, 1_000] {
            let count_before = |i: usize| (i * i) as u64;
            let w = balance.weights(items, &count_before);
            for i in 0..=items {
                assert_eq!(w.before(i), count_before(i) * UNIT, "item {i} of {items}");
            }
        }
    }

    #[test]
    fn weights_never_decrease() {
        let mut balance = StageBalance::new();
        let items = 1_000;
        let parts = [
            (0..300, 300, 900),
            (300..700, 400, 100),
            (700..1_000, 300, 500),
        ];
        for _ in 0..10 {
            balance.record(items, parts.iter().cloned());
        }
        let count_before = |i: usize| i as u64;
        let w = balance.weights(items, &count_before);
        for i in 1..=items {
            assert!(w.before(i) >= w.before(i - 1), "item {i}");
        }
        assert!(w.before(300) > w.before(1_000) - w.before(700));
    }

    /// Measured times converge on cuts that give every part the same time: items of a
    /// stage cost 3 units in the first 40 %, 1 elsewhere; parts cut at the weights' median
    /// end up within 5 % of equal time.
    #[test]
    fn cuts_converge_on_equal_times() {
        let items = 1_000usize;
        let cost = |i: usize| if i < 400 { 3u64 } else { 1 };
        let mut balance = StageBalance::new();
        let count_before = |i: usize| i as u64;
        let mut cut = items / 2;
        for _ in 0..60 {
            let time = |r: Range<usize>| r.map(cost).sum::<u64>();
            let parts = [
                (0..cut, cut as u64, time(0..cut)),
                (cut..items, (items - cut) as u64, time(cut..items)),
            ];
            balance.record(items, parts.iter().cloned());
            let w = balance.weights(items, &count_before);
            let half = w.before(items) / 2;
            cut = (0..=items).find(|&i| w.before(i) >= half).unwrap();
        }
        let (a, b): (u64, u64) = ((0..cut).map(cost).sum(), (cut..items).map(cost).sum());
        assert!(a.abs_diff(b) * 20 < a + b, "times {a} and {b} at cut {cut}");
    }

    /// One step measured far off moves a factor by at most a quarter of the doubling.
    #[test]
    fn one_odd_step_moves_the_factors_little() {
        let mut balance = StageBalance::new();
        balance.record(100, [(0..50, 50, 1_000_000), (50..100, 50, 1)].into_iter());
        assert!(balance.factor[..BINS / 2]
            .iter()
            .all(|&f| f <= UNIT + UNIT / 4));
        assert!(balance.factor[BINS / 2..]
            .iter()
            .all(|&f| f >= UNIT - UNIT / 8));
    }

    #[test]
    fn another_item_count_forgets_the_factors() {
        let mut balance = StageBalance::new();
        for _ in 0..10 {
            balance.record(100, [(0..50, 50, 300), (50..100, 50, 100)].into_iter());
        }
        let count_before = |i: usize| i as u64;
        assert_ne!(balance.weights(100, &count_before).before(50), 50 * UNIT);
        assert_eq!(balance.weights(120, &count_before).before(60), 60 * UNIT);
    }
}
