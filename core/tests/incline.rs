//! Sliding: a flat five-sphere clump on a steel plane under tilted gravity (equivalent to an
//! incline of angle θ). Below atan(μs) it stays put; above, it accelerates down the slope at
//! g(sin θ − μs cos θ) within 2 %.

use crate::common;
use arachis_core::prelude::*;
use common::*;

const MU: f64 = 0.5;
const G: f64 = 9.81;

/// Returns (x velocity at t1, at t2, t2 − t1, displacement between t1 and t2), SI units.
fn slide<S: Scalar>(theta_deg: f64) -> (f64, f64, f64, f64) {
    let mut o = Owned::<S>::new(1, 5);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.5, MU, 0.1))
        .unwrap();
    let th = theta_deg.to_radians();
    w.set_gravity_m_s2([G * th.sin(), 0.0, -G * th.cos()])
        .unwrap();
    common::add_floor(&mut w, steel);
    // A flat square "plate" (4 corner spheres, 8 mm apart, plus an overlapping centre
    // sphere): half-width 4 mm over a COM height of 2 mm, so it cannot tip below ≈ 63°.
    let r = 0.002;
    let z = r + 1e-6;
    let c = |x: f64, y: f64, rad: f64| ClumpSphere {
        center_m: [x, y, z],
        radius_m: rad,
        material: pod,
    };
    let spheres = [
        c(-0.004, -0.004, r),
        c(0.004, -0.004, r),
        c(-0.004, 0.004, r),
        c(0.004, 0.004, r),
        c(0.0, 0.0, r),
    ];
    w.add_clump(&ClumpSpec {
        spheres: &spheres,
        velocity_m_s: [0.0; 3],
        angular_velocity_rad_s: [0.0; 3],
    })
    .unwrap();
    let dt = 1e-5;
    w.set_timestep_s(dt).unwrap();
    let n1 = (0.05 / dt) as u64;
    let n2 = (0.15 / dt) as u64;
    w.run(n1).unwrap();
    let b = *w.body(BodyId(0));
    let (v1, x1) = (b.velocity.x.to_f64(), b.position.x.to_f64() * 1e-3);
    w.run(n2 - n1).unwrap();
    let b = *w.body(BodyId(0));
    let (v2, x2) = (b.velocity.x.to_f64(), b.position.x.to_f64() * 1e-3);
    (v1, v2, (n2 - n1) as f64 * dt, x2 - x1)
}

fn check<S: Scalar>() {
    let crit = MU.atan().to_degrees();
    for theta in [10.0, 20.0, 25.0] {
        let (v1, v2, _, dx) = slide::<S>(theta);
        println!(
            "{} θ {theta}° (< {crit:.2}°): v {v1:.3e} → {v2:.3e} m/s, creep {dx:.3e} m",
            S::NAME
        );
        assert!(dx.abs() < 1e-6, "{} θ {theta}: crept {dx} m", S::NAME);
        assert!(v2.abs() < 1e-4, "{} θ {theta}: v {v2}", S::NAME);
    }
    for theta in [30.0, 35.0, 45.0] {
        let (v1, v2, t, _) = slide::<S>(theta);
        let a = (v2 - v1) / t;
        let th = f64::to_radians(theta);
        let expected = G * (th.sin() - MU * th.cos());
        let rel = a / expected - 1.0;
        println!(
            "{} θ {theta}°: a {a:.5} m/s², theory {expected:.5} ({:+.3}%)",
            S::NAME,
            100.0 * rel
        );
        assert!(rel.abs() < 0.02, "{} θ {theta}: {a} vs {expected}", S::NAME);
    }
}

#[test]
fn clump_on_incline_fixed() {
    check::<Fx>();
}

#[test]
fn clump_on_incline_f64() {
    check::<f64>();
}
