//! The typed view of a plant (pull-off) study file: one struct per TOML table, every key
//! unit-suffixed and in SI. Every table denies unknown keys, so a misspelt key is an error
//! rather than a silently ignored setting.
//!
//! Top level:
//! - `[study]` ([`Header`]): name, `kind = "pull_off"` (what makes `arachis calibrate` take
//!   this path), description, citation;
//! - `[rig]` ([`Rig`]): the tensile test — the topology whose bond sets it uses, and the
//!   pull's conditions;
//! - `[measurement]` ([`MeasuredForce`]): the detachment force to calibrate to;
//! - `[factors.x1]` … `[factors.x9]` ([`FactorLevels`]): seed 001 Table 5's factors with
//!   their low/high levels;
//! - `[plan]` ([`PlanSection`]): screening, steepest ascent, central composite design,
//!   optimisation, validation.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// The `kind` that marks a plant pull-off study.
pub const KIND_PULL_OFF: &str = "pull_off";

/// The top-level sections, in the order a plant study is written.
pub const SECTIONS: [&str; 5] = ["study", "rig", "measurement", "factors", "plan"];

/// `[study]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Header {
    /// Short name.
    pub name: String,
    /// [`KIND_PULL_OFF`].
    pub kind: String,
    /// What the study is.
    pub description: String,
    /// The paper the numbers come from.
    pub citation: String,
}

/// `[rig]`: the virtual tensile test (`arachis_core::scenario::PullOff`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rig {
    /// Plant topology file, relative to the study file; its `[bonds]` give the rig's sets.
    pub topology: String,
    /// The topology bond set of the pod–stalk junction.
    pub junction_bond_set: String,
    /// The topology bond set of the stalk's own bonds.
    pub stalk_bond_set: String,
    /// Spheres in the stalk (≥ 2; the first is clamped).
    pub stalk_spheres: u32,
    /// Gripper speed, m/s.
    pub pull_speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees (0 = axial).
    pub pull_angle_deg: f64,
}

/// `[measurement]`: the measured detachment force.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeasuredForce {
    /// What was measured (`"detachment_force"`).
    pub quantity: String,
    /// The force, N.
    pub value_n: f64,
    /// Where the number comes from.
    pub source: String,
}

/// `[factors.<label>]`: a Table 5 factor's levels, in SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FactorLevels {
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
    /// Where the numbers are printed.
    #[serde(default)]
    pub source: Option<String>,
}

/// `[plan]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSection {
    /// `[plan.screening]`.
    pub screening: Screening,
    /// `[plan.steepest_ascent]`.
    pub steepest_ascent: SteepestAscent,
    /// `[plan.central_composite]`.
    pub central_composite: CentralComposite,
    /// `[plan.optimisation]`.
    pub optimisation: Optimisation,
    /// `[plan.validation]`.
    pub validation: Validation,
}

/// `[plan.screening]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Screening {
    /// `"plackett_burman"`.
    pub design: String,
    /// Runs of the design (12 or 20).
    pub runs: usize,
    /// Centre points.
    pub centre_points: usize,
    /// p below it: significant.
    pub significance: f64,
    /// p at or below it: carried (when the plan names no factors).
    pub carry_level: f64,
}

/// `[plan.steepest_ascent]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteepestAscent {
    /// Coded step of the largest-|b| factor per point.
    pub step_coded: f64,
    /// Points run at once.
    pub points: usize,
    /// Longest path.
    pub max_points: usize,
}

/// `[plan.central_composite]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CentralComposite {
    /// The factors of the design (and of the path); absent: the screening's choice.
    #[serde(default)]
    pub factors: Option<Vec<String>>,
    /// Why these factors (stated in the report).
    #[serde(default)]
    pub why: Option<String>,
    /// Axial distance α, coded.
    pub alpha: f64,
    /// Centre points.
    pub centre_points: usize,
}

/// `[plan.optimisation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Optimisation {
    /// `"target"`: desirability toward the measured force.
    pub goal: String,
}

/// `[plan.validation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Validation {
    /// Pass mark, % relative error.
    pub max_relative_error_pct: f64,
}

/// The whole file, once every section has decoded.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantStudyFile {
    /// `[study]`.
    pub study: Header,
    /// `[rig]`.
    pub rig: Rig,
    /// `[measurement]`.
    pub measurement: MeasuredForce,
    /// `[factors]`, by label.
    pub factors: BTreeMap<String, FactorLevels>,
    /// `[plan]`.
    pub plan: PlanSection,
}
