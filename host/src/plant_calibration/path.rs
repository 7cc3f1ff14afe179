//! Stage 2: the path of steepest ascent in the carried factors (seed 001 §3.1, Table 8).
//!
//! The path follows the screening fit's gradient toward the target: it starts at the
//! carried factors' corner where the fit predicts the lowest force (seed 001 Table 8 starts
//! at the low levels, 3e5 N/m³ and 6e5 Pa) and climbs, the largest-|b| factor by
//! [`STEP_CODED`] per point (a quarter of its range, as Table 8), or descends from the
//! highest corner when the target lies below even the lowest prediction. Every other factor
//! is held at its range centre. The seed's five points are run first; while the best point
//! (the one nearest the target, seed 001 Table 8's relative error) is the last, the path
//! goes on one point at a time, up to [`MAX_POINTS`]: the plan wants the point where the
//! error stops falling, and the seed's own ranges need not contain the target.

use serde::Serialize;

use super::plan::Plan;
use super::screening::Screening;
use super::simulator::PullOffSimulator;
use super::{PlantCalibrationError, RunRecord};
use crate::calibrate::Progress;
use crate::doe::{steepest_ascent, Factor};
use crate::stats::relative_error_percent;

/// Stage name.
pub const STAGE: &str = "steepest ascent";
/// Coded step of the largest-|b| factor per point (seed 001 Table 8: 1e5 N/m³ of 3e5–7e5).
pub const STEP_CODED: f64 = 0.5;
/// Points run at once (seed 001 Table 8).
pub const FIRST_POINTS: usize = 5;
/// Longest path.
pub const MAX_POINTS: usize = 12;

/// The path stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteepestPath {
    /// Carried labels, in path column order.
    pub factors: Vec<String>,
    /// Their screening coefficients, N per coded unit.
    pub coefficients: Vec<f64>,
    /// "ascent" or "descent".
    pub direction: String,
    /// Coded (screening coding) start.
    pub origin_coded: Vec<f64>,
    /// Coded change per point.
    pub step_coded: Vec<f64>,
    /// The points in order; `coded` in the screening coding of the carried factors.
    pub runs: Vec<RunRecord>,
    /// |F − T|/T × 100 % of each point (seed 001 Table 8's relative error).
    pub relative_error_pct: Vec<f64>,
    /// 1-based number of the point nearest the target.
    pub best: usize,
    /// Decisions the report must state.
    pub notes: Vec<String>,
}

impl SteepestPath {
    /// Actual values of the carried factors at coded path position `m` (0 = origin), in
    /// `plan`'s coding.
    pub fn actual_at(&self, plan: &Plan, m: f64) -> Vec<f64> {
        self.factors
            .iter()
            .zip(self.origin_coded.iter().zip(&self.step_coded))
            .map(|(l, (o, d))| {
                let f = plan
                    .factor(l)
                    .expect("carried labels are checked Table 5 labels");
                f.centre() + (o + m * d) * 0.5 * (f.high - f.low)
            })
            .collect()
    }
}

/// Runs stage 2 toward `target_n` (N).
pub fn run(
    sim: &PullOffSimulator,
    plan: &Plan,
    screening: &Screening,
    target_n: f64,
    progress: &Progress,
) -> Result<SteepestPath, PlantCalibrationError> {
    let labels = screening.carried.clone();
    let b: Vec<f64> = labels
        .iter()
        .map(|l| screening.effect(l).map_or(0.0, |e| e.coefficient))
        .collect();
    let lowest = screening.intercept - b.iter().map(|v| v.abs()).sum::<f64>();
    let ascend = target_n >= lowest;
    let g: Vec<f64> = b.iter().map(|v| if ascend { *v } else { -v }).collect();
    let origin: Vec<f64> = g.iter().map(|v| -v.signum()).collect();
    let factors = labels
        .iter()
        .map(|l| {
            plan.factor(l)
                .expect("carried labels are checked Table 5 labels")
                .factor()
        })
        .collect::<Result<Vec<Factor>, _>>()
        .map_err(|source| PlantCalibrationError::Design {
            stage: STAGE,
            source,
        })?;
    let design = steepest_ascent(
        &factors,
        &g,
        &origin,
        plan.path_step_coded,
        plan.path_max_points,
    )
    .map_err(|source| PlantCalibrationError::Design {
        stage: STAGE,
        source,
    })?;
    let largest = g.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let step: Vec<f64> = g
        .iter()
        .map(|v| plan.path_step_coded * v / largest)
        .collect();
    let setting = |i: usize| plan.settings_with(&labels, &design.actual_row(i));
    let first: Vec<[f64; 9]> = (0..plan.path_first_points).map(setting).collect();
    let mut outcomes = sim.run_batch(STAGE, &first, progress)?;
    let mut settings = first;
    let error = |f: f64| relative_error_percent(f, target_n);
    let mut notes = Vec::new();
    let best_of = |o: &[super::simulator::PullOutcome]| {
        (0..o.len())
            .min_by(|&a, &b| {
                error(o[a].detachment_force_n).total_cmp(&error(o[b].detachment_force_n))
            })
            .unwrap_or(0)
    };
    while best_of(&outcomes) + 1 == outcomes.len() && outcomes.len() < plan.path_max_points {
        let next = setting(outcomes.len());
        if let Some(reason) = plan
            .factors
            .iter()
            .zip(&next)
            .find_map(|(f, v)| f.check(*v).err())
        {
            notes.push(format!("the path stops: the next point has {reason}"));
            break;
        }
        outcomes.extend(sim.run_batch(STAGE, &[next], progress)?);
        settings.push(next);
    }
    let best = best_of(&outcomes);
    if outcomes.len() > plan.path_first_points {
        notes.push(format!(
            "the force was still approaching the target after the plan's {} points, so \
             the path went on to {} points",
            plan.path_first_points,
            outcomes.len()
        ));
    }
    if best + 1 == outcomes.len() {
        notes.push("the best point is the path's last: the target may lie beyond it".into());
    }
    let coded: Vec<Vec<f64>> = design.coded[..outcomes.len()].to_vec();
    Ok(SteepestPath {
        factors: labels,
        coefficients: b,
        direction: if ascend { "ascent" } else { "descent" }.to_owned(),
        origin_coded: origin,
        step_coded: step,
        runs: RunRecord::list(&coded, &settings, &outcomes),
        relative_error_pct: outcomes
            .iter()
            .map(|o| error(o.detachment_force_n))
            .collect(),
        best: best + 1,
        notes,
    })
}
