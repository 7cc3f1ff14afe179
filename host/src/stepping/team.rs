//! A team of threads that wait for the next stage by spinning, for the many short stages of a
//! threaded run.
//!
//! A step of the bench bed on two threads is about 0.5 ms, in two or three stages, and each
//! stage ends at a join. A rayon worker that finds no work spins only a few microseconds
//! and then sleeps; waking it costs a system call and tens of microseconds on a virtual
//! machine. Measured on the DESIGN §8 bed (2 000 spheres, 20 000 steps, 2 threads, rayon):
//! each thread sat idle about 19 % of the wall time. A [`Team`] keeps its helpers spinning
//! between stages, for as long as the run lasts, so a stage starts on every thread at once;
//! a wait that outlasts its spinning sleeps until the stage it waits for is published or
//! finished ([`Backoff`] says why it sleeps rather than yields).
//!
//! The team also times each part on the thread that runs it ([`Parallel::job_times`]), so that
//! the step can move its cuts until the parts take equally long
//! ([`arachis_core::step::balance`]); the times never change a result.
//!
//! The team lives inside [`std::thread::scope`]: [`Team::serve`] runs on each helper, the
//! stepping loop on the calling thread, and [`Team::finish`] lets the helpers go.
//!
//! ```
//! use arachis::stepping::team::Team;
//! use arachis_core::step::parts::Parallel;
//! let team = Team::new(2);
//! let mut sums = [0u64; 2];
//! std::thread::scope(|s| {
//!     s.spawn(|| team.serve(1));
//!     team.for_each(&mut sums, &|x: &mut u64| *x += 21);
//!     team.for_each(&mut sums, &|x: &mut u64| *x *= 2);
//!     team.finish();
//! });
//! assert_eq!(sums, [42, 42]);
//! ```

// The one place of the host that needs `unsafe`: a stage's closure borrows the step's data
// for less than the helpers live, so it is handed over as a raw pointer. Soundness rests on
// one rule, kept by `for_each`: it returns only after every helper has finished the stage
// and reported so (`pending` back at zero), and it writes the next stage's task only then.
#![allow(unsafe_code)]

use arachis_core::step::parts::{Parallel, MAX_PARTS};
use std::cell::UnsafeCell;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex, PoisonError};
use std::time::Instant;

/// Most spins (each a `pause` instruction, about 40–140 cycles) before a waiting thread
/// sleeps and gives its core to other threads instead: about a millisecond, several stages'
/// worth.
const MAX_SPINS: u32 = 20_000;
/// Fewest spins before sleeping, once waits keep outlasting the spinning ([`Backoff`]).
const MIN_SPINS: u32 = 16;

/// One stage's work: job `i` for a helper of index `i`.
type Task = *const (dyn Fn(usize) + Sync);

/// The threads of one run: the calling thread (part 0) and `parts − 1` helpers (module docs).
pub struct Team {
    parts: usize,
    /// Bumped by the caller to publish a stage.
    epoch: AtomicUsize,
    /// Helpers that have not yet finished the current stage.
    pending: AtomicUsize,
    /// The current stage's task and job count; written by the caller only while no helper
    /// is inside a stage (`pending` is zero).
    stage: UnsafeCell<(Option<Task>, usize)>,
    /// Set by [`Team::finish`]: the helpers return.
    done: AtomicBool,
    /// Set when a helper's job panicked; the caller panics in turn.
    panicked: AtomicBool,
    /// How long each job of the last stage ran, ns ([`Parallel::job_times`]).
    job_nanos: Vec<AtomicU64>,
    /// The job count of the last stage whose jobs were timed.
    timed_jobs: AtomicUsize,
    /// The caller's spin budget between its stages ([`Backoff`]; only the caller uses it).
    caller_spins: AtomicU32,
    /// Where a thread whose spinning is spent sleeps ([`Team::sleep_until`]); the mutex
    /// guards nothing but the hand-over between a sleeper and [`Team::wake_sleepers`].
    bed: Mutex<()>,
    wake: Condvar,
    /// Threads asleep on `wake`, or about to be.
    sleepers: AtomicUsize,
}

// SAFETY: `stage` is written only by the caller while every helper waits (module docs), and
// read by helpers only between the epoch they see and their `pending` decrement.
unsafe impl Sync for Team {}

/// A pointer to a stage's jobs that may cross threads: each index goes to one thread only.
struct Jobs<J>(*mut J);
// SAFETY: the jobs are `Send`, and no two threads get the same index.
unsafe impl<J: Send> Sync for Jobs<J> {}
unsafe impl<J: Send> Send for Jobs<J> {}

impl Team {
    /// A team for `parts` parts (at least 1): the caller and `parts − 1` helpers, each to
    /// be started on [`Team::serve`] with its index 1..parts.
    pub fn new(parts: usize) -> Self {
        Team {
            parts: parts.max(1),
            epoch: AtomicUsize::new(0),
            pending: AtomicUsize::new(0),
            stage: UnsafeCell::new((None, 0)),
            done: AtomicBool::new(false),
            panicked: AtomicBool::new(false),
            job_nanos: (0..MAX_PARTS).map(|_| AtomicU64::new(0)).collect(),
            timed_jobs: AtomicUsize::new(0),
            caller_spins: AtomicU32::new(MAX_SPINS),
            bed: Mutex::new(()),
            wake: Condvar::new(),
            sleepers: AtomicUsize::new(0),
        }
    }

    /// Run helper `index` (1..parts): every stage's job `index`, until [`Team::finish`].
    pub fn serve(&self, index: usize) {
        let mut seen = 0;
        let mut backoff = Backoff::new(MAX_SPINS);
        loop {
            let next = || self.epoch.load(Ordering::SeqCst) != seen || self.done();
            self.wait_until(&mut backoff, next);
            let epoch = self.epoch.load(Ordering::SeqCst);
            if epoch == seen {
                return; // finished, with no stage left to run
            }
            seen = epoch;
            // SAFETY: published before `epoch` (SeqCst) and not rewritten before this
            // helper decrements `pending` below.
            let (task, count) = unsafe { *self.stage.get() };
            if let (Some(task), true) = (task, index < count) {
                // SAFETY: the caller keeps the closure alive until `pending` is zero.
                let run = unsafe { &*task };
                if catch_unwind(AssertUnwindSafe(|| run(index))).is_err() {
                    self.panicked.store(true, Ordering::Release);
                }
            }
            if self.pending.fetch_sub(1, Ordering::SeqCst) == 1 {
                self.wake_sleepers();
            }
        }
    }

    /// Let the helpers return from [`Team::serve`] (call once the run is over).
    pub fn finish(&self) {
        self.done.store(true, Ordering::SeqCst);
        self.wake_sleepers();
    }

    /// Whether [`Team::finish`] was called.
    fn done(&self) -> bool {
        self.done.load(Ordering::SeqCst)
    }

    /// Spin until `ready` holds, and sleep once the spinning is spent.
    fn wait_until(&self, backoff: &mut Backoff, ready: impl Fn() -> bool) {
        while !ready() {
            if !backoff.spin() {
                self.sleep_until(&ready);
                break;
            }
        }
        backoff.done();
    }

    /// Sleep on the team's condition variable until `ready` holds.
    ///
    /// No wake-up is lost: a sleeper counts itself in `sleepers` and then tests `ready`, and
    /// a thread that makes `ready` true first publishes that and then reads `sleepers`, all
    /// in sequentially consistent order. So either the sleeper sees the change or the waker
    /// sees the sleeper, and then takes the mutex, which the sleeper holds until it waits.
    fn sleep_until(&self, ready: &impl Fn() -> bool) {
        let mut bed = self.bed.lock().unwrap_or_else(PoisonError::into_inner);
        self.sleepers.fetch_add(1, Ordering::SeqCst);
        while !ready() {
            bed = self.wake.wait(bed).unwrap_or_else(PoisonError::into_inner);
        }
        self.sleepers.fetch_sub(1, Ordering::SeqCst);
    }

    /// Wake every sleeper, after a change it may wait for ([`Team::sleep_until`]).
    fn wake_sleepers(&self) {
        if self.sleepers.load(Ordering::SeqCst) != 0 {
            let _bed = self.bed.lock().unwrap_or_else(PoisonError::into_inner);
            self.wake.notify_all();
        }
    }
}

/// How one thread waits, across the stages of a run: spin first, then sleep. The number of
/// spins adapts. A wait that ends while spinning doubles it (up to [`MAX_SPINS`]); a wait
/// that had to sleep halves it (down to [`MIN_SPINS`]).
///
/// Why: when the machine has more runnable threads than cores (two runs at once, as a test
/// harness or a user may start), the thread waited for is often off its core, and a waiter
/// that spins keeps it off. Measured with two `arachis pour` runs of 2 threads each at once
/// on 2 cores (2 000 spheres, 3 000 steps): 1.6 s each with a fixed millisecond of spinning,
/// against 0.40 s for one run alone. Yielding the core instead of sleeping was not enough:
/// the scheduler gives a yielding thread its core back at once when the thread it waits for
/// sits on the other core's queue, and a test of the bench bed's 600 spheres beside another
/// test took 227 s instead of about 20 (core/API_NOTES.md, "Threads that sleep").
#[derive(Debug, Clone, Copy)]
struct Backoff {
    budget: u32,
    spins: u32,
}

impl Backoff {
    /// A waiter that may spin `budget` times before sleeping.
    fn new(budget: u32) -> Self {
        Backoff { budget, spins: 0 }
    }

    /// Spin once, if the budget allows: false once it is spent (the waiter should sleep).
    #[inline]
    fn spin(&mut self) -> bool {
        if self.spins < self.budget {
            self.spins += 1;
            std::hint::spin_loop();
            true
        } else {
            self.spins = self.budget + 1;
            false
        }
    }

    /// The wait is over: adapt the budget for the next one.
    #[inline]
    fn done(&mut self) {
        self.budget = if self.spins <= self.budget {
            (self.budget * 2).min(MAX_SPINS)
        } else {
            (self.budget / 2).max(MIN_SPINS)
        };
        self.spins = 0;
    }
}

impl Parallel for Team {
    fn parts(&self) -> usize {
        self.parts
    }

    /// The wall-clock time of each job of the last stage, ns, measured on the thread that
    /// ran it.
    fn job_times(&self, out: &mut [u64]) -> bool {
        if out.len() < 2 || self.timed_jobs.load(Ordering::Relaxed) != out.len() {
            return false;
        }
        for (t, nanos) in out.iter_mut().zip(&self.job_nanos) {
            *t = nanos.load(Ordering::Relaxed);
        }
        true
    }

    /// Job 0 and any beyond the team's size on the calling thread, job i on helper i.
    fn for_each<J: Send>(&self, jobs: &mut [J], f: &(dyn Fn(&mut J) + Sync)) {
        let n = jobs.len();
        if self.parts == 1 || n <= 1 {
            self.timed_jobs.store(0, Ordering::Relaxed);
            jobs.iter_mut().for_each(f);
            return;
        }
        let ptr = Jobs(jobs.as_mut_ptr());
        let timed = n <= self.job_nanos.len();
        let run = move |i: usize| {
            let p = &ptr;
            let start = Instant::now();
            // SAFETY: i < n, and each index runs on exactly one thread.
            f(unsafe { &mut *p.0.add(i) });
            if timed {
                let nanos = start.elapsed().as_nanos().min(u64::MAX as u128) as u64;
                self.job_nanos[i].store(nanos, Ordering::Relaxed);
            }
        };
        let task: &(dyn Fn(usize) + Sync) = &run;
        // SAFETY: the pointer outlives its use: this function returns only after every
        // helper has decremented `pending`, and helpers touch the task only before that.
        let task: Task = unsafe {
            std::mem::transmute::<&(dyn Fn(usize) + Sync), &'static (dyn Fn(usize) + Sync)>(task)
        };
        // SAFETY: every helper is waiting for the next epoch (`pending` is zero).
        unsafe { *self.stage.get() = (Some(task), n) };
        self.pending.store(self.parts - 1, Ordering::Relaxed);
        self.epoch.fetch_add(1, Ordering::SeqCst);
        self.wake_sleepers();
        run(0);
        for i in self.parts..n {
            run(i);
        }
        let mut backoff = Backoff::new(self.caller_spins.load(Ordering::Relaxed));
        self.wait_until(&mut backoff, || self.pending.load(Ordering::SeqCst) == 0);
        self.caller_spins.store(backoff.budget, Ordering::Relaxed);
        // SAFETY: no helper is inside the stage any more.
        unsafe { *self.stage.get() = (None, 0) };
        self.timed_jobs
            .store(if timed { n } else { 0 }, Ordering::Relaxed);
        if self.panicked.load(Ordering::Acquire) {
            panic!("a stepping thread panicked");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wait that ends while spinning doubles the budget, one that had to sleep halves it,
    /// each within its bounds.
    #[test]
    fn the_spin_budget_follows_the_waits() {
        let mut b = Backoff::new(64);
        (0..10).for_each(|_| assert!(b.spin()));
        b.done();
        assert_eq!(b.budget, 128);
        assert_eq!((0..200).filter(|_| b.spin()).count(), 128);
        b.done();
        assert_eq!(b.budget, 64);
        for _ in 0..20 {
            (0..100_000).take(b.budget as usize + 1).for_each(|_| {
                b.spin();
            });
            b.done();
        }
        assert_eq!(b.budget, MIN_SPINS);
        for _ in 0..20 {
            assert!(b.spin());
            b.done();
        }
        assert_eq!(b.budget, MAX_SPINS);
    }

    /// Every job runs once per stage, on as many threads as the team has, for stages of any
    /// size (fewer jobs than threads, more jobs than threads).
    #[test]
    fn every_job_of_every_stage_runs_once() {
        let team = Team::new(3);
        let mut counts = vec![0u32; 5];
        std::thread::scope(|s| {
            s.spawn(|| team.serve(1));
            s.spawn(|| team.serve(2));
            for n in [5, 1, 2, 3, 0, 5] {
                team.for_each(&mut counts[..n], &|c: &mut u32| *c += 1);
            }
            team.finish();
        });
        assert_eq!(counts, [5, 4, 3, 2, 2]);
    }

    /// Helpers whose spinning is spent sleep, and every stage still wakes them: the caller
    /// pauses between stages far longer than any spin budget (at least 10 cycles a spin),
    /// and jobs sleep too, so both sides of the hand-over sleep in turn. A lost wake-up
    /// would hang the test.
    #[test]
    fn sleeping_threads_wake_for_every_stage() {
        let team = Team::new(3);
        let mut counts = [0u32; 3];
        let nap = std::time::Duration::from_millis(3);
        std::thread::scope(|s| {
            s.spawn(|| team.serve(1));
            s.spawn(|| team.serve(2));
            for stage in 0..40 {
                if stage % 2 == 0 {
                    std::thread::sleep(nap);
                }
                team.for_each(&mut counts, &|c: &mut u32| {
                    if *c % 3 == 1 {
                        std::thread::sleep(nap);
                    }
                    *c += 1;
                });
            }
            team.finish();
        });
        assert_eq!(counts, [40; 3]);
        assert_eq!(team.sleepers.load(Ordering::SeqCst), 0);
    }

    /// The team times each job of a stage on the thread that ran it, for the step's cuts;
    /// a stage of another job count gets no times.
    #[test]
    fn each_job_is_timed() {
        let team = Team::new(2);
        let nap = std::time::Duration::from_millis(20);
        std::thread::scope(|s| {
            s.spawn(|| team.serve(1));
            let mut jobs = [0u64, 1];
            team.for_each(&mut jobs, &|j: &mut u64| {
                if *j == 1 {
                    std::thread::sleep(nap);
                }
            });
            team.finish();
        });
        let mut times = [0u64; 2];
        assert!(team.job_times(&mut times));
        assert!(times[1] >= nap.as_nanos() as u64, "{times:?}");
        assert!(times[0] < times[1], "{times:?}");
        assert!(!team.job_times(&mut [0u64; 3]));
    }

    /// A job that panics on a helper makes the stage panic on the caller, not hang.
    #[test]
    fn a_panic_on_a_helper_reaches_the_caller() {
        let team = Team::new(2);
        let caught = std::thread::scope(|s| {
            s.spawn(|| team.serve(1));
            let r = catch_unwind(AssertUnwindSafe(|| {
                let mut jobs = [0, 1];
                team.for_each(&mut jobs, &|j: &mut i32| assert_eq!(*j, 0, "job {j}"));
            }));
            team.finish();
            r
        });
        assert!(caught.is_err());
    }
}
