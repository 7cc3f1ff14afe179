//! The roll rig: a pod sphere launched rolling without slip along a steel floor under
//! gravity. Condition: the launch speed v0, m/s; observable: the horizontal speed after
//! [`ROLL_TIME_S`] over v0.
//!
//! Without rolling resistance or drag the sphere keeps rolling (ratio 1). EPSD rolling
//! resistance brakes it by its limit torque μr·R*·Fn once the spring has wound up (a few
//! thousandths of a radian), a constant deceleration μr·g·R/(L·(1 + I/(m·L²))) ≈ μr·g/1.4 with the lever
//! L = R − α/2, so 1 − ratio falls as 1/v0; air drag decelerates by ρ·Cd·A·v²/(2·1.4·m), so
//! 1 − ratio grows with v0. The launch speed moves the two signatures apart. The contact
//! rests at its Hertz overlap under gravity, so the normal-impact effects (viscoelastic,
//! hysteretic) and the restitution do not enter; neither does cohesion, with nothing that
//! scales with the normal force but the rolling torque.
//!
//! The run starts at that overlap with ω = v0/L (the contact point at rest: no tangential
//! force at the start), and the static friction is seed 000's pod–steel value, far above
//! what rolling needs, so the sphere never slides. The LIGGGHTS deck of the same run is
//! `benches/liggghts/diagnosis/roll.in`.

use arachis_core::prelude::*;

use super::kind::{ConditionKey, Quantity, RigKind};
use super::single_sphere::*;
use crate::calibration::RigError;
use crate::limits::Limits;

/// Rolling time before the speed is read, s.
pub const ROLL_TIME_S: f64 = 0.2;
/// Pod–steel static friction (seed 000 §3.4, x7 = 0.589).
pub const POD_STEEL_FRICTION: f64 = 0.589;
/// Time steps per period of the resting contact's normal oscillation (the tangential one,
/// with the rolling inertia, is about 1.6 times faster).
const STEPS_PER_PERIOD: f64 = 60.0;

/// This rig's test.
pub const TEST: SingleSphereTest = SingleSphereTest {
    name: "roll",
    about: "rolling on the floor; speed after 0.2 s / launch speed against launch speed",
    quantity: Quantity {
        name: "roll_speed_ratio",
        unit: "-",
        label: "speed after 0.2 s / launch speed",
    },
    condition: ConditionKey::new("launch_speed_m_s", "launch speed, m/s", Limits::Positive)
        .within((0.02, 5.0), (0.05, 3.0)),
    parameters: &PARAMETERS,
    simulate,
};

/// This rig in the catalogue.
pub const KIND: RigKind = TEST.kind(|_, _| Ok(Box::new(SingleSphereRig { test: &TEST })));

/// The speed after [`ROLL_TIME_S`] over the launch speed `v0_m_s` (m/s).
fn simulate(v0_m_s: f64, p: &ModelParams) -> Result<f64, RigError> {
    let alpha = hertz_overlap_m(p, mass_kg() * GRAVITY_M_S2);
    let lever = SPHERE_RADIUS_M - 0.5 * alpha;
    let launch = Launch {
        z_m: SPHERE_RADIUS_M - alpha,
        velocity_m_s: [v0_m_s, 0.0, 0.0],
        spin_rad_s: [0.0, v0_m_s / lever, 0.0],
    };
    let mut a = one_sphere_arena();
    let mut w = floor_world_with(&mut a, p, p.restitution, Some(POD_STEEL_FRICTION), launch)?;
    w.set_gravity_m_s2([0.0, 0.0, -GRAVITY_M_S2])
        .map_err(core_err)?;
    let dt = (resting_period_s(p, alpha) / STEPS_PER_PERIOD).min(0.9 * w.max_timestep_s());
    w.set_timestep_s(dt).map_err(core_err)?;
    let steps = (ROLL_TIME_S / dt).round() as u64;
    if steps > MAX_STEPS {
        return Err(RigError(format!(
            "roll needs {steps} steps, more than {MAX_STEPS}"
        )));
    }
    w.run(steps).map_err(core_err)?;
    Ok(w.body(BodyId(0)).velocity.x.to_f64() / v0_m_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> ModelParams {
        ModelParams::from_values(
            &[("restitution", 0.5), ("youngs_modulus_pa", 8.43e6)]
                .map(|(k, v)| (k.to_owned(), v))
                .into(),
        )
        .unwrap()
    }

    /// Rolling without slip and without resistance keeps its speed: within 1e-4 over 0.2 s.
    #[test]
    fn a_free_roll_keeps_its_speed() {
        for v0 in [0.1, 2.0] {
            let r = TEST.observe(v0, &base()).unwrap();
            assert!((r - 1.0).abs() < 1e-4, "v0 {v0}: ratio {r}");
        }
    }

    /// EPSD rolling resistance past its limit: a constant torque μr·Fn·R on a sphere rolling
    /// on the lever L = R − α/2 decelerates it by μr·g·R·L/(L² + I/m), I/m = 0.4R². The
    /// ratio after T agrees with 1 − a·T/v0 within 0.2 % of the speed lost (the spring's
    /// wind-up at the start, a few 1e-3 rad, and the Q32.32 rounding of each step).
    #[test]
    fn epsd_resistance_decelerates_as_a_constant_torque() {
        let mu_r = 0.02;
        let p = ModelParams {
            epsd_rolling_friction: mu_r,
            ..base()
        };
        let r = SPHERE_RADIUS_M;
        let alpha = hertz_overlap_m(&p, mass_kg() * GRAVITY_M_S2);
        let lever = r - 0.5 * alpha;
        let decel = mu_r * GRAVITY_M_S2 * r * lever / (lever * lever + 0.4 * r * r);
        for v0 in [0.2, 1.0] {
            let got = TEST.observe(v0, &p).unwrap();
            let want = 1.0 - decel * ROLL_TIME_S / v0;
            let lost = 1.0 - want;
            assert!((got - want).abs() < 2e-3 * lost, "v0 {v0}: {got} vs {want}");
        }
    }
}
