//! Sliding on an inclined plane (static friction), seed 000 §2.6.2: a pod lies flat on the
//! steel plate, the plate tilts slowly, and the angle at which the pod starts to slide is
//! the static friction angle, μs = tan θ.
//!
//! The core's walls translate but do not turn, so the plate stays horizontal and gravity
//! turns instead — the same physics in the plate's frame (the tilt is quasi-static:
//! [`TILT_RATE_DEG_S`]). The pod (the mix's most common shape) is placed with its
//! thickness axis vertical, settles for [`SETTLE_S`], then gravity turns about y at the
//! tilt rate. The slide angle is the tilt at which the pod's centre has moved
//! [`ONSET_MM`] down the slope, confirmed once it has moved [`CONFIRM_MM`]. For a body
//! that slides rather than tips or rolls, the threshold is θ = atan μs (DESIGN §7,
//! "sticks for θ < atan μ").

use arachis_core::prelude::*;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::pod_bench::{PodTest, MOISTURE};
use super::pod_world::error::ExperimentError;
use super::pod_world::frames::FrameRecorder;
use super::pod_world::observation::*;
use super::pod_world::setup::*;
use super::pod_world::Experiment;
use crate::limits::Limits;

/// This rig's test.
pub const TEST: PodTest = PodTest {
    experiment: Experiment::InclineSlide,
    run,
};

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "incline_slide",
    about: "a pod sliding on a tilting steel plate (static friction, seed 000 §2.6.2)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: "slide_angle",
            unit: "deg",
            label: "slide angle, deg",
        },
        Quantity {
            name: "static_friction",
            unit: "-",
            label: "static friction, -",
        },
    ],
    conditions: &[
        ConditionKey::new("slope_deg", "slope, degrees", Limits::Positive),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

const EXPERIMENT: Experiment = Experiment::InclineSlide;

/// Tilt rate, degrees per second: slow enough that the onset lags the threshold by a small
/// fraction of a degree.
pub const TILT_RATE_DEG_S: f64 = 5.0;
/// Settling time on the level plate before tilting, s.
pub const SETTLE_S: f64 = 0.3;
/// Down-slope displacement marking the onset of sliding, mm (well above the elastic creep
/// of the tangential springs, about 0.01 mm for a pod).
pub const ONSET_MM: f64 = 0.1;
/// Displacement confirming a slide, mm.
pub const CONFIRM_MM: f64 = 2.0;
/// Largest tilt tried, degrees.
pub const MAX_TILT_DEG: f64 = 85.0;
/// Gravity is turned every this many seconds.
pub const TILT_UPDATE_S: f64 = 0.002;
/// Gap between the pod's lowest point and the plate at placement, mm.
pub const DROP_GAP_MM: f64 = 0.05;

/// Runs the incline rig.
pub fn run(
    inputs: &RunInputs,
    _seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let kind = inputs.typical_class();
    let template = inputs.template(kind);
    let mut arena = Arena::new(inputs, 1, template.spheres.len());
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    add_floor(&mut w, mats, EXPERIMENT)?;
    let lowest = template
        .spheres
        .iter()
        .map(|s| s.centre_mm[2] - s.radius_mm)
        .fold(f64::INFINITY, f64::min);
    let z = -lowest + DROP_GAP_MM;
    let pod = add_pod(
        &mut w,
        template,
        mats.pod,
        [0.0, 0.0, z],
        [1.0, 0.0, 0.0, 0.0],
        [0.0; 3],
        EXPERIMENT,
    )?;
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    let settle = steps_for(&w, SETTLE_S);
    run_steps(&mut w, settle, EXPERIMENT)?;
    frames.record(&w);
    let x0 = w.body(pod).position.x.to_f64();
    let g = inputs.simulation.gravity_m_s2;
    let chunk = steps_for(&w, TILT_UPDATE_S);
    let t0 = w.time_s();
    let mut onset_deg = None;
    loop {
        let tilt_deg = TILT_RATE_DEG_S * (w.time_s() - t0);
        if tilt_deg > MAX_TILT_DEG {
            break;
        }
        let (s, c) = tilt_deg.to_radians().sin_cos();
        // Plate tilted by θ about y, seen in the plate's frame: gravity has a +x part.
        w.set_gravity_m_s2([g * s, 0.0, -g * c])
            .map_err(|e| setup_error(EXPERIMENT, e))?;
        run_steps(&mut w, chunk, EXPERIMENT)?;
        let moved = w.body(pod).position.x.to_f64() - x0;
        if onset_deg.is_none() && moved > ONSET_MM {
            onset_deg = Some(tilt_deg);
        }
        if moved > CONFIRM_MM {
            break;
        }
        if (w.step_count() / chunk) % 25 == 0 {
            frames.record(&w);
        }
    }
    let moved = w.body(pod).position.x.to_f64() - x0;
    let angle = match onset_deg {
        Some(a) if moved > CONFIRM_MM => a,
        _ => {
            return Err(ExperimentError::NoObservable {
                experiment: EXPERIMENT.name(),
                reason: format!("the pod had not slid at a tilt of {MAX_TILT_DEG}°"),
            })
        }
    };
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: "slide_angle",
        value: angle,
        unit: "deg",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::InclineSlide(InclineDetails {
            static_friction: angle.to_radians().tan(),
            dt_s,
            pod_kind: template.kind.map_or("sphere", |k| k.key()),
        }),
    })
}
