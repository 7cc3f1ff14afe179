//! The typed view of a study file: one struct per TOML table, every key unit-suffixed and in
//! SI (or mm for pod geometry, as the seeds print it). Every table denies unknown keys, so
//! a misspelt key is an error rather than a silently ignored setting.
//!
//! One format for every study: a header, what the rigs simulate, the measurements, what a
//! calibration varies, and the plan. Which sections a study has depends on its rigs:
//! - `[study]` ([`StudyHeader`]): name, description, citation of the source paper (a
//!   `[diagnosis]` study names itself there instead);
//! - pods ([`crate::rigs::pod_world`]): `[materials.<name>]` ([`Material`]), `[pods]`
//!   ([`Pods`]) or `[spheres]` ([`Spheres`]), `[pairs."<a>-<b>"]` ([`Pair`]), with
//!   `[plan.modes]` and `[plan.simulation]`;
//! - the pull-off tensile test: `[rig]` ([`PullOffRigSection`]);
//! - measurements: `[[measurements]]` ([`Measurement`]: bench results with replicates at a
//!   condition), or the pull-off study's one `[measurement]` ([`MeasuredForce`]), or the
//!   experiments of `[diagnosis]` ([`DiagnosisSection`]) measured at several conditions;
//! - what varies: `[parameters."<name>"]` ([`ParameterRange`], by parameter name) or
//!   `[factors.<label>]` ([`FactorLevels`], the pull-off rig's parameters by seed 001
//!   Table 5 label);
//! - `[plan]` ([`Plan`]): the calibration plan;
//! - `[diagnosis.calibration]`: the current values of the single-sphere rigs' parameters.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::diagnosis::DiagnosisSection;
use super::measurements::Measurement;
use super::plan::Plan;
use super::pull_off::{FactorLevels, MeasuredForce, PullOffRigSection};
pub use crate::rigs::pod_world::parameters::ParameterRange;
pub use crate::rigs::pod_world::sections::{
    Material, Pair, Pods, ShapeMix, SizeClass, Spheres, StlPaths, PAIR_EFFECTS, PAIR_PROPERTIES,
};

/// The whole file. Absent sections are left out when it is written back.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyFile {
    /// `[study]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub study: Option<StudyHeader>,
    /// `[materials.<name>]`, by name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub materials: BTreeMap<String, Material>,
    /// `[pods]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pods: Option<Pods>,
    /// `[spheres]`: sphere particles in place of `[pods]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spheres: Option<Spheres>,
    /// `[pairs."<a>-<b>"]`, by pair name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub pairs: BTreeMap<String, Pair>,
    /// `[rig]`: the pull-off tensile test.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rig: Option<PullOffRigSection>,
    /// `[[measurements]]`, in file order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub measurements: Vec<Measurement>,
    /// `[measurement]`: a pull-off study's measured force.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub measurement: Option<MeasuredForce>,
    /// `[parameters."<name>"]`, by parameter name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub parameters: BTreeMap<String, ParameterRange>,
    /// `[factors.<label>]`, by label.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub factors: BTreeMap<String, FactorLevels>,
    /// `[plan]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plan: Option<Plan>,
    /// `[diagnosis]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub diagnosis: Option<DiagnosisSection>,
    /// `[priors]`: base parameters of the measured rigs measured on the bench, by parameter
    /// name (`"pod-pod.rolling_friction" = { mean = 0.335, sd = 0.012 }`), for a diagnosis
    /// of a calibration study (a `[diagnosis]` study states them under `[diagnosis.prior]`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub priors: BTreeMap<String, crate::study::diagnosis::Prior>,
}

impl StudyFile {
    /// `true` when the study describes particles for the pod rigs: `[pods]` or `[spheres]`.
    pub fn has_particles(&self) -> bool {
        self.pods.is_some() || self.spheres.is_some()
    }
}

/// The top-level sections, in the order a study file is written.
pub const SECTIONS: [&str; 13] = [
    "study",
    "materials",
    "pods",
    "spheres",
    "pairs",
    "rig",
    "measurements",
    "measurement",
    "parameters",
    "factors",
    "plan",
    "diagnosis",
    "priors",
];

/// The sections a pod study must have.
pub const POD_SECTIONS: [&str; 7] = [
    "study",
    "materials",
    "pods",
    "pairs",
    "measurements",
    "parameters",
    "plan",
];

/// The sections a pull-off study must have (`[measurement]` unless it has
/// `[[measurements]]`; `[factors]` and `[plan]` to be calibrated).
pub const PULL_OFF_SECTIONS: [&str; 3] = ["study", "rig", "measurement"];

/// `[study]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyHeader {
    /// Short name.
    pub name: String,
    /// `"pull_off"` in seed 001's study, which predates this format; it is checked against
    /// the study's rigs and otherwise not needed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    /// What the study is.
    pub description: String,
    /// The paper the numbers come from.
    pub citation: String,
}
