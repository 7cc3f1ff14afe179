//! The stacking (repose) angle by cylinder lifting, seed 000 §2.7 and §3.6.1.
//!
//! 1. Pods of the study's shape mix are placed in the steel cylinder standing on a steel
//!    floor, one per cell of a lattice (random orientation; each layer's lattice turned by
//!    a random angle; the shapes shuffled), falling at the study's 0.2 m/s, and left to
//!    settle until their kinetic energy falls below [`SETTLED_SPEED_M_S`] per pod (at the
//!    latest at `lift_start_s`, seed 000: 3.5 s).
//! 2. The cylinder rises at `lift_speed_m_s` (seed 000: 0.05 m/s) until its lower edge is
//!    above every sphere; the pods run out under it and form a pile.
//! 3. The pile settles (same criterion; at most `settle_after_lift_s`).
//! 4. The pile is "photographed" from [`VIEW_COUNT`] azimuths spread over a half turn
//!    (the views from opposite sides are mirror images) and each silhouette goes through
//!    exactly the extraction of `arachis lab repose PHOTO.png` ([`crate::repose`]: largest
//!    blob, upper contour, both flanks fitted between 20 % and 80 % of the height). The
//!    observable is the mean over views of the mean of both flanks: 2 × [`VIEW_COUNT`]
//!    flank fits. A view whose silhouette has too few contour points on a flank (a pod
//!    standing proud of a small pile can leave fewer than 5 in the fit band) is left out
//!    and listed in [`ReposeDetails::refused_views`], as a bench operator retakes an
//!    unusable photograph; fewer than half the views usable ([`min_usable_views`]) fails the run.
//!    When every view is usable the mean is the one `simulated_repose` gives, bit for bit.
//!
//! Differences from the seed, and why:
//! - All pods are placed at once instead of generated over 3 s: the settled packing before
//!   the lift is what matters, and placing at once saves most of the fill time. Settling
//!   and the end of the lift are detected from the state (deterministically) rather than
//!   waited for, which saves the idle seconds of the seed's timeline.
//! - A mode with fewer pods than the full mode uses a geometrically similar cylinder:
//!   diameter × (pods / full pods)^(1/3), so the fill height over diameter (and hence the
//!   pile's shape) matches the full-scale rig instead of spreading a few pods over a
//!   200 mm floor.

use std::f64::consts::PI;

use arachis_core::prelude::*;
use arachis_core::scenario::SplitMix64;

use super::kind::{ConditionKey, Quantity, RigKind, WorldKind};
use super::pod_bench::{PodTest, MOISTURE};
use super::pod_world::error::ExperimentError;
use super::pod_world::frames::FrameRecorder;
use super::pod_world::observation::*;
use super::pod_world::setup::*;
use super::pod_world::Experiment;
use crate::limits::Limits;
use crate::repose::{
    simulated_repose, FitBand, PileProblem, ReposeError, SimulatedRepose, Sphere as PileSphere,
};

/// This rig's test.
pub const TEST: PodTest = PodTest {
    experiment: Experiment::Repose,
    run,
};

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: "repose",
    about: "the stacking angle of a pile by cylinder lifting (seed 000 §2.7, §3.6.1)",
    world: WorldKind::Pods,
    random: true,
    quantities: &[Quantity {
        name: "repose_angle",
        unit: "deg",
        label: "repose angle, deg",
    }],
    conditions: &[
        ConditionKey::new(LIFT_SPEED, "cylinder lifting speed, m/s", Limits::Positive)
            .within(LIFT_SPEED_RANGE_M_S, LIFT_SPEED_SEARCH_M_S),
        ConditionKey::new(
            CYLINDER_DIAMETER,
            "cylinder diameter at full scale, mm",
            Limits::Positive,
        )
        .within(DIAMETER_RANGE_MM, DIAMETER_SEARCH_MM),
        MOISTURE,
    ],
    parameters: &super::pod_bench::PARAMETERS,
    build: |w, o| super::pod_bench::build(w, o, TEST),
};

const EXPERIMENT: Experiment = Experiment::Repose;

pub use super::pod_world::settings::{CYLINDER_DIAMETER, LIFT_SPEED};
/// Lifting speeds the rig accepts, m/s: from a creep at which a pile takes minutes to a
/// jerk of 1 m/s.
pub const LIFT_SPEED_RANGE_M_S: (f64, f64) = (0.001, 1.0);
/// Lifting speeds a diagnosis may propose, m/s: those of stacking-angle benches (seed 000
/// lifts at 0.05 m/s).
pub const LIFT_SPEED_SEARCH_M_S: (f64, f64) = (0.01, 0.1);
/// Cylinder diameters the rig accepts, mm at full scale (the layout refuses one narrower
/// than a pod).
pub const DIAMETER_RANGE_MM: (f64, f64) = (10.0, 1000.0);
/// Cylinder diameters a diagnosis may propose, mm at full scale: half to one and a half
/// times seed 000's assumed 200 mm.
pub const DIAMETER_SEARCH_MM: (f64, f64) = (100.0, 300.0);

/// Side views of the pile, spread evenly over 180°.
pub const VIEW_COUNT: usize = 12;
/// Fewest usable side views for a measured pile: half of them (rounded up), 6 of
/// [`VIEW_COUNT`].
pub fn min_usable_views(views: usize) -> usize {
    views.div_ceil(2)
}
/// Gap between neighbouring lattice cells beyond the pods' bounding spheres, mm.
pub const CELL_GAP_MM: f64 = 1.0;
/// Clearance between the lattice and the cylinder or floor, mm.
pub const WALL_CLEARANCE_MM: f64 = 1.0;
/// A pod counts as at rest below this speed (kinetic energy ½ m v² per pod).
pub const SETTLED_SPEED_M_S: f64 = 0.01;
/// Interval between checks of the settling and lift criteria, s.
pub const CHECK_INTERVAL_S: f64 = 0.02;
/// Minimum fill time before the settling check applies, s: the column must have landed.
pub const MIN_FILL_S: f64 = 0.1;
/// Silhouette pixel as a fraction of the smallest sphere radius: 4 pixels per radius.
pub const PIXELS_PER_MIN_RADIUS: f64 = 4.0;
/// Cylinder height above the top of the lattice, mm (an open top; nothing reaches it).
pub const CYLINDER_HEADROOM_MM: f64 = 10.0;

/// One particle of the initial lattice.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// Particle class ([`RunInputs::template`]).
    pub class: usize,
    /// Centre of mass, mm.
    pub position_mm: [f64; 3],
    /// Orientation, unit quaternion `[w, x, y, z]`.
    pub orientation: [f64; 4],
}

/// The rig as it stands before the fill: the cylinder, scaled for the mode, and every
/// particle on its lattice cell, drawn from the run's seed. [`run`] builds its world from
/// it, and `arachis export liggghts` writes the same rig for LIGGGHTS.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Cylinder diameter, mm.
    pub diameter_mm: f64,
    /// Cylinder length from the floor, mm.
    pub cylinder_length_mm: f64,
    /// The particles, in the order they are added.
    pub particles: Vec<Placed>,
    /// Spheres over all particles.
    pub sphere_total: usize,
}

impl Layout {
    /// Lays out the rig of `inputs` for placement seed `seed` (module notes, step 1).
    pub fn new(inputs: &RunInputs, seed: u64) -> Result<Self, ExperimentError> {
        let repose = &inputs.simulation.repose;
        let n = inputs.mode.pods as usize;
        let mut rng = SplitMix64::new(seed);
        let classes = inputs.shuffled_classes(n, &mut rng);
        let sphere_total: usize = classes
            .iter()
            .map(|&k| inputs.template(k).spheres.len())
            .sum();

        // Geometry (mm): a cylinder scaled for the mode.
        let scale = match inputs.full_pods {
            Some(full) if full > 0 && (n as u32) < full => (n as f64 / full as f64).cbrt(),
            _ => 1.0,
        };
        let diameter_mm = repose.cylinder_diameter_mm * scale;
        let radius_mm = 0.5 * diameter_mm;
        let bound = inputs.max_bounding_radius_mm();
        let cell = 2.0 * bound + CELL_GAP_MM;
        let reach = radius_mm - bound - WALL_CLEARANCE_MM;
        if reach < 0.0 {
            return Err(ExperimentError::Study {
                experiment: EXPERIMENT.name(),
                reason: format!(
                    "the cylinder (diameter {diameter_mm:.1} mm for {n} pods) is narrower than one pod ({:.1} mm)",
                    2.0 * bound
                ),
            });
        }
        let layer = layer_points(reach, cell);
        let layers = n.div_ceil(layer.len());
        let z0 = bound + WALL_CLEARANCE_MM;
        let top_mm = z0 + (layers as f64 - 1.0) * cell + bound;
        let cylinder_length_mm =
            top_mm.max(repose.cylinder_height_mm * scale) + CYLINDER_HEADROOM_MM;
        let particles = stack_layers(&layer, z0, cell, classes, &mut rng);
        Ok(Layout {
            diameter_mm,
            cylinder_length_mm,
            particles,
            sphere_total,
        })
    }
}

/// The particles of `classes`, in order, on layers of `layer`'s points `cell` apart upwards
/// from height `z0` (mm), each layer turned by its own random angle (so that particles do
/// not land in vertical columns) and each particle by a random orientation, all drawn from
/// `rng`.
pub fn stack_layers(
    layer: &[[f64; 2]],
    z0: f64,
    cell: f64,
    classes: Vec<usize>,
    rng: &mut SplitMix64,
) -> Vec<Placed> {
    let mut particles = Vec::with_capacity(classes.len());
    for (k, chunk) in classes.chunks(layer.len()).enumerate() {
        let turn = 2.0 * PI * unit_uniform(rng);
        let (s, c) = turn.sin_cos();
        for (p, &class) in layer.iter().zip(chunk) {
            particles.push(Placed {
                class,
                position_mm: [
                    c * p[0] - s * p[1],
                    s * p[0] + c * p[1],
                    z0 + k as f64 * cell,
                ],
                orientation: random_quaternion(rng),
            });
        }
    }
    particles
}

/// Runs the repose rig (module notes).
pub fn run(
    inputs: &RunInputs,
    seed: u64,
    options: &RunOptions,
) -> Result<Observation, ExperimentError> {
    let repose = &inputs.simulation.repose;
    let layout = Layout::new(inputs, seed)?;
    let n = layout.particles.len();
    let (diameter_mm, cylinder_length_mm) = (layout.diameter_mm, layout.cylinder_length_mm);
    let radius_mm = 0.5 * diameter_mm;
    let sphere_total = layout.sphere_total;

    let mut arena = Arena::new(inputs, n, sphere_total);
    let mut w = arena.world(EXPERIMENT)?;
    let mats = add_materials(&mut w, inputs, EXPERIMENT)?;
    let e = |s| setup_error(EXPERIMENT, s);
    add_floor(&mut w, mats, EXPERIMENT)?;
    let cylinder = w
        .add_wall(WallSpec {
            geometry: WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                radius_m: radius_mm * M_PER_MM,
                length_m: Some(cylinder_length_mm * M_PER_MM),
            },
            material: mats.wall,
            velocity_m_s: [0.0; 3],
        })
        .map_err(e)?;
    let fall = [0.0, 0.0, -repose.fill_speed_m_s];
    for p in &layout.particles {
        add_pod(
            &mut w,
            inputs.template(p.class),
            mats.pod,
            p.position_mm,
            p.orientation,
            fall,
            EXPERIMENT,
        )?;
    }
    let dt_s = set_rayleigh_timestep(&mut w, inputs, EXPERIMENT)?;
    let mut frames = FrameRecorder::new(options.vtk_dir.as_deref());
    frames.record(&w);

    let at_rest_j = at_rest_energy_j(inputs, n);
    let chunk = steps_for(&w, CHECK_INTERVAL_S);

    // 1. Fill and settle.
    let fill_end_s = repose.lift_start_s;
    settle(
        &mut w,
        chunk,
        MIN_FILL_S,
        fill_end_s,
        at_rest_j,
        &mut frames,
        EXPERIMENT,
    )?;
    let lift_start_s = w.time_s();

    // 2. Lift until the lower edge clears every sphere.
    w.set_wall_velocity_m_s(cylinder, [0.0, 0.0, repose.lift_speed_m_s])
        .map_err(e)?;
    let max_lift_s = cylinder_length_mm * M_PER_MM / repose.lift_speed_m_s;
    loop {
        run_steps(&mut w, chunk, EXPERIMENT)?;
        frames.record(&w);
        let edge_mm = (w.time_s() - lift_start_s) * repose.lift_speed_m_s / M_PER_MM;
        let highest = w
            .spheres()
            .iter()
            .map(|s| s.position.z.to_f64() + s.radius.to_f64())
            .fold(f64::NEG_INFINITY, f64::max);
        if edge_mm > highest || w.time_s() - lift_start_s > max_lift_s {
            break;
        }
    }
    let lift_end_s = w.time_s();

    // 3. Let the pile come to rest.
    while w.time_s() - lift_end_s < repose.settle_after_lift_s {
        run_steps(&mut w, chunk, EXPERIMENT)?;
        frames.record(&w);
        if kinetic_energy_j(&w) < at_rest_j {
            break;
        }
    }

    // 4. Photograph from VIEW_COUNT azimuths and fit the flanks.
    let pile: Vec<PileSphere> = w
        .spheres()
        .iter()
        .map(|s| PileSphere {
            centre_mm: s.position.to_f64(),
            radius_mm: s.radius.to_f64(),
        })
        .collect();
    let min_radius = inputs.min_sphere_radius_mm();
    let Photographs {
        measurement,
        refused: refused_views,
        mm_per_px,
    } = photograph(&pile, min_radius)?;
    let angles: Vec<f64> = measurement
        .views
        .iter()
        .map(|v| v.angle.angle_deg)
        .collect();
    let view_sd_deg = sample_sd(&angles);
    let mean_of = |f: &dyn Fn(&crate::repose::ReposeAngle) -> Option<f64>| {
        measurement
            .views
            .iter()
            .filter_map(|v| f(&v.angle))
            .sum::<f64>()
            / measurement.views.len() as f64
    };
    let details = ReposeDetails {
        pods: n as u32,
        spheres: sphere_total as u32,
        cylinder_diameter_mm: diameter_mm,
        dt_s,
        lift_start_s,
        lift_end_s,
        end_s: w.time_s(),
        steps: w.step_count(),
        final_kinetic_energy_j: kinetic_energy_j(&w),
        view_sd_deg,
        pile_height_mm: mean_of(&|a| a.height_mm),
        pile_width_mm: mean_of(&|a| a.width_mm),
        mm_per_px,
        measurement,
        refused_views,
        pile,
    };
    let digest = w.digest();
    drop(w);
    let vtk = frames.finish()?;
    Ok(Observation {
        experiment: EXPERIMENT,
        quantity: "repose_angle",
        value: details.measurement.angle_deg,
        unit: "deg",
        digest: format!("{digest:016x}"),
        vtk_series: vtk,
        details: ObservationDetails::Repose(details),
    })
}

/// Kinetic energy below which `particles` particles count as at rest, J: each at
/// [`SETTLED_SPEED_M_S`] with the mass of the most common particle.
pub fn at_rest_energy_j(inputs: &RunInputs, particles: usize) -> f64 {
    let mass_kg = inputs.template(inputs.typical_class()).mass.mass_kg;
    particles as f64 * 0.5 * mass_kg * SETTLED_SPEED_M_S * SETTLED_SPEED_M_S
}

/// The rig's photographs of a pile ([`photograph`]).
#[derive(Debug, Clone)]
pub struct Photographs {
    /// The mean angle and each usable view.
    pub measurement: SimulatedRepose,
    /// Views left out (azimuth, degrees; why).
    pub refused: Vec<(f64, String)>,
    /// Scale, mm per pixel.
    pub mm_per_px: f64,
}

/// The rig's photographs of a pile (step 4 of the module notes): [`VIEW_COUNT`] azimuths
/// over a half turn at [`PIXELS_PER_MIN_RADIUS`] pixels per radius of the smallest sphere
/// `min_radius_mm`. `arachis lab repose-pile` applies it to another engine's final
/// positions.
pub fn photograph(pile: &[PileSphere], min_radius_mm: f64) -> Result<Photographs, ExperimentError> {
    let mm_per_px = min_radius_mm / PIXELS_PER_MIN_RADIUS;
    let azimuths: Vec<f64> = (0..VIEW_COUNT)
        .map(|i| 180.0 * i as f64 / VIEW_COUNT as f64)
        .collect();
    let (measurement, refused) = measure_views(pile, &azimuths, mm_per_px)?;
    Ok(Photographs {
        measurement,
        refused,
        mm_per_px,
    })
}

/// Measures the pile from each azimuth (the `arachis lab repose` extraction, default fit
/// band), leaving out views whose flanks cannot be fitted (too few contour points) and
/// returning them with the reason; other errors, or fewer than [`min_usable_views`]
/// usable views, fail. The mean is summed in azimuth order as `simulated_repose` sums it.
pub fn measure_views(
    pile: &[PileSphere],
    azimuths: &[f64],
    mm_per_px: f64,
) -> Result<(SimulatedRepose, Vec<(f64, String)>), ExperimentError> {
    let mut views = Vec::with_capacity(azimuths.len());
    let mut refused = Vec::new();
    for &azimuth in azimuths {
        match simulated_repose(pile, &[azimuth], mm_per_px, FitBand::default()) {
            Ok(m) => views.extend(m.views),
            Err(
                e @ ReposeError::Pile {
                    problem: PileProblem::TooFewPoints { .. },
                    ..
                },
            ) => refused.push((azimuth, e.to_string())),
            Err(e) => return Err(e.into()),
        }
    }
    let needed = min_usable_views(azimuths.len());
    if views.len() < needed {
        let reasons: Vec<&str> = refused.iter().map(|(_, r)| r.as_str()).collect();
        return Err(ExperimentError::Study {
            experiment: EXPERIMENT.name(),
            reason: format!(
                "only {} of {} side views of the pile could be measured (at least {needed} needed): {}",
                views.len(),
                azimuths.len(),
                reasons.join("; ")
            ),
        });
    }
    let angle_deg = views.iter().map(|v| v.angle.angle_deg).sum::<f64>() / views.len() as f64;
    Ok((SimulatedRepose { angle_deg, views }, refused))
}

/// Cell centres of one layer: concentric rings from the reachable radius `reach` inwards,
/// `cell` apart, each holding as many points as fit `cell` apart along their chords, and
/// one centre point when the innermost ring would be smaller than half a cell. Denser than
/// a square lattice in a narrow cylinder (7 instead of 5 pods for the quick rig).
pub fn layer_points(reach: f64, cell: f64) -> Vec<[f64; 2]> {
    let mut points = Vec::new();
    let mut r = reach;
    while r >= 0.5 * cell {
        let per_ring = (PI / (0.5 * cell / r).asin()).floor().max(1.0) as usize;
        for k in 0..per_ring {
            let a = 2.0 * PI * k as f64 / per_ring as f64;
            points.push([r * a.cos(), r * a.sin()]);
        }
        r -= cell;
    }
    if r >= 0.0 {
        // Room left at the centre: the innermost ring (radius r + cell) is a cell away.
        points.push([0.0, 0.0]);
    }
    points
}

/// Sample standard deviation (n − 1, statrs); 0 for fewer than two values.
pub fn sample_sd(values: &[f64]) -> f64 {
    use statrs::statistics::Statistics;
    if values.len() < 2 {
        return 0.0;
    }
    values.std_dev()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_points_keep_a_cell_apart_inside_the_reach() {
        for (reach, cell) in [(36.5, 36.0), (22.0, 36.0), (81.0, 36.0), (5.0, 36.0)] {
            let p = layer_points(reach, cell);
            assert!(!p.is_empty());
            for (i, a) in p.iter().enumerate() {
                assert!(a[0].hypot(a[1]) <= reach + 1e-9);
                for b in &p[i + 1..] {
                    let d = (a[0] - b[0]).hypot(a[1] - b[1]);
                    assert!(d >= cell - 1e-9, "{reach} {cell}: {a:?} {b:?} {d}");
                }
            }
        }
        assert_eq!(layer_points(36.5, 36.0).len(), 7);
    }

    /// Spheres of `radius` on rings every `radius` under a cone of `angle_deg` on `base` mm.
    fn cone(angle_deg: f64, base: f64, radius: f64) -> Vec<PileSphere> {
        let tan = angle_deg.to_radians().tan();
        let mut pile = Vec::new();
        let mut ring = 0.0;
        while ring <= base {
            let count = ((2.0 * PI * ring / radius) as usize).max(1);
            for k in 0..count {
                let a = 2.0 * PI * k as f64 / count as f64;
                let mut z = radius;
                while z <= (base - ring) * tan {
                    pile.push(PileSphere {
                        centre_mm: [ring * a.cos(), ring * a.sin(), z],
                        radius_mm: radius,
                    });
                    z += radius;
                }
            }
            ring += radius;
        }
        pile
    }

    #[test]
    fn measure_views_matches_simulated_repose_and_refuses_a_tower() {
        let azimuths = [0.0, 45.0, 90.0, 135.0];
        let pile = cone(33.0, 40.0, 2.0);
        let (m, refused) = measure_views(&pile, &azimuths, 0.5).unwrap();
        let all = simulated_repose(&pile, &azimuths, 0.5, FitBand::default()).unwrap();
        assert!(refused.is_empty());
        assert_eq!(m.angle_deg.to_bits(), all.angle_deg.to_bits());
        // A single column of spheres has no flank in any view: every view is refused.
        let tower: Vec<PileSphere> = (0..10)
            .map(|i| PileSphere {
                centre_mm: [0.0, 0.0, 2.0 + 4.0 * i as f64],
                radius_mm: 2.0,
            })
            .collect();
        let err = measure_views(&tower, &azimuths, 0.5)
            .unwrap_err()
            .to_string();
        assert!(err.contains("only 0 of 4 side views"), "{err}");
    }
}
