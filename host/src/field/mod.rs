//! A field: the plants of one variety in ridge rows, their pods at depth in a bed of soil
//! grains (issue 20, item 2). A field file names the variety file, the ridge section (seed
//! 001 §3.3 harvests 1 m sections of ridge), the row and hole spacing, the plants per hole,
//! and the soil: bed depth, grain size, grain material, contacts and cohesion. Every value is
//! a study input, so a user describes their own field without code.
//!
//! [`FieldSpec::plant`] lays the field out from a seed ([`layout`]): one seed always gives the
//! same field. Each plant is grown from its own seed ([`crate::variety`]) and turned about its
//! main stem until it touches no plant placed before it; then the soil grains fill the bed
//! around the pods and stalks ([`soil`]) and settle there while the plants are held
//! ([`settle`]). [`Field::load_into`] puts everything in one core
//! world ([`world`]): contacts between plants, between pods of different plants and with the
//! soil are on. The run starts with a calm ([`calm`]): for its first steps a still, dense
//! medium's drag takes out what the settled soil's grip on the pegs sets ringing.
//!
//! ```
//! use arachis::field::FieldSpec;
//! let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../testdata/peanut-plant"));
//! let spec = FieldSpec::read(&dir.join("field-huayu.toml")).unwrap();
//! assert_eq!(spec.field.rows, 2);
//! ```
//!
//! A bad file is refused before anything is grown, with its path, line and key
//! ([`FieldErrors`], positioned as a study file's errors are).

pub mod calm;
pub mod layout;
pub mod peg;
pub mod picture;
pub mod settle;
pub mod soil;
pub mod speed_watch;
pub mod world;

use std::path::{Path, PathBuf};

use arachis_core::units::LENGTH_M_TO_MM;
use serde::Deserialize;

use crate::plausible::{DENSITY_KG_M3, FRICTION, SHEAR_MODULUS_PA};
use crate::study::error::{file_errors, StudyError};
use crate::study::source::{decode_checked, read_checked, Source};
use crate::variety::{check_spread, Spread, Variety, VarietyErrors};
pub use layout::{Field, FieldError, PlacedPlant};

file_errors!(
    /// Every error found in one field file (or in the variety file it names), in file order.
    FieldErrors,
    "field file",
    "any plant was grown"
);

/// The ridge section and its planting.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Ridge {
    /// Name shown in outputs.
    pub name: String,
    /// The variety file, relative to the field file.
    pub variety: PathBuf,
    /// Length of the ridge section along x, m.
    pub ridge_length_m: f64,
    /// Plant rows on the ridge (along x, spaced along y).
    pub rows: usize,
    /// Distance between neighbouring rows, m.
    pub row_spacing_m: f64,
    /// Distance between neighbouring holes along a row, m.
    pub hole_spacing_m: f64,
    /// Plants grown from one hole (0: a bare bed, e.g. to check the soil alone).
    pub plants_per_hole: usize,
    /// Distance between neighbouring plants of one hole, along the row, m.
    pub hole_plant_gap_m: f64,
}

/// Restitution, static and rolling friction of one soil contact (EDEM's Hertz–Mindlin
/// inputs, seed 000 §2.3).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactValues {
    /// Coefficient of restitution.
    pub restitution: f64,
    /// Coefficient of static friction.
    pub friction: f64,
    /// Coefficient of rolling friction (EDEM's CDT).
    pub rolling_friction: f64,
}

impl ContactValues {
    /// Each value outside its range, with its key: restitution in (0, 1], friction and
    /// rolling friction as [`FRICTION`] allows.
    pub fn problems(&self) -> Vec<(&'static str, String)> {
        let mut out = Vec::new();
        if !(self.restitution.is_finite() && self.restitution > 0.0 && self.restitution <= 1.0) {
            out.push((
                "restitution",
                format!("must lie in (0, 1], got {}", self.restitution),
            ));
        }
        for (key, v) in [
            ("friction", self.friction),
            ("rolling_friction", self.rolling_friction),
        ] {
            if let Err(why) = FRICTION.check(v) {
                out.push((key, why));
            }
        }
        out
    }
}

/// The soil contacts: grain–grain, grain–pod and grain–plant (stems, stalks, leaves).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SoilContacts {
    /// Grain–grain.
    pub soil: ContactValues,
    /// Grain–pod.
    pub pod: ContactValues,
    /// Grain–stalk, stem and leaf.
    pub plant: ContactValues,
}

/// The soil bed.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Soil {
    /// Depth of the bed below the surface (z = 0), m.
    pub depth_m: f64,
    /// Bed beyond each outer row and beyond each end of the ridge section, m (pods hang on
    /// laterals up to about 0.2 m from their root).
    pub margin_m: f64,
    /// Grain radius, mm, drawn per grain.
    pub grain_radius_mm: Spread,
    /// Grain particle density, kg/m³.
    pub density_kg_m3: f64,
    /// Grain Young's modulus, Pa.
    pub youngs_modulus_pa: f64,
    /// Grain Poisson's ratio.
    pub poisson: f64,
    /// JKR work of adhesion Γ of every soil contact, J/m² (0: none): pull-off 1.5πΓR*.
    pub jkr_work_of_adhesion_j_m2: f64,
    /// Steps of the field per step of the soil: the grains move once every `slow_stride`
    /// steps, by one long step (multi-rate stepping, [`arachis_core::step::multirate`]); 1
    /// steps them with the plant. It divides the field's chunk ([`CHUNK_STEPS`]), so that
    /// every checkpoint and frame falls between the soil's steps.
    #[serde(default = "single_rate")]
    pub slow_stride: u32,
    /// Time the soil settles around the held plants before the field's run, s
    /// ([`settle`]; 0 leaves the loose lattice, trimmed at the surface).
    #[serde(default = "default_settle_s")]
    pub settle_s: f64,
    /// The soil's contacts.
    pub contacts: SoilContacts,
}

/// The default [`Soil::slow_stride`]: the soil steps with the plant.
fn single_rate() -> u32 {
    1
}

/// The default [`Soil::settle_s`], s. Measured on a one-plant field (9 523 grains laid
/// 1.5 × the bed's depth high, 0.12 ms steps): the grains' kinetic energy at the end was
/// 0.019 J after 0.2 s, 0.0017 J after 0.3 s and 0.0020 J after 0.5 s, so the bed has come to
/// rest by 0.3 s; released into the field's run it then sinks by 0.08 mm in 0.02 s at any of
/// the three, where the loose lattice sinks by 2.0 mm.
pub const DEFAULT_SETTLE_S: f64 = 0.3;
/// Longest settling, s.
pub const MAX_SETTLE_S: f64 = 10.0;

fn default_settle_s() -> f64 {
    DEFAULT_SETTLE_S
}

/// The calm at the start of the field's run ([`calm`]): for its first `duration_s` every
/// body moves through a still, dense medium whose quadratic drag (the core's air drag,
/// F = −½ρC_dA|v|v) takes out what the settled field's springs give its light plant spheres.
/// Absent from a file, [`Calm::default`] (the measured calm) applies, and so do its values
/// for the keys a `[calm]` table leaves out.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Calm {
    /// How long the calm lasts from the run's start, s (0: none). Rounded down to whole
    /// chunks of the field's [`CHUNK_STEPS`] steps; with a harvester it must end before the
    /// machine sets off (the harvester's `settle_s` may not be shorter).
    pub duration_s: f64,
    /// Density of the calming medium, kg/m³.
    pub medium_density_kg_m3: f64,
    /// Drag coefficient C_d of every body in it.
    pub drag_coefficient: f64,
}

/// The default [`Calm::duration_s`], s: 10 000 of the shipped field's 7.46e-7 s steps once
/// rounded down to whole chunks ([`calm`]).
pub const DEFAULT_CALM_S: f64 = 0.0075;
/// The default [`Calm::medium_density_kg_m3`]: water's, kg/m³.
pub const DEFAULT_CALM_DENSITY_KG_M3: f64 = 1000.0;
/// The default [`Calm::drag_coefficient`]: with [`DEFAULT_CALM_DENSITY_KG_M3`], a 1 mm peg
/// sphere of 4 mg at 1 m/s decelerates at about 1 000 m/s², a soil grain at rest feels nothing.
pub const DEFAULT_CALM_DRAG_COEFFICIENT: f64 = 2.5;
/// Longest calm, s.
pub const MAX_CALM_S: f64 = 1.0;
/// Densest calming medium, kg/m³ (denser than mercury; the drag's products stay well inside
/// the fixed point).
pub const MAX_CALM_DENSITY_KG_M3: f64 = 2.0e4;
/// Largest calming drag coefficient (a flat plate broadside has about 2).
pub const MAX_CALM_DRAG_COEFFICIENT: f64 = 10.0;

impl Default for Calm {
    fn default() -> Self {
        Calm {
            duration_s: DEFAULT_CALM_S,
            medium_density_kg_m3: DEFAULT_CALM_DENSITY_KG_M3,
            drag_coefficient: DEFAULT_CALM_DRAG_COEFFICIENT,
        }
    }
}

/// A field file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FieldSpec {
    /// The ridge and its planting.
    pub field: Ridge,
    /// The soil bed.
    pub soil: Soil,
    /// The calm at the start of the run (absent: [`Calm::default`]).
    #[serde(default)]
    pub calm: Calm,
    /// The variety file's contents, read by [`FieldSpec::read`].
    #[serde(skip)]
    pub variety: Option<Variety>,
}

/// Steps of a field run's chunk: a harvester checks the pods and sets its parts' velocities
/// after each (a 9 Hz shake is then followed by about 500 chords per period at the field's
/// 8e-7 s step, [`crate::harvester::rig`]), and checkpoints and frames fall between chunks,
/// so the soil's stride divides it ([`Soil::slow_stride`]).
pub const CHUNK_STEPS: u64 = 250;

/// Most rows on one ridge.
pub const MAX_ROWS: usize = 16;
/// Most plants per hole.
pub const MAX_PLANTS_PER_HOLE: usize = 8;
/// Longest ridge section, m.
pub const MAX_RIDGE_LENGTH_M: f64 = 20.0;
/// Deepest soil bed, m.
pub const MAX_SOIL_DEPTH_M: f64 = 2.0;
/// Grain radius range, mm: from fine sand to clods.
pub const GRAIN_RADIUS_MM: (f64, f64) = (0.05, 100.0);

impl FieldSpec {
    /// Reads and checks a field file (without its variety: [`FieldSpec::read`] reads that
    /// too); `path` names it in every error.
    pub fn from_toml(path: &Path, text: &str) -> Result<Self, FieldErrors> {
        decode_checked(path, text, Self::problems).map_err(FieldErrors)
    }

    /// Reads and checks the field file at `path`, then the variety file it names.
    pub fn read(path: &Path) -> Result<Self, FieldErrors> {
        let mut spec: FieldSpec =
            read_checked(path, "field", Self::problems).map_err(FieldErrors)?;
        let variety_path = path
            .parent()
            .unwrap_or(Path::new("."))
            .join(&spec.field.variety);
        let variety =
            Variety::read(&variety_path).map_err(|VarietyErrors(errors)| FieldErrors(errors))?;
        spec.variety = Some(variety);
        Ok(spec)
    }

    /// Width of the bed across the rows, m.
    pub fn bed_width_m(&self) -> f64 {
        (self.field.rows.max(1) - 1) as f64 * self.field.row_spacing_m + 2.0 * self.soil.margin_m
    }

    /// Every value outside what a field can be built from, each at its key.
    fn problems(&self, source: &Source<'_>) -> Vec<StudyError> {
        let mut errors = Vec::new();
        let mut bad =
            |path: &[&str], reason: String| errors.push(source.error_at_keys(path, reason));
        let f = &self.field;
        let positive_below = |v: f64, max: f64| v.is_finite() && v > 0.0 && v <= max;
        for (key, v, max) in [
            ("ridge_length_m", f.ridge_length_m, MAX_RIDGE_LENGTH_M),
            ("row_spacing_m", f.row_spacing_m, MAX_RIDGE_LENGTH_M),
            ("hole_spacing_m", f.hole_spacing_m, f.ridge_length_m),
        ] {
            if !positive_below(v, max) {
                bad(
                    &["field", key],
                    format!("must be > 0 m and at most {max} m, got {v}"),
                );
            }
        }
        if !(f.hole_plant_gap_m.is_finite() && f.hole_plant_gap_m >= 0.0) {
            bad(
                &["field", "hole_plant_gap_m"],
                format!("must be ≥ 0 m, got {}", f.hole_plant_gap_m),
            );
        }
        if !(1..=MAX_ROWS).contains(&f.rows) {
            bad(
                &["field", "rows"],
                format!("must be 1 to {MAX_ROWS}, got {}", f.rows),
            );
        }
        if f.plants_per_hole > MAX_PLANTS_PER_HOLE {
            bad(
                &["field", "plants_per_hole"],
                format!(
                    "must be 0 to {MAX_PLANTS_PER_HOLE}, got {}",
                    f.plants_per_hole
                ),
            );
        }
        let s = &self.soil;
        if !positive_below(s.depth_m, MAX_SOIL_DEPTH_M) {
            bad(
                &["soil", "depth_m"],
                format!(
                    "must be > 0 m and at most {MAX_SOIL_DEPTH_M} m, got {}",
                    s.depth_m
                ),
            );
        }
        if !(s.margin_m.is_finite() && s.margin_m >= 0.0 && s.margin_m <= MAX_RIDGE_LENGTH_M) {
            bad(
                &["soil", "margin_m"],
                format!("must be 0 to {MAX_RIDGE_LENGTH_M} m, got {}", s.margin_m),
            );
        }
        check_spread(
            &mut bad,
            &["soil", "grain_radius_mm"],
            s.grain_radius_mm,
            GRAIN_RADIUS_MM.0,
            GRAIN_RADIUS_MM.1,
            "mm",
        );
        let grain_mm = s.grain_radius_mm.high();
        let layer_m = 2.0 * grain_mm / LENGTH_M_TO_MM;
        if s.depth_m.is_finite() && layer_m.is_finite() && layer_m > s.depth_m {
            bad(
                &["soil", "depth_m"],
                format!(
                    "must hold at least one layer of grains ({layer_m:.4} m for the largest grain), got {}",
                    s.depth_m
                ),
            );
        }
        if let Err(why) = DENSITY_KG_M3.check(s.density_kg_m3) {
            bad(&["soil", "density_kg_m3"], why);
        }
        if let Err(why) = SHEAR_MODULUS_PA.check(s.youngs_modulus_pa) {
            bad(&["soil", "youngs_modulus_pa"], why);
        }
        if !(s.poisson.is_finite() && s.poisson > -1.0 && s.poisson < 0.5) {
            bad(
                &["soil", "poisson"],
                format!("must lie in (−1, 0.5), got {}", s.poisson),
            );
        }
        if !(s.jkr_work_of_adhesion_j_m2.is_finite() && s.jkr_work_of_adhesion_j_m2 >= 0.0) {
            bad(
                &["soil", "jkr_work_of_adhesion_j_m2"],
                format!("must be ≥ 0 J/m², got {}", s.jkr_work_of_adhesion_j_m2),
            );
        }
        if !(s.settle_s.is_finite() && (0.0..=MAX_SETTLE_S).contains(&s.settle_s)) {
            bad(
                &["soil", "settle_s"],
                format!("must be 0 to {MAX_SETTLE_S} s, got {}", s.settle_s),
            );
        }
        let chunk = CHUNK_STEPS;
        if s.slow_stride == 0 || chunk % u64::from(s.slow_stride) != 0 {
            bad(
                &["soil", "slow_stride"],
                format!(
                    "must divide the field's {chunk}-step chunk (1, 2, 5, 10, 25, 50, 125 or 250), got {}",
                    s.slow_stride
                ),
            );
        }
        let c = &self.calm;
        for (key, v, max, unit) in [
            ("duration_s", c.duration_s, MAX_CALM_S, " s"),
            (
                "medium_density_kg_m3",
                c.medium_density_kg_m3,
                MAX_CALM_DENSITY_KG_M3,
                " kg/m³",
            ),
            (
                "drag_coefficient",
                c.drag_coefficient,
                MAX_CALM_DRAG_COEFFICIENT,
                "",
            ),
        ] {
            if !(v.is_finite() && (0.0..=max).contains(&v)) {
                bad(&["calm", key], format!("must be 0 to {max}{unit}, got {v}"));
            }
        }
        if c.duration_s > 0.0 && (c.medium_density_kg_m3 == 0.0 || c.drag_coefficient == 0.0) {
            bad(
                &["calm", "duration_s"],
                format!(
                    "is {} s, but a medium of density {} kg/m³ and drag coefficient {} calms nothing: give both > 0, or duration_s = 0 for no calm",
                    c.duration_s, c.medium_density_kg_m3, c.drag_coefficient
                ),
            );
        }
        for (name, c) in [
            ("soil", s.contacts.soil),
            ("pod", s.contacts.pod),
            ("plant", s.contacts.plant),
        ] {
            for (key, why) in c.problems() {
                bad(&["soil", "contacts", name, key], why);
            }
        }
        errors
    }
}
