//! Rolling friction (CDT, seed 000 eq. (7)): a sphere rolling without slip on a plane
//! decelerates at μr·g/1.4 and stops after 0.7·v0²/(μr·g) (DESIGN §7); within 2 %.
//! Also checks that the torque never reverses ω: once stopped, the sphere stays stopped.

use crate::common;
use arachis_core::prelude::*;
use common::*;

const G: f64 = 9.81;

fn roll<S: Scalar>(mu_r: f64, v0: f64) -> (f64, f64, f64) {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.5, 0.6, mu_r))
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    common::add_floor(&mut w, steel);
    let r = 0.004;
    w.add_sphere(SphereSpec::at_rest(pod, r, [0.0, 0.0, r + 1e-7]))
        .unwrap();
    let dt = 1e-5;
    w.set_timestep_s(dt).unwrap();
    w.run(5000).unwrap(); // settle on the plane
    w.set_body_velocity(BodyId(0), [v0, 0.0, 0.0], [0.0, v0 / r, 0.0])
        .unwrap();
    let x0 = w.body(BodyId(0)).position.x.to_f64();
    let t_stop = 1.4 * v0 / (mu_r * G);
    let n = (1.5 * t_stop / dt) as u64;
    let mut x_mid = 0.0;
    for k in 0..n {
        w.step().unwrap();
        if k == (1.2 * t_stop / dt) as u64 {
            x_mid = w.body(BodyId(0)).position.x.to_f64();
        }
    }
    let b = w.body(BodyId(0));
    let d = (b.position.x.to_f64() - x0) * 1e-3;
    (
        d,
        b.velocity.x.to_f64(),
        (b.position.x.to_f64() - x_mid) * 1e-3,
    )
}

fn check<S: Scalar>() {
    for (mu_r, v0) in [(0.1, 0.1), (0.346, 0.2), (0.159, 0.05)] {
        let (d, v_end, drift) = roll::<S>(mu_r, v0);
        let expected = 0.7 * v0 * v0 / (mu_r * G);
        let rel = d / expected - 1.0;
        println!(
            "{} μr {mu_r} v0 {v0}: distance {d:.6e} m, theory {expected:.6e} m ({:+.3}%), final v {v_end:.2e} m/s, drift after stop {drift:.2e} m",
            S::NAME,
            100.0 * rel
        );
        assert!(rel.abs() < 0.02, "{} μr {mu_r}: {d} vs {expected}", S::NAME);
        assert!(v_end.abs() < 1e-4, "{}: still moving {v_end}", S::NAME);
        // Stopped for good: a chattering constant torque would keep it creeping.
        assert!(
            drift.abs() < 1e-6,
            "{}: drift {drift} m after stopping",
            S::NAME
        );
    }
}

#[test]
fn cdt_rolling_distance_fixed() {
    check::<Fx>();
}

#[test]
fn cdt_rolling_distance_f64() {
    check::<f64>();
}

/// The CDT torque alone (tangential spring off) brings a spinning sphere to ω = 0 and never
/// past it: it cannot reverse ω within a step, up to rounding: f64 within 1e-15 rad/ms; fixed point within the
/// rounding of the direction vector, a few raw units (1 raw unit = 2.3e-10 rad/ms).
fn spin_down<S: Scalar>() -> (f64, f64) {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    let mut spec = PairSpec::hertz_mindlin(0.5, 0.6, 0.3);
    spec.terms.mindlin_tangential = false;
    w.set_pair(pod, steel, spec).unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    common::add_floor(&mut w, steel);
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 0.004 + 1e-7]))
        .unwrap();
    w.set_timestep_s(1e-5).unwrap();
    w.run(5000).unwrap();
    w.set_body_velocity(BodyId(0), [0.0; 3], [0.3, 1.0, 0.0])
        .unwrap();
    let mut min_along = f64::INFINITY;
    for _ in 0..20_000 {
        w.step().unwrap();
        let om = w.body(BodyId(0)).angular_velocity.to_f64();
        min_along = min_along.min(0.3 * om[0] + 1.0 * om[1]);
    }
    let om = w.body(BodyId(0)).angular_velocity.to_f64();
    (min_along, om[0].abs() + om[1].abs() + om[2].abs())
}

#[test]
fn cdt_never_reverses_spin() {
    let raw = 2f64.powi(-32);
    for (name, (min_along, end), floor) in [
        ("fixed", spin_down::<Fx>(), 4.0 * raw),
        ("f64", spin_down::<f64>(), 1e-15),
    ] {
        println!("{name}: min ω·ω̂0 {min_along:e} rad/ms, final |ω|₁ {end:e} rad/ms");
        assert!(min_along >= -floor, "{name}: reversed to {min_along}");
        assert!(end <= floor, "{name}: spin not stopped: {end}");
    }
}
