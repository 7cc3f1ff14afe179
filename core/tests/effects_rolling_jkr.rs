//! EPSD rolling resistance and full JKR cohesion against theory (pod spheres R 4 mm):
//! - EPSD, sphere at rest on a slope with tan φ < μr: the contact holds it at the spring's
//!   static angle θ = m·g·sin φ·(R − α/2)/k_r, k_r = 2.25·(2E*a)·μr²·R² with the Hertz a of
//!   Fn = m·g·cos φ (independent f64 calculation; tolerance 0.5 %), both from the stored θr and
//!   from the sphere's integrated rotation;
//! - EPSD above the limit (tan φ > μr): the sphere rolls with the limiting torque μr·R·Fn,
//!   acceleration g(sin φ − μr cos φ·R/R_c)/(1 + 0.4R²/R_c²), R_c = R − α/2 (tolerance 0.5 %),
//!   and within 0.2 % of the CDT law with the same μr;
//! - JKR, a sphere hanging under a fixed one with gravity ramped slowly up: at m·g = 0.5·F_c
//!   it rests at the analytic JKR overlap (tolerance 1 % of |δ|); it stays attached at
//!   0.99·F_c and falls off at 1.01·F_c, F_c = 1.5πΓR* (force-controlled pull-off).

use crate::common;
use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use common::*;
use std::f64::consts::PI;

const R_M: f64 = 0.004;
const G: f64 = 9.81;
/// Time step, s (as the CDT rolling test).
const DT_S: f64 = 1e-5;

/// Hertz overlap (mm) of a sphere (R mm) pressed by Fn (N) on a plane: Fn = (4/3)E*√R α^{3/2}.
fn hertz_overlap(fn_n: f64, r: f64, es: f64) -> f64 {
    (3.0 * fn_n / (4.0 * es * r.sqrt())).powf(2.0 / 3.0)
}

/// A pod sphere on a steel plane with gravity tilted by `phi` about y (slope along +x),
/// contact with μs `mu_s`, CDT μr `cdt`, and `fx` effects.
fn slope(o: &mut Owned<Fx>, phi: f64, mu_s: f64, cdt: f64, fx: EffectSpec) -> World<'_, Fx> {
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let steel = w.add_material(STEEL).unwrap();
    w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.5, mu_s, cdt))
        .unwrap();
    w.set_pair_effects(pod, steel, fx).unwrap();
    w.set_gravity_m_s2([G * phi.sin(), 0.0, -G * phi.cos()])
        .unwrap();
    common::add_floor(&mut w, steel);
    w.add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, R_M + 1e-7]))
        .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w
}

fn epsd(mu_r: f64) -> EffectSpec {
    EffectSpec {
        epsd_rolling_friction: mu_r,
        epsd_damping_ratio: 0.3,
        ..EffectSpec::default()
    }
}

#[test]
fn epsd_holds_a_sphere_at_the_static_spring_angle() {
    let mu_r = 0.3;
    let phi = 0.15f64.atan();
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = slope(&mut o, phi, 0.6, 0.0, epsd(mu_r));
    // Integrate the sphere's rotation about y (a single sphere's orientation is not kept).
    let mut turned = 0.0;
    for _ in 0..10_000 {
        w.step().unwrap();
        turned += w.body(BodyId(0)).angular_velocity.y.to_f64() * DT_S * 1e3;
    }
    let b = w.body(BodyId(0));
    let v = b.velocity.norm().to_f64();
    let stored = w
        .contact_slots(0)
        .next()
        .unwrap()
        .state
        .roll_angle
        .norm()
        .to_f64();
    // Theory (mm, g, ms, N, MPa).
    let r = R_M * 1e3;
    let m = sphere_mass_g(r, POD.density_kg_m3);
    let es = e_star_mpa(&POD, &STEEL);
    let g = G * 1e-3;
    let alpha = hertz_overlap(m * g * phi.cos(), r, es);
    let a = (r * alpha).sqrt();
    let k_r = 2.25 * (2.0 * es * a) * mu_r * mu_r * r * r;
    let torque = m * g * phi.sin() * (r - alpha / 2.0);
    let theta = torque / k_r;
    let limit = mu_r * r * m * g * phi.cos();
    println!(
        "EPSD static: θr stored {stored:.6e} rad, integrated {turned:.6e} rad, theory \
         {theta:.6e} rad ({:+.3} %, {:+.3} %); torque/limit {:.3}; |v| {v:.1e} m/s",
        100.0 * (stored / theta - 1.0),
        100.0 * (turned / theta - 1.0),
        torque / limit
    );
    assert!((stored / theta - 1.0).abs() < 5e-3);
    assert!((turned / theta - 1.0).abs() < 5e-3);
    assert!(v < 1e-5, "still moving: {v} m/s");
}

/// Least-squares slope of v_x(t) over steps `from..to` (m/s²).
fn rolling_acceleration(mu_r_epsd: f64, cdt: f64, phi: f64) -> f64 {
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = slope(&mut o, phi, 0.8, cdt, epsd(mu_r_epsd));
    w.run(2_000).unwrap();
    let (mut st, mut sv, mut stt, mut stv, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in 0..8_000 {
        w.step().unwrap();
        let t = k as f64 * DT_S;
        let v = w.body(BodyId(0)).velocity.x.to_f64();
        st += t;
        sv += v;
        stt += t * t;
        stv += t * v;
        n += 1.0;
    }
    (n * stv - st * sv) / (n * stt - st * st)
}

#[test]
fn epsd_rolls_with_the_limiting_torque_above_the_limit() {
    let mu_r = 0.3;
    let phi = 0.5f64.atan();
    let r = R_M * 1e3;
    let m = sphere_mass_g(r, POD.density_kg_m3);
    let es = e_star_mpa(&POD, &STEEL);
    let alpha = hertz_overlap(m * G * 1e-3 * phi.cos(), r, es);
    let rc = r - alpha / 2.0;
    let theory = G * (phi.sin() - mu_r * phi.cos() * r / rc) / (1.0 + 0.4 * r * r / (rc * rc));
    let a_epsd = rolling_acceleration(mu_r, 0.0, phi);
    let a_cdt = rolling_acceleration(0.0, mu_r, phi);
    println!(
        "EPSD rolling: a {a_epsd:.6} m/s², theory {theory:.6} ({:+.3} %), CDT {a_cdt:.6} \
         ({:+.3} % EPSD vs CDT)",
        100.0 * (a_epsd / theory - 1.0),
        100.0 * (a_epsd / a_cdt - 1.0)
    );
    assert!((a_epsd / theory - 1.0).abs() < 5e-3);
    assert!((a_epsd / a_cdt - 1.0).abs() < 2e-3);
}

/// Work of adhesion Γ, J/m², for the JKR tests.
const GAMMA: f64 = 0.1;

/// A pod sphere hanging under a fixed (kinematic) one, the pair `spec` with JKR cohesion,
/// gravity ramped from 0 to `g_end` (m/s², −z) over `ramp` steps, then held for `hold`
/// steps. Returns (attached at the end, final overlap mm).
fn hang(spec: PairSpec, g_end: f64, ramp: u64, hold: u64) -> (bool, f64) {
    let mut o = Owned::<Fx>::new(2, 2);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_pair(pod, pod, spec).unwrap();
    w.set_pair_effects(
        pod,
        pod,
        EffectSpec {
            jkr_work_of_adhesion_j_m2: GAMMA,
            ..EffectSpec::default()
        },
    )
    .unwrap();
    w.add_sphere(SphereSpec::at_rest(pod, R_M, [0.0; 3]))
        .unwrap();
    w.set_body_kinematic(BodyId(0)).unwrap();
    w.add_sphere(SphereSpec::at_rest(
        pod,
        R_M,
        [0.0, 0.0, -(2.0 * R_M - 1e-7)],
    ))
    .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    for k in 0..ramp + hold {
        let g = g_end * (k as f64 / ramp as f64).min(1.0);
        w.set_gravity_m_s2([0.0, 0.0, -g]).unwrap();
        w.step().unwrap();
    }
    let gap = w.body(BodyId(0)).position.z.to_f64() - w.body(BodyId(1)).position.z.to_f64();
    (w.contact_count() > 0, 2.0 * R_M * 1e3 - gap)
}

#[test]
fn jkr_hanging_sphere_rests_at_the_jkr_overlap_and_pulls_off_at_1_5_pi_gamma_r() {
    let r = R_M * 1e3;
    let r_star = r / 2.0;
    let m = sphere_mass_g(r, POD.density_kg_m3);
    let es = e_star_mpa(&POD, &POD);
    let gam = GAMMA * 1e-3;
    let fc = 1.5 * PI * gam * r_star;
    let g_c = fc / m * 1e3; // m/s²
                            // Equilibrium at m·g = F_c/2: solve F(a) = −F_c/2 on the stable branch (bisection in f64
                            // between the pull-off radius and a large radius; F increases with a there).
    let f_of =
        |a: f64| 4.0 * es * a.powi(3) / (3.0 * r_star) - (8.0 * PI * gam * es * a.powi(3)).sqrt();
    let (mut lo, mut hi) = ((9.0 * PI * gam * r_star * r_star / (8.0 * es)).cbrt(), 1.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f_of(mid) < -0.5 * fc {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let delta = lo * lo / r_star - (2.0 * PI * gam * lo / es).sqrt();
    // The normal-only pair takes the checked terms; with Mindlin and Coulomb on, the pair
    // takes the fused law, across the neck too (fixed point).
    for (name, spec) in [
        ("checked terms", normal_only(0.3)),
        ("fused law", PairSpec::hertz_mindlin(0.3, 0.5, 0.0)),
    ] {
        let (held, overlap) = hang(spec, 0.5 * g_c, 20_000, 10_000);
        println!(
            "JKR, {name}: F_c {fc:.6e} N (g_c {g_c:.4} m/s²); at F_c/2 overlap {overlap:.6e} \
             mm, theory {delta:.6e} mm ({:+.3} %)",
            100.0 * (overlap / delta - 1.0)
        );
        assert!(held, "{name}");
        assert!((overlap / delta - 1.0).abs() < 1e-2, "{name}");
        let (below, _) = hang(spec, 0.99 * g_c, 40_000, 5_000);
        let (above, _) = hang(spec, 1.01 * g_c, 40_000, 5_000);
        println!("JKR, {name}: attached at 0.99·F_c: {below}; at 1.01·F_c: {above}");
        assert!(below, "{name}: fell off below the JKR pull-off force");
        assert!(
            !above,
            "{name}: still attached above the JKR pull-off force"
        );
    }
}
