//! Regression test for fuzz finding F3: gravity must accelerate every body at g, however
//! light. It used to enter only as the force m·g rounded to Q32.32 (2⁻³² N); for a 0.1 mm pod
//! sphere (m ≈ 2.4e-6 g, m·g ≈ 104 raw units) that rounding alone shifted the acceleration by
//! ≈ 0.4 %. The integrator now adds g itself to the contact acceleration.
//!
//! Free fall of one sphere for N steps (no contacts, no walls): the velocity after N steps is
//! compared with N·g·dt. Expected error in fixed point: each step adds g·dt rounded to the
//! 2⁻³² mm/ms grid (≤ ½ unit), so |Δv| ≤ N/2 units plus the quantisation of g and dt
//! (relative 2⁻³² / g_internal and 2⁻³² / dt_internal); the tolerance below is that bound.

use crate::common;
use arachis_core::prelude::*;
use common::*;

/// Steps of free fall.
const STEPS: u64 = 2_000;
/// Gravity, m/s².
const G_M_S2: f64 = 9.81;
/// One Q32.32 unit.
const UNIT: f64 = 1.0 / 4_294_967_296.0;

fn fall_velocity<S: Scalar>(radius_m: f64) -> (f64, f64) {
    let mut o = Owned::<S>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -G_M_S2]).unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, radius_m, [0.0; 3]))
        .unwrap();
    let dt_s = 0.5 * w.max_timestep_s();
    w.set_timestep_s(dt_s).unwrap();
    w.run(STEPS).unwrap();
    // Internal units: mm/ms = m/s; g in mm/ms² = 1e-3·m/s²; dt in ms.
    let g = G_M_S2 * 1e-3;
    let dt_ms = dt_s * 1e3;
    let expected = -g * dt_ms * STEPS as f64;
    let got = w.body(BodyId(0)).velocity.z.to_f64();
    // Bound: ½ unit per step, plus N·dt·(g quantisation) + N·g·(dt quantisation).
    let tol = STEPS as f64 * (0.5 * UNIT + dt_ms * 0.5 * UNIT + g * 0.5 * UNIT) + UNIT;
    ((got - expected).abs(), tol)
}

#[test]
fn light_spheres_fall_at_g() {
    for r_m in [1.0e-4, 4.0e-3] {
        let (err, tol) = fall_velocity::<Fx>(r_m);
        println!("R = {r_m:e} m: |v − N·g·dt| = {err:.3e} m/s (bound {tol:.3e})");
        assert!(
            err <= tol,
            "fixed, R = {r_m} m: error {err:e} m/s > {tol:e}"
        );
        let (err, _) = fall_velocity::<f64>(r_m);
        assert!(err <= 1e-12, "f64, R = {r_m} m: error {err:e} m/s");
    }
}
