//! Compression between two plates (apparent modulus), seed 000 §2.5.3: a pod lies flat
//! on a fixed steel plate and a second steel plate comes down on it at a constant speed;
//! the force on the upper plate against its travel gives the pod's apparent modulus.
//!
//! The plate starts [`START_GAP_MM`] above the pod and moves down at [`PLATE_SPEED_M_S`]
//! (quasi-static: far below the pod's elastic wave speed) until it has compressed the pod
//! by [`COMPRESSION_MM`]. Observable: the apparent modulus E_app of the Hertz law for a
//! sphere of radius R squeezed between two rigid plates — each contact takes half the
//! travel δ, so F = (4/3) E_app/(1 − ν²) √R (δ/2)^{3/2} (DESIGN §2, seed 000 eq. (1) with
//! E* = E/(1 − ν²) against a rigid plate) — solved for E_app at the final travel, with R the
//! largest sphere of the filling (the sphere that carries the load when the pod lies flat).
//! For a one-sphere filling E_app recovers the pod's E up to the steel's compliance.

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
    experiment: Experiment::Compression,
    run,
};

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "compression",
    about: "a pod compressed between two steel plates (apparent modulus, seed 000 §2.5.3)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: "apparent_modulus",
            unit: "Pa",
            label: "apparent modulus, Pa",
        },
        Quantity {
            name: "peak_force",
            unit: "N",
            label: "peak force, N",
        },
    ],
    conditions: &[
        ConditionKey::new(
            "loading_speed_mm_min",
            "loading speed, mm/min",
            Limits::Positive,
        ),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

const EXPERIMENT: Experiment = Experiment::Compression;

/// Plate speed, m/s.
pub const PLATE_SPEED_M_S: f64 = 0.01;
/// Compression at which the force is read, mm.
pub const COMPRESSION_MM: f64 = 0.5;
/// Gap between the plate and the pod at the start, mm.
pub const START_GAP_MM: f64 = 0.2;
/// Settling time of the pod on the lower plate before the plate moves, s.
pub const SETTLE_S: f64 = 0.2;

/// Runs the compression rig.
pub fn run(
    inputs: &RunInputs,
    _seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let template = inputs.template(inputs.typical_class());
    let e = |s| setup_error(EXPERIMENT, s);
    let mut arena = Arena::new(inputs, 1, template.spheres.len());
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    let (low, high) =
        template
            .spheres
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), s| {
                (
                    l.min(s.centre_mm[2] - s.radius_mm),
                    h.max(s.centre_mm[2] + s.radius_mm),
                )
            });
    add_floor(&mut w, mats, EXPERIMENT)?;
    // The pod rests with its lowest point on the floor (set exactly: no settling drop).
    let centre_z = -low;
    let top_mm = high - low;
    let plate = w
        .add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0, 0.0, (top_mm + START_GAP_MM) * M_PER_MM],
                normal: [0.0, 0.0, -1.0],
            },
            mats.wall,
        ))
        .map_err(e)?;
    add_pod(
        &mut w,
        template,
        mats.pod,
        [0.0, 0.0, centre_z],
        [1.0, 0.0, 0.0, 0.0],
        [0.0; 3],
        EXPERIMENT,
    )?;
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    let settle = steps_for(&w, SETTLE_S);
    run_steps(&mut w, settle, EXPERIMENT)?;
    frames.record(&w);
    // The pod settled (and may have turned a little); measure its top now.
    let pod_top_mm = w
        .spheres()
        .iter()
        .map(|s| s.position.z.to_f64() + s.radius.to_f64())
        .fold(f64::NEG_INFINITY, f64::max);
    let gap_mm = top_mm + START_GAP_MM - pod_top_mm;
    w.set_wall_velocity_m_s(plate, [0.0, 0.0, -PLATE_SPEED_M_S])
        .map_err(e)?;
    let travel_mm = gap_mm + COMPRESSION_MM;
    let steps = steps_for(&w, travel_mm * M_PER_MM / PLATE_SPEED_M_S);
    run_steps(&mut w, steps, EXPERIMENT)?;
    frames.record(&w);
    let moved_mm = steps as f64 * w.timestep_s() * PLATE_SPEED_M_S / M_PER_MM;
    let delta_mm = moved_mm - gap_mm;
    let force_n = w.walls()[plate.0 as usize].force.z.to_f64();
    let radius_mm = template
        .spheres
        .iter()
        .map(|s| s.radius_mm)
        .fold(0.0, f64::max);
    // Hertz, two contacts in series: F = (4/3) E/(1 − ν²) √R (δ/2)^{3/2} (mm, N, MPa).
    let nu = inputs.pod.poisson;
    let e_mpa =
        3.0 * force_n * (1.0 - nu * nu) / (4.0 * radius_mm.sqrt() * (0.5 * delta_mm).powf(1.5));
    const PA_PER_MPA: f64 = 1e6;
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: "apparent_modulus",
        value: e_mpa * PA_PER_MPA,
        unit: "Pa",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::Compression(CompressionDetails {
            peak_force_n: force_n,
            compression_mm: delta_mm,
            radius_mm,
            dt_s,
        }),
    })
}
