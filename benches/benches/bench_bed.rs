//! Throughput of the DESIGN §8 bench bed: 2 000 pod spheres (R 4 mm) poured into a 65Mn
//! steel cylinder (R 50 mm, floor at z = 0), dt 2e-5 s, in fixed point and in f64.
//!
//! The figure is particle-steps per second (DESIGN §8): criterion's
//! `Throughput::Elements(particles × steps)` makes it print elements/s = particle-steps/s.
//!
//! Groups:
//! - `bed_full_run/{fixed,f64}`: the whole 20 000-step run from insertion, settling included.
//!   Only the stepping is timed; building the world (set-up, f64, quantisation) is not.
//!   This is the figure compared with the 5.5e6 particle-steps/s target.
//! - `bed_pour_start/{fixed,f64}`: the first 2 000 steps from insertion (quick iteration).
//! - `bed_settled_step/{fixed,f64}`: one step of the settled bed (after 20 000 steps), the
//!   densest contact network; criterion picks the step count.
//!
//! Run: `cargo bench -p arachis-benches --bench bench_bed` (all), or filter, e.g.
//! `cargo bench -p arachis-benches --bench bench_bed -- bed_pour_start`.

use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{BenchBed, DESIGN_PARTICLES, DESIGN_SETTLE_STEPS};
use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, Criterion, SamplingMode, Throughput,
};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Number of particles of the DESIGN §8 bed.
const PARTICLES: u32 = DESIGN_PARTICLES;
/// Steps of the full run (DESIGN §8: settled by step 20 000).
const FULL_RUN_STEPS: u64 = DESIGN_SETTLE_STEPS;
/// Steps of the quick pour-start group.
const POUR_START_STEPS: u64 = 2_000;
/// Criterion's smallest sample count; one full run takes seconds.
const SAMPLES: usize = 10;

/// Owned arenas of one bench bed (the scenario module is `no_std` without `alloc`).
struct BedStorage<S: Scalar>(OwnedStorage<S>);

impl<S: Scalar> BedStorage<S> {
    fn new(bed: &BenchBed) -> Self {
        BedStorage(OwnedStorage::new(bed.storage_lengths()))
    }

    /// The DESIGN §8 bed (default seed, dt 2e-5 s) over these arenas.
    fn build(&mut self, bed: &BenchBed) -> World<'_, S> {
        bed.build(self.0.storage()).expect("bench bed set-up")
    }
}

/// Time `iters` runs of `steps` steps, each from a freshly built bed; set-up is not timed.
fn time_runs<S: Scalar>(iters: u64, steps: u64) -> Duration {
    let mut total = Duration::ZERO;
    for _ in 0..iters {
        let bed = BenchBed::design();
        let mut storage = BedStorage::<S>::new(&bed);
        let mut world = storage.build(&bed);
        let t0 = Instant::now();
        world.run(steps).expect("bench bed step");
        total += t0.elapsed();
        black_box(world.digest());
    }
    total
}

/// One group timing runs of `steps` steps from insertion, fixed point then f64.
fn from_insertion(c: &mut Criterion, group: &str, steps: u64) {
    let mut g = c.benchmark_group(group);
    // Flat sampling with a tiny time budget: criterion then runs one run per sample.
    g.sample_size(SAMPLES)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(1))
        .measurement_time(Duration::from_millis(1))
        .throughput(Throughput::Elements(u64::from(PARTICLES) * steps));
    g.bench_function(Fx::NAME, |b| {
        b.iter_custom(|iters| time_runs::<Fx>(iters, steps))
    });
    g.bench_function(f64::NAME, |b| {
        b.iter_custom(|iters| time_runs::<f64>(iters, steps))
    });
    g.finish();
}

fn settled_step<S: Scalar>(g: &mut BenchmarkGroup<'_, WallTime>) {
    // Settling costs a full run, so it happens only when the filter selects this benchmark
    // (criterion calls the closure only then); the storage is leaked once so the settled world
    // can live across criterion's calls of the closure.
    let mut storage: Option<&'static mut BedStorage<S>> =
        Some(Box::leak(Box::new(BedStorage::new(&BenchBed::design()))));
    let mut settled: Option<World<'static, S>> = None;
    g.bench_function(S::NAME, |b| {
        let world = settled.get_or_insert_with(|| {
            let st = storage.take().expect("storage is taken once");
            let mut w = st.build(&BenchBed::design());
            w.run(FULL_RUN_STEPS).expect("settling run");
            eprintln!(
                "bench bed ({}) after {FULL_RUN_STEPS} steps: kinetic energy {:.3e} J, \
                 {} contacts, digest {:016x}",
                S::NAME,
                w.kinetic_energy_mj() / arachis_core::units::ENERGY_J_TO_MJ,
                w.contact_count(),
                w.digest()
            );
            w
        });
        b.iter(|| world.step().expect("settled step"))
    });
}

fn full_run(c: &mut Criterion) {
    from_insertion(c, "bed_full_run", FULL_RUN_STEPS);
}

fn pour_start(c: &mut Criterion) {
    from_insertion(c, "bed_pour_start", POUR_START_STEPS);
}

fn settled(c: &mut Criterion) {
    let mut g = c.benchmark_group("bed_settled_step");
    g.sample_size(SAMPLES)
        .throughput(Throughput::Elements(u64::from(PARTICLES)));
    settled_step::<Fx>(&mut g);
    settled_step::<f64>(&mut g);
    g.finish();
}

criterion_group!(benches, pour_start, settled, full_run);
criterion_main!(benches);
