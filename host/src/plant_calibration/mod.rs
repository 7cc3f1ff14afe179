//! `arachis plant-calibrate`: seed 001's bond-parameter calibration of the pod–stalk
//! junction on the virtual tensile test (issue 6 §4), end to end.
//!
//! 1. [`screening`]: Plackett–Burman, the nine factors of seed 001 Table 5 in 12 runs plus
//!    three centre points, first-order ANOVA with curvature (Tables 6–7);
//! 2. [`path`]: steepest ascent on the carried factors toward the target (Table 8);
//! 3. [`ccd`]: central composite design, α = 1.414, five centre points, around the best
//!    path point, quadratic ANOVA (Tables 9–11);
//! 4. [`optimum`]: desirability toward the target on the fitted surface, then a new
//!    pull-off at the optimum: the detachment force must be within 5 % of the target.
//!
//! Every response is a pull-off run ([`simulator::PullOffSimulator`], the core's
//! fixed-point rig, so the whole calibration is bit-reproducible). It shares the workflow
//! of `crate::calibrate` (seed 000) — designs from `doe`, ANOVA from `stats`, the
//! desirability search from `optimize`, the progress bar — but not its study files: the
//! factors here are bond parameters of one rig, fixed by seed 001 Table 5
//! ([`factors::TABLE5`]). No run cache: the whole plan is about 40 runs of a few
//! hundredths of a second each.

pub mod ccd;
pub mod error;
pub mod factors;
pub mod optimum;
pub mod path;
pub mod plan;
pub mod report;
pub mod screening;
pub mod simulator;

use serde::Serialize;

pub use error::PlantCalibrationError;
pub use plan::Plan;
pub use simulator::{PullOffArenas, PullOffSimulator, PullOutcome};

use crate::calibrate::Progress;

/// Format tag of `plant-calibration.json`.
pub const FORMAT: &str = "arachis-plant-calibration-1";

/// Target detachment force, N: implied by seed 001 Table 8, whose relative errors put every
/// simulated force against 7.18 N (5.17 N at 27.99 %: 5.17/(1 − 0.2799) = 7.18).
pub const TARGET_DETACHMENT_N: f64 = 7.18;

/// One pull-off run of a stage.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunRecord {
    /// Coded settings in the stage's coding.
    pub coded: Vec<f64>,
    /// The nine factors x1…x9 (SI units of seed 001 Table 5's factors).
    pub settings: Vec<f64>,
    /// Detachment force, N.
    pub detachment_force_n: f64,
    /// σc·πRb² of the run, N (the criterion's break force in pure tension).
    pub predicted_axial_n: f64,
}

impl RunRecord {
    /// Records of runs at `coded` rows with `settings` and their `outcomes`.
    pub fn list(coded: &[Vec<f64>], settings: &[[f64; 9]], outcomes: &[PullOutcome]) -> Vec<Self> {
        coded
            .iter()
            .zip(settings)
            .zip(outcomes)
            .map(|((c, s), o)| Self {
                coded: c.clone(),
                settings: s.to_vec(),
                detachment_force_n: o.detachment_force_n,
                predicted_axial_n: o.predicted_axial_n,
            })
            .collect()
    }
}

/// The rig's test conditions, for the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigInfo {
    /// Gripper speed, m/s.
    pub pull_speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees.
    pub pull_angle_deg: f64,
    /// Spheres in the stalk.
    pub stalk_spheres: u32,
    /// Junction normal stiffness per unit area (held), N/m³.
    pub junction_normal_stiffness_n_m3: f64,
}

/// Every number of a plant calibration (what `plant-calibration.json` holds).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantCalibration {
    /// [`FORMAT`].
    pub format: &'static str,
    /// The study file's name, when a study ran (`arachis calibrate STUDY`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub study: Option<String>,
    /// Target detachment force, N.
    pub target_n: f64,
    /// The plan that ran (factor levels, design settings, the named carry and why).
    pub plan: Plan,
    /// The rig.
    pub rig: RigInfo,
    /// Stage 1.
    pub screening: screening::Screening,
    /// Stage 2.
    pub path: path::SteepestPath,
    /// Stage 3.
    pub central_composite: ccd::CentralComposite,
    /// Stages 4–5.
    pub optimum: optimum::Optimum,
    /// Pull-off runs in all.
    pub runs: usize,
    /// Largest |F − σc·πRb²|/σc·πRb² over every run, %: how far the simulated force is from
    /// the criterion's break force in pure tension (exact only for an axial pull).
    pub axial_check_max_deviation_pct: f64,
}

/// Runs seed 001's plan ([`Plan::seed001`]) on `sim` toward `target_n` (N). `carry`
/// overrides the screening's choice of factors for the path and the response surface (e.g.
/// seed 001's x7, x8; 2 or 3 distinct Table 5 labels); the report says so.
pub fn calibrate(
    sim: &PullOffSimulator,
    target_n: f64,
    carry: Option<&[String]>,
    progress: &Progress,
) -> Result<PlantCalibration, PlantCalibrationError> {
    let mut plan = Plan::seed001();
    if let Some(c) = carry {
        plan::check_carry(c).map_err(|e| PlantCalibrationError::Plan(format!("--carry: {e}")))?;
        plan.carry = Some(c.to_vec());
        plan.carry_reason = Some("asked for on the command line (--carry)".into());
    }
    calibrate_plan(sim, target_n, &plan, progress)
}

/// Runs `plan` on `sim` toward `target_n` (N): screening, path, central composite,
/// optimum and validation. The plan is checked before any pull.
pub fn calibrate_plan(
    sim: &PullOffSimulator,
    target_n: f64,
    plan: &Plan,
    progress: &Progress,
) -> Result<PlantCalibration, PlantCalibrationError> {
    if !(target_n.is_finite() && target_n > 0.0) {
        return Err(PlantCalibrationError::Plan(format!(
            "the target detachment force must be a positive number of N, got {target_n}"
        )));
    }
    plan.check().map_err(PlantCalibrationError::Plan)?;
    let mut screening = screening::run(sim, plan, progress)?;
    if let Some(c) = &plan.carry {
        screening.notes.push(format!(
            "the path and the central composite design take {} ({}); the screening alone \
             would have carried {}",
            c.join(", "),
            plan.carry_reason.as_deref().unwrap_or("named by the plan"),
            screening.screening_choice.join(", ")
        ));
        screening.carried = c.clone();
    }
    let path = path::run(sim, plan, &screening, target_n, progress)?;
    let central_composite = ccd::run(sim, plan, &path, progress)?;
    let optimum = optimum::run(sim, plan, &central_composite, target_n)?;
    let all: Vec<&RunRecord> = screening
        .runs
        .iter()
        .chain(&path.runs)
        .chain(&central_composite.runs)
        .collect();
    let deviation = all
        .iter()
        .map(|r| crate::stats::relative_error_percent(r.detachment_force_n, r.predicted_axial_n))
        .fold(0.0_f64, f64::max);
    Ok(PlantCalibration {
        format: FORMAT,
        study: None,
        target_n,
        plan: plan.clone(),
        rig: RigInfo {
            pull_speed_m_s: sim.base.pull_speed_m_s,
            pull_angle_deg: sim.base.pull_angle_deg,
            stalk_spheres: sim.base.stalk_spheres,
            junction_normal_stiffness_n_m3: sim.base.junction.normal_stiffness_n_m3,
        },
        runs: all.len() + 1,
        axial_check_max_deviation_pct: deviation,
        screening,
        path,
        central_composite,
        optimum,
    })
}
