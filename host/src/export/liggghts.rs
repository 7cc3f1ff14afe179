//! A study's repose rig as a LIGGGHTS 3.8 input deck (`arachis export liggghts`), so a user
//! can run the same experiment in LIGGGHTS and the cross-check can compare the two engines
//! on it (`scripts/cross-check-repose.sh`, `docs/conventions.md`).
//!
//! The deck reproduces the rig of `rigs::repose_cylinder` step by step:
//! - the same particles at the same places: the rig's [`Layout`] for the seed, written as a
//!   `read_data` file (`particles.data`: diameter, density, position; all falling at the
//!   fill speed);
//! - the same materials (E = 2G(1 + ν), ν, ρ) and pairs (e, μs, μr), with LIGGGHTS'
//!   `tangential history`, `rolling_friction cdt` or `epsd2` (the pairs' rolling convention)
//!   and `limitForce on` (Arachis never lets the normal force attract); a pair the study keeps
//!   in EDEM's conventions, or in another rolling convention than the deck's one (LIGGGHTS sets
//!   it for all pairs), is written with the same numbers and a warning
//!   (`docs/conventions.md`);
//! - the floor as a primitive plane and the cylinder as a moving mesh (`cylinder.stl`, a
//!   prism of [`CYLINDER_SEGMENTS`] faces with its vertices on the rig's cylinder), lifted
//!   by `fix move/mesh`;
//! - the same time step (the study's fraction of the smallest sphere's Rayleigh time) and
//!   the same stage logic: fill until the kinetic energy (translational plus rotational)
//!   falls below the rig's threshold, checked every [`CHECK_INTERVAL_S`] after
//!   [`MIN_FILL_S`] and at the latest at `lift_start_s`; lift until the cylinder's lower
//!   edge clears every sphere; settle by the same criterion, at most `settle_after_lift_s`;
//! - `final.dump`: `id radius x y z` in metres, which `arachis lab repose-pile` photographs
//!   as the rig photographs its own pile.
//!
//! LIGGGHTS-PUBLIC has no multi-sphere particles, so only studies of `[spheres]` export.

use std::f64::consts::PI;
use std::fmt::Write as _;

use arachis_core::contact::{FrictionConvention, RollingConvention};
use arachis_core::pair::PairSpec;
use arachis_core::timestep::rayleigh_time_s;
use arachis_core::units::LENGTH_M_TO_MM;

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
/// Neighbour skin, in radii of the smallest sphere.
pub const SKIN_RADII: f64 = 0.25;

/// The files of an exported deck, by name.
#[derive(Debug, Clone, PartialEq)]
pub struct Deck {
    /// `in.repose`: the input script.
    pub input: String,
    /// `particles.data`: the initial particles (`read_data`).
    pub data: String,
    /// `cylinder.stl`: the cylinder's mesh, mm (the deck scales it to m).
    pub cylinder_stl: String,
    /// Warnings for the user (pairs LIGGGHTS cannot read as the study does).
    pub warnings: Vec<String>,
    /// Time step, s.
    pub dt_s: f64,
}

/// LIGGGHTS' name of a rolling convention (`rolling_friction NAME`); `None` for EDEM's, which
/// LIGGGHTS does not have.
fn liggghts_rolling_model(rolling: RollingConvention) -> Option<&'static str> {
    match rolling {
        RollingConvention::Edem => None,
        RollingConvention::LiggghtsCdt => Some("cdt"),
        RollingConvention::LiggghtsEpsd2 => Some("epsd2"),
    }
}

/// The deck's one rolling model (LIGGGHTS' `pair_style` sets it for every pair): the pod–pod
/// pair's, else the pod–wall pair's, else `cdt`.
fn deck_rolling_model(inputs: &RunInputs) -> &'static str {
    liggghts_rolling_model(inputs.pod_pod.conventions.rolling)
        .or(liggghts_rolling_model(inputs.pod_wall.conventions.rolling))
        .unwrap_or("cdt")
}

/// A warning when the deck cannot read pair `name` as the study does: a convention LIGGGHTS
/// does not have (EDEM's), or a rolling model other than the deck's `rolling_model`.
fn pair_warning(name: &str, pair: &PairSpec, rolling_model: &str) -> Option<String> {
    let rolling = liggghts_rolling_model(pair.conventions.rolling);
    let friction_ok = pair.conventions.friction == FrictionConvention::Liggghts;
    (rolling != Some(rolling_model) || !friction_ok).then(|| {
        format!(
            "pair {name} is read in conventions the deck does not have (rolling {}, friction {}; \
             the deck: rolling_friction {rolling_model}, tangential history): LIGGGHTS gets the \
             same e, μs, μr, read in its own conventions, so expect another pile \
             (docs/conventions.md); give both pairs rolling_convention = \"liggghts-cdt\" (or \
             both \"liggghts-epsd2\") and friction_convention = \"liggghts\" to compare like \
             with like",
            pair.conventions.rolling, pair.conventions.friction
        )
    })
}

/// The deck of the repose rig of `inputs` for placement seed `seed`; `source` names the
/// study in the deck's header.
pub fn repose_deck(inputs: &RunInputs, seed: u64, source: &str) -> Result<Deck, String> {
    if inputs.templates.iter().any(|t| !t.is_sphere()) {
        return Err(
            "LIGGGHTS-PUBLIC has no multi-sphere particles: only a study of [spheres] exports"
                .into(),
        );
    }
    let layout = Layout::new(inputs, seed).map_err(|e| e.to_string())?;
    let repose = &inputs.simulation.repose;
    // LIGGGHTS runs in SI: `mm(x)` gives the length x mm in metres.
    let mm = |x: f64| x / LENGTH_M_TO_MM;
    let radius_of = |class: usize| inputs.template(class).spheres[0].radius_mm;
    let min_radius_mm = inputs.min_sphere_radius_mm();
    let pod = &inputs.pod;
    let wall = &inputs.wall;
    let dt_s = inputs.simulation.dt_rayleigh_fraction
        * rayleigh_time_s(
            mm(min_radius_mm),
            pod.density_kg_m3,
            pod.youngs_modulus_pa,
            pod.poisson,
        );
    let n = layout.particles.len();
    let at_rest_j = at_rest_energy_j(inputs, n);
    let check_steps = steps_in(CHECK_INTERVAL_S, dt_s);
    let radius_mm = 0.5 * layout.diameter_mm;
    let half_width_mm = radius_mm * (1.0 + BOX_HALF_WIDTH_RADII);
    let box_top_mm = 2.0 * layout.cylinder_length_mm + radius_mm;
    let rolling_model = deck_rolling_model(inputs);
    let warnings: Vec<String> = [("pod-pod", &inputs.pod_pod), ("pod-wall", &inputs.pod_wall)]
        .into_iter()
        .filter_map(|(name, p)| pair_warning(name, p, rolling_model))
        .collect();

    let mut data = format!(
        "LIGGGHTS data file written by arachis export liggghts: {source}, seed {seed}\n\n\
         {n} atoms\n2 atom types\n\n\
         {:e} {:e} xlo xhi\n{:e} {:e} ylo yhi\n{:e} {:e} zlo zhi\n\nAtoms\n\n",
        mm(-half_width_mm),
        mm(half_width_mm),
        mm(-half_width_mm),
        mm(half_width_mm),
        mm(-radius_mm),
        mm(box_top_mm),
    );
    for (i, p) in layout.particles.iter().enumerate() {
        let [x, y, z] = p.position_mm.map(mm);
        let d = 2.0 * mm(radius_of(p.class));
        let _ = writeln!(
            data,
            "{} 1 {d:e} {:e} {x:e} {y:e} {z:e}",
            i + 1,
            pod.density_kg_m3
        );
    }
    data += "\nVelocities\n\n";
    for i in 0..n {
        let _ = writeln!(data, "{} 0 0 {:e} 0 0 0", i + 1, -repose.fill_speed_m_s);
    }

    let pair3 = |f: fn(&PairSpec) -> f64| {
        let (pp, pw) = (f(&inputs.pod_pod), f(&inputs.pod_wall));
        format!("{pp} {pw} {pw} {pw}")
    };
    // For walls LIGGGHTS wants the settings (limitForce) after the wall's geometry.
    let model = format!("model hertz tangential history rolling_friction {rolling_model}");
    let settings = "limitForce on";
    let mut input = String::new();
    let _ = write!(
        input,
        "# The repose rig by cylinder lifting of {source}, placement seed {seed}, written by
# arachis export liggghts (host/src/export/liggghts.rs) for LIGGGHTS 3.8.
# {n} spheres; cylinder {diameter:.3} mm across, {length:.3} mm long; dt {dt_s:e} s.
# Units SI. limitForce on: the normal force never attracts, as in Arachis.
# Run: liggghts -in in.repose   (writes final.dump; arachis lab repose-pile final.dump)
",
        diameter = layout.diameter_mm,
        length = layout.cylinder_length_mm,
    );
    for w in &warnings {
        let _ = writeln!(input, "# WARNING: {w}");
    }
    let _ = write!(
        input,
        "
atom_style    granular
atom_modify   map array
boundary      f f f
newton        off
communicate   single vel yes
units         si
hard_particles yes

read_data     particles.data

neighbor      {skin:e} bin
neigh_modify  delay 0

fix  m1 all property/global youngsModulus peratomtype {e_pod} {e_wall}
fix  m2 all property/global poissonsRatio peratomtype {nu_pod} {nu_wall}
fix  m3 all property/global coefficientRestitution peratomtypepair 2 {rest}
fix  m4 all property/global coefficientFriction peratomtypepair 2 {fric}
fix  m5 all property/global coefficientRollingFriction peratomtypepair 2 {roll}

pair_style  gran {model} {settings}
pair_coeff  * *

timestep  {dt_s:e}
fix  gravi all gravity {g} vector 0.0 0.0 -1.0

fix  floor all wall/gran {model} primitive type 2 zplane 0.0 {settings}
fix  cyl all mesh/surface file cylinder.stl type 2 scale 0.001
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
        skin = SKIN_RADII * mm(min_radius_mm),
        e_pod = pod.youngs_modulus_pa,
        e_wall = wall.youngs_modulus_pa,
        nu_pod = pod.poisson,
        nu_wall = wall.poisson,
        rest = pair3(|p| p.restitution),
        fric = pair3(|p| p.friction),
        roll = pair3(|p| {
            if p.terms.rolling_cdt {
                p.rolling_friction
            } else {
                0.0
            }
        }),
        g = inputs.simulation.gravity_m_s2,
        min_fill = MIN_FILL_S,
        lift_start = repose.lift_start_s,
        lift_speed = repose.lift_speed_m_s,
        max_lift = mm(layout.cylinder_length_mm) / repose.lift_speed_m_s,
        settle = repose.settle_after_lift_s,
    );
    Ok(Deck {
        input,
        data,
        cylinder_stl: cylinder_stl(radius_mm, layout.cylinder_length_mm),
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
