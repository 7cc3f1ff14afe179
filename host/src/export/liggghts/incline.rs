//! The incline rig (`rigs::incline`, seed 000 §2.6.2) as a LIGGGHTS deck (`in.incline`,
//! `particles.data`), step by step:
//! - the study's most common particle class, one sphere, placed [`DROP_GAP_MM`] above the
//!   steel plate z = 0 at rest;
//! - it settles for [`SETTLE_S`]; then, as in the rig, the plate stays level and gravity
//!   turns about y at [`TILT_RATE_DEG_S`], updated every [`TILT_UPDATE_S`] to the tilt
//!   reached at the start of that interval (`fix gravity` redefined between runs);
//! - the slide angle is the tilt of the first interval after which the sphere has moved more
//!   than [`ONSET_MM`] down the slope, once it has moved [`CONFIRM_MM`]; the deck stops
//!   there or at [`MAX_TILT_DEG`];
//! - `incline.txt`: `slide_angle_deg A` and `moved_mm D` (A = −1 if the sphere never
//!   moved [`ONSET_MM`]), the rig's own reading of the same quantities.

use std::fmt::Write as _;

use super::SKIN_RADII;
use super::{m, particles_data, preamble, timestep_s, warnings, DataParticle, Deck, DeckFile};
use crate::rigs::incline::{
    CONFIRM_MM, DROP_GAP_MM, MAX_TILT_DEG, ONSET_MM, SETTLE_S, TILT_RATE_DEG_S, TILT_UPDATE_S,
};
use crate::rigs::pod_world::setup::{steps_in, RunInputs};

/// The box around the plate, in sphere radii on each side of the sphere and above it: room
/// for the [`CONFIRM_MM`] of travel and the last interval's roll.
pub const BOX_RADII: f64 = 10.0;

/// The deck of the incline rig of `inputs` (a study of spheres); `source` names the study
/// in the deck's header.
pub fn deck(inputs: &RunInputs, source: &str) -> Result<Deck, String> {
    let class = inputs.typical_class();
    let radius_mm = inputs.template(class).spheres[0].radius_mm;
    let dt_s = timestep_s(inputs, radius_mm);
    let settle_steps = steps_in(SETTLE_S, dt_s);
    let chunk = steps_in(TILT_UPDATE_S, dt_s);
    let warnings = warnings(inputs);
    let reach_mm = BOX_RADII * radius_mm + CONFIRM_MM;
    let data = particles_data(
        inputs,
        source,
        [
            [-reach_mm, reach_mm],
            [-reach_mm, reach_mm],
            [-radius_mm, reach_mm],
        ],
        &[DataParticle {
            diameter_mm: 2.0 * radius_mm,
            centre_mm: [0.0, 0.0, radius_mm + DROP_GAP_MM],
            velocity_m_s: [0.0; 3],
        }],
    );
    let header = format!(
        "# The incline rig of {source}, written by arachis export liggghts
# (host/src/export/liggghts/incline.rs) for LIGGGHTS 3.8.
# One sphere of R {radius_mm} mm on the steel plate; gravity turns about y at {TILT_RATE_DEG_S} deg/s,
# updated every {chunk} steps; dt {dt_s:e} s.
# Units SI. limitForce on: the normal force never attracts, as in Arachis.
# Run: liggghts -in in.incline   (writes incline.txt: slide_angle_deg, moved_mm)
"
    );
    let (mut input, _) = preamble(inputs, &header, &warnings, dt_s, SKIN_RADII * radius_mm);
    let _ = write!(
        input,
        "
fix  integrate all nve/sphere
thermo  {settle_steps}

# 1. Settle on the level plate (rig: SETTLE_S).
run {settle_steps}
variable xs equal x[1]
variable x0 equal ${{xs}}
variable now equal step
variable step0 equal ${{now}}

# 2. Turn gravity about y; the tilt of each interval is the one reached at its start.
variable tilt equal {TILT_RATE_DEG_S}*(step-${{step0}})*{dt_s:e}
variable sx equal sin(v_tilt*PI/180.0)
variable sz equal -cos(v_tilt*PI/180.0)
variable moved equal x[1]-${{x0}}
variable onset equal -1
label tilting
if \"${{tilt}} > {MAX_TILT_DEG}\" then \"jump SELF done\"
variable tilt_now equal ${{tilt}}
unfix gravi
fix  gravi all gravity {g} vector ${{sx}} 0.0 ${{sz}}
run {chunk}
if \"${{onset}} < 0 && ${{moved}} > {onset_m:e}\" then \"variable onset equal ${{tilt_now}}\"
if \"${{moved}} > {confirm_m:e}\" then \"jump SELF done\"
jump SELF tilting

label done
variable moved_mm equal v_moved*1000.0
print \"arachis: slide angle ${{onset}} deg, moved ${{moved_mm}} mm\"
print \"slide_angle_deg ${{onset}}\" file incline.txt
print \"moved_mm ${{moved_mm}}\" append incline.txt
",
        g = inputs.simulation.gravity_m_s2,
        onset_m = m(ONSET_MM),
        confirm_m = m(CONFIRM_MM),
    );
    Ok(Deck {
        files: vec![
            DeckFile {
                name: "in.incline",
                text: input,
            },
            DeckFile {
                name: "particles.data",
                text: data,
            },
        ],
        warnings,
        dt_s,
    })
}
