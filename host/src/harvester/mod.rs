//! A harvester described in a file, not in code (issue 20, item 3): a digging shovel, a
//! rod-chain conveyor that shakes, and a picking drum, all of steel, travelling along the
//! ridge of a field ([`crate::field`]) at one forward speed.
//!
//! The machine is built of kinematic bodies ([`parts`]): the shovel is rows of steel spheres
//! forming an inclined plate whose leading edge runs at the digging depth; the chain is rods
//! across the ridge that spin about their own axes, so that their top surfaces carry what
//! lies on them rearwards and up at the chain speed (a roller bed standing in for the moving
//! chain: the same surface speed and the same gaps between rods); the drum is rows of teeth
//! turning about an axis across the ridge above the chain's top end. The shovel and the chain
//! can shake along their normals ([`motion`]). The shovel's edge cuts each taproot as it
//! passes under the plant's root: the root is let go ([`rig`]).
//!
//! Where pods end up is counted by [`loss`], with one stated definition of loss.
//!
//! ```
//! use arachis::harvester::HarvesterSpec;
//! let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../testdata/peanut-plant"));
//! let spec = HarvesterSpec::read(&dir.join("harvester-digger.toml")).unwrap();
//! assert!(spec.drum.speed_rpm > 0.0);
//! ```
//!
//! A bad file is refused before anything is built, with its path, line and key
//! ([`HarvesterErrors`], positioned as a study file's errors are).

pub mod loss;
pub mod motion;
pub mod parts;
pub mod picture;
pub mod report;
pub mod rig;
pub mod trial;

use std::path::Path;

use arachis_core::units::LENGTH_M_TO_MM;
use serde::Deserialize;

use crate::field::{Calm, ContactValues};
use crate::study::error::{file_errors, StudyError};
use crate::study::source::{decode_checked, read_checked, Source};

file_errors!(
    /// Every error found in one harvester file, in file order.
    HarvesterErrors,
    "harvester file",
    "anything was built"
);

/// The machine as a whole.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Machine {
    /// Name shown in outputs.
    pub name: String,
    /// Forward speed along +x (the ridge), m/s.
    pub forward_speed_m_s: f64,
    /// Working width across the ridge (shovel, chain and drum), m.
    pub width_m: f64,
    /// Gap between the shovel's edge and the bed's front face at the start, m.
    pub start_gap_m: f64,
    /// Time the field settles under gravity before the machine sets off, s (the bed is laid
    /// out loose, [`crate::field::soil`]). At least the field's calm
    /// ([`crate::field::Calm::duration_s`], [`HarvesterSpec::check_waits_for_calm`]).
    pub settle_s: f64,
}

/// A sinusoidal shake along a part's normal: d(t) = A sin(2π f t).
#[derive(Debug, Clone, Copy, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shake {
    /// Frequency f, Hz (0: no shake).
    pub frequency_hz: f64,
    /// Amplitude A, mm.
    pub amplitude_mm: f64,
}

/// The digging shovel: a flat plate rising rearwards from its edge.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Shovel {
    /// Depth of the edge below the ground, m.
    pub depth_m: f64,
    /// Inclination of the plate to the horizontal, degrees.
    pub angle_deg: f64,
    /// Length of the plate along its slope, m.
    pub length_m: f64,
    /// Radius of the steel spheres the plate is made of, mm.
    pub sphere_radius_mm: f64,
    /// Shake of the plate along its normal.
    #[serde(default)]
    pub shake: Shake,
}

/// The rod-chain conveyor: rods across the ridge from the shovel's top edge rearwards and up.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Chain {
    /// Length along its slope, m.
    pub length_m: f64,
    /// Inclination to the horizontal, degrees.
    pub angle_deg: f64,
    /// Surface speed of the chain, rearwards and up along its slope, m/s.
    pub speed_m_s: f64,
    /// Rod diameter, mm.
    pub rod_diameter_mm: f64,
    /// Centre-to-centre rod pitch, mm (the gap between rods is pitch − diameter).
    pub rod_pitch_mm: f64,
    /// Shake of the chain along its normal.
    #[serde(default)]
    pub shake: Shake,
}

/// The picking drum: rows of teeth about an axis across the ridge, above the chain's top end.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drum {
    /// Radius of the tooth centres, m.
    pub radius_m: f64,
    /// Speed, r/min; the teeth at the bottom move rearwards, as the chain's top does.
    pub speed_rpm: f64,
    /// Radius of one tooth (a steel sphere), mm.
    pub tooth_radius_mm: f64,
    /// Rows of teeth around the drum, evenly spaced.
    pub rows: usize,
    /// Distance between neighbouring teeth of one row across the ridge, mm.
    pub tooth_pitch_mm: f64,
    /// Gap between the tooth circle and the chain's last rod, m.
    pub clearance_m: f64,
}

/// Where picked pods are collected: a horizontal opening under the drum.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Collector {
    /// Height of the opening above the ground, m.
    pub height_m: f64,
    /// How far it reaches ahead of the drum's axis (towards the chain), m.
    pub ahead_of_drum_m: f64,
    /// How far it reaches behind the drum's axis, m.
    pub behind_drum_m: f64,
}

/// Contacts of the machine's steel with the soil (its contacts with pods and plants are
/// seed 001 Table 2's, as the harvest of issue 6 uses).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteelContacts {
    /// Soil grain against steel.
    pub soil: ContactValues,
}

/// A harvester file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HarvesterSpec {
    /// The machine.
    pub harvester: Machine,
    /// The digging shovel.
    pub shovel: Shovel,
    /// The rod-chain conveyor.
    pub chain: Chain,
    /// The picking drum.
    pub drum: Drum,
    /// The collector.
    pub collector: Collector,
    /// Steel contacts with the soil.
    pub steel_contacts: SteelContacts,
}

/// Fastest forward speed accepted, m/s (a fast combine runs at about 2 m/s).
pub const MAX_FORWARD_SPEED_M_S: f64 = 10.0;
/// Largest machine dimension accepted (width, lengths, radii, heights), m.
pub const MAX_SIZE_M: f64 = 10.0;
/// Largest sphere, rod or tooth radius accepted, mm.
pub const MAX_STEEL_RADIUS_MM: f64 = 100.0;
/// Steepest shovel or chain accepted, degrees.
pub const MAX_ANGLE_DEG: f64 = 80.0;
/// Fastest drum accepted, r/min.
pub const MAX_DRUM_RPM: f64 = 5000.0;
/// Most tooth rows accepted.
pub const MAX_DRUM_ROWS: usize = 64;
/// Longest settling time accepted, s (the field's bound for its soil's settling).
pub use crate::field::MAX_SETTLE_S;
/// Highest shake frequency accepted, Hz.
pub const MAX_SHAKE_HZ: f64 = 200.0;

impl HarvesterSpec {
    /// Reads and checks a harvester file's text; `path` names it in every error.
    pub fn from_toml(path: &Path, text: &str) -> Result<Self, HarvesterErrors> {
        decode_checked(path, text, Self::problems).map_err(HarvesterErrors)
    }

    /// Reads and checks the harvester file at `path`.
    pub fn read(path: &Path) -> Result<Self, HarvesterErrors> {
        read_checked(path, "harvester", Self::problems).map_err(HarvesterErrors)
    }

    /// Checks that the machine of the file at `path` waits out the calm at the start of a
    /// field's run (`calm`, of the field file `field`, [`crate::field::calm`]): it must set
    /// off into still air, so its `settle_s` may not be shorter than the calm. The error is
    /// positioned at `harvester.settle_s`.
    pub fn check_waits_for_calm(
        &self,
        path: &Path,
        calm: &Calm,
        field: &Path,
    ) -> Result<(), HarvesterErrors> {
        if calm.duration_s <= self.harvester.settle_s {
            return Ok(());
        }
        let reason = format!(
            "must be at least the field's calm ({}: calm.duration_s = {} s), got {}: the machine would set off before the field has come to rest",
            field.display(),
            calm.duration_s,
            self.harvester.settle_s
        );
        // The file read well once; read again, it gives the position of `settle_s`.
        let unpositioned = StudyError {
            file: path.to_owned(),
            key: Default::default(),
            position: None,
            reason: reason.clone(),
        };
        let positioned = read_checked::<HarvesterSpec>(path, "harvester", |_, source| {
            vec![source.error_at_keys(&["harvester", "settle_s"], reason)]
        });
        Err(HarvesterErrors(
            positioned.err().unwrap_or_else(|| vec![unpositioned]),
        ))
    }

    /// Every value outside what a harvester can be built from, each at its key.
    fn problems(&self, source: &Source<'_>) -> Vec<StudyError> {
        let mut errors = Vec::new();
        let mut bad =
            |path: &[&str], reason: String| errors.push(source.error_at_keys(path, reason));
        let within = |v: f64, lo: f64, hi: f64| v.is_finite() && v > lo && v <= hi;
        let m = &self.harvester;
        let (s, c, d, k) = (&self.shovel, &self.chain, &self.drum, &self.collector);
        for (path, v, lo, hi, unit) in [
            (
                ["harvester", "forward_speed_m_s"],
                m.forward_speed_m_s,
                0.0,
                MAX_FORWARD_SPEED_M_S,
                "m/s",
            ),
            (["harvester", "width_m"], m.width_m, 0.0, MAX_SIZE_M, "m"),
            (["shovel", "depth_m"], s.depth_m, 0.0, MAX_SIZE_M, "m"),
            (
                ["shovel", "angle_deg"],
                s.angle_deg,
                0.0,
                MAX_ANGLE_DEG,
                "°",
            ),
            (["shovel", "length_m"], s.length_m, 0.0, MAX_SIZE_M, "m"),
            (
                ["shovel", "sphere_radius_mm"],
                s.sphere_radius_mm,
                0.0,
                MAX_STEEL_RADIUS_MM,
                "mm",
            ),
            (["chain", "length_m"], c.length_m, 0.0, MAX_SIZE_M, "m"),
            (["chain", "angle_deg"], c.angle_deg, 0.0, MAX_ANGLE_DEG, "°"),
            (
                ["chain", "speed_m_s"],
                c.speed_m_s,
                0.0,
                MAX_FORWARD_SPEED_M_S,
                "m/s",
            ),
            (
                ["chain", "rod_diameter_mm"],
                c.rod_diameter_mm,
                0.0,
                2.0 * MAX_STEEL_RADIUS_MM,
                "mm",
            ),
            (["drum", "radius_m"], d.radius_m, 0.0, MAX_SIZE_M, "m"),
            (
                ["drum", "speed_rpm"],
                d.speed_rpm,
                0.0,
                MAX_DRUM_RPM,
                "r/min",
            ),
            (
                ["drum", "tooth_radius_mm"],
                d.tooth_radius_mm,
                0.0,
                MAX_STEEL_RADIUS_MM,
                "mm",
            ),
            (
                ["drum", "tooth_pitch_mm"],
                d.tooth_pitch_mm,
                0.0,
                MAX_SIZE_M * LENGTH_M_TO_MM,
                "mm",
            ),
        ] {
            if !within(v, lo, hi) {
                bad(
                    &path,
                    format!("must be > {lo} {unit} and at most {hi} {unit}, got {v}"),
                );
            }
        }
        if !(m.settle_s.is_finite() && (0.0..=MAX_SETTLE_S).contains(&m.settle_s)) {
            bad(
                &["harvester", "settle_s"],
                format!("must be 0 to {MAX_SETTLE_S} s, got {}", m.settle_s),
            );
        }
        for (path, v) in [
            (["harvester", "start_gap_m"], m.start_gap_m),
            (["drum", "clearance_m"], d.clearance_m),
            (["collector", "height_m"], k.height_m),
            (["collector", "ahead_of_drum_m"], k.ahead_of_drum_m),
            (["collector", "behind_drum_m"], k.behind_drum_m),
        ] {
            if !(v.is_finite() && (0.0..=MAX_SIZE_M).contains(&v)) {
                bad(&path, format!("must be 0 to {MAX_SIZE_M} m, got {v}"));
            }
        }
        for (part, shake) in [("shovel", s.shake), ("chain", c.shake)] {
            if !(shake.frequency_hz.is_finite()
                && (0.0..=MAX_SHAKE_HZ).contains(&shake.frequency_hz))
            {
                bad(
                    &[part, "shake", "frequency_hz"],
                    format!("must be 0 to {MAX_SHAKE_HZ} Hz, got {}", shake.frequency_hz),
                );
            }
            if !(shake.amplitude_mm.is_finite()
                && (0.0..=MAX_SIZE_M * LENGTH_M_TO_MM).contains(&shake.amplitude_mm))
            {
                bad(
                    &[part, "shake", "amplitude_mm"],
                    format!("must be ≥ 0 mm, got {}", shake.amplitude_mm),
                );
            }
        }
        if c.rod_pitch_mm.is_finite()
            && c.rod_diameter_mm.is_finite()
            && c.rod_pitch_mm <= c.rod_diameter_mm
        {
            bad(
                &["chain", "rod_pitch_mm"],
                format!(
                    "must exceed the rod diameter ({} mm), or the rods leave no gap, got {}",
                    c.rod_diameter_mm, c.rod_pitch_mm
                ),
            );
        } else if !within(c.rod_pitch_mm, 0.0, MAX_SIZE_M * LENGTH_M_TO_MM) {
            bad(
                &["chain", "rod_pitch_mm"],
                format!("must be a positive length in mm, got {}", c.rod_pitch_mm),
            );
        }
        if !(1..=MAX_DRUM_ROWS).contains(&d.rows) {
            bad(
                &["drum", "rows"],
                format!("must be 1 to {MAX_DRUM_ROWS}, got {}", d.rows),
            );
        }
        if d.tooth_radius_mm.is_finite()
            && d.radius_m.is_finite()
            && d.tooth_radius_mm / LENGTH_M_TO_MM >= d.radius_m
        {
            bad(
                &["drum", "tooth_radius_mm"],
                format!(
                    "must be smaller than the drum's radius ({} m), got {}",
                    d.radius_m, d.tooth_radius_mm
                ),
            );
        }
        for ((path, count), limit) in parts::row_counts(self)
            .into_iter()
            .zip(std::iter::repeat(parts::MAX_ROW_SPHERES))
        {
            if count > limit {
                bad(
                    &path,
                    format!(
                        "puts {count} spheres across the {} m width; one row holds at most {limit}",
                        m.width_m
                    ),
                );
            }
        }
        for (key, why) in self.steel_contacts.soil.problems() {
            bad(&["steel_contacts", "soil", key], why);
        }
        errors
    }
}
