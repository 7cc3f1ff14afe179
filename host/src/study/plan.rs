//! The calibration plan (`[plan]` and its sub-tables): the sequence of designs, the target,
//! validation, and — for a pod study — run modes and simulation settings.
//!
//! The sequence (seed 000 §3.3–3.6, seed 001 §3.1–3.2, issue 4 §4):
//! 1. `[plan.screening]`: a Plackett–Burman design over every varied parameter, the unused
//!    columns kept as dummies for the error estimate (seed 000 §3.3: 8 factors in 12 runs,
//!    3 dummies), with optional centre points (seed 001 Table 6: 3); factors with
//!    p < `significance` are significant, and those at p ≤ `carry_level` (default: the
//!    significant ones) go on.
//! 2. `[plan.steepest_ascent]`: `points` points from coded `origin_coded` (default −1, the
//!    low levels), the largest-effect factor moving `step_coded` per point (seed 000
//!    Table 6, seed 001 Table 8). Parameters that did not pass screening are held at the
//!    study's value (or, without one, the centre of their range). With `max_points` the path
//!    goes on when its planned points fall short ([`PathExtension`]).
//! 3. The response surface, one of:
//!    - `[plan.box_behnken]`: around the two consecutive path points whose responses
//!      bracket the target (seed 000 §3.4), with `centre_points` replicated centres (seed
//!      000 Table 8: 5), and `[plan.model]` (seed 000 eq. (22): quadratic);
//!    - `[plan.central_composite]`: around the best path point with its neighbours at ±1,
//!      axial points at ±`alpha` (seed 001 Tables 9–10), `centre_points` centres, a
//!      quadratic model; `factors` may name the factors it takes (seed 001 §3.1: X7, X8)
//!      with `why`.
//! 4. `[plan.optimisation]`: `goal = "target"`, desirability toward the target (the one goal;
//!    the table may be left out).
//! 5. `[plan.target]`: the measurement the optimum must hit (seed 000 §3.6.1: 31.06°);
//!    left out, the study's one measurement.
//! 6. `[plan.validation]`: the measurement the optimum is run against (left out: the
//!    target's), the largest accepted relative error ψ = |ζ′ − ζ|/ζ × 100 % (seed 000
//!    eq. (21)) and the replicates averaged.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::rigs::pod_world::settings::{Mode, ReposeSettings, Simulation};

/// `[plan]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// The run mode used unless the command line picks another (a key of `modes`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mode: Option<String>,
    /// Screening design.
    pub screening: Screening,
    /// Path of steepest ascent.
    pub steepest_ascent: SteepestAscent,
    /// Box–Behnken response surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub box_behnken: Option<BoxBehnken>,
    /// Central composite response surface.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub central_composite: Option<CentralComposite>,
    /// Response-surface model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub model: Option<Model>,
    /// The optimisation goal.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub optimisation: Option<Optimisation>,
    /// The calibration target.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub target: Option<Target>,
    /// The validation run.
    pub validation: Validation,
    /// Named run modes (`quick`, `full`) of a pod study.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub modes: BTreeMap<String, Mode>,
    /// Simulation settings shared by every run of a pod study.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulation: Option<Simulation>,
}

/// The keys of `[plan]`, in the order they are decoded.
pub const PLAN_KEYS: [&str; 11] = [
    "mode",
    "screening",
    "steepest_ascent",
    "box_behnken",
    "central_composite",
    "model",
    "optimisation",
    "target",
    "validation",
    "modes",
    "simulation",
];

/// Plackett–Burman designs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ScreeningDesign {
    /// 12 runs, 11 columns.
    Pb12,
    /// 20 runs, 19 columns.
    Pb20,
    /// 12 or 20 runs, as `runs` says (seed 001's study).
    PlackettBurman,
}

/// The Plackett–Burman run counts available.
pub const PLACKETT_BURMAN_RUNS: [u32; 2] = [12, 20];

/// `[plan.screening]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Screening {
    /// The design.
    pub design: ScreeningDesign,
    /// Runs of a `plackett_burman` design (12 or 20).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub runs: Option<u32>,
    /// Dummy columns; when given, must equal columns − varied parameters (a check that the
    /// file and the design agree).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dummies: Option<u32>,
    /// Centre points added to the design (seed 001 Table 6 has 3; seed 000 none).
    #[serde(default)]
    pub centre_points: u32,
    /// Significance level α: a factor is significant when p < α.
    pub significance: f64,
    /// A factor goes on when p ≤ this level (seed 001 Table 7: 0.01); absent, the
    /// significant ones go on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub carry_level: Option<f64>,
}

impl Screening {
    /// Runs without centre points: 12 or 20 (a `plackett_burman` design without a valid
    /// `runs` reads as 12; validation reports it).
    pub fn design_runs(&self) -> u32 {
        match (self.design, self.runs) {
            (ScreeningDesign::Pb20, _) | (ScreeningDesign::PlackettBurman, Some(20)) => 20,
            _ => 12,
        }
    }

    /// Two-level columns (factors + dummies).
    pub fn columns(&self) -> u32 {
        self.design_runs() - 1
    }
}

/// How the path goes on when its planned points fall short of the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PathExtension {
    /// Gaps doubling, two points at a time, until a response crosses the target (seed
    /// 000's study; the default with a Box–Behnken design).
    Doubling,
    /// One step at a time while the point nearest the target is the last (seed 001's
    /// study; the default with a central composite design).
    SingleSteps,
}

/// `[plan.steepest_ascent]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteepestAscent {
    /// Points on the path, the origin included.
    pub points: u32,
    /// Coded step of the largest-effect factor per point.
    pub step_coded: f64,
    /// Coded start of every carried factor (−1 = low level, the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub origin_coded: Option<f64>,
    /// The longest path when the planned points fall short; absent, the path stops at
    /// `points` (seed 000 Table 6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_points: Option<u32>,
    /// How the path goes on (default: the response-surface design's, [`PathExtension`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extension: Option<PathExtension>,
}

/// Coded start of the path when `origin_coded` is absent: the low levels.
pub const DEFAULT_ORIGIN_CODED: f64 = -1.0;

/// `[plan.box_behnken]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxBehnken {
    /// Replicated centre points (the pure-error estimate needs ≥ 2).
    pub centre_points: u32,
}

/// `[plan.central_composite]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CentralComposite {
    /// The factors of the design (and of the path), by label; absent: the screening's
    /// choice.
    #[serde(default)]
    pub factors: Option<Vec<String>>,
    /// Why these factors (stated in the report).
    #[serde(default)]
    pub why: Option<String>,
    /// Axial distance α, coded.
    pub alpha: f64,
    /// Centre points.
    pub centre_points: u32,
}

/// Response-surface model orders.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModelOrder {
    /// Main effects only.
    Linear,
    /// Main effects and two-factor interactions.
    Interaction,
    /// Full second order (seed 000 eq. (22)).
    Quadratic,
}

/// `[plan.model]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Model {
    /// Model order.
    pub order: ModelOrder,
}

/// The one optimisation goal: desirability toward the target.
pub const GOAL_TARGET: &str = "target";

/// `[plan.optimisation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Optimisation {
    /// [`GOAL_TARGET`].
    pub goal: String,
}

/// `[plan.target]`: which measurement the optimisation aims at. Its value is the
/// measurement's mean, never repeated here.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// The experiment (a rig's name).
    pub experiment: String,
    /// The quantity.
    pub quantity: String,
    /// Narrows the choice when the experiment was measured at several conditions.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub condition: BTreeMap<String, f64>,
}

/// `[plan.validation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Validation {
    /// The experiment (default: the target's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub experiment: Option<String>,
    /// The quantity (default: the target's).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub quantity: Option<String>,
    /// Narrows the choice when the experiment was measured at several conditions.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub condition: BTreeMap<String, f64>,
    /// Largest accepted relative error ψ, % (seed 000 eq. (21)).
    pub max_relative_error_pct: f64,
    /// Independent runs of the optimum, averaged (default
    /// [`DEFAULT_VALIDATION_REPLICATES`]; one for a rig without random placement).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replicates: Option<u32>,
}

/// Runs of the optimum when `[plan.validation] replicates` is absent.
pub const DEFAULT_VALIDATION_REPLICATES: u32 = 3;
