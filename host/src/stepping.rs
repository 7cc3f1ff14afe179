//! Stepping a core world on several threads.
//!
//! The core splits the contact and integration stages of a step into parts over disjoint body
//! ranges and lets the caller run them ([`arachis_core::step::parts::Parallel`]); it owns no
//! threads. [`Stepper`] runs those parts on a rayon pool of its own, with the per-thread force
//! arenas the core needs ([`OwnedThreadScratch`]). In fixed point the result is the same bits
//! for any thread count (DESIGN §5; tested in `core/tests/digest_scenarios.rs`), so the count
//! is a speed setting only.
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

use anyhow::Context;
use arachis_core::error::StepError;
use arachis_core::num::Scalar;
use arachis_core::owned::OwnedThreadScratch;
use arachis_core::step::parts::Parallel;
use arachis_core::world::World;
use rayon::prelude::*;
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

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

/// Run `steps` steps of `world` on [`run_threads`] threads (the pool is built once per
/// thread count and shared; the per-thread force arenas are allocated per call, so call it
/// for many steps at a time). Small worlds, where a thread hand-off costs more than it
/// saves, step on the calling thread.
pub fn run<S: Scalar>(world: &mut World<'_, S>, steps: u64) -> Result<(), StepError> {
    let threads = run_threads();
    if threads <= 1 || world.spheres().len() < MIN_SPHERES_PER_THREAD * threads {
        return world.run(steps);
    }
    let pool = shared_pool(threads);
    let mut scratch = OwnedThreadScratch::<S>::new(threads, world.bodies().len());
    let parts = PoolParts {
        pool: &pool,
        parts: threads,
    };
    let mut arenas = scratch.arenas();
    step_on_pool(world, steps, &parts, &mut arenas)
}

/// Run `steps` steps with the stepping loop itself on a thread of `parts.pool`: each stage's
/// parts are then split from that thread's own queue, which the other threads, still
/// spinning from the stage before, take at once. Calling the pool from outside for each stage
/// instead put the caller to sleep and woke the pool twice a step: 2 threads then gained only
/// 1.25–1.35× on the bench bed, with 2 s of system time in futex calls.
fn step_on_pool<S: Scalar>(
    world: &mut World<'_, S>,
    steps: u64,
    parts: &PoolParts<'_>,
    arenas: &mut [arachis_core::world::ThreadScratch<'_, S>],
) -> Result<(), StepError> {
    parts.pool.install(|| {
        for _ in 0..steps {
            world.step_with(parts, arenas)?;
        }
        Ok(())
    })
}

/// Fewer spheres than this per thread step on one thread in [`run`]: a part then holds too
/// little work to pay for waking a thread each stage (a few microseconds).
pub const MIN_SPHERES_PER_THREAD: usize = 256;

/// The process's pool of `threads` threads, built on first use.
fn shared_pool(threads: usize) -> Arc<rayon::ThreadPool> {
    static POOLS: Mutex<Vec<(usize, Arc<rayon::ThreadPool>)>> = Mutex::new(Vec::new());
    let mut pools = POOLS.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, p)) = pools.iter().find(|(n, _)| *n == threads) {
        return p.clone();
    }
    // A pool that cannot start degrades to rayon's global pool's behaviour on one thread.
    let pool = Arc::new(
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("arachis-step-{i}"))
            .build()
            .unwrap_or_else(|_| {
                rayon::ThreadPoolBuilder::new()
                    .num_threads(1)
                    .build()
                    .expect("a one-thread pool")
            }),
    );
    pools.push((threads, pool.clone()));
    pool
}

/// Check a `--threads` value: 1 to [`MAX_THREADS`].
pub fn check_threads(threads: usize) -> anyhow::Result<usize> {
    anyhow::ensure!(
        (1..=MAX_THREADS).contains(&threads),
        "--threads must be between 1 and {MAX_THREADS}, got {threads}"
    );
    Ok(threads)
}

/// Runs the parts of a stage on a rayon pool.
struct PoolParts<'p> {
    pool: &'p rayon::ThreadPool,
    parts: usize,
}

impl Parallel for PoolParts<'_> {
    fn parts(&self) -> usize {
        self.parts
    }
    /// Called from a thread of the pool ([`step_on_pool`]): the parts go to its queue.
    fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync)) {
        jobs.par_iter_mut().for_each(f);
    }
}

/// Steps worlds on a fixed number of threads (module docs).
pub struct Stepper<S: Scalar> {
    /// The pool, when more than one thread is asked for.
    pool: Option<rayon::ThreadPool>,
    threads: usize,
    /// Force arenas of the extra parts, sized for the last world stepped.
    scratch: OwnedThreadScratch<S>,
    scratch_bodies: usize,
}

impl<S: Scalar> Stepper<S> {
    /// A stepper on `threads` threads (1 steps on the calling thread). Errors for a count
    /// outside 1..=[`MAX_THREADS`] or when the operating system refuses the threads.
    pub fn new(threads: usize) -> anyhow::Result<Self> {
        let threads = check_threads(threads)?;
        let pool = if threads > 1 {
            Some(
                rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .thread_name(|i| format!("arachis-step-{i}"))
                    .build()
                    .context("cannot start the stepping threads")?,
            )
        } else {
            None
        };
        Ok(Stepper {
            pool,
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
        let Some(pool) = &self.pool else {
            return world.run(steps);
        };
        let bodies = world.bodies().len();
        if bodies != self.scratch_bodies {
            self.scratch = OwnedThreadScratch::new(self.threads, bodies);
            self.scratch_bodies = bodies;
        }
        let parts = PoolParts {
            pool,
            parts: self.threads,
        };
        let mut arenas = self.scratch.arenas();
        step_on_pool(world, steps, &parts, &mut arenas)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use arachis_core::prelude::*;
    use arachis_core::scenario::bench_bed::BenchBed;

    /// The same bed stepped on 1, 2 and 3 threads ends on the same digest.
    #[test]
    fn thread_count_does_not_change_the_bits() {
        let bed = BenchBed {
            particles: 300,
            seed: 7,
        };
        let digest = |threads| {
            let mut arena = crate::arena::OwnedStorage::<Fx>::new(bed.storage_lengths());
            let mut world = bed.build(arena.storage()).unwrap();
            Stepper::new(threads).unwrap().run(&mut world, 400).unwrap();
            world.digest()
        };
        let one = digest(1);
        assert_eq!(digest(2), one);
        assert_eq!(digest(3), one);
    }

    /// [`run`] on the default thread count gives the digest of a one-thread run.
    #[test]
    fn run_on_the_default_threads_matches_one_thread() {
        let bed = BenchBed {
            particles: 600,
            seed: 11,
        };
        let digest = |threaded: bool| {
            let mut arena = crate::arena::OwnedStorage::<Fx>::new(bed.storage_lengths());
            let mut world = bed.build(arena.storage()).unwrap();
            if threaded {
                run(&mut world, 300).unwrap();
            } else {
                world.run(300).unwrap();
            }
            world.digest()
        };
        assert_eq!(digest(true), digest(false));
    }

    #[test]
    fn refuses_zero_and_absurd_thread_counts() {
        assert!(Stepper::<Fx>::new(0).is_err());
        assert!(Stepper::<Fx>::new(MAX_THREADS + 1).is_err());
    }
}
