//! Plant pull-off studies: the study file that makes `arachis calibrate STUDY` run seed
//! 001's calibration of the pod–stalk junction (issue 6 §4) instead of seed 000's repose
//! plan. `testdata/peanut-plant/study.toml` is seed 001's study.
//!
//! A study file whose `[study]` table says `kind = "pull_off"` ([`is_plant_study`]) is read
//! here ([`file_format`]); any other goes to `crate::study` unchanged. Loading reuses the
//! pod study's machinery — the spanned TOML source, section-by-section decoding, and
//! [`StudyErrors`] naming file, key, line:column and reason — and checks everything before
//! any pull: the nine Table 5 factors and only those, low < high within physical limits,
//! the measured force, the topology and its bond sets, and every plan setting
//! ([`validate`]). A valid study becomes a [`Plan`] and a [`PullOffSimulator`] for
//! `crate::plant_calibration::calibrate_plan`.

pub mod file_format;
pub mod validate;

use std::path::{Path, PathBuf};

use arachis_core::bond::BondSetSpec;
use arachis_core::scenario::pull_off::{PullOff, TAG_JUNCTION, TAG_STALK};
use toml::de::DeTable;

use crate::plant::topology::BondSet;
use crate::plant::Topology;
use crate::plant_calibration::factors::TABLE5;
use crate::plant_calibration::{Plan, PullOffSimulator};
use crate::study::source::Source;
use crate::study::StudyErrors;
pub use file_format::{PlantStudyFile, KIND_PULL_OFF};

/// A plant study that passed every check (only [`PlantStudy::load`] and
/// [`PlantStudy::from_toml`] make one).
#[derive(Debug, Clone, PartialEq)]
pub struct PlantStudy {
    path: PathBuf,
    file: PlantStudyFile,
    junction: BondSet,
    stalk: BondSet,
}

/// True when the file at `path` reads as TOML whose `[study]` table has
/// `kind = "pull_off"` (a file with syntax errors still counts when that key parses). An
/// unreadable file is not one: the pod study loader then reports it.
pub fn is_plant_study(path: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(path) else {
        return false;
    };
    let (doc, _) = DeTable::parse_recoverable(&text);
    doc.get_ref()
        .get("study")
        .and_then(|s| s.get_ref().as_table())
        .and_then(|s| s.get("kind"))
        .and_then(|k| k.get_ref().as_str())
        == Some(KIND_PULL_OFF)
}

impl PlantStudy {
    /// Reads, parses and validates the plant study at `path`.
    pub fn load(path: &Path) -> Result<Self, StudyErrors> {
        Self::from_toml(&crate::study::read_study_text(path)?, path)
    }

    /// Parses and validates `text` as if read from `path` (which names the file in messages
    /// and anchors the topology path).
    pub fn from_toml(text: &str, path: &Path) -> Result<Self, StudyErrors> {
        let src = Source::parse(path, text).map_err(|e| StudyErrors(e).sorted())?;
        let file = validate::decode(&src).map_err(|e| StudyErrors(e).sorted())?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let (sets, errors) = validate::validate(&src, &file, dir);
        match sets {
            Some((junction, stalk)) if errors.is_empty() => Ok(Self {
                path: path.to_owned(),
                file,
                junction,
                stalk,
            }),
            _ => Err(StudyErrors(errors).sorted()),
        }
    }

    /// The file it was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The validated content.
    pub fn file(&self) -> &PlantStudyFile {
        &self.file
    }

    /// A few lines for `arachis study check`: the measurement, the factors and the plan.
    pub fn summary(&self) -> String {
        let f = &self.file;
        let p = &f.plan;
        let mut lines = vec![
            format!(
                "plant pull-off study {} ({})",
                f.study.name,
                self.path.display()
            ),
            format!(
                "measured {} = {} N ({})",
                f.measurement.quantity, f.measurement.value_n, f.measurement.source
            ),
            format!(
                "rig: {} m/s at {}°, {} stalk spheres, bond sets {} / {} of {}",
                f.rig.pull_speed_m_s,
                f.rig.pull_angle_deg,
                f.rig.stalk_spheres,
                f.rig.junction_bond_set,
                f.rig.stalk_bond_set,
                f.rig.topology
            ),
        ];
        for factor in self.plan().factors {
            lines.push(format!(
                "  {} {} ({}): {} … {}",
                factor.label, factor.description, factor.unit, factor.low, factor.high
            ));
        }
        lines.push(format!(
            "plan: Plackett–Burman {} runs + {} centre points; steepest ascent step {} coded, \
             {}–{} points; central composite on {} (α = {}, {} centre points); goal {}; \
             validation within {} %",
            p.screening.runs,
            p.screening.centre_points,
            p.steepest_ascent.step_coded,
            p.steepest_ascent.points,
            p.steepest_ascent.max_points,
            p.central_composite
                .factors
                .as_ref()
                .map_or("the screening's choice".to_owned(), |f| f.join(", ")),
            p.central_composite.alpha,
            p.central_composite.centre_points,
            p.optimisation.goal,
            p.validation.max_relative_error_pct
        ));
        lines.join("\n")
    }

    /// The measured detachment force, N.
    pub fn target_n(&self) -> f64 {
        self.file.measurement.value_n
    }

    /// The calibration plan the file states.
    pub fn plan(&self) -> Plan {
        let p = &self.file.plan;
        let mut plan = Plan::seed001();
        plan.factors = TABLE5.map(|mut f| {
            let levels = &self.file.factors[f.label];
            f.low = levels.low;
            f.high = levels.high;
            f
        });
        plan.screening_runs = p.screening.runs;
        plan.screening_centre_points = p.screening.centre_points;
        plan.significance = p.screening.significance;
        plan.carry_level = p.screening.carry_level;
        plan.path_step_coded = p.steepest_ascent.step_coded;
        plan.path_first_points = p.steepest_ascent.points;
        plan.path_max_points = p.steepest_ascent.max_points;
        plan.ccd_alpha = p.central_composite.alpha;
        plan.ccd_centre_points = p.central_composite.centre_points;
        plan.carry = p.central_composite.factors.clone();
        plan.carry_reason = p
            .central_composite
            .why
            .as_ref()
            .map(|why| format!("named by the study's [plan.central_composite] factors: {why}"));
        plan.max_relative_error_pct = p.validation.max_relative_error_pct;
        plan
    }

    /// The tensile test the file describes: the default rig's geometry (seed 001 Table 1)
    /// with the topology's junction and stalk bond sets and the study's pull conditions.
    pub fn simulator(&self) -> PullOffSimulator {
        let r = &self.file.rig;
        PullOffSimulator {
            base: PullOff {
                stalk_spheres: r.stalk_spheres,
                pull_speed_m_s: r.pull_speed_m_s,
                pull_angle_deg: r.pull_angle_deg,
                junction: spec(TAG_JUNCTION, &self.junction),
                stalk: spec(TAG_STALK, &self.stalk),
                ..PullOff::default()
            },
        }
    }
}

/// The core's bond set of a topology bond set.
fn spec(tag: u16, b: &BondSet) -> BondSetSpec {
    BondSetSpec {
        tag,
        normal_stiffness_n_m3: b.kn_n_m3,
        tangential_stiffness_n_m3: b.kt_n_m3,
        normal_strength_pa: b.sigma_c_pa,
        tangential_strength_pa: b.tau_c_pa,
        radius_m: b.radius_m,
    }
}

/// The topology at `path`, read and checked.
pub fn read_topology(path: &Path) -> Result<Topology, String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read the topology {}: {e}", path.display()))?;
    let t = Topology::from_toml(&text).map_err(|e| e.to_string())?;
    t.check().map_err(|e| e.to_string())?;
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_pull_off_kind_is_a_plant_study() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("s.toml");
        std::fs::write(&p, "[study]\nkind = \"pull_off\"\nname = [\n").unwrap();
        assert!(is_plant_study(&p));
        std::fs::write(&p, "[study]\nname = \"pods\"\n").unwrap();
        assert!(!is_plant_study(&p));
        assert!(!is_plant_study(&dir.path().join("missing.toml")));
    }
}
