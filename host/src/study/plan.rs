//! The calibration plan: seed 000's sequence of designs, the target, validation, run modes
//! and simulation settings (`[plan]` and its sub-tables).
//!
//! The sequence (seed 000 §3.3–3.6, issue 4 §4):
//! 1. `[plan.screening]`: a Plackett–Burman design over every varied parameter, the unused
//!    columns kept as dummies for the error estimate (seed 000 §3.3: 8 factors in 12 runs,
//!    3 dummies); factors with p < `significance` go on.
//! 2. `[plan.steepest_ascent]`: `points` points from coded `origin_coded`, the
//!    largest-effect factor moving `step_coded` per point (seed 000 Table 6: 5 points from
//!    the low levels). Parameters that did not pass screening are held at their base value
//!    in the study (or, without one, the centre of their range); seed 000 §3.4's held values
//!    0.386, 3.04 MPa, 0.339, 0.589, 0.159 are those centres.
//! 3. `[plan.box_behnken]`: around the two consecutive path points whose responses bracket
//!    the target (seed 000 §3.4: the 2nd and 3rd points become −1 and +1), with
//!    `centre_points` replicated centres (seed 000 Table 8: 5).
//! 4. `[plan.model]`: the response-surface order (seed 000 eq. (22): quadratic).
//! 5. `[plan.target]`: the measurement the optimum must hit (seed 000 §3.6.1: 31.06°).
//! 6. `[plan.validation]`: the measurement the optimum is simulated against, and the largest
//!    accepted relative error ψ = |ζ′ − ζ|/ζ × 100 % (seed 000 eq. (21)).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use super::measurements::Experiment;

/// `[plan]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// The run mode used unless the command line picks another (a key of `modes`).
    pub mode: String,
    /// Screening design.
    pub screening: Screening,
    /// Path of steepest ascent.
    pub steepest_ascent: SteepestAscent,
    /// Box–Behnken design.
    pub box_behnken: BoxBehnken,
    /// Response-surface model.
    pub model: Model,
    /// The calibration target.
    pub target: Target,
    /// The validation run.
    pub validation: Validation,
    /// Named run modes (`quick`, `full`).
    pub modes: BTreeMap<String, Mode>,
    /// Simulation settings shared by every run.
    pub simulation: Simulation,
}

/// Plackett–Burman run counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ScreeningDesign {
    /// 12 runs, 11 columns.
    Pb12,
    /// 20 runs, 19 columns.
    Pb20,
}

impl ScreeningDesign {
    /// Two-level columns (factors + dummies).
    pub fn columns(self) -> u32 {
        match self {
            Self::Pb12 => 11,
            Self::Pb20 => 19,
        }
    }

    /// Runs without centre points.
    pub fn runs(self) -> u32 {
        self.columns() + 1
    }
}

/// `[plan.screening]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Screening {
    /// The design.
    pub design: ScreeningDesign,
    /// Dummy columns; when given, must equal columns − varied parameters (a check that the
    /// file and the design agree).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dummies: Option<u32>,
    /// Centre points added to the design (seed 001 Table 6 has 3; seed 000 none).
    #[serde(default)]
    pub centre_points: u32,
    /// Significance level α: a factor passes screening when p < α.
    pub significance: f64,
}

/// `[plan.steepest_ascent]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SteepestAscent {
    /// Points on the path, the origin included.
    pub points: u32,
    /// Coded step of the largest-effect factor per point.
    pub step_coded: f64,
    /// Coded start of every significant factor (−1 = low level).
    pub origin_coded: f64,
    /// When the response has not reached the target by the last of `points`, the path goes
    /// on, the gap between points doubling each time, until the response crosses the target,
    /// the factors reach their physical limits, or the path has this many points in all.
    /// Absent: the path stops at `points` (seed 000 Table 6).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_points: Option<u32>,
}

/// `[plan.box_behnken]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BoxBehnken {
    /// Replicated centre points (the pure-error estimate needs ≥ 2).
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

/// `[plan.target]`: which measurement the optimisation aims at. Its value is the
/// measurement's mean, never repeated here.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// The experiment.
    pub experiment: Experiment,
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
    /// The experiment.
    pub experiment: Experiment,
    /// The quantity.
    pub quantity: String,
    /// Narrows the choice when the experiment was measured at several conditions.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub condition: BTreeMap<String, f64>,
    /// Largest accepted relative error ψ, % (seed 000 eq. (21)).
    pub max_relative_error_pct: f64,
    /// Independent simulations of the optimum, averaged (default
    /// [`DEFAULT_VALIDATION_REPLICATES`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replicates: Option<u32>,
}

/// Simulations of the optimum when `[plan.validation] replicates` is absent.
pub const DEFAULT_VALIDATION_REPLICATES: u32 = 3;

impl Validation {
    /// Simulations of the optimum to average.
    pub fn replicates(&self) -> u32 {
        self.replicates.unwrap_or(DEFAULT_VALIDATION_REPLICATES)
    }
}

/// `[plan.modes.<name>]`: problem size.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mode {
    /// Pods generated per repose run.
    pub pods: u32,
    /// Spheres filling each pod shape.
    pub spheres_per_pod: u32,
}

/// `[plan.simulation]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Simulation {
    /// Time step as a fraction of the Rayleigh time T_R = πR√(ρ/G)/(0.1631ν + 0.8766)
    /// (DESIGN §2; seed 000 §2.7 uses 20 %).
    pub dt_rayleigh_fraction: f64,
    /// Broad-phase cell size in smallest sphere radii (seed 000 §2.7: 3R).
    pub grid_cell_radii: f64,
    /// Gravitational acceleration, m/s².
    pub gravity_m_s2: f64,
    /// Seed of the pseudo-random pod placement and orientation.
    pub random_seed: u64,
    /// Material of the cylinder, floor and plates (a `[materials]` key; seed 000 §2.4:
    /// 65Mn steel).
    pub wall_material: String,
    /// The repose (cylinder-lifting) experiment.
    pub repose: ReposeSettings,
}

/// `[plan.simulation.repose]`: the cylinder-lifting test (seed 000 §2.7).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReposeSettings {
    /// Inner diameter of the cylinder, mm.
    pub cylinder_diameter_mm: f64,
    /// Height of the cylinder, mm.
    pub cylinder_height_mm: f64,
    /// Time over which the pods are generated, s.
    pub fill_time_s: f64,
    /// Speed of the generated pods, m/s.
    pub fill_speed_m_s: f64,
    /// Time at which the cylinder starts to rise, s.
    pub lift_start_s: f64,
    /// Cylinder lifting speed, m/s.
    pub lift_speed_m_s: f64,
    /// Time the pile is left to settle after the cylinder has cleared it, s.
    pub settle_after_lift_s: f64,
}
