//! The study file (TOML), one format for every rig (issue 17): what the rigs simulate
//! (materials, pods and contact pairs; or the pull-off rig and its plant topology; or the
//! fixed single-sphere rigs), bench measurements with replicates at their conditions, the
//! parameters a calibration varies and over what ranges, and the calibration plan.
//! `testdata/peanut-pods-saline/study.toml` is seed 000's study,
//! `testdata/peanut-plant/study.toml` seed 001's, `testdata/diagnosis-tutorial/` the
//! diagnosis tutorial's ([`file_format`] lists the sections).
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
//! A loaded study builds its rigs from the rig catalogue ([`Study::rig`]) and its
//! calibration problem for the engine ([`problem`]); the diagnosis commands read its
//! measurements ([`Study::measurements`]) and current parameter values.

pub mod builtin;
pub mod decode;
pub mod diagnosis;
pub mod error;
pub mod file_format;
pub mod key_path;
pub mod measurements;
pub mod plan;
pub mod problem;
pub mod pull_off;
pub(crate) mod source;
pub mod summary;
pub mod validate;

use std::path::{Path, PathBuf};

use arachis_core::scenario::PullOff;
use serde::Serialize;

pub use crate::nearest_name::nearest_name;
pub use crate::rigs::pod_world::parameters;
pub use crate::rigs::pod_world::parameters::{ParameterRange, ParameterSpec, REGISTRY};
pub use crate::rigs::pod_world::{Experiment, RunSpec, Varied};
pub use error::{StudyError, StudyErrors};
pub use file_format::StudyFile;
pub use key_path::KeyPath;
pub use measurements::Measurement;

use crate::calibration::{Condition, ParameterValues, Rig, RigError};
use crate::plant::topology::BondSet;
use crate::rigs::kind::{RigOptions, Worlds};
use crate::rigs::pod_world::{
    ExperimentError, ModeName, Observation, ParameterSpec as Spec, Particles, PodWorld, RunOptions,
};
use crate::rigs::{catalogue, pod_bench};
use pull_off::ReadFile;
use source::Source;

/// A study that has passed every check. Only [`Study::load`] and [`Study::from_toml`] make
/// one, so holding a `Study` means the file is valid.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    path: PathBuf,
    file: StudyFile,
    measurements: Vec<Measurement>,
    /// The pull-off rig's junction and stalk bond sets, from its topology.
    bond_sets: Option<(BondSet, BondSet)>,
}

/// The text of the study file at `path`, or the error naming it.
pub(crate) fn read_study_text(path: &Path) -> Result<String, StudyErrors> {
    crate::io::text::read_text(path).map_err(|e| {
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
    /// and anchors relative paths).
    pub fn from_toml(text: &str, path: &Path) -> Result<Self, StudyErrors> {
        Self::from_toml_reading(text, path, &|p| crate::io::text::read_text(p))
    }

    /// Like [`Study::from_toml`], reading the files the study names (a plant topology)
    /// with `read` (a study built into the program serves its own).
    pub fn from_toml_reading(
        text: &str,
        path: &Path,
        read: ReadFile<'_>,
    ) -> Result<Self, StudyErrors> {
        let src = Source::parse(path, text).map_err(|e| StudyErrors(e).sorted())?;
        let file = decode::decode_file(&src).map_err(|e| StudyErrors(e).sorted())?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let (bond_sets, errors) = validate::validate(&src, &file, dir, read);
        if !errors.is_empty() || (file.rig.is_some() && bond_sets.is_none()) {
            return Err(StudyErrors(errors).sorted());
        }
        Ok(Self {
            path: path.to_owned(),
            measurements: measurements::study_measurements(&file),
            file,
            bond_sets,
        })
    }

    /// The file it was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The validated content.
    pub fn file(&self) -> &StudyFile {
        &self.file
    }

    /// The plan's default run mode (`[plan] mode`), if it names one.
    pub fn plan_mode(&self) -> Result<Option<ModeName>, ExperimentError> {
        self.file
            .plan
            .as_ref()
            .and_then(|p| p.mode.as_deref())
            .map(str::parse)
            .transpose()
    }

    /// The study's name (`[study] name`, or `[diagnosis] name`).
    pub fn name(&self) -> &str {
        match (&self.file.study, &self.file.diagnosis) {
            (Some(h), _) => &h.name,
            (None, Some(d)) => &d.name,
            (None, None) => "",
        }
    }

    /// Every measurement: `[[measurements]]`, `[measurement]` and the points of
    /// `[diagnosis]`, in that order.
    pub fn measurements(&self) -> &[Measurement] {
        &self.measurements
    }

    /// The measurements grouped into series of one rig's quantity at several conditions
    /// ([`measurements::study_series`]).
    pub fn series(&self) -> Vec<measurements::Series> {
        measurements::study_series(&self.file)
    }

    /// The measurement the plan's target names, or the study's only one (validation
    /// guarantees exactly one; `None` for a study without a plan and with several).
    pub fn target(&self) -> Option<&Measurement> {
        match self.file.plan.as_ref().and_then(|p| p.target.as_ref()) {
            Some(t) => self.find(&t.experiment, &t.quantity, &t.condition),
            None if self.measurements.len() == 1 => self.measurements.first(),
            None => None,
        }
    }

    /// The measurement the plan's validation names, else the target.
    pub fn validation(&self) -> Option<&Measurement> {
        let v = &self.file.plan.as_ref()?.validation;
        match (&v.experiment, &v.quantity) {
            (Some(e), Some(q)) => self.find(e, q, &v.condition),
            _ => self.target(),
        }
    }

    fn find(
        &self,
        experiment: &str,
        quantity: &str,
        condition: &Condition,
    ) -> Option<&Measurement> {
        self.measurements
            .iter()
            .find(|m| m.matches(experiment, quantity, condition))
    }

    /// The pod world, when the study has one.
    pub fn pod_world(&self) -> Option<PodWorld<'_>> {
        let f = &self.file;
        let plan = f.plan.as_ref()?;
        Some(PodWorld {
            materials: &f.materials,
            particles: match (&f.pods, &f.spheres) {
                (Some(pods), _) => Particles::Pods(pods),
                (None, Some(spheres)) => Particles::Spheres(spheres),
                (None, None) => return None,
            },
            pairs: &f.pairs,
            parameters: &f.parameters,
            modes: &plan.modes,
            simulation: plan.simulation.as_ref()?,
            dir: self.path.parent().unwrap_or(Path::new(".")),
        })
    }

    /// The pull-off rig's set-up, when the study has one: the default rig's geometry with
    /// the topology's bond sets and the study's pull.
    pub fn pull_off_setup(&self) -> Option<PullOff> {
        let (junction, stalk) = self.bond_sets.as_ref()?;
        Some(pull_off::rig_setup(
            self.file.rig.as_ref()?,
            junction,
            stalk,
        ))
    }

    /// What the study's rigs are built from.
    pub fn worlds(&self) -> Worlds<'_> {
        Worlds {
            pods: self.pod_world(),
            pull_off: self.pull_off_setup(),
            dir: self.path.parent(),
        }
    }

    /// The rig named `experiment` over this study.
    pub fn rig(
        &self,
        experiment: &str,
        options: &RigOptions,
    ) -> Result<Box<dyn Rig + '_>, RigError> {
        let kind = catalogue::find(experiment).ok_or_else(|| {
            RigError(format!(
                "no rig '{experiment}' (rigs: {})",
                catalogue::names().join(", ")
            ))
        })?;
        (kind.build)(&self.worlds(), options)
    }

    /// The current values of the single-sphere rigs' parameters (`[diagnosis.calibration]`),
    /// else the held values of the varied factors.
    pub fn current_values(&self) -> ParameterValues {
        match &self.file.diagnosis {
            Some(d) => d.calibration.values(),
            None => self
                .factors()
                .into_iter()
                .map(|f| (f.name, f.held))
                .collect(),
        }
    }

    /// The varied parameters of the pod world, in registry order (seed 000 Table 3's
    /// x1…x8); none without one.
    pub fn varied(&self) -> Vec<Varied<'_>> {
        self.pod_world().map(|w| w.varied()).unwrap_or_default()
    }

    /// The value held when `spec` is not varied ([`PodWorld::held_value`]).
    pub fn held_value(&self, spec: &Spec) -> Option<f64> {
        self.pod_world()?.held_value(spec)
    }

    /// Scanned STL paths, resolved against the study file's folder.
    pub fn stl_paths(&self) -> Vec<(&'static str, PathBuf)> {
        self.pod_world().map(|w| w.stl_paths()).unwrap_or_default()
    }

    /// The full specification of one pod run ([`PodWorld::run_spec`]).
    pub fn run_spec(
        &self,
        experiment: Experiment,
        condition: &Condition,
        values: &ParameterValues,
        mode: &str,
    ) -> Result<RunSpec, String> {
        self.pod_world()
            .ok_or_else(|| "the study has no pod world".to_owned())?
            .run_spec(experiment, condition, values, mode)
    }

    /// The condition of the study's first measurement of `experiment` (none when it has
    /// none): where a rig run outside a calibration stands.
    pub fn condition_of(&self, experiment: &str) -> Condition {
        self.measurements
            .iter()
            .find(|m| m.experiment == experiment)
            .map(|m| m.condition.clone())
            .unwrap_or_default()
    }

    /// Runs the pod bench test `experiment` directly at [`Study::condition_of`] it, for its
    /// whole observation (`arachis simulate`; [`crate::rigs::pod_bench::run_pod_test`]).
    pub fn run_experiment(
        &self,
        experiment: Experiment,
        values: &ParameterValues,
        mode: ModeName,
        seed: u64,
        options: &RunOptions,
    ) -> Result<Observation, ExperimentError> {
        let world = self.pod_world().ok_or_else(|| ExperimentError::Study {
            experiment: experiment.name(),
            reason: "the study has no pod world ([materials], [pods], [pairs], [plan.modes], \
                     [plan.simulation])"
                .into(),
        })?;
        pod_bench::run_pod_test(
            &world,
            catalogue::pod_test(experiment),
            &self.condition_of(experiment.name()),
            values,
            mode,
            seed,
            options,
        )
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
        let derived = self.file.plan.as_ref().map(|plan| {
            let target = self.target();
            let factors = self.factors();
            Derived {
                target_value: target.and_then(Measurement::mean).unwrap_or(f64::NAN),
                target_replicates: target.and_then(Measurement::replicates),
                target_replicates_printed: target.is_some_and(Measurement::has_replicates),
                validation_value: self
                    .validation()
                    .and_then(Measurement::mean)
                    .unwrap_or(f64::NAN),
                screening_dummies: plan
                    .screening
                    .columns()
                    .saturating_sub(factors.len() as u32),
                varied: factors
                    .into_iter()
                    .map(|f| VariedExport {
                        centre: f.centre(),
                        name: f.name,
                        label: f.label,
                        unit: f.unit,
                        low: f.low,
                        high: f.high,
                    })
                    .collect(),
            }
        });
        StudyExport {
            format: STUDY_JSON_FORMAT,
            study: &self.file,
            derived,
        }
    }
}

/// Format tag of [`Study::to_json`].
pub const STUDY_JSON_FORMAT: &str = "arachis-study-1";

#[derive(Serialize)]
struct StudyExport<'a> {
    format: &'static str,
    study: &'a StudyFile,
    #[serde(skip_serializing_if = "Option::is_none")]
    derived: Option<Derived>,
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
    name: String,
    label: String,
    unit: String,
    low: f64,
    high: f64,
    centre: f64,
}
