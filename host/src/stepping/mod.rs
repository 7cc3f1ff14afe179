//! Stepping a core world on several threads.
//!
//! The core splits the contact and integration stages of a step into parts over disjoint body
//! ranges and lets the caller run them ([`arachis_core::step::parts::Parallel`]); it owns no
//! threads. [`run`] and [`Stepper`] run those parts on a [`Team`] of threads that spin
//! between stages, with the per-thread force arenas the core needs ([`OwnedThreadScratch`]).
//! In fixed point the result is the same bits for any thread count (DESIGN §5; tested in
//! `core/tests/digest_scenarios.rs`), so the count is a speed setting only.
//!
//! ```
//! use arachis::stepping::Stepper;
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::bench_bed::BenchBed;
//! let bed = BenchBed { particles: 50, seed: 1 };
//! let mut arena = arachis::arena::OwnedStorage::<Fx>::new(bed.storage_lengths());
//! let mut world = bed.build(arena.storage()).unwrap();
//! let mut stepper = Stepper::new(2).unwrap();
//! stepper.run(&mut world, 10).unwrap();
//! assert_eq!(world.step_count(), 10);
//! ```

use arachis_core::error::StepError;
use arachis_core::num::Scalar;
use arachis_core::owned::OwnedThreadScratch;
use arachis_core::world::World;

use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};

pub mod team;
use team::Team;

/// Largest `--threads` accepted: far more than any machine this runs on has cores, small
/// enough that a typo (`--threads 100000`) is refused instead of spawning threads.
pub const MAX_THREADS: usize = arachis_core::step::parts::MAX_PARTS;

/// Threads per run set by [`set_default_threads`] (0: not set).
static DEFAULT_THREADS: AtomicUsize = AtomicUsize::new(0);

/// Every core the operating system offers this process (1 if it cannot tell).
pub fn available_cores() -> usize {
    std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(MAX_THREADS)
}

/// The number of threads a run steps on when its caller does not say: the value of
/// [`set_default_threads`] (the command line's `--threads`), else every core.
pub fn default_threads() -> usize {
    match DEFAULT_THREADS.load(Ordering::Relaxed) {
        0 => available_cores(),
        n => n,
    }
}

thread_local! {
    /// Threads per run for [`run`] on this thread, set by [`with_threads`] (0: the default).
    static RUN_THREADS: Cell<usize> = const { Cell::new(0) };
}

/// Run `f` with [`run`] stepping on `threads` threads on this thread: a campaign that runs
/// several simulations at once gives each its share of the cores.
pub fn with_threads<R>(threads: usize, f: impl FnOnce() -> R) -> R {
    let before = RUN_THREADS.with(|t| t.replace(threads.clamp(1, MAX_THREADS)));
    let result = f();
    RUN_THREADS.with(|t| t.set(before));
    result
}

/// The threads [`run`] uses on this thread.
pub fn run_threads() -> usize {
    match RUN_THREADS.with(Cell::get) {
        0 => default_threads(),
        n => n,
    }
}

/// Set the threads per run of [`run`] for the rest of the process (a speed setting: in fixed
/// point the result does not depend on it). Errors as [`check_threads`].
pub fn set_default_threads(threads: usize) -> anyhow::Result<()> {
    DEFAULT_THREADS.store(check_threads(threads)?, Ordering::Relaxed);
    Ok(())
}

/// Run `steps` steps of `world` on [`run_threads`] threads (the helper threads start and the
/// per-thread force arenas are allocated per call, so call it for many steps at a time).
/// Small worlds, where a thread hand-off costs more than it saves, step on the calling
/// thread.
pub fn run<S: Scalar>(world: &mut World<'_, S>, steps: u64) -> Result<(), StepError> {
    let threads = run_threads();
    if threads <= 1 || world.spheres().len() < MIN_SPHERES_PER_THREAD * threads {
        return world.run(steps);
    }
    let mut scratch = OwnedThreadScratch::<S>::new(threads, world.bodies().len());
    let mut arenas = scratch.arenas();
    step_on_team(world, steps, threads, &mut arenas)
}

/// Run `steps` steps on a [`Team`] of up to `threads` threads, as many as [`Cores`] gives.
fn step_on_team<S: Scalar>(
    world: &mut World<'_, S>,
    steps: u64,
    threads: usize,
    arenas: &mut [arachis_core::world::ThreadScratch<'_, S>],
) -> Result<(), StepError> {
    let cores = Cores::reserve(threads);
    step_with_helpers(world, steps, cores.0, arenas)
}

/// Run `steps` steps in `parts` parts: the stepping loop on the calling thread (part 0), one
/// helper thread per other part, started for this call and let go at its end. A helper that
/// cannot be started leaves the run on the calling thread alone.
fn step_with_helpers<S: Scalar>(
    world: &mut World<'_, S>,
    steps: u64,
    parts: usize,
    arenas: &mut [arachis_core::world::ThreadScratch<'_, S>],
) -> Result<(), StepError> {
    if parts <= 1 {
        return world.run(steps);
    }
    let team = Team::new(parts);
    std::thread::scope(|s| {
        // Lets the helpers go however the loop below ends, a panic included.
        let _finish = Finish(&team);
        for i in 1..parts {
            let t = &team;
            let started = std::thread::Builder::new()
                .name(format!("arachis-step-{i}"))
                .spawn_scoped(s, move || t.serve(i));
            if started.is_err() {
                return world.run(steps);
            }
        }
        (0..steps).try_for_each(|_| world.step_with(&team, arenas))
    })
}

/// Cores taken by the threaded runs of this process, their calling threads included.
static CORES_IN_USE: AtomicUsize = AtomicUsize::new(0);

/// The cores one threaded run holds (at least 1), given back when dropped.
///
/// Why: a [`Team`]'s threads wait by spinning before they sleep, so two runs at once (two
/// tests of one test binary, say) should not put more threads on the cores than there are
/// cores, or a helper spins, and then pays a wake-up, while the thread it waits for has no
/// core. A run alone gets the threads it asks
/// for; beside others it gets what is free, at least its own calling thread. The result does
/// not depend on the count.
struct Cores(usize);

impl Cores {
    fn reserve(wanted: usize) -> Self {
        let total = available_cores();
        let mut in_use = CORES_IN_USE.load(Ordering::Relaxed);
        loop {
            let got = if in_use == 0 {
                wanted
            } else {
                wanted.min(total.saturating_sub(in_use)).max(1)
            };
            match CORES_IN_USE.compare_exchange_weak(
                in_use,
                in_use + got,
                Ordering::AcqRel,
                Ordering::Relaxed,
            ) {
                Ok(_) => return Cores(got),
                Err(now) => in_use = now,
            }
        }
    }
}

impl Drop for Cores {
    fn drop(&mut self) {
        CORES_IN_USE.fetch_sub(self.0, Ordering::AcqRel);
    }
}

/// Calls [`Team::finish`] when dropped.
struct Finish<'t>(&'t Team);

impl Drop for Finish<'_> {
    fn drop(&mut self) {
        self.0.finish();
    }
}

/// Fewer spheres than this per thread step on one thread in [`run`]: a part then holds too
/// little work to pay for handing a stage to a helper thread.
pub const MIN_SPHERES_PER_THREAD: usize = 256;

/// Check a `--threads` value: 1 to [`MAX_THREADS`].
pub fn check_threads(threads: usize) -> anyhow::Result<usize> {
    anyhow::ensure!(
        (1..=MAX_THREADS).contains(&threads),
        "--threads must be between 1 and {MAX_THREADS}, got {threads}"
    );
    Ok(threads)
}

/// Steps worlds on a fixed number of threads (module docs).
pub struct Stepper<S: Scalar> {
    threads: usize,
    /// Force arenas of the extra parts, sized for the last world stepped.
    scratch: OwnedThreadScratch<S>,
    scratch_bodies: usize,
}

impl<S: Scalar> Stepper<S> {
    /// A stepper on `threads` threads (1 steps on the calling thread; the helpers start for
    /// each [`Stepper::run`]). Errors for a count outside 1..=[`MAX_THREADS`].
    pub fn new(threads: usize) -> anyhow::Result<Self> {
        let threads = check_threads(threads)?;
        Ok(Stepper {
            threads,
            scratch: OwnedThreadScratch::new(0, 0),
            scratch_bodies: 0,
        })
    }

    /// The number of threads.
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// Run `steps` steps of `world`, stopping at the first error.
    pub fn run(&mut self, world: &mut World<'_, S>, steps: u64) -> Result<(), StepError> {
        if self.threads == 1 {
            return world.run(steps);
        }
        let bodies = world.bodies().len();
        if bodies != self.scratch_bodies {
            self.scratch = OwnedThreadScratch::new(self.threads, bodies);
            self.scratch_bodies = bodies;
        }
        let mut arenas = self.scratch.arenas();
        step_on_team(world, steps, self.threads, &mut arenas)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use arachis_core::prelude::*;
    use arachis_core::scenario::bench_bed::BenchBed;

    /// The digest of bench bed (`particles`, `seed`) after `step` has run it.
    fn bed_digest(particles: u32, seed: u64, step: impl FnOnce(&mut World<'_, Fx>)) -> u64 {
        let bed = BenchBed { particles, seed };
        let mut arena = crate::arena::OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut world = bed.build(arena.storage()).unwrap();
        step(&mut world);
        world.digest()
    }

    /// The same bed stepped on 1, 2 and 3 threads ends on the same digest.
    #[test]
    fn thread_count_does_not_change_the_bits() {
        let digest = |threads| {
            bed_digest(300, 7, |w| {
                Stepper::new(threads).unwrap().run(w, 400).unwrap()
            })
        };
        let one = digest(1);
        assert_eq!(digest(2), one);
        assert_eq!(digest(3), one);
    }

    /// Teams of exactly 2 and 3 threads (no core reservation, whatever else runs in the
    /// process) step the bed to the digest of a serial run.
    #[test]
    fn a_team_steps_to_the_serial_bits() {
        let digest = |parts: usize| {
            bed_digest(300, 7, |w| {
                let mut scratch = OwnedThreadScratch::<Fx>::new(parts, w.bodies().len());
                step_with_helpers(w, 400, parts, &mut scratch.arenas()).unwrap()
            })
        };
        let serial = digest(1);
        assert_eq!(digest(2), serial);
        assert_eq!(digest(3), serial);
    }

    /// [`run`] on the default thread count gives the digest of a one-thread run.
    #[test]
    fn run_on_the_default_threads_matches_one_thread() {
        let threaded = bed_digest(600, 11, |w| run(w, 300).unwrap());
        assert_eq!(threaded, bed_digest(600, 11, |w| w.run(300).unwrap()));
    }

    #[test]
    fn refuses_zero_and_absurd_thread_counts() {
        assert!(Stepper::<Fx>::new(0).is_err());
        assert!(Stepper::<Fx>::new(MAX_THREADS + 1).is_err());
    }
}
