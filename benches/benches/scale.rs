//! Throughput and memory at scale: the packed block ([`PackedBlock`], a dense contact network
//! from the first step) of 2 000, 20 000 and 200 000 pod spheres, fixed point and f64, one
//! thread. Time and memory per particle should stay flat with size (issue 16).
//!
//! Each sample times [`STEPS`] steps of a block built (untimed) and stepped [`WARM_UP_STEPS`]
//! steps beforehand; criterion prints elements/s = particle-steps/s. Before the first sample of
//! each size the bench prints the arena bytes per sphere (every arena the world steps in: the
//! caller-provided [`OwnedStorage`]).
//!
//! The group `free_sphere` times [`FREE_STEPS`] steps of one pod sphere falling freely (no
//! wall, no contact), where only the fixed cost of a step (setting up its stages) is left: the
//! one-sphere rigs of a diagnosis and a calibration run millions of such steps.
//!
//! Run: `cargo bench -p arachis-benches --bench scale` (all sizes; the 200 000-sphere samples
//! take several seconds each), or e.g. `cargo bench -p arachis-benches --bench scale -- /2000`.

use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{SPHERE_RADIUS_UM, TIMESTEP_S};
use arachis_core::scenario::materials::{GRAVITY_M_S2, POD, POD_POD};
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
/// Steps timed per sample.
const STEPS: u64 = 100;
/// Steps timed per sample of the free sphere (0.4 s of fall at the bench bed's time step).
const FREE_STEPS: u64 = 20_000;
/// Steps run before timing, so the neighbour list and the contact history exist.
const WARM_UP_STEPS: u64 = 20;
/// Criterion's smallest sample count.
const SAMPLES: usize = 10;

/// Time `iters` runs of [`STEPS`] steps, each on a freshly built and warmed-up block.
fn time_runs<S: Scalar>(block: PackedBlock, iters: u64) -> Duration {
    let mut total = Duration::ZERO;
    for _ in 0..iters {
        let mut arenas = OwnedStorage::<S>::new(block.storage_lengths());
        let mut world = block.build(arenas.storage()).expect("packed block set-up");
        world.run(WARM_UP_STEPS).expect("warm-up steps");
        let t0 = Instant::now();
        world.run(STEPS).expect("timed steps");
        total += t0.elapsed();
        black_box(world.digest());
    }
    total
}

fn size<S: Scalar>(g: &mut BenchmarkGroup<'_, WallTime>, particles: u32) {
    let block = PackedBlock { particles };
    let bytes = OwnedStorage::<S>::new(block.storage_lengths()).bytes();
    eprintln!(
        "packed block of {particles} spheres ({}): {bytes} arena bytes, {:.0} per sphere",
        S::NAME,
        bytes as f64 / f64::from(particles)
    );
    g.throughput(Throughput::Elements(u64::from(particles) * STEPS));
    g.bench_with_input(BenchmarkId::new(S::NAME, particles), &block, |b, &block| {
        b.iter_custom(|iters| time_runs::<S>(block, iters))
    });
}

fn scale(c: &mut Criterion) {
    let mut g = c.benchmark_group("packed_block");
    g.sample_size(SAMPLES)
        .sampling_mode(SamplingMode::Flat)
        .warm_up_time(Duration::from_millis(1))
        .measurement_time(Duration::from_millis(1));
    for particles in SIZES {
        size::<Fx>(&mut g, particles);
        size::<f64>(&mut g, particles);
    }
    g.finish();
    let mut g = c.benchmark_group("free_sphere");
    g.sample_size(SAMPLES)
        .sampling_mode(SamplingMode::Flat)
        .measurement_time(Duration::from_secs(1))
        .throughput(Throughput::Elements(FREE_STEPS));
    g.bench_function(Fx::NAME, |b| {
        b.iter_custom(|iters| (0..iters).map(|_| time_free_fall()).sum())
    });
    g.finish();
}

/// Time [`FREE_STEPS`] steps of one freshly built pod sphere falling from rest.
fn time_free_fall() -> Duration {
    let mut arenas = OwnedStorage::<Fx>::new(StorageLengths::for_spheres(1, 1));
    let mut world = World::new(arenas.storage()).expect("world");
    let pod = world.add_material(POD).expect("material");
    world.set_pair(pod, pod, POD_POD).expect("pair");
    world.set_gravity_m_s2(GRAVITY_M_S2).expect("gravity");
    let radius_m = SPHERE_RADIUS_UM as f64 * 1e-6;
    world
        .add_sphere(SphereSpec::at_rest(pod, radius_m, [0.0; 3]))
        .expect("sphere");
    world.set_timestep_s(TIMESTEP_S).expect("time step");
    let t0 = Instant::now();
    world.run(FREE_STEPS).expect("free fall");
    let elapsed = t0.elapsed();
    black_box(world.digest());
    elapsed
}

criterion_group!(benches, scale);
criterion_main!(benches);
