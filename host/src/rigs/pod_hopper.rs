//! Whole pods running out of a flat-bottomed silo through a circular orifice (issue 22
//! item 1; the rig of pod spheres is [`super::hopper`]). The response is the mass flow rate,
//! g/s; the condition that moves it is the orifice's diameter, mm.
//!
//! 1. The study's pod mix is laid out on the repose rig's lattice ([`layer_points`]) inside a
//!    steel silo of radius [`SILO_RADIUS_IN_POD_RADII`] bounding radii of the largest pod,
//!    which stands on a steel orifice plate ([`arachis_core::wall::OrificePlate`]) closed by
//!    a shutter. The silo holds at least [`MIN_PODS`] pods, or the mode's count when that is
//!    larger ([`pods_in_silo`]): a quick mode's 150 pods would lie about two pods deep.
//! 2. The pods fall at the study's fill speed, each with a random sideways velocity of up to
//!    [`SCATTER_SPEED_M_S`] so that they mix and do not stack in the lattice's rings, land
//!    and settle (the repose rig's criterion,
//!    at most [`MAX_SETTLE_S`] after the highest pod could have landed).
//! 3. The shutter drops away at [`SHUTTER_SPEED_M_S`] and stops as the catch floor, deep
//!    enough below the plate ([`catch_depth_mm`]) that the heap of discharged pods never
//!    reaches the orifice.
//! 4. The discharged mass (pods whose centre of mass is below the plate) is sampled every
//!    [`SAMPLE_INTERVAL_S`]. The mass flow rate is the mass between the crossings of
//!    [`FLOW_WINDOW`] (fractions of the fill) over the time between them; each crossing time
//!    is interpolated between two samples. The fraction of the fill that ran out
//!    is a second response ([`DISCHARGED_FRACTION`]).
//!
//! Why a window of fractions and not of times: the flow lasts from a fraction of a second to
//! seconds over the orifices a diagnosis searches, and the first pods out are the transient
//! of the opening. A jammed hopper still answers: if the flow stalls for [`STALL_S`], or
//! has not reached the upper crossing within [`MAX_DISCHARGE_S`], the window ends when the
//! last mass crossed (and starts at the opening when even the lower crossing was not
//! reached), and the details say `jammed`.
//!
//! By Beverloo's law, W = C·ρ_b·√g·(D − k·d)^(5/2) (Beverloo, Leniger & van de Velde 1961),
//! the orifice diameter D enters through the empty annulus k·d, so the shape of W against D
//! tells friction (which changes C and k a little) from cohesion (which chokes small
//! orifices far more than large ones).

use arachis_core::prelude::*;
use arachis_core::scenario::hopper::discharged_mass_g;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::pod_bench::{PodTest, MOISTURE};
use super::pod_bulk_density::landing_time_s;
use super::pod_world::error::ExperimentError;
use super::pod_world::frames::FrameRecorder;
use super::pod_world::observation::*;
use super::pod_world::setup::*;
use super::pod_world::Experiment;
use super::repose_cylinder::{
    at_rest_energy_j, layer_points, stack_layers, Placed, CELL_GAP_MM, CHECK_INTERVAL_S,
    WALL_CLEARANCE_MM,
};
use crate::limits::Limits;
use arachis_core::scenario::SplitMix64;

/// This rig's test.
pub const TEST: PodTest = PodTest {
    experiment: Experiment::PodHopper,
    run,
};

const EXPERIMENT: Experiment = Experiment::PodHopper;

/// The orifice-diameter condition, mm.
pub const ORIFICE_DIAMETER: &str = "orifice_diameter_mm";
/// The mass flow rate response, g/s (as the sphere hopper's).
pub const MASS_FLOW_RATE: &str = "mass_flow_rate";
/// The fraction of the fill that ran out before the flow stopped or the window closed: a
/// second response, below [`FLOW_WINDOW`]'s upper fraction only when the silo jammed.
pub const DISCHARGED_FRACTION: &str = "discharged_fraction";
/// Orifice diameter without a measurement that names one, mm. ASSUMPTION: seed 000 has no
/// hopper test. 200 mm is about six pod lengths (34.3 mm, seed 001 Table 1). Measured on the
/// shipped study's quick pods (seed 1, 1 000 pods): at the quick calibration's optimum they
/// run out of 200 mm at 2.9 kg/s, and arch over 150 mm after 38 % of the fill; with the
/// study's bench coefficients (which pile at 54° in Arachis) they run out of 200 mm at
/// 0.45 kg/s and arch after 47 %.
pub const DEFAULT_ORIFICE_MM: f64 = 200.0;
/// Orifice diameters the rig accepts, mm (a run also refuses one that leaves less than a
/// pod between the orifice and the silo's wall, or is narrower than a pod).
pub const ORIFICE_RANGE_MM: (f64, f64) = (5.0, 400.0);
/// Orifice diameters a diagnosis may propose, mm: about 4.4 to 7.3 pod lengths, from where
/// the calibrated pods start to arch to where the silo's wall (335 mm across for the
/// shipped pods) leaves less than two pods' room beside the orifice.
pub const ORIFICE_SEARCH_MM: (f64, f64) = (150.0, 250.0);
/// The silo's radius in bounding radii of the largest pod: 168 mm for the shipped study's
/// pods. Measured: in a silo of 7 radii (235 mm) the study's pods arched across the whole
/// silo after a third of the fill had run out of 150 mm, and in one of 7 radii a fill of
/// sphere particles stood along the wall the same way; so the silo is at least about twice
/// as wide as the orifices searched.
pub const SILO_RADIUS_IN_POD_RADII: f64 = 10.0;
/// Fewest pods in the silo. 1 000 of the shipped study's quick pods settle about 13–16 cm
/// deep in its silo (highest centre 126 mm at the quick calibration's optimum, 159 mm with
/// the bench coefficients): less than the orifice, so the flow is read from the first half
/// of the fill. More pods cost proportionally more time.
pub const MIN_PODS: u32 = 1000;
/// Largest horizontal launch speed of a pod, m/s: each pod starts with a velocity drawn
/// uniformly from a disc of this radius, so that the lattice's rings (the same radius in
/// every layer) do not stack into cylindrical shells along the wall that stand when the
/// silo empties beside them (measured: half of a fill of spheres stood so).
pub const SCATTER_SPEED_M_S: f64 = 0.3;
/// Longest wait for the fill to come to rest after the highest pod could have landed, s.
pub const MAX_SETTLE_S: f64 = 1.0;
/// Speed at which the shutter drops away, m/s: faster than a pod falling from rest can
/// follow over any catch depth below 0.8 m (free fall reaches 2 m/s only after 0.2 m, and
/// overtakes the shutter after 0.8 m).
pub const SHUTTER_SPEED_M_S: f64 = 2.0;
/// The fractions of the fill between whose crossings the flow rate is read. Measured on the
/// shipped study's quick pods through 150 mm: the flow stopped with 63 % of the fill out,
/// the rest held on the floor of the silo and arched above it.
pub const FLOW_WINDOW: (f64, f64) = (0.1, 0.5);
/// Interval between two readings of the discharged mass, s.
pub const SAMPLE_INTERVAL_S: f64 = 0.002;
/// Longest discharge after the opening, s: the shipped study's pods take about 2 s to pass
/// the window through 130 mm.
pub const MAX_DISCHARGE_S: f64 = 6.0;
/// A discharge that adds no mass for this long has arched over the orifice and stops, s
/// (nothing in the rig shakes an arch loose).
pub const STALL_S: f64 = 0.5;
/// Steepest heap the discharged pods can form on the catch floor, degrees (above every
/// repose angle measured for pods, seed 000 §3.6: 31°; Arachis' quick piles: up to 55°).
pub const STEEPEST_HEAP_DEG: f64 = 60.0;
/// Solid fraction assumed for the heap, when sizing the catch floor's depth: looser than
/// any pod bed measured (0.44 for the shipped study's pods, `pod_bulk_density`).
pub const LOOSEST_HEAP_SOLID_FRACTION: f64 = 0.35;
/// Grams in a kilogram.
const G_PER_KG: f64 = 1e3;
/// Cubic millimetres in a cubic metre.
const MM3_PER_M3: f64 = 1e9;

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "pod_hopper",
    about:
        "the study's pods running out of a flat-bottomed silo through an orifice (mass flow rate)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: MASS_FLOW_RATE,
            unit: "g/s",
            label: "mass flow rate, g/s",
        },
        Quantity {
            name: DISCHARGED_FRACTION,
            unit: "-",
            label: "fraction of the fill discharged",
        },
    ],
    conditions: &[
        ConditionKey::new(ORIFICE_DIAMETER, "orifice diameter, mm", Limits::Positive)
            .within(ORIFICE_RANGE_MM, ORIFICE_SEARCH_MM),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

/// The orifice diameter of a run, mm: its condition's, else [`DEFAULT_ORIFICE_MM`].
pub fn orifice_diameter_mm(inputs: &RunInputs) -> f64 {
    inputs
        .spec
        .condition
        .get(ORIFICE_DIAMETER)
        .copied()
        .unwrap_or(DEFAULT_ORIFICE_MM)
}

/// Pods in the silo: the mode's count, at least [`MIN_PODS`].
pub fn pods_in_silo(inputs: &RunInputs) -> u32 {
    inputs.mode.pods.max(MIN_PODS)
}

/// Depth of the catch floor below the orifice plate, mm: the height of a cone of the whole
/// fill heaped at [`STEEPEST_HEAP_DEG`] with [`LOOSEST_HEAP_SOLID_FRACTION`], plus a pod
/// length. A cone of height h and slope θ holds V = π·h³/(3·tan²θ).
pub fn catch_depth_mm(pods_volume_mm3: f64, bounding_radius_mm: f64) -> f64 {
    let heap_mm3 = pods_volume_mm3 / LOOSEST_HEAP_SOLID_FRACTION;
    let tan = STEEPEST_HEAP_DEG.to_radians().tan();
    (3.0 * tan * tan * heap_mm3 / std::f64::consts::PI).cbrt() + 2.0 * bounding_radius_mm
}

/// The silo and its pods before the fill (module notes, step 1).
#[derive(Debug, Clone, PartialEq)]
pub struct HopperLayout {
    /// Silo radius, mm.
    pub silo_radius_mm: f64,
    /// Silo height above the orifice plate, mm.
    pub silo_height_mm: f64,
    /// Depth of the catch floor below the plate, mm.
    pub catch_depth_mm: f64,
    /// The pods, in the order they are added (positions above the plate's centre).
    pub particles: Vec<Placed>,
    /// Each pod's horizontal launch velocity, m/s, in the order of `particles`.
    pub scatter_m_s: Vec<[f64; 2]>,
    /// Spheres over all pods.
    pub sphere_total: usize,
}

impl HopperLayout {
    /// Lays out the silo of `inputs` for placement seed `seed`.
    pub fn new(inputs: &RunInputs, seed: u64) -> Self {
        let n = pods_in_silo(inputs) as usize;
        let mut rng = SplitMix64::new(seed);
        let classes = inputs.shuffled_classes(n, &mut rng);
        let sphere_total = classes
            .iter()
            .map(|&k| inputs.template(k).spheres.len())
            .sum();
        let volume_mm3: f64 = classes
            .iter()
            .map(|&k| inputs.template(k).mass.mass_kg / inputs.pod.density_kg_m3)
            .sum::<f64>()
            * MM3_PER_M3;
        let bound = inputs.max_bounding_radius_mm();
        let cell = 2.0 * bound + CELL_GAP_MM;
        let silo_radius_mm = SILO_RADIUS_IN_POD_RADII * bound;
        let layer = layer_points(silo_radius_mm - bound - WALL_CLEARANCE_MM, cell);
        let z0 = bound + WALL_CLEARANCE_MM;
        let particles = stack_layers(&layer, z0, cell, classes, &mut rng);
        let scatter_m_s = particles
            .iter()
            .map(|_| {
                let (turn, reach) = (unit_uniform(&mut rng), unit_uniform(&mut rng).sqrt());
                let (s, c) = (std::f64::consts::TAU * turn).sin_cos();
                [SCATTER_SPEED_M_S * reach * c, SCATTER_SPEED_M_S * reach * s]
            })
            .collect();
        let top_mm = particles
            .iter()
            .map(|p| p.position_mm[2])
            .fold(0.0, f64::max)
            + bound;
        HopperLayout {
            silo_radius_mm,
            silo_height_mm: top_mm + WALL_CLEARANCE_MM,
            catch_depth_mm: catch_depth_mm(volume_mm3, bound),
            particles,
            scatter_m_s,
            sphere_total,
        }
    }
}

/// Where the discharge stood at each reading: time after the opening (s) and the mass
/// below the plate (g).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Reading {
    t_s: f64,
    mass_g: f64,
}

/// The time at which the discharged mass first reaches `mass_g`, interpolated between the
/// two readings around it, or `None` if it never does.
fn crossing_s(readings: &[Reading], mass_g: f64) -> Option<f64> {
    let k = readings.iter().position(|r| r.mass_g >= mass_g)?;
    let b = readings[k];
    let Some(a) = k.checked_sub(1).map(|j| readings[j]) else {
        return Some(b.t_s);
    };
    Some(a.t_s + (b.t_s - a.t_s) * (mass_g - a.mass_g) / (b.mass_g - a.mass_g))
}

/// The flow rate over [`FLOW_WINDOW`] of a fill of `total_g`, g/s, with the window's start
/// and end (s after the opening) and whether the discharge stopped short of its end.
fn flow_rate(readings: &[Reading], total_g: f64) -> (f64, [f64; 2], bool) {
    let (low, high) = (FLOW_WINDOW.0 * total_g, FLOW_WINDOW.1 * total_g);
    let last = readings.last().copied().unwrap_or(Reading {
        t_s: 0.0,
        mass_g: 0.0,
    });
    let (start, start_g) = crossing_s(readings, low).map_or((0.0, 0.0), |t| (t, low));
    let (end, end_g, jammed) = match crossing_s(readings, high) {
        Some(t) => (t, high, false),
        None => (
            crossing_s(readings, last.mass_g).unwrap_or(last.t_s),
            last.mass_g,
            true,
        ),
    };
    let rate = if end > start {
        (end_g - start_g) / (end - start)
    } else {
        0.0
    };
    (rate, [start, end], jammed)
}

/// Runs the pod hopper (module notes).
pub fn run(
    inputs: &RunInputs,
    seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let orifice_mm = orifice_diameter_mm(inputs);
    let layout = HopperLayout::new(inputs, seed);
    let bound_mm = inputs.max_bounding_radius_mm();
    let widest_mm = 2.0 * (layout.silo_radius_mm - 2.0 * bound_mm);
    if !(2.0 * bound_mm..=widest_mm).contains(&orifice_mm) {
        return Err(ExperimentError::Study {
            experiment: EXPERIMENT.name(),
            reason: format!(
                "{ORIFICE_DIAMETER} = {orifice_mm} does not fit this silo ({:.1} mm across): \
                 it must be from one pod ({:.1} mm) to the silo's diameter less two pods \
                 ({widest_mm:.1} mm)",
                2.0 * layout.silo_radius_mm,
                2.0 * bound_mm
            ),
        });
    }
    let n = layout.particles.len();
    let mut arena = Arena::new(inputs, n, layout.sphere_total);
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    let e = |s| setup_error(EXPERIMENT, s);
    let up = [0.0, 0.0, 1.0];
    w.add_wall(WallSpec::fixed(
        WallGeometry::OrificePlate {
            centre_m: [0.0; 3],
            normal: up,
            hole_radius_m: 0.5 * orifice_mm * M_PER_MM,
        },
        mats.wall,
    ))
    .map_err(e)?;
    w.add_wall(WallSpec::fixed(
        WallGeometry::Cylinder {
            base_m: [0.0; 3],
            axis: up,
            radius_m: layout.silo_radius_mm * M_PER_MM,
            length_m: Some(layout.silo_height_mm * M_PER_MM),
        },
        mats.wall,
    ))
    .map_err(e)?;
    let shutter = add_floor(&mut w, mats, EXPERIMENT)?;
    let fill_speed = inputs.simulation.repose.fill_speed_m_s;
    for (p, [vx, vy]) in layout.particles.iter().zip(&layout.scatter_m_s) {
        add_pod(
            &mut w,
            inputs.template(p.class),
            mats.pod,
            p.position_mm,
            p.orientation,
            [*vx, *vy, -fill_speed],
            EXPERIMENT,
        )?;
    }
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    frames.record(&w);

    // Fill and settle.
    let highest_mm = layout.silo_height_mm - bound_mm;
    let landed_s = landing_time_s(highest_mm, fill_speed, inputs.simulation.gravity_m_s2);
    let chunk = steps_for(&w, CHECK_INTERVAL_S);
    settle(
        &mut w,
        chunk,
        landed_s,
        landed_s + MAX_SETTLE_S,
        at_rest_energy_j(inputs, n),
        &mut frames,
        EXPERIMENT,
    )?;
    let total_g: f64 = w.bodies().iter().map(|b| b.mass.to_f64()).sum();
    let fill_level_mm = w
        .bodies()
        .iter()
        .map(|b| b.position.z.to_f64())
        .fold(0.0, f64::max);

    // Open, catch, and read the discharge.
    let opened_s = w.time_s();
    let moving =
        |w: &mut World<'_, Fx>, v: f64| w.set_wall_velocity_m_s(shutter, [0.0, 0.0, v]).map_err(e);
    moving(&mut w, -SHUTTER_SPEED_M_S)?;
    let travel = steps_for(&w, layout.catch_depth_mm * M_PER_MM / SHUTTER_SPEED_M_S);
    let reading = steps_for(&w, SAMPLE_INTERVAL_S);
    let mut readings = vec![Reading {
        t_s: 0.0,
        mass_g: 0.0,
    }];
    let mut stepped = 0;
    let frame_every = (steps_for(&w, CHECK_INTERVAL_S) / reading).max(1);
    let stall = (STALL_S / SAMPLE_INTERVAL_S).round() as usize;
    let flowing = |readings: &[Reading]| {
        let k = readings.len();
        k <= stall || readings[k - 1].mass_g > readings[k - 1 - stall].mass_g
    };
    while readings
        .last()
        .is_some_and(|r| r.mass_g < FLOW_WINDOW.1 * total_g)
        && w.time_s() - opened_s < MAX_DISCHARGE_S
        && flowing(&readings)
    {
        let steps = if stepped < travel {
            reading.min(travel - stepped)
        } else {
            reading
        };
        run_steps(&mut w, steps, EXPERIMENT)?;
        stepped += steps;
        if stepped == travel {
            moving(&mut w, 0.0)?;
        }
        if readings.len() as u64 % frame_every == 0 {
            frames.record(&w);
        }
        readings.push(Reading {
            t_s: w.time_s() - opened_s,
            mass_g: discharged_mass_g(&w),
        });
    }
    frames.record(&w);
    let (rate, window_s, jammed) = flow_rate(&readings, total_g);
    let details = HopperDetails {
        pods: n as u32,
        spheres: layout.sphere_total as u32,
        silo_diameter_mm: 2.0 * layout.silo_radius_mm,
        orifice_diameter_mm: orifice_mm,
        catch_depth_mm: layout.catch_depth_mm,
        fill_mass_kg: total_g / G_PER_KG,
        fill_level_mm,
        dt_s,
        opened_s,
        window_s,
        jammed,
        discharged_fraction: readings.last().map_or(0.0, |r| r.mass_g / total_g),
        end_s: w.time_s(),
        steps: w.step_count(),
    };
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: MASS_FLOW_RATE,
        value: rate,
        unit: "g/s",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::PodHopper(details),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn readings(points: &[(f64, f64)]) -> Vec<Reading> {
        points
            .iter()
            .map(|&(t_s, mass_g)| Reading { t_s, mass_g })
            .collect()
    }

    #[test]
    fn the_window_reads_between_interpolated_crossings() {
        // 100 g discharged at 50 g/s from 0.1 s: 10 g at 0.3 s, 50 g at 1.1 s.
        let r = readings(&[
            (0.0, 0.0),
            (0.2, 5.0),
            (0.6, 25.0),
            (1.4, 65.0),
            (1.8, 85.0),
        ]);
        let (rate, window, jammed) = flow_rate(&r, 100.0);
        assert!((rate - 50.0).abs() < 1e-9, "{rate}");
        assert!((window[0] - 0.3).abs() < 1e-12 && (window[1] - 1.1).abs() < 1e-12);
        assert!(!jammed);
    }

    #[test]
    fn a_jammed_hopper_reads_to_its_last_reading() {
        let r = readings(&[(0.0, 0.0), (0.5, 30.0), (1.0, 40.0), (4.0, 40.0)]);
        let (rate, window, jammed) = flow_rate(&r, 100.0);
        // 10 g crossed at 1/6 s; the flow stopped at 40 g at 1 s, short of 50 g.
        assert!(jammed);
        assert!((window[0] - 1.0 / 6.0).abs() < 1e-12 && window[1] == 1.0);
        assert!((rate - 30.0 / (1.0 - 1.0 / 6.0)).abs() < 1e-9, "{rate}");
        // Nothing out at all: no flow.
        let none = readings(&[(0.0, 0.0), (4.0, 0.0)]);
        assert_eq!(flow_rate(&none, 100.0).0, 0.0);
    }

    #[test]
    fn the_catch_floor_holds_the_steepest_heap() {
        // 1 000 cm³ of pods heap to 2 857 cm³ in a 60° cone: h = (3·3·V/π)^{1/3} = 20.1 cm.
        let depth = catch_depth_mm(1.0e6, 10.0);
        let heap_mm3 = 1.0e6 / LOOSEST_HEAP_SOLID_FRACTION;
        let h = depth - 20.0;
        let cone = std::f64::consts::PI * h.powi(3) / (3.0 * 3.0);
        assert!(
            (cone - heap_mm3).abs() < 1e-6 * heap_mm3,
            "{cone} vs {heap_mm3}"
        );
    }
}
