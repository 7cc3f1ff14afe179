//! Optional effects against theory (pod sphere R 4 mm on a steel plane, normal terms only):
//! - viscoelastic damping: rebound/impact ratio at 0.5, 2 and 5 m/s vs an independent f64
//!   RK4 integration of Brilliantov's force law (tolerance 0.3 %), and e falls with speed;
//! - SJKR cohesion: resting overlap under gravity vs the root of (4/3)E*√R α^{3/2} − 2πkRα = mg
//!   (tolerance 0.5 %);
//! - air drag: free-fall distance after 0.5 s vs the closed form (v_t²/g)·ln cosh(g t/v_t)
//!   (tolerance 0.05 %);
//! - with every effect set to its off value, the state digest equals the plain law's.

use crate::common;
use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use common::*;

const R_M: f64 = 0.004;

fn world_on_floor<S: Scalar>(
    o: &mut Owned<S>,
    e: f64,
    fx: EffectSpec,
    z_m: f64,
    v: f64,
) -> World<'_, S> {
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, normal_only(e)).unwrap();
    w.set_pair_effects(pod, steel, fx).unwrap();
    common::add_floor(&mut w, steel);
    let mut s = SphereSpec::at_rest(pod, R_M, [0.0, 0.0, z_m]);
    s.velocity_m_s = [0.0, 0.0, -v];
    w.add_sphere(s).unwrap();
    w
}

/// Rebound/impact ratio of the core with viscoelastic time `tau_s` and no other damping.
fn core_rebound(tau_s: f64, v: f64) -> f64 {
    let fx = EffectSpec {
        viscoelastic_time_s: tau_s,
        ..EffectSpec::default()
    };
    rebound_ratio(fx, v)
}

/// Rebound/impact ratio of a sphere dropped on the floor at `v` m/s with effects `fx` and no
/// other damping: stepped (dt = t_c/4000) until the contact has ended and the sphere rises.
fn rebound_ratio(fx: EffectSpec, v: f64) -> f64 {
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = world_on_floor(&mut o, 1.0, fx, R_M + 1e-7, v);
    let r = R_M * 1e3;
    let (_, _, t_c) = hertz_theory(
        sphere_mass_g(r, POD.density_kg_m3),
        r,
        e_star_mpa(&POD, &STEEL),
        v,
    );
    w.set_timestep_s(t_c / 4000.0 * 1e-3).unwrap();
    let mut touched = false;
    for _ in 0..1_000_000 {
        w.step().unwrap();
        if w.walls()[0].force.norm().to_f64() > 0.0 {
            touched = true;
        } else if touched && w.body(BodyId(0)).velocity.z.to_f64() > 0.0 {
            break;
        }
    }
    w.body(BodyId(0)).velocity.z.to_f64() / v
}

/// Independent reference: RK4 of m ξ̈ = −max(0, (4/3)E*√R (ξ^{3/2} + A√ξ ξ̇)), internal units.
fn reference_rebound(tau_s: f64, v: f64) -> f64 {
    let r = R_M * 1e3;
    let m = sphere_mass_g(r, POD.density_kg_m3);
    let es = e_star_mpa(&POD, &STEEL);
    let a_ms = tau_s * 1e3;
    let acc = |x: f64, xd: f64| -> f64 {
        if x <= 0.0 {
            return 0.0;
        }
        let f = 4.0 / 3.0 * es * (r * x).sqrt() * (x + a_ms * xd);
        -f.max(0.0) / m
    };
    let (_, _, t_c) = hertz_theory(m, r, es, v);
    let h = t_c / 200_000.0;
    let (mut x, mut xd) = (0.0f64, v);
    loop {
        let k1 = (xd, acc(x, xd));
        let k2 = (
            xd + 0.5 * h * k1.1,
            acc(x + 0.5 * h * k1.0, xd + 0.5 * h * k1.1),
        );
        let k3 = (
            xd + 0.5 * h * k2.1,
            acc(x + 0.5 * h * k2.0, xd + 0.5 * h * k2.1),
        );
        let k4 = (xd + h * k3.1, acc(x + h * k3.0, xd + h * k3.1));
        x += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        xd += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        if x <= 0.0 && xd < 0.0 {
            return -xd / v;
        }
    }
}

#[test]
fn viscoelastic_restitution_matches_reference_and_falls_with_speed() {
    let tau = 1.0e-5;
    let mut last = f64::INFINITY;
    for v in [0.5, 2.0, 5.0] {
        let got = core_rebound(tau, v);
        let reference = reference_rebound(tau, v);
        println!("viscoelastic A {tau:e} s, v {v} m/s: core {got:.5}, RK4 {reference:.5}");
        assert!(
            (got / reference - 1.0).abs() < 3e-3,
            "v {v}: {got} vs {reference}"
        );
        assert!(got < last, "restitution must fall with impact speed");
        last = got;
    }
    // Off value: perfectly elastic (no other damping on).
    assert!((core_rebound(0.0, 2.0) - 1.0).abs() < 2e-3);
}

#[test]
fn sjkr_resting_overlap_matches_force_balance() {
    let k = 2.0e4; // J/m³
    let mut o = Owned::<Fx>::new(1, 1);
    let fx = EffectSpec {
        cohesion_energy_density_j_m3: k,
        ..EffectSpec::default()
    };
    let mut w = world_on_floor(&mut o, 0.2, fx, R_M, 0.0);
    let g = 9.81;
    w.set_gravity_m_s2([0.0, 0.0, -g]).unwrap();
    w.set_timestep_s(5e-6).unwrap();
    w.run(8000).unwrap();
    let got_mm = R_M * 1e3 - w.body(BodyId(0)).position.z.to_f64();
    // Force balance in N and mm.
    let r = R_M * 1e3;
    let es = e_star_mpa(&POD, &STEEL);
    let weight_n = sphere_mass_g(r, POD.density_kg_m3) * 1e-3 * g;
    let net = |a: f64| {
        4.0 / 3.0 * es * r.sqrt() * a.powf(1.5)
            - 2.0 * std::f64::consts::PI * k * 1e-6 * r * a
            - weight_n
    };
    let (mut lo, mut hi) = (1e-6, 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if net(mid) > 0.0 {
            hi = mid
        } else {
            lo = mid
        }
    }
    let hertz_only = (3.0 * weight_n / (4.0 * es * r.sqrt())).powf(2.0 / 3.0);
    println!("SJKR k {k} J/m³: resting overlap core {got_mm:.6} mm, balance {lo:.6} mm, Hertz only {hertz_only:.6} mm");
    assert!((got_mm / lo - 1.0).abs() < 5e-3);
    assert!(
        lo > hertz_only * 1.05,
        "cohesion must deepen the overlap noticeably"
    );
}

#[test]
fn air_drag_fall_matches_closed_form() {
    let cd = 0.47;
    let rho = arachis_core::effects::AIR_DENSITY_20C_KG_M3;
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, 1.0]))
        .unwrap();
    let g = 9.81;
    w.set_gravity_m_s2([0.0, 0.0, -g]).unwrap();
    w.set_air_drag(rho, cd).unwrap();
    let dt = 5e-5;
    w.set_timestep_s(dt).unwrap();
    let n = 10_000u64; // 0.5 s
    w.run(n).unwrap();
    let t = n as f64 * dt;
    let fell_m = 1.0 - w.body(BodyId(0)).position.z.to_f64() * 1e-3;
    let m_kg = sphere_mass_g(R_M * 1e3, POD.density_kg_m3) * 1e-3;
    let area = std::f64::consts::PI * R_M * R_M;
    let vt = (2.0 * m_kg * g / (rho * cd * area)).sqrt();
    let theory = vt * vt / g * (g * t / vt).cosh().ln();
    let vacuum = 0.5 * g * t * t;
    println!("drag Cd {cd}: fell {fell_m:.6} m in {t} s, closed form {theory:.6} m, vacuum {vacuum:.6} m");
    // Kick–drift integration error is O(dt) in position: g·t·dt/2 ≈ 1.2e-4 m here.
    assert!((fell_m - theory).abs() < 5e-4 * theory);
    assert!(vacuum - theory > 20.0 * (fell_m - theory).abs());
}

#[test]
fn effects_off_leave_the_state_bit_identical() {
    let run = |set: bool| {
        let mut o = Owned::<Fx>::new(1, 1);
        let mut w = world_on_floor(&mut o, 0.5, EffectSpec::default(), R_M + 1e-4, 1.0);
        if set {
            w.set_air_drag(1.2, 0.0).unwrap();
        }
        w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
        w.set_timestep_s(5e-6).unwrap();
        w.run(400).unwrap();
        w.digest()
    };
    assert_eq!(run(false), run(true));
}

#[test]
fn hysteretic_restitution_is_sqrt_one_minus_lambda() {
    // Hertz loading, shifted-Hertz unloading, no other damping: e = √(1 − λ) at any speed
    // (energy argument in contact/hysteretic_normal.rs). Tolerance 0.3 % (time discretisation).
    for (lambda, v) in [(0.3, 0.5), (0.3, 3.0), (0.6, 1.0)] {
        let fx = EffectSpec {
            plastic_fraction: lambda,
            ..EffectSpec::default()
        };
        let e = rebound_ratio(fx, v);
        let theory = (1.0 - lambda).sqrt();
        println!("hysteretic lambda {lambda}, v {v} m/s: e {e:.5}, theory {theory:.5}");
        assert!((e / theory - 1.0).abs() < 3e-3, "{e} vs {theory}");
    }
}
