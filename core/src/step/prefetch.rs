//! Memory hints for the stages that read spheres in neighbour-list order: a hint asks the
//! processor to start loading a cache line that a later iteration will read, so that the load
//! overlaps the work in between instead of stalling it. A hint changes no value and no
//! result; on processors without one it does nothing.
//!
//! Why: the contact scan reads each entry's partner sphere record (two cache lines) in the
//! order of the list, which is not the order of memory. Once the records outgrow the
//! processor's second-level cache (1 MiB here: about 5 460 sphere records), each such read
//! waits for the third level; perf put about half of the shipped field's scan samples on that load
//! (`core/API_NOTES.md`).
//!
//! ```
//! use arachis_core::step::prefetch::{prefetch_record, worth_hinting};
//! let records = [0u64; 32];
//! assert!(!worth_hinting(&records)); // 256 bytes stay in cache without hints
//! prefetch_record(&records, 8, 2); // a hint only: nothing to observe
//! prefetch_record(&records, 99, 1); // outside the records: nothing at all
//! assert_eq!(records[8], 0);
//! ```

/// Bytes of one cache line on the processors this core is tuned for (x86-64).
pub const CACHE_LINE_BYTES: usize = 64;

/// Bytes of one core's second-level cache on the machine the hints were measured on (Intel
/// Xeon, 1 MiB a core). Records that fit in it are read from it without a hint, and a hint
/// then costs its instructions for nothing: the bench bed (2 000 spheres, 384 KiB of sphere
/// records) ran no faster with hints, the shipped field (34 612 spheres, 6.6 MiB) in 0.84×
/// the time (core/API_NOTES.md).
pub const SECOND_LEVEL_CACHE_BYTES: usize = 1 << 20;

/// Whether records such as `records` are worth hinting: when they outgrow
/// [`SECOND_LEVEL_CACHE_BYTES`].
#[inline(always)]
pub fn worth_hinting<T>(records: &[T]) -> bool {
    core::mem::size_of_val(records) > SECOND_LEVEL_CACHE_BYTES
}

/// Hint that the first `lines` cache lines of `records[index]` will be read soon; nothing
/// when `index` lies outside `records` (a wall key in a neighbour entry, the end of a run).
#[inline(always)]
pub fn prefetch_record<T>(records: &[T], index: usize, lines: usize) {
    if let Some(r) = records.get(index) {
        prefetch_lines(r, lines);
    }
}

/// Hint that the `lines` cache lines starting at `at` will be read soon.
#[inline(always)]
fn prefetch_lines<T>(at: &T, lines: usize) {
    let base = at as *const T as *const i8;
    for k in 0..lines {
        // `wrapping_add`: the address is only a hint and is never dereferenced, so it may
        // run past the end of `at`'s allocation.
        hint(base.wrapping_add(k * CACHE_LINE_BYTES));
    }
}

#[cfg(target_arch = "x86_64")]
#[inline(always)]
fn hint(p: *const i8) {
    use core::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
    // SAFETY: a prefetch never faults and never changes memory, whatever the address; SSE,
    // which the instruction needs, is part of every x86-64 processor.
    unsafe { _mm_prefetch::<_MM_HINT_T0>(p) }
}

#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
fn hint(_p: *const i8) {}
