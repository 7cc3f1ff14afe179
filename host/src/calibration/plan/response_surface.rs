//! Stage 3: a response-surface design around the best path point and its fit (seed 000
//! §3.5; seed 001 §3.2). The design and its box are the plan's
//! ([`super::box_behnken`], [`super::central_composite`]); this stage turns the box's two
//! path positions into the ±1 levels of each factor, runs the design, and fits the plan's
//! model with `stats::analyze` (Type III SS, lack of fit against the pure error of the
//! replicated centre points).
//!
//! A factor the path does not move (both box ends at the same level) gets ± half a step of
//! its own coding, on the admissible side of a limit that holds it.

use super::super::executor::{replicate_indices, Executor, PlannedRun, RunRecord};
use super::super::settings::{SurfaceDesign, SurfaceSettings};
use super::super::{CalibrateError, Factor, Objective};
use super::steepest_ascent::SteepestAscent;
use super::{box_behnken, central_composite};
use crate::optimize::Polynomial;
use crate::stats::{analyze, Anova, CodedDesign};

/// Stage name in messages and the progress bar.
pub fn stage(design: SurfaceDesign) -> &'static str {
    match design {
        SurfaceDesign::BoxBehnken => "box-behnken",
        SurfaceDesign::CentralComposite { .. } => "central composite",
    }
}

/// Two levels closer than this fraction of the factor's screening range are the same level.
const SAME_LEVEL_FRACTION: f64 = 1e-9;

/// How the box's path points were chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BoxChoice {
    /// Two neighbouring path points whose responses bracket the target.
    Bracketing,
    /// The best point's neighbours on either side.
    AroundBest,
}

/// Fewest and most factors the design takes (the screening carries that many on).
pub fn factor_range(design: SurfaceDesign) -> std::ops::RangeInclusive<usize> {
    match design {
        SurfaceDesign::BoxBehnken => box_behnken::MIN_FACTORS..=box_behnken::MAX_FACTORS,
        SurfaceDesign::CentralComposite { .. } => {
            central_composite::MIN_FACTORS..=central_composite::MAX_FACTORS
        }
    }
}

/// The response-surface stage's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseSurface {
    /// The design.
    pub design: SurfaceDesign,
    /// The factors with the box's levels (coded ±1).
    pub factors: Vec<Factor>,
    /// How the box was chosen.
    pub choice: BoxChoice,
    /// Path points (1-based, may be 0 or past the last point) of coded −1 and +1 of the
    /// lead factor.
    pub path_points: [i64; 2],
    /// The best path point (1-based) the box was built around.
    pub best_path_point: usize,
    /// Centre points.
    pub centre_points: usize,
    /// The runs, standard order, coded in the box's coding.
    pub runs: Vec<RunRecord>,
    /// The model fitted ("Linear", "2FI", "Quadratic").
    pub model: String,
    /// Its ANOVA and coded equation.
    pub anova: Anova,
}

impl ResponseSurface {
    /// The fitted coded equation as a polynomial (cheap to evaluate, unlike rebuilding the
    /// terms per call with `Anova::predict`; the same bits).
    pub fn surface(&self) -> Polynomial {
        let names = self.factors.iter().map(|f| f.label.clone()).collect();
        let terms: Vec<(&str, f64)> = self
            .anova
            .coefficients
            .iter()
            .map(|c| (c.term.as_str(), c.estimate))
            .collect();
        Polynomial::new(names, &terms).expect("the fit's terms are terms of its factors")
    }

    /// Half-width of the coded box the optimum is searched in: 1 for a Box–Behnken design,
    /// α (the star points) for a central composite one.
    pub fn search_half_width(&self) -> f64 {
        match self.design {
            SurfaceDesign::BoxBehnken => 1.0,
            SurfaceDesign::CentralComposite { alpha } => alpha,
        }
    }
}

/// Runs stage 3 around the best point of `path`.
pub fn run(
    executor: &Executor,
    target: &Objective<'_>,
    all: &[Factor],
    path: &SteepestAscent,
    step_coded: f64,
    settings: &SurfaceSettings,
) -> Result<ResponseSurface, CalibrateError> {
    let stage = stage(settings.design);
    let best = path.best - 1;
    let (positions, choice) = match settings.design {
        SurfaceDesign::BoxBehnken => {
            let responses: Vec<f64> = path.runs.iter().map(|r| r.response).collect();
            box_behnken::box_positions(&responses, best, target.value)
        }
        SurfaceDesign::CentralComposite { .. } => central_composite::box_positions(best),
    };
    let ends = [
        path.actual_point(&path.coded_point(path.position(positions[0]))),
        path.actual_point(&path.coded_point(path.position(positions[1]))),
    ];
    let factors: Vec<Factor> = path
        .factors
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let (mut low, mut high) = (ends[0][i].min(ends[1][i]), ends[0][i].max(ends[1][i]));
            if high - low <= SAME_LEVEL_FRACTION * (f.high - f.low) {
                let half = 0.5 * step_coded * 0.5 * (f.high - f.low);
                (low, high) = (low - half, high + half);
                // A factor the path holds at a limit keeps the box on the admissible side.
                if f.admissible(low) != low {
                    (low, high) = (f.admissible(low), f.admissible(low) + 2.0 * half);
                } else if f.admissible(high) != high {
                    (low, high) = (f.admissible(high) - 2.0 * half, f.admissible(high));
                }
            }
            f.with_levels(low, high)
        })
        .collect();
    let design_err = |source| CalibrateError::Design { stage, source };
    let doe_factors = factors
        .iter()
        .map(Factor::doe)
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let design = match settings.design {
        SurfaceDesign::BoxBehnken => box_behnken::design(&doe_factors, settings.centre_points),
        SurfaceDesign::CentralComposite { alpha } => {
            central_composite::design(&doe_factors, alpha, settings.centre_points)
        }
    }
    .map_err(design_err)?;
    let planned: Vec<PlannedRun> = design
        .coded
        .iter()
        .zip(replicate_indices(&design.coded))
        .enumerate()
        .map(|(i, (row, replicate))| PlannedRun {
            coded: row.clone(),
            values: factors
                .iter()
                .zip(design.actual_row(i))
                .map(|(f, v)| (f.name.clone(), v))
                .collect(),
            replicate,
        })
        .collect();
    let runs = executor.run_batch(stage, target, all, &planned)?;
    let labels: Vec<String> = factors.iter().map(|f| f.label.clone()).collect();
    let stats_err = |source| CalibrateError::Stats { stage, source };
    let coded = CodedDesign::new(
        labels,
        design.coded.clone(),
        runs.iter().map(|r| r.response).collect(),
    )
    .map_err(stats_err)?;
    let anova = analyze(&coded, settings.model).map_err(stats_err)?;
    Ok(ResponseSurface {
        design: settings.design,
        factors,
        choice,
        path_points: [positions[0] + 1, positions[1] + 1],
        best_path_point: path.best,
        centre_points: settings.centre_points,
        runs,
        model: settings.model.label().to_owned(),
        anova,
    })
}
