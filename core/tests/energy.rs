//! Energy: frictionless spheres with e = 1 in a closed box, no gravity, keep their total
//! energy (kinetic + Hertz elastic, (8/15)E*√R* α^{5/2} per contact) within 0.1 % over 1e5
//! steps, in fixed point and f64. Energy is sampled every 10 steps, including during contacts.
//!
//! The integrator is kick–drift (leapfrog), so stored velocities sit half a step after the
//! positions; the energy at step n uses x_n and v_n = (v_{n−½} + v_{n+½})/2, the velocity-Verlet
//! synchronisation.

use crate::common;
use arachis_core::prelude::*;
use common::*;

const N: usize = 6;
const R: f64 = 4.0; // mm
const HALF: f64 = 25.0; // mm, box half-width

#[derive(Clone)]
struct Snap {
    pos: Vec<[f64; 3]>,
    vel: Vec<[f64; 3]>,
    mass: Vec<f64>,
}

fn snap<S: Scalar>(w: &World<S>) -> Snap {
    Snap {
        pos: w.spheres().iter().map(|s| s.position.to_f64()).collect(),
        vel: w.bodies().iter().map(|b| b.velocity.to_f64()).collect(),
        mass: w.bodies().iter().map(|b| b.mass.to_f64()).collect(),
    }
}

/// Energy at the positions of `before` with velocities averaged over `before` and `after`.
fn total_energy(before: &Snap, after: &Snap, e_pp: f64, e_pw: f64) -> f64 {
    let mut e = 0.0;
    for k in 0..before.vel.len() {
        let v: Vec<f64> = (0..3)
            .map(|d| 0.5 * (before.vel[k][d] + after.vel[k][d]))
            .collect();
        e += 0.5 * before.mass[k] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    }
    let s = &before.pos;
    for i in 0..s.len() {
        let p = s[i];
        for &q in &s[i + 1..] {
            let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
            let a = 2.0 * R - d;
            if a > 0.0 {
                e += 8.0 / 15.0 * e_pp * (R / 2.0).sqrt() * a.powf(2.5);
            }
        }
        for c in p {
            for a in [R - (c + HALF), R - (HALF - c)] {
                if a > 0.0 {
                    e += 8.0 / 15.0 * e_pw * R.sqrt() * a.powf(2.5);
                }
            }
        }
    }
    e
}

fn run<S: Scalar>() -> (f64, f64) {
    let mut o = Owned::<S>::new(N, N);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, pod, normal_only(1.0)).unwrap();
    w.set_pair(pod, steel, normal_only(1.0)).unwrap();
    let h = HALF * 1e-3;
    w.add_wall(WallSpec::fixed(
        WallGeometry::AaBox {
            min_m: [-h; 3],
            max_m: [h; 3],
        },
        steel,
    ))
    .unwrap();
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for k in 0..N {
        let pos = [
            (k % 3) as f64 * 0.012 - 0.012,
            (k / 3) as f64 * 0.012 - 0.006,
            rnd() * 0.02,
        ];
        let mut s = SphereSpec::at_rest(pod, R * 1e-3, pos);
        s.velocity_m_s = [rnd(), rnd(), rnd()];
        w.add_sphere(s).unwrap();
    }
    w.set_timestep_s(1.25e-5).unwrap();
    let e_pp = e_star_mpa(&POD, &POD);
    let e_pw = e_star_mpa(&POD, &STEEL);
    let mut before = snap(&w);
    w.step().unwrap();
    let e0 = total_energy(&before, &snap(&w), e_pp, e_pw);
    let mut worst = 0.0f64;
    let mut contact_steps = 0u32;
    let mut end = 0.0;
    for k in 0..100_000u32 {
        let sample = k % 10 == 0 || k == 99_999;
        if sample {
            before = snap(&w);
        }
        w.step().unwrap();
        if sample {
            end = total_energy(&before, &snap(&w), e_pp, e_pw) / e0 - 1.0;
            worst = worst.max(end.abs());
        }
        contact_steps += (w.walls()[0].force.norm().to_f64() != 0.0) as u32;
    }
    assert!(
        contact_steps > 1000,
        "too few wall contact steps ({contact_steps}) to test anything"
    );
    (worst, end)
}

#[test]
fn elastic_box_energy_fixed() {
    let (worst, end) = run::<Fx>();
    println!("fixed: worst |ΔE/E0| {worst:.3e}, at end {end:+.3e}");
    assert!(worst < 1e-3);
}

#[test]
fn elastic_box_energy_f64() {
    let (worst, end) = run::<f64>();
    println!("f64: worst |ΔE/E0| {worst:.3e}, at end {end:+.3e}");
    assert!(worst < 1e-3);
}
