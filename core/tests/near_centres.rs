//! Regression test for fuzz finding F4: at very small centre distances (|d|² only a few dozen
//! raw Q32.32 units) the contact normal must still be a unit vector; otherwise vt = v − n(v·n)
//! keeps a part of the normal velocity and the tangential terms push along the normal.
//!
//! Set-up: two pod spheres (R 4 mm) whose centres are d apart, with only the tangential terms
//! on (Mindlin spring + tangential damping; no normal force, no Coulomb limit, no rolling), and
//! a relative velocity of 1 m/s along d plus 1 m/s across it. The contact force then lies in the
//! tangent plane exactly; the test measures |F·n̂|/|F| with n̂ = d/|d| computed in f64 from the
//! quantised centres.
//! Tolerance 1e-6: a unit normal rounded to Q32.32 leaks ≈ 1e-9; the unnormalised normal of
//! F4 leaked ≈ 1e-2 at |d| = 0.13 µm.

use crate::common;
use arachis_core::prelude::*;
use common::*;

/// Largest accepted |F·n̂|/|F|.
const LEAK_TOLERANCE: f64 = 1e-6;

fn tangential_only() -> PairSpec {
    PairSpec {
        restitution: 0.5,
        friction: 0.0,
        rolling_friction: 0.0,
        conventions: arachis_core::contact::Conventions::EDEM,
        terms: TermSwitches {
            hertz_normal: false,
            normal_damping: false,
            mindlin_tangential: true,
            tangential_damping: true,
            coulomb_limit: false,
            rolling_cdt: false,
        },
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// |F·n̂|/|F| on sphere 1 after one step, centres `d_m` (m) apart along (3, 4, 12)/13.
fn normal_leak<S: Scalar>(d_len_m: f64) -> f64 {
    let dir = [3.0 / 13.0, 4.0 / 13.0, 12.0 / 13.0];
    let across = [0.8, -0.6, 0.0]; // unit, ⟂ dir
    let d_m = dir.map(|c| c * d_len_m);
    let mut o = Owned::<S>::new(2, 2);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_pair(pod, pod, tangential_only()).unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0; 3]))
        .unwrap();
    let mut s = SphereSpec::at_rest(pod, 0.004, d_m);
    s.velocity_m_s = [0, 1, 2].map(|k| dir[k] + across[k]);
    w.add_sphere(s).unwrap();
    w.set_timestep_s(1e-6).unwrap();
    // n̂ from the quantised centres (before the step moves them), so that only the normal's
    // own rounding is measured, not the quantisation of the positions.
    let (p0, p1) = (
        w.spheres()[0].position.to_f64(),
        w.spheres()[1].position.to_f64(),
    );
    let dq = [p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]];
    let dir = dq.map(|c| c / norm(dq));
    w.step().unwrap();
    let f = w.body(BodyId(1)).force.to_f64();
    let f_len = norm(f);
    assert!(f_len > 0.0, "{}: no tangential force", S::NAME);
    let f_n = f[0] * dir[0] + f[1] * dir[1] + f[2] * dir[2];
    (f_n / f_len).abs()
}

#[test]
fn tangential_force_stays_in_the_tangent_plane_at_tiny_centre_distances() {
    // 0.13 µm: |d|² ≈ 1.7e-8 mm² ≈ 73 raw units; 13 µm; and an ordinary 7 mm.
    for d in [1.3e-7, 1.3e-5, 7e-3] {
        let fixed = normal_leak::<Fx>(d);
        let float = normal_leak::<f64>(d);
        println!("|d| = {d:.1e} m: normal leak fixed {fixed:.2e}, f64 {float:.2e}");
        assert!(
            fixed < LEAK_TOLERANCE,
            "fixed: leak {fixed:.3e} at |d| = {d:e} m"
        );
        assert!(
            float < LEAK_TOLERANCE,
            "f64: leak {float:.3e} at |d| = {d:e} m"
        );
    }
}
