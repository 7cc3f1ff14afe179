//! Spinning walls (`World::set_wall_spin_rad_s`): a rotating drum drags its contents by the
//! motion of its surface.
//!
//! Theory: a sphere in a drum spinning about a horizontal axis rolls without slip on the
//! drum's surface and settles where the friction force that drives its spin balances the
//! rolling resistance that brakes it. With CDT rolling friction (seed 000 eq. (7)) both
//! torques act on the same lever L about the centre: F_t·L = μr·F_n·L, and with
//! F_t = m·g·sin θ, F_n = m·g·cos θ the sphere rests at θ = atan μr from the bottom,
//! whatever the drum's speed, as long as it does not slide (μs > μr).

use crate::common;

use arachis_core::prelude::*;
use common::{pod_steel_world, Owned};

/// Drum radius, m.
const DRUM_RADIUS_M: f64 = 0.05;
/// Sphere radius, m.
const SPHERE_RADIUS_M: f64 = 0.004;
/// Drum speed, rad/s (about 10 rpm).
const DRUM_SPEED_RAD_S: f64 = 1.0;
/// Time step, s, and the time to settle and to average over, s.
const DT_S: f64 = 2e-5;
const SETTLE_S: f64 = 1.5;
const AVERAGE_S: f64 = 0.5;
/// Largest difference of the resting angle from atan μr, degrees: the sphere rocks about its
/// rest with a small damped amplitude, and the Hertz overlap shortens the lever by α/2 on
/// both torques alike.
const ANGLE_TOL_DEG: f64 = 0.3;

/// The mean angle of the sphere's centre from the drum's lowest line (degrees, positive on
/// the side the bottom of the drum moves towards), over the last `AVERAGE_S` of a run.
fn resting_angle_deg<S: Scalar>(rolling_friction: f64, spin_rad_s: f64) -> f64 {
    let pair = PairSpec::hertz_mindlin(0.3, 0.8, rolling_friction);
    let mut o = Owned::<S>::new(1, 1);
    let (mut w, pod, steel) = pod_steel_world(&mut o, pair);
    w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
    let drum = w
        .add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 1.0, 0.0],
                radius_m: DRUM_RADIUS_M,
                length_m: None,
            },
            steel,
        ))
        .unwrap();
    w.add_sphere(SphereSpec {
        material: pod,
        radius_m: SPHERE_RADIUS_M,
        position_m: [0.0, 0.0, -(DRUM_RADIUS_M - SPHERE_RADIUS_M)],
        velocity_m_s: [0.0; 3],
        angular_velocity_rad_s: [0.0; 3],
    })
    .unwrap();
    w.set_timestep_s(DT_S).unwrap();
    w.set_wall_spin_rad_s(drum, spin_rad_s).unwrap();
    w.run((SETTLE_S / DT_S) as u64).unwrap();
    let samples = (AVERAGE_S / DT_S) as u64;
    let mut sum = 0.0;
    for _ in 0..samples {
        w.step().unwrap();
        let [x, _, z] = w.bodies()[0].position.to_f64();
        // Spin +y carries the drum's bottom towards −x.
        sum += (-x * spin_rad_s.signum()).atan2(-z).to_degrees();
    }
    sum / samples as f64
}

#[test]
fn a_sphere_in_a_spinning_drum_rests_at_atan_of_its_rolling_friction() {
    for mu_r in [0.1, 0.3] {
        let expected = f64::atan(mu_r).to_degrees();
        for (name, got) in [
            ("fixed", resting_angle_deg::<Fx>(mu_r, DRUM_SPEED_RAD_S)),
            ("f64", resting_angle_deg::<f64>(mu_r, DRUM_SPEED_RAD_S)),
            (
                "fixed, reversed",
                resting_angle_deg::<Fx>(mu_r, -DRUM_SPEED_RAD_S),
            ),
        ] {
            println!("μr {mu_r}, {name}: {got:.3}° (theory {expected:.3}°)");
            assert!(
                (got - expected).abs() < ANGLE_TOL_DEG,
                "μr {mu_r}, {name}: {got:.3}° against atan μr = {expected:.3}°"
            );
        }
    }
}

#[test]
fn a_drum_at_rest_leaves_the_sphere_at_the_bottom_and_a_box_cannot_spin() {
    let angle = resting_angle_deg::<Fx>(0.3, 0.0);
    assert!(angle.abs() < 1e-6, "{angle}");
    let mut o = Owned::<Fx>::new(1, 1);
    let (mut w, _, steel) = pod_steel_world(&mut o, PairSpec::hertz_mindlin(0.3, 0.8, 0.1));
    let bx = w
        .add_wall(WallSpec::fixed(
            WallGeometry::AaBox {
                min_m: [-0.1; 3],
                max_m: [0.1; 3],
            },
            steel,
        ))
        .unwrap();
    assert!(matches!(
        w.set_wall_spin_rad_s(bx, 1.0),
        Err(SetupError::BadWall { .. })
    ));
    assert!(w.set_wall_spin_rad_s(bx, 0.0).is_ok());
    assert!(w.set_wall_spin_rad_s(bx, f64::NAN).is_err());
}
