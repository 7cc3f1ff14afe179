//! Stage 2: the path of steepest ascent (seed 000 §3.4, Table 6).
//!
//! The path moves the carried factors along the screening fit's gradient (their coded
//! coefficients bᵢ in the screening coding), the largest-|b| factor by `step_coded` per
//! point (`doe::steepest_ascent`); every other parameter is held at the study's value, or
//! without one at its range's centre ([`crate::study::Study::held_value`]; seed 000 §3.4
//! holds x1, x2, x6, x7, x8 at 0.386, 3.04 MPa, 0.339, 0.589, 0.159).
//!
//! Which way: toward the target. The path climbs from the corner of the carried factors
//! where the screening fit predicts its lowest response (each factor at
//! `origin_coded`·sign(bᵢ); −1 gives seed 000's start at the low levels), unless the target
//! lies below even that prediction; then it descends from the highest corner. The best
//! point is the one whose response is nearest the target (seed 000 Table 6: point 3,
//! ψ = 1.35 %); the report says when that is the last point of the path, where the target
//! may lie beyond it.

use serde::Serialize;

use super::screening::{FactorInfo, Screening};
use super::{planned_runs, CalibrateError, RunRecord, Runner, TargetInfo};
use crate::doe::{steepest_ascent, Factor};
use crate::stats::relative_error_percent;
use crate::study::parameters::lookup;

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "steepest ascent";

/// The path stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteepestAscent {
    /// The carried factors (screening coding).
    pub factors: Vec<FactorInfo>,
    /// Their screening coefficients, response units per coded unit.
    pub coefficients: Vec<f64>,
    /// "ascent" or "descent".
    pub direction: String,
    /// Screening-fit prediction at the path's origin, response units.
    pub predicted_at_origin: f64,
    /// Coded start of each factor.
    pub origin_coded: Vec<f64>,
    /// Coded change of each factor per point.
    pub step_coded: Vec<f64>,
    /// The path points in order (coded in the screening coding).
    pub runs: Vec<RunRecord>,
    /// ψ = |ζ′ − ζ|/ζ × 100 % of each point against the target (seed 000 eq. (21)).
    pub relative_error_pct: Vec<f64>,
    /// 1-based number of the point nearest the target.
    pub best: usize,
    /// The best point is the path's last.
    pub best_at_path_end: bool,
    /// Decisions the report must state.
    pub notes: Vec<String>,
}

impl SteepestAscent {
    /// Coded point `m` of the path (0 = origin; may lie before or past the run points).
    pub fn coded_point(&self, m: f64) -> Vec<f64> {
        self.origin_coded
            .iter()
            .zip(&self.step_coded)
            .map(|(o, d)| o + m * d)
            .collect()
    }

    /// Actual values of coded path point `coded`, one per factor.
    pub fn actual_point(&self, coded: &[f64]) -> Vec<f64> {
        self.factors
            .iter()
            .zip(coded)
            .map(|(f, &x)| 0.5 * (f.low + f.high) + x * 0.5 * (f.high - f.low))
            .collect()
    }
}

/// +1 for non-negative, −1 for negative.
fn sign(v: f64) -> f64 {
    if v < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// Runs stage 2.
pub fn run(
    runner: &Runner<'_>,
    target: &TargetInfo,
    screening: &Screening,
) -> Result<SteepestAscent, CalibrateError> {
    let study = runner.study();
    let plan = &study.file().plan.steepest_ascent;
    let carried = screening.selected_factors();
    let factors: Vec<FactorInfo> = carried.iter().map(|(f, _)| (*f).clone()).collect();
    let b: Vec<f64> = carried.iter().map(|(_, b)| *b).collect();
    // The screening fit with every other factor at its held value (coded).
    let mut base = screening.intercept;
    for (f, e) in screening.factors.iter().zip(&screening.effects) {
        if screening.selected.contains(&f.label) {
            continue;
        }
        let held = lookup(&f.name)
            .and_then(|s| study.held_value(s))
            .unwrap_or(0.5 * (f.low + f.high));
        base += e.coefficient * (held - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low));
    }
    let predict = |x: &[f64]| base + b.iter().zip(x).map(|(b, x)| b * x).sum::<f64>();
    let lowest: Vec<f64> = b.iter().map(|bi| -sign(*bi)).collect();
    let ascend = target.value >= predict(&lowest);
    let gradient: Vec<f64> = b.iter().map(|bi| if ascend { *bi } else { -bi }).collect();
    let origin: Vec<f64> = gradient
        .iter()
        .map(|g| plan.origin_coded * sign(*g))
        .collect();
    let doe_factors = factors
        .iter()
        .map(FactorInfo::factor)
        .collect::<Result<Vec<Factor>, _>>()
        .map_err(|source| CalibrateError::Design {
            stage: STAGE,
            source,
        })?;
    let design = steepest_ascent(
        &doe_factors,
        &gradient,
        &origin,
        plan.step_coded,
        plan.points as usize,
    )
    .map_err(|source| CalibrateError::Design {
        stage: STAGE,
        source,
    })?;
    let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    let step: Vec<f64> = gradient
        .iter()
        .map(|g| plan.step_coded * g / largest)
        .collect();
    let planned = planned_runs(&factors, &design);
    let runs = runner.run_batch(STAGE, target.experiment, &target.condition, &planned)?;
    let errors: Vec<f64> = runs
        .iter()
        .map(|r| relative_error_percent(r.response, target.value))
        .collect();
    let best = (0..runs.len())
        .min_by(|&a, &b| errors[a].total_cmp(&errors[b]))
        .unwrap_or(0);
    let at_end = best + 1 == runs.len();
    let mut notes = Vec::new();
    if at_end {
        notes.push(format!(
            "the best point is the path's last (point {}): the target may lie beyond the path, \
             so the Box–Behnken box reaches one step past it",
            best + 1
        ));
    }
    if best == 0 {
        notes.push(
            "the best point is the path's first: the response moved away from the target \
             along the whole path"
                .to_owned(),
        );
    }
    Ok(SteepestAscent {
        factors,
        coefficients: b.clone(),
        direction: if ascend { "ascent" } else { "descent" }.to_owned(),
        predicted_at_origin: predict(&origin),
        origin_coded: origin,
        step_coded: step,
        runs,
        relative_error_pct: errors,
        best: best + 1,
        best_at_path_end: at_end,
        notes,
    })
}
