//! Poured bulk density of whole pods: the study's pod mix falls from a drop height into the
//! repose rig's steel cylinder, settles, and the bed's bulk density is read in a slab well
//! inside it (issue 22 item 1; the sphere rig is [`super::bulk_density`]).
//!
//! 1. The pods are laid out as for the repose test ([`Layout`]: the study's shape mix on a
//!    lattice of cells, random orientations, the cylinder scaled for the mode), the whole
//!    lattice lifted so that its lowest centres of mass start [`DROP_HEIGHT`] above the floor.
//!    They fall at the study's fill speed.
//! 2. The run lasts until the highest pod has had time to land
//!    ([`landing_time_s`]) and the bed is at rest (the repose rig's criterion, kinetic energy
//!    below [`SETTLED_SPEED_M_S`] per pod), at most [`MAX_SETTLE_S`] longer.
//! 3. The level of the bed is read as a bench operator reads a graduated cylinder, as the
//!    mean height of its top surface ([`surface_level_mm`]). The measuring slab starts one
//!    pod length (twice the largest bounding radius) above the floor and ends one pod length
//!    below the level, so neither the floor's layering nor the bumpy top enters the figure.
//! 4. The bulk density is the pods' mass in the slab over the slab's volume inside the
//!    cylinder ([`slab_mass_kg`]): each pod's mass counts by the share of its spheres'
//!    volume that lies between the slab's planes.
//!
//! Why a slab and not the whole bed over the level: the floor and the top surface hold the
//! bed's loosest layers, whose thickness is a pod, whatever the pod count; in the quick
//! mode's short bed (about 150 mm) they would weigh as much as the inside.
//!
//! The drop height is a condition of the rig (`drop_height_mm`); a study without a
//! measurement of the rig runs at [`DEFAULT_DROP_HEIGHT_MM`].

use std::f64::consts::PI;

use arachis_core::prelude::*;
use arachis_core::scenario::bulk_density::sphere_volume_between;
use arachis_core::units::LENGTH_M_TO_MM;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::pod_bench::{PodTest, MOISTURE};
use super::pod_world::error::ExperimentError;
use super::pod_world::frames::FrameRecorder;
use super::pod_world::observation::*;
use super::pod_world::setup::*;
use super::pod_world::Experiment;
pub use super::repose_cylinder::SETTLED_SPEED_M_S;
use super::repose_cylinder::{at_rest_energy_j, Layout, CHECK_INTERVAL_S, WALL_CLEARANCE_MM};
use crate::limits::Limits;
use crate::repose::Sphere as PileSphere;

/// This rig's test.
pub const TEST: PodTest = PodTest {
    experiment: Experiment::PodBulkDensity,
    run,
};

const EXPERIMENT: Experiment = Experiment::PodBulkDensity;

/// The drop-height condition, mm: from the floor to the lowest pods' centres of mass at
/// release.
pub const DROP_HEIGHT: &str = "drop_height_mm";
/// The bulk density response, kg/m³.
pub const BULK_DENSITY: &str = "bulk_density";
/// The bed's level (mean height of its top surface), mm: a second response.
pub const BED_LEVEL: &str = "bed_level";
/// Drop height without a measurement that names one, mm. ASSUMPTION: seed 000 measures no
/// bulk density; 100 mm is a hand-poured fill from just above the cylinder's rim.
pub const DEFAULT_DROP_HEIGHT_MM: f64 = 100.0;
/// Drop heights the rig accepts, mm: from a pod lowered onto the floor to a fall of 1 m.
pub const DROP_HEIGHT_RANGE_MM: (f64, f64) = (30.0, 1000.0);
/// Drop heights a diagnosis may propose, mm.
pub const DROP_HEIGHT_SEARCH_MM: (f64, f64) = (50.0, 500.0);
/// Longest wait for the bed to come to rest after the highest pod has landed, s.
pub const MAX_SETTLE_S: f64 = 1.5;

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "pod_bulk_density",
    about: "the study's pods poured from a drop height into the repose cylinder (bulk density)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[
        Quantity {
            name: BULK_DENSITY,
            unit: "kg/m^3",
            label: "bulk density, kg/m³",
        },
        Quantity {
            name: BED_LEVEL,
            unit: "mm",
            label: "bed level, mm",
        },
    ],
    conditions: &[
        ConditionKey::new(DROP_HEIGHT, "drop height, mm", Limits::Positive)
            .within(DROP_HEIGHT_RANGE_MM, DROP_HEIGHT_SEARCH_MM),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

/// The drop height of a run, mm: its condition's, else [`DEFAULT_DROP_HEIGHT_MM`].
pub fn drop_height_mm(inputs: &RunInputs) -> f64 {
    inputs
        .spec
        .condition
        .get(DROP_HEIGHT)
        .copied()
        .unwrap_or(DEFAULT_DROP_HEIGHT_MM)
}

/// Time for a centre released `height_mm` above the floor at `speed_m_s` downwards to fall
/// to the floor under `gravity_m_s2`, s: the root of h = v₀t + ½gt².
pub fn landing_time_s(height_mm: f64, speed_m_s: f64, gravity_m_s2: f64) -> f64 {
    let h = height_mm / LENGTH_M_TO_MM;
    ((speed_m_s * speed_m_s + 2.0 * gravity_m_s2 * h).sqrt() - speed_m_s) / gravity_m_s2
}

/// Runs the pod bulk-density rig (module notes).
pub fn run(
    inputs: &RunInputs,
    seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let drop_mm = drop_height_mm(inputs);
    let study_error = |reason: String| ExperimentError::Study {
        experiment: EXPERIMENT.name(),
        reason,
    };
    let bound_mm = inputs.max_bounding_radius_mm();
    if drop_mm < bound_mm + WALL_CLEARANCE_MM {
        return Err(study_error(format!(
            "a drop height of {drop_mm} mm puts the pods into the floor: it must be at least \
             their bounding radius and clearance, {:.1} mm",
            bound_mm + WALL_CLEARANCE_MM
        )));
    }
    let layout = Layout::new(inputs, seed)?;
    let lowest_mm = layout
        .particles
        .iter()
        .map(|p| p.position_mm[2])
        .fold(f64::INFINITY, f64::min);
    let lift_mm = drop_mm - lowest_mm;
    let highest_mm = layout
        .particles
        .iter()
        .map(|p| p.position_mm[2])
        .fold(f64::NEG_INFINITY, f64::max)
        + lift_mm;

    let n = layout.particles.len();
    let mut arena = Arena::new(inputs, n, layout.sphere_total);
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    let e = |s| setup_error(EXPERIMENT, s);
    let radius_mm = 0.5 * layout.diameter_mm;
    add_floor(&mut w, mats, EXPERIMENT)?;
    w.add_wall(WallSpec::fixed(
        WallGeometry::Cylinder {
            base_m: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            radius_m: radius_mm * M_PER_MM,
            length_m: None,
        },
        mats.wall,
    ))
    .map_err(e)?;
    let fill_speed = inputs.simulation.repose.fill_speed_m_s;
    for p in &layout.particles {
        let [x, y, z] = p.position_mm;
        add_pod(
            &mut w,
            inputs.template(p.class),
            mats.pod,
            [x, y, z + lift_mm],
            p.orientation,
            [0.0, 0.0, -fill_speed],
            EXPERIMENT,
        )?;
    }
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    frames.record(&w);

    // Fall, land and settle.
    let landed_s = landing_time_s(highest_mm, fill_speed, inputs.simulation.gravity_m_s2);
    let at_rest_j = at_rest_energy_j(inputs, n);
    let chunk = steps_for(&w, CHECK_INTERVAL_S);
    let until_s = landed_s + MAX_SETTLE_S;
    settle(
        &mut w,
        chunk,
        landed_s,
        until_s,
        at_rest_j,
        &mut frames,
        EXPERIMENT,
    )?;

    // Read the level and weigh the slab.
    let bed = bed_of(&w);
    let min_radius_mm = inputs.min_sphere_radius_mm();
    let level_mm = surface_level_mm(&bed, radius_mm, min_radius_mm);
    let slab_mm = [2.0 * bound_mm, level_mm - 2.0 * bound_mm];
    if slab_mm[1] - slab_mm[0] < 2.0 * bound_mm {
        return Err(study_error(format!(
            "the bed of {n} pods is {level_mm:.1} mm deep: too shallow for a measuring slab \
             a pod length ({:.1} mm) thick between a pod length above the floor and below \
             its level; use a mode with more pods",
            2.0 * bound_mm
        )));
    }
    let mass_kg = slab_mass_kg(&bed, slab_mm);
    let slab_m3 = PI * radius_mm * radius_mm * (slab_mm[1] - slab_mm[0]) / MM3_PER_M3;
    let density = mass_kg / slab_m3;
    let details = BulkDensityDetails {
        pods: n as u32,
        spheres: layout.sphere_total as u32,
        cylinder_diameter_mm: layout.diameter_mm,
        drop_height_mm: drop_mm,
        dt_s,
        end_s: w.time_s(),
        steps: w.step_count(),
        final_kinetic_energy_j: kinetic_energy_j(&w),
        level_mm,
        slab_mm,
        slab_mass_kg: mass_kg,
        bed,
    };
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: BULK_DENSITY,
        value: density,
        unit: "kg/m^3",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::PodBulkDensity(details),
    })
}

/// Cubic millimetres in a cubic metre.
const MM3_PER_M3: f64 = 1e9;

/// Every pod of `w` (by body, in body order) with its mass and spheres.
fn bed_of(w: &World<'_, Fx>) -> Vec<BedPod> {
    let mut pods: Vec<BedPod> = w
        .bodies()
        .iter()
        .map(|b| BedPod {
            mass_kg: b.mass.to_f64() * KG_PER_G,
            spheres: Vec::new(),
        })
        .collect();
    for s in w.spheres() {
        pods[s.body as usize].spheres.push(PileSphere {
            centre_mm: s.position.to_f64(),
            radius_mm: s.radius.to_f64(),
        });
    }
    pods
}

/// Kilograms in a gram (the core's mass unit).
const KG_PER_G: f64 = 1e-3;

/// The mean height of the bed's top surface inside a cylinder of radius `radius_mm`, mm:
/// over a square grid of pitch `pitch_mm` (cells whose centres lie inside the cylinder),
/// the height of the highest sphere surface above each cell's centre, or 0 where no sphere
/// covers it. A report in f64, never fed back into stepping.
pub fn surface_level_mm(bed: &[BedPod], radius_mm: f64, pitch_mm: f64) -> f64 {
    let cells = (radius_mm / pitch_mm).ceil() as i64;
    let mut tops = vec![0.0_f64; ((2 * cells + 1) * (2 * cells + 1)) as usize];
    let index = |i: i64, j: i64| ((i + cells) * (2 * cells + 1) + (j + cells)) as usize;
    for s in bed.iter().flat_map(|p| &p.spheres) {
        let [cx, cy, cz] = s.centre_mm;
        let r = s.radius_mm;
        let (i0, i1) = (
            ((cx - r) / pitch_mm).floor() as i64,
            ((cx + r) / pitch_mm).ceil() as i64,
        );
        let (j0, j1) = (
            ((cy - r) / pitch_mm).floor() as i64,
            ((cy + r) / pitch_mm).ceil() as i64,
        );
        for i in i0.max(-cells)..=i1.min(cells) {
            for j in j0.max(-cells)..=j1.min(cells) {
                let (dx, dy) = (i as f64 * pitch_mm - cx, j as f64 * pitch_mm - cy);
                let d2 = dx * dx + dy * dy;
                if d2 < r * r {
                    let top = cz + (r * r - d2).sqrt();
                    let cell = &mut tops[index(i, j)];
                    *cell = cell.max(top);
                }
            }
        }
    }
    let (mut sum, mut count) = (0.0, 0usize);
    for i in -cells..=cells {
        for j in -cells..=cells {
            let (x, y) = (i as f64 * pitch_mm, j as f64 * pitch_mm);
            if x * x + y * y <= radius_mm * radius_mm {
                sum += tops[index(i, j)];
                count += 1;
            }
        }
    }
    sum / count.max(1) as f64
}

/// The pods' mass between the heights `slab_mm` = [bottom, top], kg: each pod's mass times
/// the share of its spheres' volume between the two planes (the spheres of a pod overlap,
/// so a share is weighted by sphere volume, not by the pod's own; only pods cut by a plane
/// are affected, and they count the same on average). A report in f64.
pub fn slab_mass_kg(bed: &[BedPod], slab_mm: [f64; 2]) -> f64 {
    bed.iter()
        .map(|pod| {
            let (inside, whole) = pod.spheres.iter().fold((0.0, 0.0), |(a, b), s| {
                let [_, _, z] = s.centre_mm;
                let r = s.radius_mm;
                (
                    a + sphere_volume_between(z, r, slab_mm[0], slab_mm[1]),
                    b + 4.0 / 3.0 * PI * r * r * r,
                )
            });
            pod.mass_kg * inside / whole
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(z: f64, r: f64) -> BedPod {
        BedPod {
            mass_kg: 1.0,
            spheres: vec![PileSphere {
                centre_mm: [0.0, 0.0, z],
                radius_mm: r,
            }],
        }
    }

    #[test]
    fn the_level_under_a_dome_is_its_mean_height() {
        // One sphere of radius R = 50 centred 10 mm below the floor spans the whole
        // cylinder of radius ρ = 30: its top over the disc has the mean
        // c + (2/(3ρ²))·(R³ − (R² − ρ²)^{3/2}) (the integral of √(R² − d²) over the disc).
        let (c, r, rho): (f64, f64, f64) = (-10.0, 50.0, 30.0);
        let expected = c + 2.0 / (3.0 * rho * rho) * (r * r * r - (r * r - rho * rho).powf(1.5));
        let level = surface_level_mm(&[ball(c, r)], rho, 0.05);
        // The grid's cells along the disc's rim are in or out whole: 0.1 % of the height.
        assert!(
            (level - expected).abs() < 1e-3 * expected,
            "{level} vs {expected}"
        );
        // Where nothing covers the floor, the level is the floor.
        assert_eq!(surface_level_mm(&[], rho, 0.5), 0.0);
    }

    #[test]
    fn the_slab_counts_whole_spheres_and_cut_ones_by_volume() {
        let bed = [ball(50.0, 4.0), ball(100.0, 4.0), ball(20.0, 4.0)];
        // Inside, outside, and cut through its centre by the bottom plane.
        let m = slab_mass_kg(&bed, [20.0, 80.0]);
        assert!((m - 1.5).abs() < 1e-12, "{m}");
    }
}
