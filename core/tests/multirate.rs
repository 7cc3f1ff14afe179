//! Multi-rate stepping (`arachis_core::step::multirate`): slow bodies move once every k
//! steps by the long step k·dt, their contacts with each other once a cycle.
//!
//! Checked here: single-rate bits are unchanged; a slow body in free fall follows the
//! long-step scheme exactly; a stack of a fast sphere on a slow one on a floor comes to the
//! single-rate equilibrium (Hertz theory); a bed of slow and fast spheres settles to the
//! single-rate bed's floor load, with the same bits on any thread count; checkpoints between
//! cycles resume bit for bit, and within one are refused; bad settings are refused.

use crate::common::*;
use arachis_core::prelude::*;
use arachis_core::scenario::BenchBed;
use arachis_core::state_words::CheckpointError;
use arachis_core::world::checkpoint::{WordReader, WordWriter};

/// Standard gravity, m/s² (mm/ms²).
const G: f64 = 9.81;

/// A bed of `particles` spheres of the DESIGN §8 bench bed at time step `dt_s`, with every
/// body whose id satisfies `slow` marked slow and stride `k`.
fn bed_world<'a>(
    arenas: &'a mut Owned<Fx>,
    bed: &BenchBed,
    dt_s: f64,
    k: u32,
    slow: impl Fn(u32) -> bool,
) -> World<'a, Fx> {
    let mut w = bed.build_with_timestep(arenas.storage(), dt_s).unwrap();
    w.set_slow_stride(k).unwrap();
    for id in 0..w.bodies().len() as u32 {
        if slow(id) {
            w.set_body_slow(BodyId(id), true).unwrap();
        }
    }
    w
}

/// The upward force of every wall on the bed, N (the sum of the walls' z forces, reversed:
/// a wall's force is what the spheres exert on it).
fn wall_lift_n(w: &World<'_, Fx>) -> f64 {
    -w.walls()
        .iter()
        .map(|wall| wall.force.z.to_f64())
        .sum::<f64>()
}

/// Total weight of the bodies, N.
fn weight_n(w: &World<'_, Fx>) -> f64 {
    w.bodies().iter().map(|b| b.mass.to_f64()).sum::<f64>() * 1e-3 * G
}

#[test]
fn with_stride_one_the_slow_marks_change_no_bit() {
    let bed = BenchBed {
        particles: 200,
        seed: 3,
    };
    let run = |marked: bool| {
        let mut arenas = Owned::<Fx>::with_lengths(bed.storage_lengths());
        let mut w = bed_world(&mut arenas, &bed, 2e-5, 1, |_| marked);
        w.run(3_000).unwrap();
        w.digest()
    };
    assert_eq!(run(true), run(false));
}

#[test]
fn a_slow_body_in_free_fall_takes_long_kick_drift_steps() {
    // Symplectic Euler with the long step h = k·dt: after n cycles v = −g·n·h and
    // z = z0 − g·h²·n(n+1)/2 (each kick before its drift); within a cycle nothing moves.
    let (k, dt_s, cycles) = (8u32, 5e-6, 50u64);
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let b = w
        .add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 1.0]))
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    w.set_timestep_s(dt_s).unwrap();
    w.set_slow_stride(k).unwrap();
    w.set_body_slow(b, true).unwrap();
    for n in 1..=cycles {
        w.run(u64::from(k) - 1).unwrap();
        let z_before = w.body(b).position.z.to_f64();
        w.run(1).unwrap();
        let h_ms = f64::from(k) * dt_s * 1e3;
        let nf = n as f64;
        let v = w.body(b).velocity.z.to_f64();
        let z = w.body(b).position.z.to_f64();
        // Rounding: one unit of 2^-32 per product, a few products a cycle.
        assert!(
            (v + G * nf * h_ms * 1e-3).abs() < 1e-8 * nf,
            "v {v} at cycle {n}"
        );
        let z_theory = 1000.0 - G * 1e-3 * h_ms * h_ms * nf * (nf + 1.0) / 2.0;
        assert!((z - z_theory).abs() < 1e-8 * nf * nf, "z {z} vs {z_theory}");
        if n > 1 {
            // Within the cycle the body stood still, and then moved by the long step.
            assert!(z < z_before);
        }
    }
}

/// The floor force (N), the weight (N) and the top sphere's height (mm) of a stack: a 5 mm
/// sphere on a 4 mm sphere on a floor, pod material, settled for 0.4 s, with stride `k` and
/// the bottom and top spheres slow as `slow` says.
fn stack(k: u32, slow: [bool; 2]) -> (f64, f64, f64) {
    let mut o = Owned::<Fx>::new(2, 2);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    w.set_pair(pod, pod, normal_only(0.3)).unwrap();
    add_floor(&mut w, pod);
    let low = w
        .add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 0.00395]))
        .unwrap();
    let top = w
        .add_sphere(SphereSpec::at_rest(pod, 0.005, [0.0, 0.0, 0.01285]))
        .unwrap();
    w.set_gravity_m_s2([0.0, 0.0, -G]).unwrap();
    w.set_timestep_s(4e-6).unwrap();
    w.set_slow_stride(k).unwrap();
    w.set_body_slow(low, slow[0]).unwrap();
    w.set_body_slow(top, slow[1]).unwrap();
    w.run(100_000).unwrap();
    (
        wall_lift_n(&w),
        weight_n(&w),
        w.body(top).position.z.to_f64(),
    )
}

#[test]
fn a_stack_of_slow_and_fast_spheres_rests_where_hertz_puts_it() {
    // Single rate: both overlaps follow Hertz, δ = (3F/(4E*√R*))^(2/3). The top sphere
    // rests at R1 − δ_floor + R1 + R2 − δ_pair above the floor.
    let e_star = e_star_mpa(&POD, &POD); // MPa = N/mm²
    let m_top_n = sphere_mass_g(5.0, POD.density_kg_m3) * 1e-3 * G;
    let delta =
        |f_n: f64, r_star_mm: f64| (3.0 * f_n / (4.0 * e_star * r_star_mm.sqrt())).powf(2.0 / 3.0);
    // Multi-rate: with the bottom sphere slow, the top one's contact acts every step and the
    // bottom sphere's cycle mean carries it; with both slow, their contact acts once a cycle
    // and counts 16 times. The same equilibrium, within 2e-4 mm (4 % of the pair's 4.6 µm
    // overlap; a load counted once instead of 16 times would overlap 6.3 times as far).
    for (k, slow) in [
        (1, [false, false]),
        (16, [true, false]),
        (16, [false, true]),
        (16, [true, true]),
    ] {
        let (floor, weight, z) = stack(k, slow);
        // The floor against the 4 mm sphere: R* = 4 mm, E* as pod–pod (the floor is pod).
        let z_theory = 4.0 - delta(weight, 4.0) + 4.0 + 5.0 - delta(m_top_n, 20.0 / 9.0);
        assert!(
            (floor - weight).abs() < 1e-3 * weight,
            "k {k}, {slow:?}: floor {floor} N"
        );
        assert!(
            (z - z_theory).abs() < 2e-4,
            "k {k}, {slow:?}: top {z} mm vs {z_theory}"
        );
    }
}

/// The bench bed of 150 spheres after `steps` steps of dt = 1e-5 s (stride `k`, odd ids
/// slow when `mixed`, else all): its kinetic energy (mJ), wall lift (N), weight (N), mean
/// centre height (mm) and digest.
fn bed_after(steps: u64, k: u32, mixed: bool, threads: usize) -> (f64, f64, f64, f64, u64) {
    let bed = BenchBed {
        particles: 150,
        seed: 11,
    };
    let mut arenas = Owned::<Fx>::with_lengths(bed.storage_lengths());
    let mut w = bed_world(&mut arenas, &bed, 1e-5, k, |id| !mixed || id % 2 == 1);
    run_threaded(&mut w, steps, threads);
    let n = w.bodies().len() as f64;
    let mean_z = w
        .bodies()
        .iter()
        .map(|b| b.position.z.to_f64())
        .sum::<f64>()
        / n;
    (
        w.kinetic_energy_mj(),
        wall_lift_n(&w),
        weight_n(&w),
        mean_z,
        w.digest(),
    )
}

/// Steps for the bed to settle: 0.8 s. (At 0.6 s, single-rate beds of other seeds still
/// held 1e-5 to 5e-3 mJ.)
const SETTLE_STEPS: u64 = 80_000;

#[test]
#[cfg_attr(debug_assertions, ignore = "release only: run by scripts/test-all.sh")]
fn a_bed_of_slow_and_fast_spheres_settles_like_a_single_rate_bed() {
    let (ke_1, lift_1, weight, z_1, _) = bed_after(SETTLE_STEPS, 1, false, 1);
    // Settled by DESIGN §8's measure (1e-6 J = 1e-3 mJ); the walls carry the weight.
    assert!(ke_1 < 1e-3, "single rate {ke_1} mJ");
    assert!(
        (lift_1 - weight).abs() < 0.01 * weight,
        "single rate lift {lift_1} N"
    );
    for mixed in [false, true] {
        let (ke, lift, _, z, _) = bed_after(SETTLE_STEPS, 4, mixed, 1);
        assert!(ke < 1e-3, "stride 4 (mixed {mixed}): {ke} mJ");
        assert!(
            (lift - weight).abs() < 0.01 * weight,
            "stride 4 lift {lift} N"
        );
        // Two random packings of 150 spheres about 1.6 layers deep. Single-rate beds of
        // seeds 11–14 settle at mean heights of 6.36–6.93 mm: a spread of 0.57 mm.
        assert!((z - z_1).abs() < 0.6, "mean height {z} mm against {z_1}");
    }
}

#[test]
fn slow_and_fast_bodies_step_with_the_same_bits_on_any_thread_count() {
    let one = bed_after(6_000, 4, true, 1).4;
    for threads in [2, 3, 4] {
        assert_eq!(
            bed_after(6_000, 4, true, threads).4,
            one,
            "{threads} threads"
        );
    }
    // Not the single-rate bits: the slow bodies did step differently.
    assert_ne!(bed_after(6_000, 1, true, 1).4, one);
}

/// Steps of 1e-5 s after which the checkpoint test's bed of 150 spheres has landed, at the
/// end of a cycle of 5.
const LANDED_STEPS: u64 = 40_005;

#[test]
fn checkpoints_fall_between_cycles_and_resume_bit_for_bit() {
    let bed = BenchBed {
        particles: 150,
        seed: 5,
    };
    let mut first = Owned::<Fx>::with_lengths(bed.storage_lengths());
    let mut w = bed_world(&mut first, &bed, 1e-5, 5, |id| id % 3 != 0);
    // Late enough for slow pairs to touch (the bed has landed).
    w.run(LANDED_STEPS - 2).unwrap();
    let mut words = Vec::new();
    assert_eq!(
        w.write_checkpoint(&mut WordWriter::new(|x| words.push(x))),
        Err(CheckpointError::MidCycle {
            steps: LANDED_STEPS - 2,
            stride: 5
        })
    );
    w.run(2).unwrap();
    let slow = |id: u32| id % 3 != 0;
    let slow_pairs: usize = (0..w.spheres().len() as u32)
        .filter(|&s| slow(s))
        .map(|s| {
            w.contact_slots(s)
                .filter(|c| c.partner < w.spheres().len() as u32 && slow(c.partner))
                .count()
        })
        .sum();
    assert!(
        slow_pairs > 20,
        "{slow_pairs} slow pairs touch, {} contacts",
        w.contact_count()
    );
    words.clear();
    w.write_checkpoint(&mut WordWriter::new(|x| words.push(x)))
        .unwrap();
    w.run(2_000).unwrap();
    let mut second = Owned::<Fx>::with_lengths(bed.storage_lengths());
    let mut v = bed_world(&mut second, &bed, 1e-5, 5, |id| id % 3 != 0);
    v.read_checkpoint(&mut WordReader::new(words.iter().copied()))
        .unwrap();
    v.run(2_000).unwrap();
    assert_eq!(v.digest(), w.digest());
    // Writing one changed nothing for the writer either (the words do not hold the list's
    // slow-pair flags, which both worlds set again): the bits of a world that never wrote.
    let mut third = Owned::<Fx>::with_lengths(bed.storage_lengths());
    let mut u = bed_world(&mut third, &bed, 1e-5, 5, |id| id % 3 != 0);
    u.run(LANDED_STEPS + 2_000).unwrap();
    assert_eq!(u.digest(), w.digest());
}

#[test]
fn bad_strides_and_long_steps_are_refused() {
    let mut o = Owned::<Fx>::new(1, 1);
    let mut w = World::new(o.storage()).unwrap();
    let pod = w.add_material(POD).unwrap();
    let b = w
        .add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 1.0]))
        .unwrap();
    for bad in [0, arachis_core::step::multirate::MAX_SLOW_STRIDE + 1] {
        assert!(matches!(
            w.set_slow_stride(bad),
            Err(SetupError::BadSlowStride { .. })
        ));
    }
    assert!(matches!(
        w.set_body_slow(BodyId(7), true),
        Err(SetupError::UnknownId { id: 7 })
    ));
    // The 4 mm pod's Rayleigh time is 1.85e-4 s, so the long step may reach 7.4e-5 s.
    w.set_timestep_s(2e-5).unwrap();
    w.set_body_slow(b, true).unwrap();
    w.set_slow_stride(3).unwrap();
    assert!(matches!(
        w.set_slow_stride(4),
        Err(SetupError::TimeStepTooLarge { .. })
    ));
    assert_eq!(w.slow_stride(), 3, "a refused stride leaves the last one");
    // A time step raised afterwards is caught before the step changes anything.
    w.set_timestep_s(3e-5).unwrap();
    let before = w.digest();
    assert!(matches!(w.step(), Err(StepError::TimeStepTooLarge { .. })));
    assert_eq!(w.digest(), before);
}

#[test]
fn a_body_no_longer_slow_meets_its_partners_every_step() {
    // Two copies of a bed, all slow for 0.25 s (landed and colliding; their entries between
    // slow bodies are flagged by then), then every mark taken off: one keeps stride 4, the
    // other goes back to single-rate stepping. With no slow body left, both must step alike.
    let bed = BenchBed {
        particles: 120,
        seed: 9,
    };
    let run = |back_to_one: bool| {
        let mut arenas = Owned::<Fx>::with_lengths(bed.storage_lengths());
        let mut w = bed_world(&mut arenas, &bed, 1e-5, 4, |_| true);
        w.run(25_000).unwrap();
        for id in 0..w.bodies().len() as u32 {
            w.set_body_slow(BodyId(id), false).unwrap();
        }
        if back_to_one {
            w.set_slow_stride(1).unwrap();
        }
        w.run(2_000).unwrap();
        w.digest()
    };
    assert_eq!(run(false), run(true));
}
