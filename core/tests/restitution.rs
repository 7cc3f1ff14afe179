//! Restitution: rebound/impact speed ratio for input e ∈ {0.1, 0.3, 0.5, 0.7, 0.9} at 0.1, 1
//! and 5 m/s, pod sphere (R 4 mm) on a steel plane, normal terms only, no gravity.
//!
//! The core clips the total normal force at ≥ 0 (no attraction), so the effective e differs
//! from the input e (Thornton, Cummins & Cleary 2013). The measured ratio must agree within
//! 0.5 % with an independent adaptive RK45 integration of the same single-contact equation
//! (tests/common). `cargo test --test scenarios restitution:: -- --nocapture` prints the table.

use crate::common;
use arachis_core::prelude::*;
use common::*;

const ES: [f64; 5] = [0.1, 0.3, 0.5, 0.7, 0.9];
const VS: [f64; 3] = [0.1, 1.0, 5.0];
const R_M: f64 = 0.004;

fn measure<S: Scalar>(e: f64, v: f64) -> f64 {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, normal_only(e)).unwrap();
    common::add_floor(&mut w, steel);
    let mut s = SphereSpec::at_rest(pod, R_M, [0.0, 0.0, R_M + 1e-7]);
    s.velocity_m_s = [0.0, 0.0, -v];
    w.add_sphere(s).unwrap();
    let r = R_M * 1e3;
    let (_, _, t_c) = hertz_theory(
        sphere_mass_g(r, POD.density_kg_m3),
        r,
        e_star_mpa(&POD, &STEEL),
        v,
    );
    let dt_ms = t_c / 4000.0;
    w.set_timestep_s(dt_ms * 1e-3).unwrap();
    let mut touched = false;
    for _ in 0..1_000_000 {
        w.step().unwrap();
        let f = w.walls()[0].force.norm().to_f64();
        if f > 0.0 {
            touched = true;
        } else if touched {
            break;
        }
    }
    assert!(touched);
    w.body(BodyId(0)).velocity.z.to_f64() / v
}

fn table<S: Scalar>() {
    let r = R_M * 1e3;
    let m = sphere_mass_g(r, POD.density_kg_m3);
    let es = e_star_mpa(&POD, &STEEL);
    println!(
        "restitution ({}): input e | v m/s | measured | reference RK45 | rel. diff",
        S::NAME
    );
    let mut worst = 0.0f64;
    for &e in &ES {
        for &v in &VS {
            let got = measure::<S>(e, v);
            let reference = restitution_reference(m, r, es, e, v) / v;
            let rel = got / reference - 1.0;
            worst = worst.max(rel.abs());
            println!(
                "  {e:.1} | {v:>4} | {got:.6} | {reference:.6} | {:+.4}%",
                100.0 * rel
            );
            assert!(
                rel.abs() < 0.005,
                "{} e {e} v {v}: {got} vs {reference}",
                S::NAME
            );
        }
    }
    println!("  worst relative difference {:.4}%", 100.0 * worst);
}

#[test]
fn restitution_table_fixed() {
    table::<Fx>();
}

#[test]
fn restitution_table_f64() {
    table::<f64>();
}
