//! The study file (TOML): materials, pod geometry, contact pairs, bench measurements with
//! replicates, the parameters calibration varies and over what ranges, and the calibration
//! plan (issue 4 §3). `testdata/peanut-pods-saline/study.toml` is seed 000's study.
//!
//! Loading parses and validates the whole file before anything is simulated. Every error
//! names the file, the key path and (where the file has it) the line:column, and the
//! loader reports all errors it finds, not just the first:
//!
//! ```
//! let text = std::fs::read_to_string("../testdata/peanut-pods-saline/study.toml").unwrap();
//! let bad = text.replace("[parameters.\"pod-pod.static_friction\"]", "[parameters.\"pod-pod.static_fricton\"]");
//! let path = std::path::Path::new("../testdata/peanut-pods-saline/study.toml");
//! let err = arachis::study::Study::from_toml(&bad, path).unwrap_err();
//! let msg = err.to_string();
//! assert!(msg.contains(r#"parameters."pod-pod.static_fricton": unknown parameter"#));
//! assert!(msg.contains("did you mean 'pod-pod.static_friction'?"));
//! ```
//!
//! The format is built to grow without breaking files (issues 5 and 6): measurements carry
//! a `condition` table so one experiment can be measured at several conditions; materials
//! and pairs are named maps, so a plant study adds `stalk`, `stem` and their pairs; the
//! parameter, quantity and condition registries are single tables that later effects extend.

pub mod decode;
pub mod error;
pub mod file_format;
pub mod key_path;
pub mod measurements;
pub mod nearest_name;
pub mod parameters;
pub mod plan;
pub mod plan_settings;
pub mod run_spec;
pub(crate) mod source;
pub mod stl_check;
pub mod summary;
pub mod validate;

use std::path::{Path, PathBuf};

use serde::Serialize;

pub use error::{StudyError, StudyErrors};
pub use file_format::StudyFile;
pub use key_path::KeyPath;
pub use measurements::{Experiment, Measurement};
pub use nearest_name::nearest_name;
pub use parameters::{ParameterRange, ParameterSpec, REGISTRY};
pub use run_spec::RunSpec;

use parameters::Owner;
use source::Source;

/// A study that has passed every check. Only [`Study::load`] and [`Study::from_toml`] make
/// one, so holding a `Study` means the file is valid.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    path: PathBuf,
    file: StudyFile,
}

/// A parameter the study varies, with its range and report label.
#[derive(Debug, Clone, PartialEq)]
pub struct Varied<'a> {
    /// The registry entry.
    pub spec: &'static ParameterSpec,
    /// The range in the study.
    pub range: &'a ParameterRange,
    /// The report label (the study's, else the registry's).
    pub label: String,
}

/// The text of the study file at `path`, or the error naming it.
pub(crate) fn read_study_text(path: &Path) -> Result<String, StudyErrors> {
    std::fs::read_to_string(path).map_err(|e| {
        StudyErrors(vec![StudyError {
            file: path.to_owned(),
            key: KeyPath::root(),
            position: None,
            reason: format!("cannot read the study file: {e}"),
        }])
    })
}

impl Study {
    /// Reads, parses and validates the study at `path`.
    pub fn load(path: &Path) -> Result<Self, StudyErrors> {
        Self::from_toml(&read_study_text(path)?, path)
    }

    /// Parses and validates `text` as if read from `path` (which names the file in messages
    /// and anchors relative STL paths).
    pub fn from_toml(text: &str, path: &Path) -> Result<Self, StudyErrors> {
        let src = Source::parse(path, text).map_err(|e| StudyErrors(e).sorted())?;
        let file = decode::decode_file(&src).map_err(|e| StudyErrors(e).sorted())?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let errors = validate::validate(&src, &file, dir);
        if errors.is_empty() {
            Ok(Self {
                path: path.to_owned(),
                file,
            })
        } else {
            Err(StudyErrors(errors).sorted())
        }
    }

    /// The file it was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The validated content.
    pub fn file(&self) -> &StudyFile {
        &self.file
    }

    /// The measurement the plan's target names (validation guarantees exactly one).
    pub fn target(&self) -> &Measurement {
        let t = &self.file.plan.target;
        self.find(t.experiment, &t.quantity, &t.condition)
    }

    /// The measurement the plan's validation names.
    pub fn validation(&self) -> &Measurement {
        let v = &self.file.plan.validation;
        self.find(v.experiment, &v.quantity, &v.condition)
    }

    fn find(
        &self,
        experiment: Experiment,
        quantity: &str,
        condition: &std::collections::BTreeMap<String, f64>,
    ) -> &Measurement {
        self.file
            .measurements
            .iter()
            .find(|m| m.matches(experiment, quantity, condition))
            .expect("validated: exactly one measurement matches")
    }

    /// The varied parameters, in registry order (seed 000 Table 3's x1…x8).
    pub fn varied(&self) -> Vec<Varied<'_>> {
        REGISTRY
            .iter()
            .filter_map(|spec| {
                self.file.parameters.get(spec.name).map(|range| Varied {
                    spec,
                    range,
                    label: range.label.clone().unwrap_or_else(|| spec.label.to_owned()),
                })
            })
            .collect()
    }

    /// The value the study gives for `spec` in its material or pair, if any.
    pub fn base_value(&self, spec: &ParameterSpec) -> Option<f64> {
        match spec.owner {
            Owner::Material(m) => self
                .file
                .materials
                .get(m)
                .and_then(|mat| match spec.property {
                    "poisson" => Some(mat.poisson),
                    "shear_modulus_pa" => Some(mat.shear_modulus_pa),
                    "density_kg_m3" => Some(mat.density_kg_m3),
                    _ => None,
                }),
            Owner::Pair(p) => self
                .file
                .pairs
                .get(p)
                .and_then(|pair| pair.property(spec.property)),
        }
    }

    /// The value held when `spec` is not being varied: the study's value, else the centre
    /// of its range (seed 000 §3.4 holds x1, x2, x6–x8 at their ranges' centres). `None`
    /// when the study has neither (the parameter's owner is absent).
    pub fn held_value(&self, spec: &ParameterSpec) -> Option<f64> {
        self.base_value(spec).or_else(|| {
            self.file
                .parameters
                .get(spec.name)
                .map(ParameterRange::centre)
        })
    }

    /// Scanned STL paths, resolved against the study file's directory.
    pub fn stl_paths(&self) -> Vec<(&'static str, PathBuf)> {
        let dir = self.path.parent().unwrap_or(Path::new("."));
        self.file
            .pods
            .stl
            .entries()
            .into_iter()
            .map(|(shape, p)| (shape, dir.join(p)))
            .collect()
    }

    /// The study written back as TOML (comments are not kept).
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(&self.file).expect("a validated study serialises")
    }

    /// The validated study as pretty JSON: the file's content plus the derived numbers a
    /// report needs (target value, varied parameters with labels and centres, dummies).
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.export()).expect("a validated study serialises")
    }

    /// Writes [`Study::to_json`] to `path` atomically (never a half-written file).
    pub fn write_json(&self, path: &Path) -> anyhow::Result<()> {
        crate::io::write_string_atomic(path, &self.to_json())
    }

    fn export(&self) -> StudyExport<'_> {
        let target = self.target();
        let validation = self.validation();
        StudyExport {
            format: STUDY_JSON_FORMAT,
            study: &self.file,
            derived: Derived {
                target_value: target.mean().unwrap_or(f64::NAN),
                target_replicates: target.replicates(),
                target_replicates_printed: target.has_replicates(),
                validation_value: validation.mean().unwrap_or(f64::NAN),
                screening_dummies: self.file.plan.screening.design.columns()
                    - self.file.parameters.len() as u32,
                varied: self
                    .varied()
                    .into_iter()
                    .map(|v| VariedExport {
                        name: v.spec.name,
                        label: v.label,
                        unit: v.spec.unit,
                        low: v.range.low,
                        high: v.range.high,
                        centre: v.range.centre(),
                    })
                    .collect(),
            },
        }
    }
}

/// Format tag of [`Study::to_json`].
pub const STUDY_JSON_FORMAT: &str = "arachis-study-1";

#[derive(Serialize)]
struct StudyExport<'a> {
    format: &'static str,
    study: &'a StudyFile,
    derived: Derived,
}

#[derive(Serialize)]
struct Derived {
    target_value: f64,
    target_replicates: Option<u32>,
    target_replicates_printed: bool,
    validation_value: f64,
    screening_dummies: u32,
    varied: Vec<VariedExport>,
}

#[derive(Serialize)]
struct VariedExport {
    name: &'static str,
    label: String,
    unit: &'static str,
    low: f64,
    high: f64,
    centre: f64,
}
