//! Micro benchmarks of the contact law alone, fixed point and f64:
//! - `contact_law_evaluate`: [`PairParams::evaluate`] on one pod–pod contact (all
//!   Hertz–Mindlin + CDT terms on);
//! - `contact_fused`: the fused base law ([`arachis_core::contact::fused`]) on the same
//!   contact, from the narrow phase's inputs;
//! - `contact_lanes`: the narrow-lane kernel ([`arachis_core::contact::lanes`]) on sixteen
//!   pod–pod contacts of the settled bed at once, in each build this processor runs, against
//!   the Q32.32 fused law on the same sixteen (`fixed`, one after another);
//! - `contact_roots`: the two square roots the narrow phase takes per contact, a = √(R*α) and
//!   √(a·m*) (seed 000 eqs. (2), (4)), over overlaps of the settled bed.
//!
//! The broad and narrow phases are crate-private in `arachis-core`, so they are measured only
//! inside the bench bed.
//!
//! Run: `cargo bench -p arachis-benches --bench contact_law`.

use arachis_core::contact::fused::{evaluate, FusedContact, FusedPair, Geometry};
use arachis_core::contact::lanes::{evaluate_with, Isa, LaneBatch, LANES};
use arachis_core::contact::{ContactKinematics, ContactState};
use arachis_core::material::MaterialSpec;
use arachis_core::num::Envelope;
use arachis_core::pair::{PairParams, PairSpec};
use arachis_core::prelude::{Fx, Scalar, Vec3};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use std::hint::black_box;

/// A pod–pod contact of the settled bed (internal units mm, g, ms): R* 2 mm, overlap 0.018 mm.
fn kinematics<S: Scalar>() -> ContactKinematics<S> {
    let r_star = 2.0_f64;
    let overlap = 0.018_f64;
    let m_star = 0.078_f64;
    let a = (r_star * overlap).sqrt();
    ContactKinematics {
        normal: Vec3::from_f64([0.0, 0.6, 0.8]),
        overlap: S::from_f64(overlap),
        contact_radius: S::from_f64(a),
        sqrt_a_mstar: S::from_f64((a * m_star).sqrt()),
        vn: S::from_f64(-0.01),
        vt: Vec3::from_f64([0.003, 0.0016, -0.0012]),
        dt: S::from_f64(0.02),
        lever_i: S::from_f64(3.99),
        lever_j: S::from_f64(3.99),
        r_star: S::from_f64(r_star),
        w_rel: Vec3::ZERO,
        rolling_inertia: S::ZERO,
    }
}

/// The pod–pod pair of the bench bed (DESIGN §8): e 0.335, μs 0.854, μr 0.346.
fn pod_pair<S: Scalar>() -> PairParams<S> {
    let pod = MaterialSpec {
        youngs_modulus_pa: 8.43e6,
        poisson: 0.386,
        density_kg_m3: 582.0,
    }
    .validate()
    .expect("pod material");
    PairParams::new(&pod, &pod, &PairSpec::hertz_mindlin(0.335, 0.854, 0.346))
}

fn bench_law<S: Scalar>(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    let params: PairParams<S> = pod_pair();
    let k = kinematics::<S>();
    let start = ContactState {
        delta: Vec3::from_f64([1e-4, -2e-4, 0.0]),
        ..ContactState::default()
    };
    g.bench_function(S::NAME, |b| {
        b.iter(|| {
            // Restart from the same history so every iteration does the same work.
            let mut state = start;
            let f = params.evaluate(black_box(&k), &mut state);
            black_box((f, state))
        })
    });
}

fn law(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact_law_evaluate");
    g.throughput(Throughput::Elements(1));
    bench_law::<Fx>(&mut g);
    bench_law::<f64>(&mut g);
    g.finish();
}

/// Overlaps α (mm) spread over a settled bed's range, so the roots see varied inputs.
const ROOT_OVERLAPS_MM: [f64; 8] = [0.002, 0.005, 0.009, 0.014, 0.018, 0.025, 0.04, 0.07];

fn bench_roots<S: Scalar>(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    let r_star = S::from_f64(2.0);
    let m_star = S::from_f64(0.078);
    let overlaps = ROOT_OVERLAPS_MM.map(S::from_f64);
    g.bench_function(S::NAME, |b| {
        b.iter(|| {
            overlaps.map(|alpha| {
                let a = (black_box(r_star) * alpha).sqrt();
                (a, (a * black_box(m_star)).sqrt())
            })
        })
    });
}

fn roots(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact_roots");
    g.throughput(Throughput::Elements(ROOT_OVERLAPS_MM.len() as u64));
    bench_roots::<Fx>(&mut g);
    bench_roots::<f64>(&mut g);
    g.finish();
}

/// The fused base law on the same contact, from the narrow phase's inputs.
fn bench_fused<S: Scalar>(g: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>)
where
    S::Fast: Envelope,
{
    let params: PairParams<S> = pod_pair();
    let pair = params.fused.fast();
    let f = |x: f64| S::from_f64(x).to_fast();
    // Centres 7.982 mm apart along (0, 0.6, 0.8): R 4 mm each, overlap 0.018 mm.
    let contact = FusedContact {
        geometry: Geometry::Spheres {
            d: Vec3::new(f(0.0), f(0.6 * 7.982), f(0.8 * 7.982)),
            d2: f(7.982 * 7.982),
            r_j: f(4.0),
        },
        r_i: f(4.0),
        r_star: f(2.0),
        m_star: f(0.078),
        v_centres: Vec3::new(f(0.003), f(-0.004), f(0.0012)),
        spin_i: Vec3::new(f(0.01), f(0.0), f(-0.02)),
        spin_j: Vec3::new(f(0.0), f(0.015), f(0.0)),
        offset_i: None,
        offset_j: None,
        dt: f(0.02),
    };
    let start = Vec3::new(f(1e-4), f(-2e-4), f(0.0));
    g.bench_function(S::NAME, |b| {
        b.iter(|| {
            let mut delta = start;
            let load = evaluate(black_box(&contact), black_box(&pair), &mut delta);
            black_box((load, delta))
        })
    });
}

fn fused(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact_fused");
    g.throughput(Throughput::Elements(1));
    bench_fused::<Fx>(&mut g);
    bench_fused::<f64>(&mut g);
    g.finish();
}

/// [`LANES`] pod–pod contacts of the settled bed: R 4 mm, overlaps near 0.018 mm, normals and
/// velocities varied (internal units), as the fused law and as one lane batch.
fn batch_contacts() -> (Vec<FusedContact<f64>>, LaneBatch, FusedPair<f64>) {
    let params: PairParams<f64> = pod_pair();
    let p = params.fused;
    let raw = |x: f64| (x * 4294967296.0).round() as i64;
    let mut batch = LaneBatch::default();
    let mut contacts = Vec::new();
    for l in 0..LANES {
        let t = 0.3 * l as f64;
        let dist = 7.982 - 0.002 * l as f64;
        let n = Vec3::new(0.6 * t.cos(), 0.6 * t.sin(), 0.8);
        let c = FusedContact {
            geometry: Geometry::Spheres {
                d: n.scale(dist),
                d2: dist * dist,
                r_j: 4.0,
            },
            r_i: 4.0,
            r_star: 2.0,
            m_star: 0.078,
            v_centres: Vec3::new(0.003, -0.004 * l as f64, 0.0012),
            spin_i: Vec3::new(0.01, 0.0, -0.02),
            spin_j: Vec3::new(0.0, 0.015, 0.001 * l as f64),
            offset_i: None,
            offset_j: None,
            dt: 0.02,
        };
        for k in 0..3 {
            let (d, v, wi, wj) = (n.scale(dist), c.v_centres, c.spin_i, c.spin_j);
            let pick = |x: Vec3<f64>| [x.x, x.y, x.z][k];
            batch.d[k][l] = raw(pick(d));
            batch.v[k][l] = raw(pick(v));
            batch.spin_i[k][l] = raw(pick(wi));
            batch.spin_j[k][l] = raw(pick(wj));
            batch.delta[k][l] = raw([1e-4, -2e-4, 0.0][k]);
        }
        batch.r_i[l] = raw(4.0);
        batch.r_j[l] = raw(4.0);
        batch.r_star[l] = raw(2.0);
        batch.m_star[l] = raw(0.078);
        batch.set_pair(l, &p.map(|x| Fx::from_f64(x).to_fast()));
        contacts.push(c);
    }
    (contacts, batch, p)
}

fn lanes(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact_lanes");
    g.throughput(Throughput::Elements(LANES as u64));
    let (contacts, batch, p) = batch_contacts();
    let dt = (0.02 * 4294967296.0f64).round() as i64;
    for isa in Isa::ALL.into_iter().filter(|i| i.available()) {
        g.bench_function(format!("{isa:?}"), |b| {
            b.iter(|| evaluate_with(isa, black_box(&batch), black_box(dt)))
        });
    }
    let to = |x: f64| Fx::from_f64(x).to_fast();
    let fixed: Vec<_> = contacts.iter().map(|c| c.map(to)).collect();
    let pair = p.map(to);
    let start = Vec3::new(to(1e-4), to(-2e-4), to(0.0));
    g.bench_function("fixed", |b| {
        b.iter(|| {
            for c in fixed.iter() {
                let mut delta = start;
                black_box((evaluate(black_box(c), black_box(&pair), &mut delta), delta));
            }
        })
    });
    g.finish();
}

criterion_group!(benches, law, roots, fused, lanes);
criterion_main!(benches);
