//! The cell-grid broad phase finds exactly the overlapping pairs a brute-force O(N²) search
//! finds, with a generous grid and with a grid so small that cells must be merged.

mod common;
use arachis_core::prelude::*;
use common::*;

fn count_contacts(cells_len: usize, seed: u64) -> (u32, u32) {
    let n = 300;
    let mut o = Owned::<Fx>::new(n, n);
    o.cells.truncate(cells_len);
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
