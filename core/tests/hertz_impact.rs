//! Chung & Ooi (2011) tests 1–2: elastic normal impact (e = 1, μ = 0), sphere–plane and
//! sphere–sphere. Peak force, maximum overlap and contact duration within 1 % of Hertz theory,
//! in fixed point and f64.

use crate::common;
use arachis_core::prelude::*;
use common::*;

const R_M: f64 = 0.01; // 10 mm radius
const V: f64 = 0.2; // m/s approach speed

struct Measured {
    max_overlap: f64,
    peak_force: f64,
    duration: f64,
}

/// `sphere_sphere`: two equal spheres approaching at ±V/2; else one sphere onto a plane.
fn impact<S: Scalar>(sphere_sphere: bool) -> (Measured, (f64, f64, f64)) {
    let mut o = Owned::<S>::new(2, 2);
    let mut w = World::new(o.storage()).unwrap();
    let m = w.add_material(STIFF).unwrap();
    w.set_pair(m, m, normal_only(1.0)).unwrap();
    let r = R_M * 1e3;
    let mass = sphere_mass_g(r, STIFF.density_kg_m3);
    let e_star = e_star_mpa(&STIFF, &STIFF);
    let (m_star, r_star) = if sphere_sphere {
        (mass / 2.0, r / 2.0)
    } else {
        (mass, r)
    };
    let theory = hertz_theory(m_star, r_star, e_star, V);
    let gap = 1e-6; // m
    if sphere_sphere {
        let mut a = SphereSpec::at_rest(m, R_M, [0.0, 0.0, 0.0]);
        a.velocity_m_s = [V / 2.0, 0.0, 0.0];
        let mut b = SphereSpec::at_rest(m, R_M, [2.0 * R_M + gap, 0.0, 0.0]);
        b.velocity_m_s = [-V / 2.0, 0.0, 0.0];
        w.add_sphere(a).unwrap();
        w.add_sphere(b).unwrap();
    } else {
        common::add_floor(&mut w, m);
        let mut a = SphereSpec::at_rest(m, R_M, [0.0, 0.0, R_M + gap]);
        a.velocity_m_s = [0.0, 0.0, -V];
        w.add_sphere(a).unwrap();
    }
    let dt_ms = theory.2 / 2000.0;
    w.set_timestep_s(dt_ms * 1e-3).unwrap();
    let overlap = |w: &World<S>| -> f64 {
        let s = w.spheres();
        if sphere_sphere {
            2.0 * r - (s[1].position - s[0].position).norm().to_f64()
        } else {
            r - s[0].position.z.to_f64()
        }
    };
    let mut meas = Measured {
        max_overlap: 0.0,
        peak_force: 0.0,
        duration: 0.0,
    };
    let mut in_contact_steps = 0u64;
    let mut started = false;
    for _ in 0..100_000 {
        w.step().unwrap();
        // The force accumulated this step acted at the pre-step positions; the overlap after
        // the drift is the next step's. Use the force on the last body (its contact force).
        let f = w.bodies().last().unwrap().force.norm().to_f64();
        meas.peak_force = meas.peak_force.max(f);
        let a = overlap(&w);
        meas.max_overlap = meas.max_overlap.max(a);
        if f > 0.0 {
            started = true;
            in_contact_steps += 1;
        } else if started {
            break;
        }
    }
    meas.duration = in_contact_steps as f64 * dt_ms;
    (meas, theory)
}

fn check<S: Scalar>(sphere_sphere: bool) {
    let (m, (a, f, t)) = impact::<S>(sphere_sphere);
    let name = if sphere_sphere {
        "sphere-sphere"
    } else {
        "sphere-plane"
    };
    let ea = m.max_overlap / a - 1.0;
    let ef = m.peak_force / f - 1.0;
    let et = m.duration / t - 1.0;
    println!(
        "{name} {}: overlap {:.6e} mm (theory {a:.6e}, {:+.3}%), force {:.6} N (theory {f:.6}, {:+.3}%), duration {:.6e} ms (theory {t:.6e}, {:+.3}%)",
        S::NAME, m.max_overlap, 100.0 * ea, m.peak_force, 100.0 * ef, m.duration, 100.0 * et
    );
    assert!(ea.abs() < 0.01, "{name} {}: overlap error {ea}", S::NAME);
    assert!(ef.abs() < 0.01, "{name} {}: force error {ef}", S::NAME);
    assert!(et.abs() < 0.01, "{name} {}: duration error {et}", S::NAME);
}

#[test]
fn sphere_plane_fixed() {
    check::<Fx>(false);
}
#[test]
fn sphere_plane_f64() {
    check::<f64>(false);
}
#[test]
fn sphere_sphere_fixed() {
    check::<Fx>(true);
}
#[test]
fn sphere_sphere_f64() {
    check::<f64>(true);
}
