//! Every setting of a calibration plan: what a study's `[plan]` becomes once loaded. The
//! engine reads nothing else, so the same stages serve any rig.
//!
//! The two seeds differ in three rules, each kept as a setting rather than a second copy of
//! a stage:
//! - which factors go on after screening: the significant ones (p < α, seed 000 Table 5)
//!   or those at a stricter carry level (p ≤ 0.01, seed 001 Table 7), or the ones the plan
//!   names ([`NamedFactors`]);
//! - how a path that has not reached its target goes on ([`Extension`]);
//! - the response-surface design and its box ([`SurfaceDesign`]).

use crate::doe::PlackettBurmanRuns;
use crate::stats::ModelOrder;

/// The whole plan.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanSettings {
    /// Stage 1.
    pub screening: ScreeningSettings,
    /// Stage 2.
    pub path: PathSettings,
    /// Stage 3.
    pub surface: SurfaceSettings,
    /// Stage 5 (stage 4, the optimum, has no settings: its goal is the target).
    pub validation: ValidationSettings,
}

/// Factors a plan names for the path and the response surface, overriding the screening's
/// choice (seed 001 §3.1 carries X7 and X8).
#[derive(Debug, Clone, PartialEq)]
pub struct NamedFactors {
    /// Their labels, in the order the later stages take them.
    pub labels: Vec<String>,
    /// Why, in words, for the report.
    pub reason: String,
}

/// `[plan.screening]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ScreeningSettings {
    /// The Plackett–Burman design.
    pub runs: PlackettBurmanRuns,
    /// Centre points added (they split off the curvature term).
    pub centre_points: usize,
    /// Significance level α: a factor is significant when p < α.
    pub significance: f64,
    /// A factor goes on when p ≤ this level; `None`: when it is significant.
    pub carry_level: Option<f64>,
    /// Factors named by the plan, if any.
    pub named: Option<NamedFactors>,
}

/// How the path goes on when its planned points have not reached the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Extension {
    /// It does not: the path is the planned points (seed 000 Table 6).
    None,
    /// Gaps doubling from two steps (positions 6, 10, 18, … after the planned 0–4), two
    /// points at a time, until a response crosses the target, every factor is held by a
    /// limit, or the path has `max_points` points (seed 000's study, for a model whose
    /// response over the screened box misses the target).
    Doubling {
        /// Longest path, the origin included.
        max_points: usize,
    },
    /// One step at a time while the point nearest the target is the last one, up to
    /// `max_points` points; it stops where the next point would leave a physical limit
    /// (seed 001's study: the plan wants the point where the error stops falling).
    SingleSteps {
        /// Longest path, the origin included.
        max_points: usize,
    },
}

/// `[plan.steepest_ascent]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathSettings {
    /// Planned points, the origin included.
    pub points: usize,
    /// Coded step of the largest-|b| factor per point.
    pub step_coded: f64,
    /// Coded start of each factor, signed toward the low-response corner (−1: seed 000's
    /// low levels).
    pub origin_coded: f64,
    /// What happens when the planned points fall short.
    pub extension: Extension,
}

/// The response-surface design, each with the box its seed chose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceDesign {
    /// Box–Behnken around the two path points that bracket the target (seed 000 §3.4–3.5).
    BoxBehnken,
    /// Central composite with axial distance `alpha` (coded), centred on the best path
    /// point with its neighbours at ±1 (seed 001 Tables 9–10); the optimum is searched
    /// inside the star points.
    CentralComposite {
        /// Axial distance α, coded.
        alpha: f64,
    },
}

/// The response-surface stage.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSettings {
    /// The design.
    pub design: SurfaceDesign,
    /// Replicated centre points (pure error).
    pub centre_points: usize,
    /// The model fitted.
    pub model: ModelOrder,
}

/// `[plan.validation]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ValidationSettings {
    /// Independent runs of the optimum, averaged.
    pub replicates: u32,
    /// Largest accepted relative error ψ = |ζ′ − ζ|/ζ × 100 %, % (seed 000 eq. (21)).
    pub max_relative_error_pct: f64,
}
