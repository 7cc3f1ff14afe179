//! The repose rig by cylinder lifting (`rigs::repose_cylinder`) as a LIGGGHTS deck
//! (`in.repose`, `particles.data`, `cylinder.stl`), step by step:
//! - the rig's [`Layout`] for the seed: the same particles at the same places, all falling at
//!   the fill speed;
//! - the cylinder as a moving mesh (`cylinder.stl`, a prism of [`CYLINDER_SEGMENTS`] faces with
//!   its vertices on the rig's cylinder), lifted by `fix move/mesh`;
//! - the same stage logic: fill until the kinetic energy (translational plus rotational)
//!   falls below the rig's threshold, checked every [`CHECK_INTERVAL_S`] after
//!   [`MIN_FILL_S`] and at the latest at `lift_start_s`; lift until the cylinder's lower
//!   edge clears every sphere; settle by the same criterion, at most `settle_after_lift_s`;
//! - `final.dump`: `id radius x y z` in metres, which `arachis lab repose-pile` photographs
//!   as the rig photographs its own pile.

use std::f64::consts::PI;
use std::fmt::Write as _;

use super::SKIN_RADII;
use super::{m, particles_data, preamble, timestep_s, warnings, DataParticle, Deck, DeckFile};
use crate::rigs::pod_world::setup::{steps_in, RunInputs};
use crate::rigs::repose_cylinder::{at_rest_energy_j, Layout, CHECK_INTERVAL_S, MIN_FILL_S};

/// Faces around the cylinder's mesh: its faces lie inside the rig's cylinder by at most
/// R(1 − cos(π/N)) = 5.4e-4 R (0.012 mm on a quick rig's 23 mm radius).
pub const CYLINDER_SEGMENTS: usize = 96;
/// Height over width of the mesh's faces: LIGGGHTS refuses slivers whose smallest angle is
/// below its curvature limit (0.26° was refused), and every face costs time in each step's
/// contact search, so the faces are tall but not thin (smallest angle 2.9°).
pub const MAX_FACE_ASPECT: f64 = 20.0;
/// The box around the rig, in cylinder radii beyond the cylinder, on each side: room for
/// the pile to spread after the lift (a quick pile of spheres spreads to 3.6 diameters).
pub const BOX_HALF_WIDTH_RADII: f64 = 12.0;

/// The deck of the repose rig of `inputs` (a study of spheres) for placement seed `seed`;
/// `source` names the study in the deck's header.
pub fn deck(inputs: &RunInputs, seed: u64, source: &str) -> Result<Deck, String> {
    let layout = Layout::new(inputs, seed).map_err(|e| e.to_string())?;
    let repose = &inputs.simulation.repose;
    let radius_of = |class: usize| inputs.template(class).spheres[0].radius_mm;
    let min_radius_mm = inputs.min_sphere_radius_mm();
    let dt_s = timestep_s(inputs, min_radius_mm);
    let n = layout.particles.len();
    let at_rest_j = at_rest_energy_j(inputs, n);
    let check_steps = steps_in(CHECK_INTERVAL_S, dt_s);
    let radius_mm = 0.5 * layout.diameter_mm;
    let half_width_mm = radius_mm * (1.0 + BOX_HALF_WIDTH_RADII);
    let box_top_mm = 2.0 * layout.cylinder_length_mm + radius_mm;
    let warnings = warnings(inputs);
    let particles: Vec<DataParticle> = layout
        .particles
        .iter()
        .map(|p| DataParticle {
            diameter_mm: 2.0 * radius_of(p.class),
            centre_mm: p.position_mm,
            velocity_m_s: [0.0, 0.0, -repose.fill_speed_m_s],
        })
        .collect();
    let data = particles_data(
        inputs,
        &format!("{source}, seed {seed}"),
        [
            [-half_width_mm, half_width_mm],
            [-half_width_mm, half_width_mm],
            [-radius_mm, box_top_mm],
        ],
        &particles,
    );
    let header = format!(
        "# The repose rig by cylinder lifting of {source}, placement seed {seed}, written by
# arachis export liggghts (host/src/export/liggghts/repose.rs) for LIGGGHTS 3.8.
# {n} spheres; cylinder {diameter:.3} mm across, {length:.3} mm long; dt {dt_s:e} s.
# Units SI. limitForce on: the normal force never attracts, as in Arachis.
# Run: liggghts -in in.repose   (writes final.dump; arachis lab repose-pile final.dump)
",
        diameter = layout.diameter_mm,
        length = layout.cylinder_length_mm,
    );
    let (mut input, model) = preamble(inputs, &header, &warnings, dt_s, SKIN_RADII * min_radius_mm);
    let _ = write!(
        input,
        "fix  cyl all mesh/surface file cylinder.stl type 2 scale 0.001
fix  can all wall/gran {model} mesh n_meshes 1 meshes cyl {settings}

fix  integrate all nve/sphere

# update_on_run_end: the stage tests below read these between runs.
compute ke all ke update_on_run_end yes
compute rke all erotate/sphere update_on_run_end yes
compute rad all property/atom radius
variable ztop atom z+c_rad
compute zmax all reduce max v_ztop
variable highest equal c_zmax
thermo_style  custom step atoms c_ke c_rke c_zmax
thermo_modify lost ignore norm no
thermo        {check_steps}

variable at_rest equal {at_rest_j:e}
variable energy equal c_ke+c_rke
variable t equal step*{dt_s:e}

# 1. Fill and settle (rig step 1).
label fill
run {check_steps}
if \"${{t}} >= {min_fill} && ${{energy}} < ${{at_rest}}\" then \"jump SELF lift\"
if \"${{t}} < {lift_start}\" then \"jump SELF fill\"

# 2. Lift until the lower edge clears every sphere (rig step 2).
label lift
variable lift_start equal ${{t}}
print \"arachis: lift starts at ${{lift_start}} s\"
fix  raise all move/mesh mesh cyl linear 0.0 0.0 {lift_speed}
variable lifted equal step*{dt_s:e}-${{lift_start}}
variable edge equal v_lifted*{lift_speed}
label lifting
run {check_steps}
if \"${{edge}} <= ${{highest}} && ${{lifted}} <= {max_lift}\" then \"jump SELF lifting\"
variable lift_end equal ${{t}}
print \"arachis: lift ends at ${{lift_end}} s\"
variable settling equal step*{dt_s:e}-${{lift_end}}

# 3. Let the pile come to rest (rig step 3).
label settle
run {check_steps}
if \"${{energy}} >= ${{at_rest}} && ${{settling}} < {settle}\" then \"jump SELF settle\"
print \"arachis: end at ${{t}} s\"

write_dump all custom final.dump id radius x y z
",
        model = model.model,
        settings = model.settings,
        min_fill = MIN_FILL_S,
        lift_start = repose.lift_start_s,
        lift_speed = repose.lift_speed_m_s,
        max_lift = m(layout.cylinder_length_mm) / repose.lift_speed_m_s,
        settle = repose.settle_after_lift_s,
    );
    Ok(Deck {
        files: vec![
            DeckFile {
                name: "in.repose",
                text: input,
            },
            DeckFile {
                name: "particles.data",
                text: data,
            },
            DeckFile {
                name: "cylinder.stl",
                text: cylinder_stl(radius_mm, layout.cylinder_length_mm),
            },
        ],
        warnings,
        dt_s,
    })
}

/// An open cylinder of radius `radius_mm` from z = 0 to `length_mm` about the z axis, as an
/// ASCII STL prism of [`CYLINDER_SEGMENTS`] faces whose vertices lie on the cylinder, cut
/// into rows at most [`MAX_FACE_ASPECT`] times as tall as a face is wide (LIGGGHTS refuses a
/// mesh of slivers: "the minimum angle of mesh element ... is lower than the specified
/// curvature"), with the normals pointing to the axis, where the particles are.
pub fn cylinder_stl(radius_mm: f64, length_mm: f64) -> String {
    let width = 2.0 * PI * radius_mm / CYLINDER_SEGMENTS as f64;
    let rows = ((length_mm / (MAX_FACE_ASPECT * width)).ceil() as usize).max(1);
    let at = |k: usize, row: usize| {
        let a = 2.0 * PI * k as f64 / CYLINDER_SEGMENTS as f64;
        let z = length_mm * row as f64 / rows as f64;
        [radius_mm * a.cos(), radius_mm * a.sin(), z]
    };
    let triangles: Vec<[[f64; 3]; 3]> = (0..rows)
        .flat_map(|row| {
            (0..CYLINDER_SEGMENTS).flat_map(move |k| {
                let (a0, a1) = (at(k, row), at(k + 1, row));
                let (b0, b1) = (at(k, row + 1), at(k + 1, row + 1));
                [[a0, b1, a1], [a0, b0, b1]]
            })
        })
        .collect();
    crate::shapes::ascii_stl_text("cylinder", &triangles)
}
