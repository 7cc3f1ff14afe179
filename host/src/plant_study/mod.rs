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
//! ([`validate`]). A valid study becomes calibration factors, plan settings and a
//! [`PullOffRig`] for the calibration engine.

pub mod file_format;
pub mod validate;

use std::path::{Path, PathBuf};

use arachis_core::bond::BondSetSpec;
use arachis_core::scenario::pull_off::{PullOff, TAG_JUNCTION, TAG_STALK};
use toml::de::DeTable;

use crate::calibration::settings::{
    Extension, NamedFactors, PathSettings, PlanSettings, ScreeningSettings, SurfaceDesign,
    SurfaceSettings, ValidationSettings,
};
use crate::calibration::Factor;
use crate::doe::PlackettBurmanRuns;
use crate::plant::topology::BondSet;
use crate::plant::Topology;
use crate::rigs::pull_off::{PullOffRig, PARAMETERS};
use crate::stats::ModelOrder;
use crate::study::source::Source;
use crate::study::StudyErrors;
pub use file_format::{PlantStudyFile, KIND_PULL_OFF};

/// The shipped seed 001 study, as built in.
const SHIPPED_STUDY: &str = include_str!("../../../testdata/peanut-plant/study.toml");
/// Where the shipped study lies in the repository (it names the built-in study in messages).
const SHIPPED_STUDY_PATH: &str = "testdata/peanut-plant/study.toml";

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
        Self::from_toml_reading(text, path, &|p| std::fs::read_to_string(p))
    }

    /// Like [`PlantStudy::from_toml`], reading the files the study names (its topology)
    /// with `read` (a study built into the program serves its own).
    pub fn from_toml_reading(
        text: &str,
        path: &Path,
        read: ReadFile<'_>,
    ) -> Result<Self, StudyErrors> {
        let src = Source::parse(path, text).map_err(|e| StudyErrors(e).sorted())?;
        let file = validate::decode(&src).map_err(|e| StudyErrors(e).sorted())?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let (sets, errors) = validate::validate(&src, &file, dir, read);
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

    /// Seed 001's study as shipped (`testdata/peanut-plant/study.toml` and its topology),
    /// built into the program.
    pub fn shipped() -> Self {
        let path = Path::new(SHIPPED_STUDY_PATH);
        let read = |p: &Path| {
            if p.file_name() == Some(std::ffi::OsStr::new(crate::plant::SHIPPED_TOPOLOGY_FILE)) {
                Ok(crate::plant::SHIPPED_TOPOLOGY.to_owned())
            } else {
                std::fs::read_to_string(p)
            }
        };
        Self::from_toml_reading(SHIPPED_STUDY, path, &read).expect("the shipped study is valid")
    }

    /// Sets the measured detachment force, N (checked by the caller).
    pub fn set_target_n(&mut self, force_n: f64) {
        self.file.measurement.value_n = force_n;
    }

    /// Sets the pull's speed (m/s) and direction from the stalk axis (degrees), checked by
    /// the caller.
    pub fn set_pull(&mut self, speed_m_s: f64, angle_deg: f64) {
        self.file.rig.pull_speed_m_s = speed_m_s;
        self.file.rig.pull_angle_deg = angle_deg;
    }

    /// Names the factors of the path and the central composite design (checked with
    /// [`validate::check_carry`]), and why; `None` leaves the choice to the screening.
    pub fn set_named_factors(
        &mut self,
        labels: Option<Vec<String>>,
        why: &str,
    ) -> Result<(), String> {
        if let Some(l) = &labels {
            validate::check_carry(l)?;
        }
        let c = &mut self.file.plan.central_composite;
        c.why = labels.as_ref().map(|_| why.to_owned());
        c.factors = labels;
        Ok(())
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
        for f in self.factors() {
            let p = crate::rigs::pull_off::by_name(&f.name).expect("a pull-off factor");
            lines.push(format!(
                "  {} {} ({}): {} … {}",
                f.label, p.description, f.unit, f.low, f.high
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

    /// The nine factors of seed 001 Table 5 with the study's levels, each held at its
    /// range's centre when not varied.
    pub fn factors(&self) -> Vec<Factor> {
        PARAMETERS
            .iter()
            .map(|p| {
                let levels = &self.file.factors[p.label];
                Factor {
                    name: p.name.to_owned(),
                    label: p.label.to_owned(),
                    unit: p.unit.to_owned(),
                    low: levels.low,
                    high: levels.high,
                    held: 0.5 * (levels.low + levels.high),
                    physical: p.limits,
                    admitted: p.limits,
                }
            })
            .collect()
    }

    /// The plan the file states: seed 001's sequence (the path going on one step at a time
    /// while it approaches the target, a central composite response surface, one
    /// validation pull of the deterministic rig).
    pub fn plan_settings(&self) -> PlanSettings {
        let p = &self.file.plan;
        let c = &p.central_composite;
        PlanSettings {
            screening: ScreeningSettings {
                runs: if p.screening.runs == 20 {
                    PlackettBurmanRuns::Twenty
                } else {
                    PlackettBurmanRuns::Twelve
                },
                centre_points: p.screening.centre_points,
                significance: p.screening.significance,
                carry_level: Some(p.screening.carry_level),
                named: c.factors.clone().map(|labels| NamedFactors {
                    labels,
                    reason: format!(
                        "named by the study's [plan.central_composite] factors: {}",
                        c.why.as_deref().unwrap_or_default()
                    ),
                }),
            },
            path: PathSettings {
                points: p.steepest_ascent.points,
                step_coded: p.steepest_ascent.step_coded,
                origin_coded: -1.0,
                extension: Extension::SingleSteps {
                    max_points: p.steepest_ascent.max_points,
                },
            },
            surface: SurfaceSettings {
                design: SurfaceDesign::CentralComposite { alpha: c.alpha },
                centre_points: c.centre_points,
                model: ModelOrder::Quadratic,
            },
            validation: ValidationSettings {
                replicates: 1,
                max_relative_error_pct: p.validation.max_relative_error_pct,
            },
        }
    }

    /// The tensile test the file describes: the default rig's geometry (seed 001 Table 1)
    /// with the topology's junction and stalk bond sets and the study's pull conditions.
    pub fn rig(&self) -> PullOffRig {
        let r = &self.file.rig;
        PullOffRig {
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

/// Reads a file a study names.
pub type ReadFile<'a> = &'a dyn Fn(&Path) -> std::io::Result<String>;

/// The topology at `path`, read with `read` and checked.
pub fn read_topology(path: &Path, read: ReadFile<'_>) -> Result<Topology, String> {
    let text =
        read(path).map_err(|e| format!("cannot read the topology {}: {e}", path.display()))?;
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
