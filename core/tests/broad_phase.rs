//! The cell-grid broad phase finds exactly the overlapping pairs a brute-force O(N²) search
//! finds, with a generous grid and with a grid so small that cells must be merged.

use crate::common;
use arachis_core::prelude::*;
use common::*;

fn count_contacts(cells_len: usize, seed: u64) -> (u32, u32) {
    let n = 300;
    let mut o = Owned::<Fx>::with_lengths(StorageLengths {
        cells: cells_len,
        ..StorageLengths::for_spheres(n, n)
    });
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_pair(pod, pod, PairSpec::hertz_mindlin(0.5, 0.5, 0.1))
        .unwrap();
    let mut s = seed;
    let mut rnd = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut pts = Vec::new();
    for k in 0..n {
        // Mixed radii 1–4 mm in a 60 mm cube, with a far outlier stretching the bounding box.
        let r = 0.001 + 0.003 * rnd();
        let p = if k == 0 {
            [5.0, 5.0, 5.0]
        } else {
            [0.06 * rnd(), 0.06 * rnd(), 0.06 * rnd()]
        };
        w.add_sphere(SphereSpec::at_rest(pod, r, p)).unwrap();
        pts.push((p, r));
    }
    w.set_timestep_s(1e-9).unwrap();
    w.step().unwrap();
    let mut brute = 0;
    for i in 0..n {
        for j in i + 1..n {
            let (p, a) = pts[i];
            let (q, b) = pts[j];
            let d2 = (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2);
            if d2 < (a + b) * (a + b) {
                brute += 1;
            }
        }
    }
    (w.contact_count(), brute)
}

#[test]
fn grid_matches_brute_force() {
    for (cells, seed) in [(100_000, 1u64), (2400, 7), (64, 99), (2, 5)] {
        let (grid, brute) = count_contacts(cells, seed);
        println!("cells {cells}: grid {grid} contacts, brute force {brute}");
        assert!(brute > 50, "test too sparse: {brute}");
        assert_eq!(grid, brute, "cells {cells}");
    }
}

/// Fuzz finding F2 (fuzz/examples/broad_phase_spread.rs): tiny spheres very far apart made the
/// cell-merge search take minutes; it is now a doubling + bisection, O(log k).
#[test]
fn far_apart_tiny_spheres_step_quickly() {
    for sep in [9e5, 3e5, 1.0] {
        let mut o = Owned::<Fx>::new(2, 2);
        let mut w = World::new(o.storage()).unwrap();
        let m = w
            .add_material(MaterialSpec {
                youngs_modulus_pa: 8.43e6,
                poisson: 0.386,
                density_kg_m3: 1e7,
            })
            .unwrap();
        w.set_pair(m, m, PairSpec::hertz_mindlin(0.335, 0.854, 0.346))
            .unwrap();
        w.add_sphere(SphereSpec::at_rest(m, 1e-5, [0.0; 3]))
            .unwrap();
        w.add_sphere(SphereSpec::at_rest(m, 1e-5, [sep; 3]))
            .unwrap();
        w.set_timestep_s(w.max_timestep_s() / 2.0).unwrap();
        let t = std::time::Instant::now();
        w.run(3).unwrap();
        assert!(
            t.elapsed().as_secs_f64() < 5.0,
            "separation {sep}: {:?}",
            t.elapsed()
        );
    }
}

/// Fuzz finding F1: centres 1e-6 mm apart along x (|d|² underflows Q32.32) must be pushed
/// apart along x, not along the coincident-centre fallback +z.
#[test]
fn near_coincident_centres_use_the_true_normal() {
    fn run<S: Scalar>() -> [f64; 3] {
        let mut o = Owned::<S>::new(2, 2);
        let mut w = World::new(o.storage()).unwrap();
        let pod = w.add_material(POD).unwrap();
        w.set_pair(pod, pod, normal_only(0.5)).unwrap();
        w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0; 3]))
            .unwrap();
        w.add_sphere(SphereSpec::at_rest(pod, 0.004, [1e-9, 0.0, 0.0]))
            .unwrap();
        w.set_timestep_s(1e-7).unwrap();
        w.step().unwrap();
        w.body(BodyId(1)).velocity.to_f64()
    }
    for (name, v) in [("fixed", run::<Fx>()), ("f64", run::<f64>())] {
        println!("{name}: v1 = {v:?}");
        assert!(v[0] > 0.0 && v[2].abs() < 1e-6 * v[0], "{name}: {v:?}");
    }
}
