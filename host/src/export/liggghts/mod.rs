//! A study's rig as a LIGGGHTS 3.8 input deck (`arachis export liggghts`), so a user can run
//! the same experiment in LIGGGHTS and the cross-checks can compare the two engines on it
//! (`scripts/cross-check-repose.sh`, `scripts/cross-check-incline.sh`, `docs/conventions.md`).
//!
//! Each deck reproduces its rig step by step, from the same parts:
//! - the same particles at the same places, written as a `read_data` file
//!   (`particles.data`: diameter, density, position, velocity);
//! - the same materials (E = 2G(1 + ν), ν, ρ) and pairs (e, μs, μr), with LIGGGHTS'
//!   `tangential history`, `rolling_friction cdt` or `epsd2` (the pairs' rolling convention)
//!   and `limitForce on` (Arachis never lets the normal force attract); a pair the study keeps
//!   in EDEM's conventions, or in another rolling convention than the deck's one (LIGGGHTS sets
//!   it for all pairs), is written with the same numbers and a warning
//!   (`docs/conventions.md`);
//! - the floor as a primitive plane, and the rig's time step: the study's fraction of the
//!   smallest sphere's Rayleigh time.
//!
//! The rigs: [`repose`] (cylinder lifting; `in.repose`) and [`incline`] (a sphere on a tilting
//! plate; `in.incline`). LIGGGHTS-PUBLIC has no multi-sphere particles, so only studies of
//! `[spheres]` export.
//!
//! ```
//! use arachis::export::liggghts::DeckFile;
//! let f = DeckFile { name: "in.incline", text: "run 1\n".into() };
//! assert_eq!(f.name, "in.incline");
//! ```

pub mod incline;
pub mod repose;

use std::fmt::Write as _;

use arachis_core::contact::{FrictionConvention, RollingConvention};
use arachis_core::pair::PairSpec;
use arachis_core::timestep::rayleigh_time_s;
use arachis_core::units::LENGTH_M_TO_MM;

use crate::rigs::pod_world::setup::RunInputs;
use crate::rigs::pod_world::Experiment;

/// Neighbour skin, in radii of the smallest sphere.
pub const SKIN_RADII: f64 = 0.25;

/// One file of a deck.
#[derive(Debug, Clone, PartialEq)]
pub struct DeckFile {
    /// The file's name in the deck's folder.
    pub name: &'static str,
    /// Its text.
    pub text: String,
}

/// The files of an exported deck, the input script first.
#[derive(Debug, Clone, PartialEq)]
pub struct Deck {
    /// The input script, then the files it reads.
    pub files: Vec<DeckFile>,
    /// Warnings for the user (pairs LIGGGHTS cannot read as the study does).
    pub warnings: Vec<String>,
    /// Time step, s.
    pub dt_s: f64,
}

impl Deck {
    /// The input script's name (`liggghts -in NAME`).
    pub fn input_name(&self) -> &'static str {
        self.files[0].name
    }
}

/// The experiments that export, by name (for error messages).
pub const EXPORTED: &str = "repose, incline_slide";

/// The deck of `experiment`'s rig for `inputs` and placement seed `seed`; `source` names the
/// study in the deck's header. Errors: a study of pods, or an experiment without a deck.
pub fn deck(
    experiment: Experiment,
    inputs: &RunInputs,
    seed: u64,
    source: &str,
) -> Result<Deck, String> {
    if inputs.templates.iter().any(|t| !t.is_sphere()) {
        return Err(
            "LIGGGHTS-PUBLIC has no multi-sphere particles: only a study of [spheres] exports"
                .into(),
        );
    }
    match experiment {
        Experiment::Repose => repose::deck(inputs, seed, source),
        Experiment::InclineSlide => incline::deck(inputs, source),
        other => Err(format!(
            "export liggghts writes the rigs {EXPORTED} (asked for {})",
            other.name()
        )),
    }
}

/// The length `x_mm` mm in metres (LIGGGHTS runs in SI).
fn m(x_mm: f64) -> f64 {
    x_mm / LENGTH_M_TO_MM
}

/// The rigs' time step for spheres down to `radius_mm`: the study's fraction of the pod
/// material's Rayleigh time at that radius (`set_rayleigh_timestep`), s.
fn timestep_s(inputs: &RunInputs, radius_mm: f64) -> f64 {
    let pod = &inputs.pod;
    inputs.simulation.dt_rayleigh_fraction
        * rayleigh_time_s(
            m(radius_mm),
            pod.density_kg_m3,
            pod.youngs_modulus_pa,
            pod.poisson,
        )
}

/// One particle of a `read_data` file: diameter, mm; centre, mm; velocity, m/s.
struct DataParticle {
    diameter_mm: f64,
    centre_mm: [f64; 3],
    velocity_m_s: [f64; 3],
}

/// A `read_data` file of pod-material particles (type 1) in the box `bounds_mm` (lo, hi per
/// axis, mm).
fn particles_data(
    inputs: &RunInputs,
    heading: &str,
    bounds_mm: [[f64; 2]; 3],
    particles: &[DataParticle],
) -> String {
    let n = particles.len();
    let mut data = format!(
        "LIGGGHTS data file written by arachis export liggghts: {heading}\n\n\
         {n} atoms\n2 atom types\n\n"
    );
    for ([lo, hi], axis) in bounds_mm.iter().zip(["x", "y", "z"]) {
        let _ = writeln!(data, "{:e} {:e} {axis}lo {axis}hi", m(*lo), m(*hi));
    }
    data += "\nAtoms\n\n";
    for (i, p) in particles.iter().enumerate() {
        let [x, y, z] = p.centre_mm.map(m);
        let d = m(p.diameter_mm);
        let rho = inputs.pod.density_kg_m3;
        let _ = writeln!(data, "{} 1 {d:e} {rho:e} {x:e} {y:e} {z:e}", i + 1);
    }
    data += "\nVelocities\n\n";
    for (i, p) in particles.iter().enumerate() {
        let [vx, vy, vz] = p.velocity_m_s;
        let _ = writeln!(data, "{} {vx:e} {vy:e} {vz:e} 0 0 0", i + 1);
    }
    data
}

/// The contact settings and model every wall and pair of a deck uses.
struct Model {
    /// `model hertz tangential history rolling_friction NAME`.
    model: String,
    /// LIGGGHTS wants the settings (limitForce) after a wall's geometry.
    settings: &'static str,
}

/// The opening of a deck: `header` (comment lines), the warnings, the particles
/// (`particles.data`), materials, pairs, time step, gravity (fix `gravi`, along −z) and the
/// floor z = 0; the deck adds its own walls and `fix integrate all nve/sphere`.
fn preamble(
    inputs: &RunInputs,
    header: &str,
    warnings: &[String],
    dt_s: f64,
    skin_mm: f64,
) -> (String, Model) {
    let model = Model {
        model: format!(
            "model hertz tangential history rolling_friction {}",
            deck_rolling_model(inputs)
        ),
        settings: "limitForce on",
    };
    let (pod, wall) = (&inputs.pod, &inputs.wall);
    let pair3 = |f: fn(&PairSpec) -> f64| {
        let (pp, pw) = (f(&inputs.pod_pod), f(&inputs.pod_wall));
        format!("{pp} {pw} {pw} {pw}")
    };
    let mut input = header.to_string();
    for w in warnings {
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
",
        skin = m(skin_mm),
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
        model = model.model,
        settings = model.settings,
        g = inputs.simulation.gravity_m_s2,
    );
    (input, model)
}

/// The warnings of `inputs`' pairs against the deck's rolling model.
fn warnings(inputs: &RunInputs) -> Vec<String> {
    let rolling_model = deck_rolling_model(inputs);
    [("pod-pod", &inputs.pod_pod), ("pod-wall", &inputs.pod_wall)]
        .into_iter()
        .filter_map(|(name, p)| pair_warning(name, p, rolling_model))
        .collect()
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
