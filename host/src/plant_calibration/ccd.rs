//! Stage 3: the central composite design around the best path point and its quadratic fit
//! (seed 001 §3.2, Tables 9–11).
//!
//! As in seed 001 Table 9, the best path point is the centre and its neighbours on the path
//! are the ±1 levels (Table 8's points 2 and 4 around point 3); α = 1.414 and five centre
//! points (Table 10: 13 runs for two factors). Factors not carried stay at their range
//! centres. The full quadratic model is fitted and tested by ANOVA (Table 11).

use serde::Serialize;

use super::path::SteepestPath;
use super::plan::Plan;
use super::simulator::PullOffSimulator;
use super::{PlantCalibrationError, RunRecord};
use crate::calibrate::Progress;
use crate::doe::{central_composite, Alpha, Factor};
use crate::stats::{analyze, Anova, CodedDesign, ModelOrder};

/// Stage name.
pub const STAGE: &str = "central composite";
/// Axial distance, coded (seed 001 Table 9).
pub const ALPHA: f64 = 1.414;
/// Centre points (seed 001 Table 10).
pub const CENTRE_POINTS: usize = 5;

/// A factor of the design, actual levels at coded ∓1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CcdFactor {
    /// Label (x1…x9).
    pub label: String,
    /// Unit (SI).
    pub unit: String,
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
}

impl CcdFactor {
    /// Actual value at coded `x`.
    pub fn actual(&self, x: f64) -> f64 {
        0.5 * (self.low + self.high) + x * 0.5 * (self.high - self.low)
    }
}

/// The response-surface stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CentralComposite {
    /// The factors (this stage's coding).
    pub factors: Vec<CcdFactor>,
    /// α, coded.
    pub alpha: f64,
    /// Runs in standard order (cube, axial, centre).
    pub runs: Vec<RunRecord>,
    /// The quadratic ANOVA.
    pub anova: Anova,
}

/// Runs stage 3.
pub fn run(
    sim: &PullOffSimulator,
    plan: &Plan,
    path: &SteepestPath,
    progress: &Progress,
) -> Result<CentralComposite, PlantCalibrationError> {
    let m = (path.best - 1) as f64;
    let (lo, hi) = (path.actual_at(plan, m - 1.0), path.actual_at(plan, m + 1.0));
    let factors: Vec<CcdFactor> = path
        .factors
        .iter()
        .enumerate()
        .map(|(i, l)| CcdFactor {
            label: l.clone(),
            unit: plan.factor(l).map_or("", |f| f.unit).to_owned(),
            low: lo[i].min(hi[i]),
            high: lo[i].max(hi[i]),
        })
        .collect();
    let design_err = |source| PlantCalibrationError::Design {
        stage: STAGE,
        source,
    };
    let doe_factors = factors
        .iter()
        .map(|f| Factor::new(&f.label, &f.unit, f.low, f.high))
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let design = central_composite(
        &doe_factors,
        Alpha::Value(plan.ccd_alpha),
        plan.ccd_centre_points,
    )
    .map_err(design_err)?;
    let settings: Vec<[f64; 9]> = design
        .coded
        .iter()
        .map(|row| {
            let values: Vec<f64> = factors.iter().zip(row).map(|(f, &x)| f.actual(x)).collect();
            plan.settings_with(&path.factors, &values)
        })
        .collect();
    let outcomes = sim.run_batch(STAGE, &settings, progress)?;
    let y: Vec<f64> = outcomes.iter().map(|o| o.detachment_force_n).collect();
    let stats_err = |source| PlantCalibrationError::Stats {
        stage: STAGE,
        source,
    };
    let anova = analyze(
        &CodedDesign::new(path.factors.clone(), design.coded.clone(), y).map_err(stats_err)?,
        ModelOrder::Quadratic,
    )
    .map_err(stats_err)?;
    Ok(CentralComposite {
        runs: RunRecord::list(&design.coded, &settings, &outcomes),
        factors,
        alpha: plan.ccd_alpha,
        anova,
    })
}
