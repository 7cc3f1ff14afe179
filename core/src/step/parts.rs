//! Splitting a step into parts that may run on several threads.
//!
//! The contact and integration stages run in parts over disjoint ranges of bodies (whole
//! bodies, so a clump's spheres stay together). The core stays `no_std` and owns no threads:
//! a [`Parallel`] runner given by the caller (the host uses a thread pool; [`Serial`] runs the
//! parts one after another) calls each part once. In fixed point the result is the same bits
//! for any number of parts, because each contact depends only on the state at the start of
//! the step and on its own history, and forces are summed as exact integers
//! ([`crate::num::Scalar::Sum`]). A runner that measures how long each part ran
//! ([`Parallel::job_times`]) lets the step move its cuts until the parts take equally long
//! ([`super::balance`]).
//!
//! ```
//! use arachis_core::step::parts::{Parallel, Serial};
//! let mut jobs = [1, 2, 3];
//! Serial.for_each(&mut jobs, &|j: &mut i32| *j *= 10);
//! assert_eq!(jobs, [10, 20, 30]);
//! assert_eq!(Serial.parts(), 1);
//! ```

use crate::material::MAX_MATERIALS;
use crate::pair::PairParams;
use core::ops::Range;

/// Largest number of parts a stage is split into.
pub const MAX_PARTS: usize = 64;

/// Pair parameters by material index.
pub(crate) type PairTable<S> = [[PairParams<S>; MAX_MATERIALS]; MAX_MATERIALS];

/// Runs the parts of a stage, possibly at the same time on several threads.
pub trait Parallel: Sync {
    /// How many parts to split each stage into (the thread count; at least 1).
    fn parts(&self) -> usize;
    /// Call `f` once on every job and return when all calls have returned. The calls may run
    /// in any order and at the same time.
    fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync));
    /// How long each job of the last [`Parallel::for_each`] ran, in any unit common to the
    /// jobs, if the runner measured it and that call had `out.len()` jobs: fills `out` and
    /// returns true. The step moves its cuts by these times ([`super::balance`]); they never
    /// change a result. The default measures nothing.
    fn job_times(&self, out: &mut [u64]) -> bool {
        let _ = out;
        false
    }
}

/// Runs the parts one after another on the calling thread.
#[derive(Clone, Copy, Debug, Default)]
pub struct Serial;

impl Parallel for Serial {
    fn parts(&self) -> usize {
        1
    }
    fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync)) {
        for j in jobs {
            f(j);
        }
    }
}

/// Split `0..n` items into at most `parts` ranges of about equal `weight`, cutting only
/// where `cut_ok(i)` allows a range to start at i (0 and n always do). Ranges are in order,
/// non-empty and cover `0..n`; fewer than `parts` come back when cuts are scarce.
pub(crate) fn split_ranges<const N: usize>(
    n: usize,
    parts: usize,
    weight_before: impl Fn(usize) -> u64,
    mut cut_ok: impl FnMut(usize) -> bool,
    out: &mut heapless::Vec<Range<usize>, N>,
) {
    out.clear();
    let parts = parts.clamp(1, N.min(MAX_PARTS));
    let total = weight_before(n);
    let mut start = 0;
    for p in 1..parts {
        if start >= n {
            break;
        }
        // The first allowed cut at or after the point where the weight reaches p/parts.
        let target = total * p as u64 / parts as u64;
        let mut at = partition(start, n, |i| weight_before(i) < target).max(start + 1);
        while at < n && !cut_ok(at) {
            at += 1;
        }
        if at >= n {
            break;
        }
        let _ = out.push(start..at);
        start = at;
    }
    if start < n || out.is_empty() {
        let _ = out.push(start..n);
    }
}

/// Widen `range` to cover index `i` (an empty range becomes `i..i + 1`): the hull of the
/// bodies a part wrote in its scratch arena.
#[inline(always)]
pub(crate) fn widen(range: &mut Range<usize>, i: usize) {
    if range.start >= range.end {
        *range = i..i + 1;
    } else {
        range.start = range.start.min(i);
        range.end = range.end.max(i + 1);
    }
}

/// The hull of two ranges (an empty range adds nothing).
pub(crate) fn hull(a: Range<usize>, b: Range<usize>) -> Range<usize> {
    match (a.is_empty(), b.is_empty()) {
        (true, _) => b,
        (_, true) => a,
        _ => a.start.min(b.start)..a.end.max(b.end),
    }
}

/// The first i in `lo..hi` with `!pred(i)` (`pred` true then false), or `hi`.
fn partition(mut lo: usize, mut hi: usize, pred: impl Fn(usize) -> bool) -> usize {
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        if pred(mid) {
            lo = mid + 1;
        } else {
            hi = mid;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;

    fn split(
        n: usize,
        parts: usize,
        cut: impl Fn(usize) -> bool,
    ) -> heapless::Vec<Range<usize>, MAX_PARTS> {
        let mut out = heapless::Vec::new();
        split_ranges(n, parts, |i| i as u64, cut, &mut out);
        out
    }

    #[test]
    fn ranges_cover_everything_in_order() {
        for n in [0, 1, 2, 7, 100] {
            for parts in [1, 2, 3, 4, 7, 200] {
                let r = split(n, parts, |i| i % 3 == 0);
                assert!(!r.is_empty());
                assert_eq!(r[0].start, 0);
                assert_eq!(r.last().unwrap().end, n);
                for w in r.windows(2) {
                    assert_eq!(w[0].end, w[1].start);
                    assert!(w[1].start % 3 == 0, "cut at a forbidden place");
                }
                assert!(r.len() <= parts.min(MAX_PARTS));
            }
        }
    }

    #[test]
    fn widen_and_hull_cover_their_inputs() {
        let mut r = 0..0;
        widen(&mut r, 7);
        assert_eq!(r, 7..8);
        widen(&mut r, 3);
        widen(&mut r, 5);
        assert_eq!(r, 3..8);
        assert_eq!(hull(0..0, 4..6), 4..6);
        assert_eq!(hull(4..6, 9..9), 4..6);
        assert_eq!(hull(4..6, 1..5), 1..6);
    }

    #[test]
    fn equal_weights_give_equal_ranges() {
        let r = split(100, 4, |_| true);
        let lens: heapless::Vec<usize, 4> = r.iter().map(|x| x.len()).collect();
        assert_eq!(&lens[..], &[25, 25, 25, 25]);
    }
}
