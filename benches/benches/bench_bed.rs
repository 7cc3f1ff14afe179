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

use arachis_core::prelude::*;
use bench_bed::BedStorage;
use criterion::measurement::WallTime;
use criterion::{
    criterion_group, criterion_main, BenchmarkGroup, Criterion, SamplingMode, Throughput,
};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Number of particles of the DESIGN §8 bed.
const PARTICLES: usize = bench_bed::PARTICLES;
/// Steps of the full run (DESIGN §8: settled by step 20 000).
const FULL_RUN_STEPS: u64 = bench_bed::SETTLE_STEPS;
/// Steps of the quick pour-start group.
const POUR_START_STEPS: u64 = 2_000;
/// Criterion's smallest sample count; one full run takes seconds.
const SAMPLES: usize = 10;

/// Time `iters` runs of `steps` steps, each from a freshly built bed; set-up is not timed.
fn time_runs<S: Scalar>(iters: u64, steps: u64) -> Duration {
    let mut total = Duration::ZERO;
    for _ in 0..iters {
        let mut storage = BedStorage::<S>::new(PARTICLES);
        let mut world = bench_bed::build(&mut storage, PARTICLES).expect("bench bed set-up");
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
        .throughput(Throughput::Elements(PARTICLES as u64 * steps));
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
        Some(Box::leak(Box::new(BedStorage::new(PARTICLES))));
    let mut settled: Option<World<'static, S>> = None;
    g.bench_function(S::NAME, |b| {
        let world = settled.get_or_insert_with(|| {
            let st = storage.take().expect("storage is taken once");
            let mut w = bench_bed::build(st, PARTICLES).expect("bench bed set-up");
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
        .throughput(Throughput::Elements(PARTICLES as u64));
    settled_step::<Fx>(&mut g);
    settled_step::<f64>(&mut g);
    g.finish();
}

criterion_group!(benches, pour_start, settled, full_run);
criterion_main!(benches);

/// TEMPORARY copy of the DESIGN §8 bed until `arachis_core::scenario` has it (branch `scen`);
/// then this module goes and the bench uses the scenario module.
mod bench_bed {
    use arachis_core::prelude::*;

    /// Particles of the bed.
    pub const PARTICLES: usize = 2_000;
    /// Steps by which the bed has settled (DESIGN §8).
    pub const SETTLE_STEPS: u64 = 20_000;
    const RADIUS_M: f64 = 0.004;
    const INSERT_RADIUS_M: f64 = 0.045;
    const INSERT_Z_MIN_M: f64 = 0.010;
    const INSERT_Z_MAX_M: f64 = 0.400;
    const CONTAINER_RADIUS_M: f64 = 0.050;
    const INSERT_SPEED_M_S: f64 = 0.2;
    const DT_S: f64 = 2e-5;
    const SEED: u64 = 0x0A2A_C415_BED0_0008;

    /// Owned arenas for one bed.
    pub struct BedStorage<S> {
        bodies: Vec<Body<S>>,
        spheres: Vec<Sphere<S>>,
        contacts: Vec<ContactSlot<S>>,
        index: Vec<u32>,
        cells: Vec<u32>,
    }

    impl<S: Scalar> BedStorage<S> {
        pub fn new(n: usize) -> Self {
            let l = StorageLengths::for_spheres(n, n);
            BedStorage {
                bodies: vec![Body::default(); l.bodies],
                spheres: vec![Sphere::default(); l.spheres],
                contacts: vec![ContactSlot::default(); l.contacts],
                index: vec![0; l.sphere_index],
                cells: vec![0; l.cells],
            }
        }
    }

    /// SplitMix64 → uniform [0, 1).
    fn uniform(state: &mut u64) -> f64 {
        *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = *state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Random sphere centres without overlap, spheres wholly inside r ≤ 45 mm,
    /// 10 mm ≤ z ≤ 400 mm (rejection sampling, fixed seed).
    fn centres(n: usize) -> Vec<[f64; 3]> {
        let mut s = SEED;
        let mut pts: Vec<[f64; 3]> = Vec::with_capacity(n);
        let rmax = INSERT_RADIUS_M - RADIUS_M;
        let min_d2 = (2.0 * RADIUS_M) * (2.0 * RADIUS_M);
        while pts.len() < n {
            let x = (2.0 * uniform(&mut s) - 1.0) * rmax;
            let y = (2.0 * uniform(&mut s) - 1.0) * rmax;
            let z = INSERT_Z_MIN_M
                + RADIUS_M
                + uniform(&mut s) * (INSERT_Z_MAX_M - INSERT_Z_MIN_M - 2.0 * RADIUS_M);
            if x * x + y * y > rmax * rmax {
                continue;
            }
            let clear = pts.iter().all(|p| {
                let d = [p[0] - x, p[1] - y, p[2] - z];
                d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= min_d2
            });
            if clear {
                pts.push([x, y, z]);
            }
        }
        pts
    }

    /// Build the bed in `st`.
    pub fn build<S: Scalar>(st: &mut BedStorage<S>, n: usize) -> Result<World<'_, S>, SetupError> {
        let mut w = World::new(Storage {
            bodies: &mut st.bodies,
            spheres: &mut st.spheres,
            contacts: &mut st.contacts,
            sphere_index: &mut st.index,
            cells: &mut st.cells,
        })?;
        let pod = w.add_material(MaterialSpec {
            youngs_modulus_pa: 8.43e6,
            poisson: 0.386,
            density_kg_m3: 582.0,
        })?;
        let steel = w.add_material(MaterialSpec {
            youngs_modulus_pa: 2.05e11,
            poisson: 0.3,
            density_kg_m3: 7865.0,
        })?;
        w.set_pair(pod, pod, PairSpec::hertz_mindlin(0.335, 0.854, 0.346))?;
        w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.339, 0.589, 0.159))?;
        w.set_gravity_m_s2([0.0, 0.0, -9.81])?;
        w.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: [0.0, 0.0, 1.0],
            },
            steel,
        ))?;
        w.add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                radius_m: CONTAINER_RADIUS_M,
                length_m: None,
            },
            steel,
        ))?;
        for p in centres(n) {
            let mut s = SphereSpec::at_rest(pod, RADIUS_M, p);
            s.velocity_m_s = [0.0, 0.0, -INSERT_SPEED_M_S];
            w.add_sphere(s)?;
        }
        w.set_timestep_s(DT_S)?;
        Ok(w)
    }
}
