//! Rolling friction in EDEM's and in LIGGGHTS' conventions, against theory
//! (`arachis_core::contact::convention`, `docs/conventions.md`).
//!
//! A pod sphere (R 4 mm) rests under gravity on a fixed sphere of the same size or on a steel
//! floor, with the tangential spring off so that only rolling friction acts on its spin. It is
//! set spinning at ω0 and decelerates at a constant rate, a = μr·F·L/I with I = 0.4·m·R²
//! and, at rest, F = m·g (the elastic and the total normal force then agree):
//! - EDEM (seed 000 eq. (7)): L = R − α/2, the lever from the centre to the contact point;
//! - LIGGGHTS (`rolling_model_cdt.h`): L = R* = R/2 on an equal sphere, L = R on a wall;
//! - LIGGGHTS' `epsd2` (`rolling_model_epsd2.h`): the same lever once its spring torque has
//!   reached the limit μr·F·R* (two steps here; the rate is measured from step 100).
//!
//! Once the spin has stopped, `epsd2`'s spring holds the sphere like a torsion spring: it
//! rocks about its centre with period 2π·√(I/k_r), k_r = 8G*·a·R*² (a = √(R*·α) of the settled
//! contact), matched to [`PERIOD_TOLERANCE`].
//!
//! The measured rate matches theory to 2e-5 (the settled normal force differs from m·g by the
//! residue of the settling oscillation, and fixed point rounds ω by 2.3e-10 rad/ms per step).
//! A spin about the normal (torsion) is untouched in LIGGGHTS' convention and braked in
//! EDEM's; and two free spheres colliding with unequal spins keep their total angular momentum
//! in LIGGGHTS' convention, whose torques are equal and opposite, but not in EDEM's.

use crate::common;
use arachis_core::effects::EffectSpec;
use arachis_core::error::CapacityKind;
use arachis_core::prelude::*;
use common::*;

/// Gravity, m/s².
const G: f64 = 9.81;
/// Sphere radius, m.
const R_M: f64 = 0.004;
/// Time step, s.
const DT_S: f64 = 1e-5;
/// Steps to settle the resting sphere before it is spun.
const SETTLE_STEPS: u64 = 5_000;
/// Rolling friction coefficient of the tests.
const MU_R: f64 = 0.3;
/// Relative tolerance of the deceleration against theory.
const RATE_TOLERANCE: f64 = 2e-5;
/// Steps after the spin is set before the deceleration is measured: `epsd2`'s spring needs a
/// few steps to reach its limit (the other conventions are at it from the first step).
const RATE_FROM_STEP: u64 = 100;
/// Relative tolerance of the `epsd2` rocking period: leapfrog's period error, (ω·dt)²/24, is
/// 1e-5 at 400 steps a period; the normal force's settling residue moves a by less than 1e-4.
const PERIOD_TOLERANCE: f64 = 1e-3;

/// LIGGGHTS' `epsd2` rolling with its `tangential history` Coulomb test.
const EPSD2: Conventions = Conventions {
    rolling: RollingConvention::LiggghtsEpsd2,
    friction: FrictionConvention::Liggghts,
};

/// What the spinning sphere rests on.
#[derive(Clone, Copy, Debug)]
enum Support {
    /// A kinematic (fixed) pod sphere of the same radius below it.
    Sphere,
    /// The steel floor z = 0.
    Floor,
}

/// Spin the resting sphere at `w0` rad/s and return (measured deceleration, theory), rad/ms².
fn spin_down<S: Scalar>(conventions: Conventions, support: Support, w0: [f64; 3]) -> (f64, f64) {
    let mut o = Owned::<S>::new(2, 2);
    let mut spec = PairSpec::hertz_mindlin(0.5, 0.6, MU_R).with_conventions(conventions);
    spec.terms.mindlin_tangential = false;
    let (mut w, pod, steel) = pod_steel_world(&mut o, spec);
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    let top_z = match support {
        Support::Sphere => {
            let base = w
                .add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, 0.0]))
                .unwrap();
            w.set_body_kinematic(base).unwrap();
            2.0 * R_M + 1e-7
        }
        Support::Floor => {
            add_floor(&mut w, steel);
            R_M + 1e-7
        }
    };
    let top = w
        .add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, top_z]))
        .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w.run(SETTLE_STEPS).unwrap();
    let r = R_M * 1e3;
    let z = w.body(top).position.z.to_f64();
    let (overlap, r_star) = match support {
        Support::Sphere => (2.0 * r - z, r / 2.0),
        Support::Floor => (r - z, r),
    };
    let lever = match conventions.rolling {
        RollingConvention::Edem => r - overlap / 2.0,
        RollingConvention::LiggghtsCdt | RollingConvention::LiggghtsEpsd2 => r_star,
    };
    let g = G * 1e-3; // mm/ms²
    let theory = MU_R * g * lever / (0.4 * r * r);
    w.set_body_velocity(top, [0.0; 3], w0).unwrap();
    w.run(RATE_FROM_STEP).unwrap();
    let w0_ms = w.body(top).angular_velocity.to_f64();
    let speed0 = w0_ms.iter().map(|x| x * x).sum::<f64>().sqrt();
    // Half of the stopping time of the fastest case (lever R).
    let steps = (0.5 * speed0 / (MU_R * g * r / (0.4 * r * r)) / (DT_S * 1e3)) as u64;
    w.run(steps).unwrap();
    let w1 = w.body(top).angular_velocity.to_f64();
    let speed1 = w1.iter().map(|x| x * x).sum::<f64>().sqrt();
    let t_ms = steps as f64 * DT_S * 1e3;
    ((speed0 - speed1) / t_ms, theory)
}

fn check_spin_down<S: Scalar>() {
    for conventions in [Conventions::EDEM, Conventions::LIGGGHTS, EPSD2] {
        for support in [Support::Sphere, Support::Floor] {
            let (rate, theory) = spin_down::<S>(conventions, support, [20.0, 0.0, 0.0]);
            let rel = rate / theory - 1.0;
            println!(
                "{} {:?} on {support:?}: {rate:.8e} rad/ms², theory {theory:.8e} ({rel:+.2e})",
                S::NAME,
                conventions.rolling
            );
            assert!(
                rel.abs() < RATE_TOLERANCE,
                "{} {conventions:?} {support:?}: {rate} vs {theory}",
                S::NAME
            );
        }
    }
}

#[test]
fn spin_down_at_each_conventions_lever_fixed() {
    check_spin_down::<Fx>();
}

#[test]
fn spin_down_at_each_conventions_lever_f64() {
    check_spin_down::<f64>();
}

/// `epsd2` after the spin-down: the sphere on the fixed sphere rocks on its rolling spring.
/// Returns (measured period, 2π·√(I/k_r)), ms.
fn epsd2_rocking<S: Scalar>() -> (f64, f64) {
    let mut o = Owned::<S>::new(2, 2);
    let mut spec = PairSpec::hertz_mindlin(0.5, 0.6, MU_R).with_conventions(EPSD2);
    spec.terms.mindlin_tangential = false;
    let (mut w, pod, _) = pod_steel_world(&mut o, spec);
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    let base = w
        .add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, 0.0]))
        .unwrap();
    w.set_body_kinematic(base).unwrap();
    let top = w
        .add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, 2.0 * R_M + 1e-7]))
        .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w.run(SETTLE_STEPS).unwrap();
    // A small spin, stopped by the spring within a few steps: then it rocks.
    w.set_body_velocity(top, [0.0; 3], [0.0, 1.0, 0.0]).unwrap();
    w.run(RATE_FROM_STEP).unwrap();
    // Times (ms) at which ω_y changes sign, over ten periods.
    let dt_ms = DT_S * 1e3;
    let mut crossings = Vec::new();
    let mut last = w.body(top).angular_velocity.y.to_f64();
    let mut step = 0u64;
    while crossings.len() < 21 {
        w.step().unwrap();
        step += 1;
        let now = w.body(top).angular_velocity.y.to_f64();
        if (now > 0.0) != (last > 0.0) {
            // Linear interpolation between the two steps.
            crossings.push((step as f64 - now / (now - last)) * dt_ms);
        }
        last = now;
        assert!(step < 200_000, "no rocking");
    }
    let period = (crossings[20] - crossings[0]) / 10.0;
    let r = R_M * 1e3;
    let overlap = 2.0 * r - w.body(top).position.z.to_f64();
    let r_star = r / 2.0;
    let g_star = w.pair(pod, pod).unwrap().g_star_mpa;
    let k_r = 8.0 * g_star * (r_star * overlap).sqrt() * r_star * r_star; // N·mm/rad
    let inertia = 1.0 / w.body(top).inv_inertia.y.to_f64(); // g·mm²
    (period, 2.0 * std::f64::consts::PI * (inertia / k_r).sqrt())
}

#[test]
fn epsd2_spring_rocks_at_its_stiffness() {
    for (name, (period, theory)) in [
        ("fixed", epsd2_rocking::<Fx>()),
        ("f64", epsd2_rocking::<f64>()),
    ] {
        let rel = period / theory - 1.0;
        println!("{name} epsd2 rocking: {period:.6} ms, theory {theory:.6} ms ({rel:+.2e})");
        assert!(rel.abs() < PERIOD_TOLERANCE, "{name}: {period} vs {theory}");
    }
}

/// Torsion: a spin about the contact normal. LIGGGHTS removes the normal part of its rolling
/// torque, so the spin is kept bit for bit; EDEM's torque brakes it at the rolling rate.
#[test]
fn torsion_kept_by_liggghts_braked_by_edem() {
    let spin = [0.0, 0.0, 20.0];
    for conventions in [Conventions::LIGGGHTS, EPSD2] {
        let (rate, _) = spin_down::<Fx>(conventions, Support::Floor, spin);
        assert_eq!(rate, 0.0, "{conventions:?} braked a pure twist");
    }
    let (rate, theory) = spin_down::<Fx>(Conventions::EDEM, Support::Floor, spin);
    assert!(
        (rate / theory - 1.0).abs() < RATE_TOLERANCE,
        "{rate} vs {theory}"
    );
}

/// Two free spheres, no gravity, collide head on along x with spins (0, 20, 0) and
/// (0, 5, 0) rad/s; the tangential spring is off, so rolling friction is the only torque.
/// Returns the total angular momentum about y before and after, g·mm²/ms.
fn collide<S: Scalar>(conventions: Conventions) -> (f64, f64) {
    let mut o = Owned::<S>::new(2, 2);
    let mut spec = PairSpec::hertz_mindlin(0.5, 0.6, MU_R).with_conventions(conventions);
    spec.terms.mindlin_tangential = false;
    let (mut w, pod, _) = pod_steel_world(&mut o, spec);
    let a = w
        .add_sphere(SphereSpec::at_rest(pod, R_M, [0.0, 0.0, 0.0]))
        .unwrap();
    let b = w
        .add_sphere(SphereSpec::at_rest(pod, R_M, [2.0 * R_M + 1e-6, 0.0, 0.0]))
        .unwrap();
    w.set_body_velocity(a, [0.0; 3], [0.0, 20.0, 0.0]).unwrap();
    w.set_body_velocity(b, [-0.5, 0.0, 0.0], [0.0, 5.0, 0.0])
        .unwrap();
    w.set_timestep_s(DT_S / 10.0).unwrap();
    let momentum = |w: &World<'_, S>| {
        [a, b]
            .iter()
            .map(|&id| {
                let body = w.body(id);
                body.angular_velocity.y.to_f64() / body.inv_inertia.y.to_f64()
            })
            .sum::<f64>()
    };
    let before = momentum(&w);
    w.run(20_000).unwrap();
    let touched = w.body(a).velocity.x.to_f64() < 0.0;
    assert!(touched, "the spheres never met");
    (before, momentum(&w))
}

#[test]
fn liggghts_pair_torques_conserve_angular_momentum() {
    for (name, (before, after)) in [
        ("fixed cdt", collide::<Fx>(Conventions::LIGGGHTS)),
        ("f64 cdt", collide::<f64>(Conventions::LIGGGHTS)),
        ("fixed epsd2", collide::<Fx>(EPSD2)),
        ("f64 epsd2", collide::<f64>(EPSD2)),
    ] {
        let rel = (after / before - 1.0).abs();
        println!("{name} LIGGGHTS: L {before:.9e} → {after:.9e} ({rel:.1e})");
        assert!(rel < 1e-7, "{name}: angular momentum changed by {rel}");
    }
    let (before, after) = collide::<f64>(Conventions::EDEM);
    let rel = (after / before - 1.0).abs();
    println!("f64 EDEM: L {before:.9e} → {after:.9e} ({rel:.1e})");
    // Both spins are braked: the total falls by a visible fraction.
    assert!(rel > 1e-3, "EDEM's torques should not conserve L: {rel}");
}

/// `epsd2` keeps a torque per contact: a world without an effect-history arena refuses the
/// pair (rather than dropping the torque each step), and the core's EPSD effect, a second
/// rolling spring, cannot be added on top of it.
#[test]
fn epsd2_needs_an_effect_arena_and_excludes_the_epsd_effect() {
    let spec = PairSpec::hertz_mindlin(0.5, 0.6, MU_R).with_conventions(EPSD2);
    assert!(spec.needs_effect_history());
    assert!(!PairSpec::hertz_mindlin(0.5, 0.6, 0.0)
        .with_conventions(EPSD2)
        .needs_effect_history());
    let mut bare = Owned::<Fx>::with_lengths(StorageLengths::for_spheres(1, 1));
    let mut w = World::new(bare.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let refused = w.set_pair(pod, pod, spec).unwrap_err();
    assert!(
        matches!(
            refused,
            SetupError::Capacity {
                kind: CapacityKind::EffectHistory,
                ..
            }
        ),
        "{refused:?}"
    );
    let mut o = Owned::<Fx>::new(1, 1);
    let (mut w, pod, _) = pod_steel_world(&mut o, spec);
    let epsd = EffectSpec {
        epsd_rolling_friction: 0.2,
        ..EffectSpec::default()
    };
    assert!(matches!(
        w.set_pair_effects(pod, pod, epsd),
        Err(SetupError::IncompatibleEffects { .. })
    ));
}
