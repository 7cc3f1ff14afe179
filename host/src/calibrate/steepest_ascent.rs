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
//!
//! Going on past the planned points (`[plan.steepest_ascent] max_points`): seed 000's five
//! points suffice when its screening ranges bracket the target, but a model whose response
//! over those ranges misses the target (ours: every quick pile of the seed's ranges stands
//! at 35–54° against 31.06°) would end the path short of it. Then the path continues, the
//! gap between points doubling (positions 6, 10, 18, … after the planned 0–4), so the
//! target is reached in few runs even far outside the screened box, until a response
//! crosses the target, `max_points` are run, or every factor is held by a limit. Points are
//! run [`EXTENSION_BATCH`] at a time, a fixed number so the runs (and the JSON) do not
//! depend on the machine's core count.
//!
//! Limits on the path: inside its screened range a factor takes any value the study admits;
//! beyond it, only values inside the parameter's own physical limits
//! ([`crate::study::limits::Limits`], e.g. μ ≥ 0, ν < 0.5). A factor that would leave them stops at
//! the closed bound (μ at 0, e at 1) or, where the bound is open (ν < 0.5), at its screened
//! level on that side, while the other factors go on.

use serde::Serialize;

use super::screening::{FactorInfo, Screening};
use super::{planned_runs, CalibrateError, PlannedRun, RunRecord, Runner, TargetInfo};
use crate::doe::{steepest_ascent, Factor};
use crate::stats::relative_error_percent;
use crate::study::limits::Limits;
use crate::study::parameters::lookup;

/// Path points run together when the path goes on past the planned points.
pub const EXTENSION_BATCH: usize = 2;

/// Gap, in path steps, between the last planned point and the first extension point; each
/// later gap is twice the one before.
const FIRST_EXTENSION_GAP: f64 = 2.0;

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
    /// Path position of each run (0 = origin; 0, 1, … for the planned points, then the
    /// doubling gaps of an extension).
    pub positions: Vec<f64>,
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
    /// Coded point `m` of the path (0 = origin; may lie before or past the run points),
    /// each factor held at its limits as the module notes say.
    pub fn coded_point(&self, m: f64) -> Vec<f64> {
        self.factors
            .iter()
            .zip(self.origin_coded.iter().zip(&self.step_coded))
            .map(|(f, (o, d))| f.coded(f.admissible(f.actual(o + m * d))))
            .collect()
    }

    /// Path position of run `index` (0-based), extrapolated by the neighbouring gap for
    /// −1 and for one past the last run.
    pub fn position(&self, index: i64) -> f64 {
        let p = &self.positions;
        let gap = |a: usize, b: usize| p.get(b).zip(p.get(a)).map_or(1.0, |(b, a)| b - a);
        match usize::try_from(index) {
            Ok(i) if i < p.len() => p[i],
            Ok(_) => p.last().copied().unwrap_or(0.0) + gap(p.len().saturating_sub(2), p.len() - 1),
            Err(_) => p.first().copied().unwrap_or(0.0) - gap(0, 1),
        }
    }

    /// Actual values of coded path point `coded`, one per factor.
    pub fn actual_point(&self, coded: &[f64]) -> Vec<f64> {
        self.factors
            .iter()
            .zip(coded)
            .map(|(f, &x)| f.actual(x))
            .collect()
    }
}

impl FactorInfo {
    /// The value of coded level `x` in this factor's coding, in its unit.
    pub fn actual(&self, x: f64) -> f64 {
        0.5 * (self.low + self.high) + x * 0.5 * (self.high - self.low)
    }

    /// The coded level of `value` in this factor's coding.
    pub fn coded(&self, value: f64) -> f64 {
        (value - 0.5 * (self.low + self.high)) / (0.5 * (self.high - self.low))
    }

    /// `value` where the path may take it (module notes): unchanged inside the screened
    /// range or the parameter's physical limits, else the nearest closed bound or the
    /// screened level on that side.
    pub fn admissible(&self, value: f64) -> f64 {
        let limits = lookup(&self.name).map_or(Limits::NonNegative, |s| s.limits);
        if (self.low..=self.high).contains(&value) || limits.check(value).is_ok() {
            return value;
        }
        let edge = if value > self.high {
            self.high
        } else {
            self.low
        };
        limits.nearest_admissible(value).unwrap_or(edge)
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
    let mut path = SteepestAscent {
        factors,
        coefficients: b.clone(),
        direction: if ascend { "ascent" } else { "descent" }.to_owned(),
        predicted_at_origin: predict(&origin),
        origin_coded: origin,
        step_coded: step,
        positions: (0..planned.len()).map(|m| m as f64).collect(),
        runs: runner.run_batch(STAGE, target.experiment, &target.condition, &planned)?,
        relative_error_pct: Vec::new(),
        best: 0,
        best_at_path_end: false,
        notes: Vec::new(),
    };
    let max_points = plan.max_points.map_or(0, |m| m as usize);
    let first_side = path.runs.first().map(|r| r.response >= target.value);
    let mut gap = FIRST_EXTENSION_GAP;
    let mut held = false;
    while path.runs.len() < max_points
        && path
            .runs
            .iter()
            .all(|r| Some(r.response >= target.value) == first_side)
    {
        let mut batch = Vec::new();
        let mut last = path.coded_point(path.position(path.runs.len() as i64 - 1));
        while batch.len() < EXTENSION_BATCH && path.runs.len() + batch.len() < max_points {
            let m = path.positions.last().copied().unwrap_or(0.0) + gap;
            let coded = path.coded_point(m);
            if coded == last {
                held = true;
                break;
            }
            gap *= 2.0;
            path.positions.push(m);
            let values = path
                .factors
                .iter()
                .zip(path.actual_point(&coded))
                .map(|(f, v)| (f.name.clone(), v))
                .collect();
            last = coded.clone();
            batch.push(PlannedRun {
                coded,
                values,
                replicate: 0,
            });
        }
        if batch.is_empty() {
            break;
        }
        let first = path.runs.len();
        let records = runner.run_batch(STAGE, target.experiment, &target.condition, &batch)?;
        path.runs
            .extend(records.into_iter().enumerate().map(|(i, mut r)| {
                r.run = first + i + 1;
                r
            }));
    }
    if path.runs.len() > planned.len() {
        path.notes.push(format!(
            "the planned {} points did not reach the target, so the path went on with \
             doubling gaps to {} points (positions {:?})",
            planned.len(),
            path.runs.len(),
            &path.positions[planned.len()..]
        ));
    }
    if held {
        path.notes.push(
            "the path stopped where every factor is held by a physical limit or its \
             screened level"
                .to_owned(),
        );
    }
    let runs = &path.runs;
    let errors: Vec<f64> = runs
        .iter()
        .map(|r| relative_error_percent(r.response, target.value))
        .collect();
    let best = (0..runs.len())
        .min_by(|&a, &b| errors[a].total_cmp(&errors[b]))
        .unwrap_or(0);
    let at_end = best + 1 == runs.len();
    if at_end {
        path.notes.push(format!(
            "the best point is the path's last (point {}): the target may lie beyond the path, \
             so the Box–Behnken box reaches one step past it",
            best + 1
        ));
    }
    if best == 0 {
        path.notes.push(
            "the best point is the path's first: the response moved away from the target \
             along the whole path"
                .to_owned(),
        );
    }
    path.relative_error_pct = errors;
    path.best = best + 1;
    path.best_at_path_end = at_end;
    Ok(path)
}
