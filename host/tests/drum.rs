//! The rotating-drum rig (`rigs/drum.rs`): it passes the conformance test every rig passes,
//! the drum lifts a settled bed as a rigid block (the bed's angle grows by the drum's turn,
//! which is what the spinning walls must do while the surface lies below its angle of
//! repose), and rolling resistance raises the dynamic angle.

use arachis::calibration::{Condition, ParameterValues, Rig, RunRequest};
use arachis::rigs::conformance;
use arachis::rigs::drum::{
    DrumRig, BASE_SEED, DEFAULT_PARTICLES, DYNAMIC_ANGLE, KIND, PARTICLES, ROTATION_SPEED,
};
use arachis_core::owned::OwnedStorage;
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::TIMESTEP_S;
use arachis_core::scenario::drum::{bed_angle_deg, Drum};

/// Drum speed of the block test, rad/s, and the turn it checks, rad (17°: far below any angle
/// of repose of the pods, so nothing flows yet).
const BLOCK_SPEED_RAD_S: f64 = 1.0;
const BLOCK_TURN_RAD: f64 = 0.3;
/// Settling time before the drum turns, s.
const SETTLE_S: f64 = 0.3;
/// Largest difference between the bed's rise and the drum's turn, degrees: the bed settles a
/// little further as it tilts (0.36° measured).
const BLOCK_TOL_DEG: f64 = 1.0;
/// Smallest rise of the dynamic angle from pod–pod rolling friction 0.02 to 0.2 at 30 rpm,
/// degrees (measured 34.4° and 42.0°).
const ROLLING_RISE_DEG: f64 = 5.0;

fn values(pairs: &[(&str, f64)]) -> ParameterValues {
    pairs.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect()
}

#[test]
fn the_drum_passes_the_rig_conformance_test() {
    // A small bed at a high speed: conformance asks about the interface, not the physics.
    let values = values(&[("pod-pod.static_friction", 0.5)]);
    let condition = Condition::from([
        (ROTATION_SPEED.to_owned(), 60.0),
        (PARTICLES.to_owned(), 40.0),
    ]);
    let checked =
        conformance::check_fixed(&KIND, &values, &condition).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(checked.responses.len(), 1);
}

#[test]
fn the_drum_lifts_a_settled_bed_as_a_rigid_block() {
    let drum = Drum {
        particles: DEFAULT_PARTICLES,
        seed: BASE_SEED,
    };
    let mut arenas = OwnedStorage::<Fx>::new(drum.storage_lengths());
    let mut world = drum.build(arenas.storage()).unwrap();
    let steps = |s: f64| (s / TIMESTEP_S).round() as u64;
    world.run(steps(SETTLE_S)).unwrap();
    let before = bed_angle_deg(&world, BLOCK_SPEED_RAD_S);
    Drum::spin(&mut world, BLOCK_SPEED_RAD_S).unwrap();
    world
        .run(steps(BLOCK_TURN_RAD / BLOCK_SPEED_RAD_S))
        .unwrap();
    let rise = bed_angle_deg(&world, BLOCK_SPEED_RAD_S) - before;
    let turn = BLOCK_TURN_RAD.to_degrees();
    println!("bed angle {before:.2}° → +{rise:.2}° for a turn of {turn:.2}°");
    assert!(
        (rise - turn).abs() < BLOCK_TOL_DEG,
        "the bed rose {rise:.2}° while the drum turned {turn:.2}°"
    );
}

#[test]
fn rolling_resistance_raises_the_dynamic_angle() {
    let angle = |rolling: f64| {
        let values = values(&[
            ("pod-pod.static_friction", 0.3),
            ("pod-pod.rolling_friction", rolling),
            ("pod-steel.static_friction", 0.3),
            ("pod-steel.rolling_friction", 0.02),
        ]);
        let condition = Condition::from([(ROTATION_SPEED.to_owned(), 30.0)]);
        let request = RunRequest {
            values: &values,
            condition: &condition,
            replicate: 0,
        };
        DrumRig.run(&request).unwrap_or_else(|e| panic!("{e}"))[DYNAMIC_ANGLE]
    };
    let (low, high) = (angle(0.02), angle(0.2));
    println!("dynamic angle at 30 rpm: {low:.2}° (μr 0.02), {high:.2}° (μr 0.2)");
    assert!(
        high - low > ROLLING_RISE_DEG,
        "{low:.2}° → {high:.2}°: rolling resistance barely raised the angle"
    );
}
