//! The dynamic angle of repose of whole pods in a rotating drum (issue 22 item 1; the rig of
//! pod spheres is [`super::drum`]).
//!
//! 1. The study's pod mix is laid out on a lattice of cells inside a steel drum whose axis
//!    is horizontal (+y): in each cross-section the cells of the repose rig's layer
//!    ([`layer_points`]), the layers side by side along the axis, every pod turned at random
//!    and the shapes shuffled ([`DrumLayout`]). The drum's radius is
//!    [`DRUM_RADIUS_IN_POD_RADII`] bounding radii of the largest pod, so its cross-section
//!    is the same in every mode; its length holds the lattice, so a mode with more pods has a
//!    longer drum, not a fuller one.
//! 2. The pods fall onto the drum's floor and settle (the repose rig's criterion, at most
//!    [`MAX_SETTLE_S`]).
//! 3. The drum and its end plates turn together at the condition's speed
//!    ([`ROTATION_SPEED`], rpm); after [`SPIN_UP_TURN_RAD`] the bed's angle is read
//!    [`SAMPLES`] times over the next [`MEASURE_TURN_RAD`], and the observable is their mean.
//!
//! The angle is the core's [`bed_angle_deg`]: the direction from the drum's axis to the bed's
//! centre of mass, which for a flat surface in a circular drum is the surface's inclination.
//! Pods are clumps, and a clump's position is its centre of mass, so the same reading serves.

use std::f64::consts::TAU;

use arachis_core::prelude::*;
use arachis_core::scenario::drum::{bed_angle_deg, Drum, FAR_END, NEAR_END, SHELL};
use arachis_core::scenario::SplitMix64;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::pod_bench::{PodTest, MOISTURE};
use super::pod_world::error::ExperimentError;
use super::pod_world::frames::FrameRecorder;
use super::pod_world::observation::*;
use super::pod_world::setup::*;
use super::pod_world::Experiment;
use super::repose_cylinder::{
    at_rest_energy_j, layer_points, sample_sd, Placed, CELL_GAP_MM, CHECK_INTERVAL_S, MIN_FILL_S,
    WALL_CLEARANCE_MM,
};
use crate::limits::Limits;

/// This rig's test.
pub const TEST: PodTest = PodTest {
    experiment: Experiment::PodDrum,
    run,
};

const EXPERIMENT: Experiment = Experiment::PodDrum;

/// The drum-speed condition, rpm.
pub const ROTATION_SPEED: &str = "rotation_speed_rpm";
/// The dynamic angle of repose, degrees.
pub const DYNAMIC_ANGLE: &str = "dynamic_angle";
/// Drum speed without a measurement that names one, rpm. ASSUMPTION: seed 000 has no drum
/// test; 10 rpm keeps a bed of pods in the rolling regime (Froude number ω²R/g ≈ 0.02 in
/// the quick drum).
pub const DEFAULT_SPEED_RPM: f64 = 10.0;
/// Speeds the rig accepts, rpm: below, a run takes minutes; above, the Froude number of the
/// quick drum passes 0.25 and the bed cataracts.
pub const SPEED_RANGE_RPM: (f64, f64) = (1.0, 40.0);
/// Speeds a diagnosis may propose, rpm.
pub const SPEED_SEARCH_RPM: (f64, f64) = (2.0, 20.0);
/// The drum's radius in bounding radii of the largest pod: about 150 mm for seed 001's mean
/// pod, so that the bed of a quick mode fills about a fifth of the drum and is several pods
/// deep.
pub const DRUM_RADIUS_IN_POD_RADII: f64 = 8.5;
/// Longest wait for the pods to settle before the drum turns, s.
pub const MAX_SETTLE_S: f64 = 1.0;
/// Turn of the drum before the first reading, rad (172°). Measured on the shipped study's
/// quick mode at 10 rpm (seed 1): after 1.5 rad the reading still crept from 54.8° to 60.4°
/// over the next 1.5 rad, as the bed passed from a lifted block to steady flow.
pub const SPIN_UP_TURN_RAD: f64 = 3.0;
/// Turn over which the readings are taken, rad. The study's pods flow in slumps: at 10 rpm
/// the reading rose from 60.9° to 66.9° and fell back to 64.9° over these 3 rad, so a shorter
/// window would read the phase of a slump rather than the bed.
pub const MEASURE_TURN_RAD: f64 = 3.0;
/// Readings of the bed's angle, evenly spaced over [`MEASURE_TURN_RAD`].
pub const SAMPLES: u32 = 30;
/// Radians per second in one rpm.
const RAD_S_PER_RPM: f64 = TAU / 60.0;

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "pod_drum",
    about: "the study's pods in a drum turning about a horizontal axis (dynamic angle of repose)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[Quantity {
        name: DYNAMIC_ANGLE,
        unit: "deg",
        label: "dynamic angle of repose, deg",
    }],
    conditions: &[
        ConditionKey::new(ROTATION_SPEED, "drum speed, rpm", Limits::Positive)
            .within(SPEED_RANGE_RPM, SPEED_SEARCH_RPM),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

/// The drum speed of a run, rpm: its condition's, else [`DEFAULT_SPEED_RPM`].
pub fn speed_rpm(inputs: &RunInputs) -> f64 {
    inputs
        .spec
        .condition
        .get(ROTATION_SPEED)
        .copied()
        .unwrap_or(DEFAULT_SPEED_RPM)
}

/// The drum and its pods before the fill (module notes, step 1).
#[derive(Debug, Clone, PartialEq)]
pub struct DrumLayout {
    /// Drum radius, mm.
    pub radius_mm: f64,
    /// Drum length between its end plates, mm.
    pub length_mm: f64,
    /// The pods, in the order they are added (positions relative to the drum's centre).
    pub particles: Vec<Placed>,
    /// Spheres over all pods.
    pub sphere_total: usize,
}

impl DrumLayout {
    /// Lays out the drum of `inputs` for placement seed `seed`.
    pub fn new(inputs: &RunInputs, seed: u64) -> Self {
        let n = inputs.mode.pods as usize;
        let mut rng = SplitMix64::new(seed);
        let classes = inputs.shuffled_classes(n, &mut rng);
        let sphere_total = classes
            .iter()
            .map(|&k| inputs.template(k).spheres.len())
            .sum();
        let bound = inputs.max_bounding_radius_mm();
        let cell = 2.0 * bound + CELL_GAP_MM;
        let radius_mm = DRUM_RADIUS_IN_POD_RADII * bound;
        let section = layer_points(radius_mm - bound - WALL_CLEARANCE_MM, cell);
        let layers = n.div_ceil(section.len()).max(1);
        let length_mm = layers as f64 * cell + 2.0 * WALL_CLEARANCE_MM;
        let particles = classes
            .into_iter()
            .enumerate()
            .map(|(i, class)| {
                let [x, z] = section[i % section.len()];
                let y = -0.5 * length_mm
                    + WALL_CLEARANCE_MM
                    + (0.5 + (i / section.len()) as f64) * cell;
                Placed {
                    class,
                    position_mm: [x, y, z],
                    orientation: random_quaternion(&mut rng),
                }
            })
            .collect();
        DrumLayout {
            radius_mm,
            length_mm,
            particles,
            sphere_total,
        }
    }

    /// Adds the drum (shell, near and far end plates, in that order) and the pods at rest to
    /// `w`, whose materials are `mats`.
    pub fn build(
        &self,
        w: &mut World<'_, Fx>,
        inputs: &RunInputs,
        mats: RigMaterials,
    ) -> Result<(), ExperimentError> {
        let e = |s| setup_error(EXPERIMENT, s);
        let half_m = 0.5 * self.length_mm * M_PER_MM;
        let shell = w
            .add_wall(WallSpec::fixed(
                WallGeometry::Cylinder {
                    base_m: [0.0; 3],
                    axis: [0.0, 1.0, 0.0],
                    radius_m: self.radius_mm * M_PER_MM,
                    length_m: None,
                },
                mats.wall,
            ))
            .map_err(e)?;
        let plate = |y: f64, ny: f64| {
            WallSpec::fixed(
                WallGeometry::Plane {
                    point_m: [0.0, y, 0.0],
                    normal: [0.0, ny, 0.0],
                },
                mats.wall,
            )
        };
        let near = w.add_wall(plate(-half_m, 1.0)).map_err(e)?;
        let far = w.add_wall(plate(half_m, -1.0)).map_err(e)?;
        debug_assert_eq!((shell, near, far), (SHELL, NEAR_END, FAR_END));
        for p in &self.particles {
            let t = inputs.template(p.class);
            add_pod(
                w,
                t,
                mats.pod,
                p.position_mm,
                p.orientation,
                [0.0; 3],
                EXPERIMENT,
            )?;
        }
        Ok(())
    }
}

/// Turns the drum and both end plates together at `omega_rad_s` about +y: the core's drum
/// rig's [`Drum::spin`], since [`DrumLayout::build`] adds the same walls first, in its order.
pub fn spin(w: &mut World<'_, Fx>, omega_rad_s: f64) -> Result<(), ExperimentError> {
    Drum::spin(w, omega_rad_s).map_err(|e| ExperimentError::Study {
        experiment: EXPERIMENT.name(),
        reason: e.to_string(),
    })
}

/// Runs the pod drum (module notes).
pub fn run(
    inputs: &RunInputs,
    seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let layout = DrumLayout::new(inputs, seed);
    let n = layout.particles.len();
    let mut arena = Arena::new(inputs, n, layout.sphere_total);
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    layout.build(&mut w, inputs, mats)?;
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    frames.record(&w);
    let at_rest_j = at_rest_energy_j(inputs, n);
    let chunk = steps_for(&w, CHECK_INTERVAL_S);
    settle(
        &mut w,
        chunk,
        MIN_FILL_S,
        MAX_SETTLE_S,
        at_rest_j,
        &mut frames,
        EXPERIMENT,
    )?;
    let settled_angle_deg = bed_angle_deg(&w, 1.0);
    let spin_start_s = w.time_s();

    let speed = speed_rpm(inputs);
    let omega = speed * RAD_S_PER_RPM;
    spin(&mut w, omega)?;
    let spin_up = steps_for(&w, SPIN_UP_TURN_RAD / omega);
    run_steps(&mut w, spin_up, EXPERIMENT)?;
    frames.record(&w);
    let reading = steps_for(&w, MEASURE_TURN_RAD / omega / f64::from(SAMPLES));
    let mut samples_deg = Vec::with_capacity(SAMPLES as usize);
    for _ in 0..SAMPLES {
        run_steps(&mut w, reading, EXPERIMENT)?;
        frames.record(&w);
        samples_deg.push(bed_angle_deg(&w, omega));
    }
    let angle = samples_deg.iter().sum::<f64>() / samples_deg.len() as f64;
    let details = DrumDetails {
        pods: n as u32,
        spheres: layout.sphere_total as u32,
        radius_mm: layout.radius_mm,
        length_mm: layout.length_mm,
        speed_rpm: speed,
        froude: omega * omega * layout.radius_mm * M_PER_MM / inputs.simulation.gravity_m_s2,
        dt_s,
        settled_angle_deg,
        spin_start_s,
        end_s: w.time_s(),
        steps: w.step_count(),
        sample_sd_deg: sample_sd(&samples_deg),
        samples_deg,
    };
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: DYNAMIC_ANGLE,
        value: angle,
        unit: "deg",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::PodDrum(details),
    })
}
