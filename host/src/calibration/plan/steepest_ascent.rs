//! Stage 2: the path of steepest ascent (seed 000 §3.4, Table 6; seed 001 §3.1, Table 8).
//!
//! The path moves the carried factors along the screening fit's gradient (their coded
//! coefficients bᵢ in the screening coding), the largest-|b| factor by `step_coded` per
//! point (`doe::steepest_ascent`); every other factor is held at its held value (seed 000
//! §3.4 holds x1, x2, x6, x7, x8 at 0.386, 3.04 MPa, 0.339, 0.589, 0.159).
//!
//! Which way: toward the target. The path climbs from the corner of the carried factors
//! where the screening fit predicts its lowest response (each factor at
//! `origin_coded`·sign(bᵢ); −1 gives the seeds' start at the low levels), unless the target
//! lies below even that prediction; then it descends from the highest corner. The best
//! point is the one whose response is nearest the target (seed 000 Table 6: point 3,
//! ψ = 1.35 %; seed 001 Table 8: point 3, 4.31 %).
//!
//! Going on past the planned points ([`Extension`]):
//! - doubling: the gap between points doubles (positions 6, 10, 18, … after the planned
//!   0–4), so a target far outside the screened box is reached in few runs, until a
//!   response crosses the target. Points run [`EXTENSION_BATCH`] at a time, a fixed number
//!   so the runs do not depend on the machine's core count. Beyond its screened range a
//!   factor stays inside its physical limits ([`Factor::admissible`]): it stops at a closed
//!   bound (μ at 0, e at 1) or, where the bound is open (ν < 0.5), at its screened level,
//!   while the others go on; the path ends when every factor is held;
//! - single steps: one point at a time while the point nearest the target is the last, and
//!   no further once the next point would leave a physical limit.

use serde::Serialize;

use super::super::executor::{Executor, PlannedRun, RunRecord};
use super::super::settings::{Extension, PathSettings};
use super::super::{CalibrateError, Factor, Objective};
use super::screening::Screening;
use crate::doe::steepest_ascent;
use crate::stats::relative_error_percent;

/// Path points run together by a doubling extension.
pub const EXTENSION_BATCH: usize = 2;

/// Gap, in path steps, between the last planned point and the first point of a doubling
/// extension; each later gap is twice the one before.
const FIRST_EXTENSION_GAP: f64 = 2.0;

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "steepest ascent";

/// Which way the path goes (serialised as its [`Direction::name`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Up the screening gradient (the target lies above the lowest prediction).
    Ascent,
    /// Down it.
    Descent,
}

impl Direction {
    /// "ascent" or "descent".
    pub fn name(self) -> &'static str {
        match self {
            Self::Ascent => "ascent",
            Self::Descent => "descent",
        }
    }
}

/// The path stage's numbers (serialised without how it ended, which a report words).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteepestAscent {
    /// The carried factors (screening coding), in carried order.
    pub factors: Vec<Factor>,
    /// Their screening coefficients, response units per coded unit.
    pub coefficients: Vec<f64>,
    /// Which way.
    pub direction: Direction,
    /// Screening-fit prediction at the path's origin, response units.
    pub predicted_at_origin: f64,
    /// Coded start of each factor.
    pub origin_coded: Vec<f64>,
    /// Coded change of each factor per point.
    pub step_coded: Vec<f64>,
    /// Path position of each run (0 = origin; 0, 1, … for the planned points, then the
    /// extension's).
    pub positions: Vec<f64>,
    /// The path points in order (coded in the screening coding).
    pub runs: Vec<RunRecord>,
    /// ψ = |ζ′ − ζ|/ζ × 100 % of each point against the target (seed 000 eq. (21)).
    pub relative_error_pct: Vec<f64>,
    /// 1-based number of the point nearest the target.
    pub best: usize,
    /// The planned points.
    #[serde(skip)]
    pub planned: usize,
    /// The extension that ran.
    #[serde(skip)]
    pub extension: Extension,
    /// A doubling extension ended because every factor was held by a limit.
    #[serde(skip)]
    pub held_at_limits: bool,
    /// A single-step extension ended because the next point would leave a limit (why).
    #[serde(skip)]
    pub stopped_at_limit: Option<String>,
}

impl SteepestAscent {
    /// Coded point `m` of the path (0 = origin; may lie before or past the run points),
    /// each factor held at its limits ([`Factor::admissible`]).
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

    /// The best point is the path's last.
    pub fn best_at_path_end(&self) -> bool {
        self.best == self.runs.len()
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

/// Runs stage 2 toward `target` over the study's `all` factors.
pub fn run(
    executor: &Executor,
    target: &Objective<'_>,
    all: &[Factor],
    screening: &Screening,
    settings: &PathSettings,
) -> Result<SteepestAscent, CalibrateError> {
    let carried = screening.carried_factors();
    let factors: Vec<Factor> = carried.iter().map(|(f, _)| (*f).clone()).collect();
    let b: Vec<f64> = carried.iter().map(|(_, b)| *b).collect();
    // The screening fit with every other factor at its held value (coded).
    let mut base = screening.intercept;
    for (f, e) in screening.factors.iter().zip(&screening.effects) {
        if screening.choice.carried.contains(&f.label) {
            continue;
        }
        base += e.coefficient * (f.held - 0.5 * (f.low + f.high)) / (0.5 * (f.high - f.low));
    }
    let predict = |x: &[f64]| base + b.iter().zip(x).map(|(b, x)| b * x).sum::<f64>();
    let lowest: Vec<f64> = b.iter().map(|bi| -sign(*bi)).collect();
    let direction = if target.value >= predict(&lowest) {
        Direction::Ascent
    } else {
        Direction::Descent
    };
    let gradient: Vec<f64> = b
        .iter()
        .map(|bi| match direction {
            Direction::Ascent => *bi,
            Direction::Descent => -bi,
        })
        .collect();
    let origin: Vec<f64> = gradient
        .iter()
        .map(|g| settings.origin_coded * sign(*g))
        .collect();
    let design_err = |source| CalibrateError::Design {
        stage: STAGE,
        source,
    };
    let doe_factors = factors
        .iter()
        .map(Factor::doe)
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let rows = match settings.extension {
        Extension::SingleSteps { max_points } => max_points.max(settings.points),
        _ => settings.points,
    };
    let design = steepest_ascent(&doe_factors, &gradient, &origin, settings.step_coded, rows)
        .map_err(design_err)?;
    let largest = gradient.iter().fold(0.0_f64, |m, g| m.max(g.abs()));
    let step: Vec<f64> = gradient
        .iter()
        .map(|g| settings.step_coded * g / largest)
        .collect();
    let names: Vec<String> = factors.iter().map(|f| f.name.clone()).collect();
    let design_run = |m: usize| PlannedRun {
        coded: design.coded[m].clone(),
        values: names.iter().cloned().zip(design.actual_row(m)).collect(),
        replicate: 0,
    };
    let planned: Vec<PlannedRun> = (0..settings.points).map(design_run).collect();
    let mut path = SteepestAscent {
        factors,
        coefficients: b.clone(),
        direction,
        predicted_at_origin: predict(&origin),
        origin_coded: origin,
        step_coded: step,
        positions: (0..planned.len()).map(|m| m as f64).collect(),
        runs: executor.run_batch(STAGE, target, all, &planned)?,
        relative_error_pct: Vec::new(),
        best: 0,
        planned: planned.len(),
        extension: settings.extension,
        held_at_limits: false,
        stopped_at_limit: None,
    };
    let errors = |runs: &[RunRecord]| -> Vec<f64> {
        runs.iter()
            .map(|r| relative_error_percent(r.response, target.value))
            .collect()
    };
    let best_of = |runs: &[RunRecord]| {
        let e = errors(runs);
        (0..runs.len())
            .min_by(|&a, &b| e[a].total_cmp(&e[b]))
            .unwrap_or(0)
    };
    match settings.extension {
        Extension::None => {}
        Extension::Doubling { max_points } => {
            extend_doubling(executor, target, all, &mut path, max_points)?;
        }
        Extension::SingleSteps { max_points } => {
            while best_of(&path.runs) + 1 == path.runs.len() && path.runs.len() < max_points {
                let next = design_run(path.runs.len());
                if let Some(reason) = path
                    .factors
                    .iter()
                    .find_map(|f| f.physical.check(next.values[&f.name]).err())
                {
                    path.stopped_at_limit = Some(reason);
                    break;
                }
                let number = path.runs.len() + 1;
                path.positions.push(path.runs.len() as f64);
                let mut record = executor.run_batch(STAGE, target, all, &[next])?;
                record[0].run = number;
                path.runs.extend(record);
            }
        }
    }
    path.relative_error_pct = errors(&path.runs);
    path.best = best_of(&path.runs) + 1;
    Ok(path)
}

/// Goes on with doubling gaps until a response crosses the target (module notes).
fn extend_doubling(
    executor: &Executor,
    target: &Objective<'_>,
    all: &[Factor],
    path: &mut SteepestAscent,
    max_points: usize,
) -> Result<(), CalibrateError> {
    let first_side = path.runs.first().map(|r| r.response >= target.value);
    let mut gap = FIRST_EXTENSION_GAP;
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
                path.held_at_limits = true;
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
        let records = executor.run_batch(STAGE, target, all, &batch)?;
        path.runs
            .extend(records.into_iter().enumerate().map(|(i, mut r)| {
                r.run = first + i + 1;
                r
            }));
    }
    Ok(())
}
