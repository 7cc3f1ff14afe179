//! Throughput and memory at scale: the packed block ([`PackedBlock`], a dense contact network
//! from the first step) of 2 000, 20 000 and 200 000 pod spheres, fixed point and f64, one
//! thread. Time and memory per particle should stay flat with size (issue 16).
//!
//! Each sample times [`STEPS`] steps of a block built (untimed) and stepped [`WARM_UP_STEPS`]
//! steps beforehand; criterion prints elements/s = particle-steps/s. Before the first sample of
//! each size the bench prints the arena bytes per sphere (every arena the world steps in: the
//! caller-provided [`OwnedStorage`]).
//!
//! The group `small_block` times blocks of [`SMALL_SIZES`] spheres, where the fixed cost of a
//! step (setting up its stages) outweighs its contacts: the one-sphere rigs of a diagnosis and
//! a calibration run millions of such steps.
//!
//! Run: `cargo bench -p arachis-benches --bench scale` (all sizes; the 200 000-sphere samples
//! take several seconds each), or e.g. `cargo bench -p arachis-benches --bench scale -- /2000`.

use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use arachis_core::scenario::PackedBlock;
use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, BenchmarkId, Criterion, SamplingMode,
    Throughput,
};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Block sizes (spheres).
const SIZES: [u32; 3] = [2_000, 20_000, 200_000];
/// Small block sizes (spheres).
const SMALL_SIZES: [u32; 2] = [1, 8];
/// Steps timed per sample.
const STEPS: u64 = 100;
/// Steps timed per sample of a small block.
const SMALL_STEPS: u64 = 20_000;
/// Steps run before timing, so the neighbour list and the contact history exist.
const WARM_UP_STEPS: u64 = 20;
/// Criterion's smallest sample count.
const SAMPLES: usize = 10;

/// Time `iters` runs of `steps` steps, each on a freshly built and warmed-up block.
fn time_runs<S: Scalar>(block: PackedBlock, steps: u64, iters: u64) -> Duration {
    let mut total = Duration::ZERO;
    for _ in 0..iters {
        let mut arenas = OwnedStorage::<S>::new(block.storage_lengths());
        let mut world = block.build(arenas.storage()).expect("packed block set-up");
        world.run(WARM_UP_STEPS).expect("warm-up steps");
        let t0 = Instant::now();
        world.run(steps).expect("timed steps");
        total += t0.elapsed();
        black_box(world.digest());
    }
    total
}

fn size<S: Scalar>(g: &mut BenchmarkGroup<'_, WallTime>, particles: u32, steps: u64) {
    let block = PackedBlock { particles };
    let bytes = OwnedStorage::<S>::new(block.storage_lengths()).bytes();
    eprintln!(
        "packed block of {particles} spheres ({}): {bytes} arena bytes, {:.0} per sphere",
        S::NAME,
        bytes as f64 / f64::from(particles)
    );
    g.throughput(Throughput::Elements(u64::from(particles) * steps));
    g.bench_with_input(BenchmarkId::new(S::NAME, particles), &block, |b, &block| {
        b.iter_custom(|iters| time_runs::<S>(block, steps, iters))
    });
}

fn scale(c: &mut Criterion) {
    let mut g = c.benchmark_group("packed_block");
    g.sample_size(SAMPLES)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(1))
        .measurement_time(Duration::from_millis(1));
    for particles in SIZES {
        size::<Fx>(&mut g, particles, STEPS);
        size::<f64>(&mut g, particles, STEPS);
    }
    g.finish();
    let mut g = c.benchmark_group("small_block");
    g.sample_size(SAMPLES)
        .sampling_mode(SamplingMode::Flat)
        .measurement_time(Duration::from_secs(1));
    for particles in SMALL_SIZES {
        size::<Fx>(&mut g, particles, SMALL_STEPS);
    }
    g.finish();
}

criterion_group!(benches, scale);
criterion_main!(benches);
