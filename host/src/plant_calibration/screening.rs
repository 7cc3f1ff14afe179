//! Stage 1: Plackett–Burman screening of the nine factors of seed 001 Table 5 (12 runs,
//! two dummy columns, three centre points: seed 001 Table 6), a first-order fit and ANOVA
//! with the centre-point curvature term (`stats::analyze`; seed 001 Table 7).
//!
//! Seed 001 §3.1 calls p < 0.05 significant and carries the "extremely significant" ones
//! (p ≤ 0.01: x7 and x8) to the response surface. The same rule is applied here, with at
//! least [`MIN_CARRIED`] (a central composite design needs two factors) and at most
//! [`MAX_CARRIED`] carried: a shortfall is filled, an excess cut, by |effect|, and the
//! report says so.

use serde::Serialize;

use super::plan::Plan;
use super::simulator::PullOffSimulator;
use super::{PlantCalibrationError, RunRecord};
use crate::calibrate::Progress;
use crate::doe::plackett_burman;
use crate::stats::{analyze, Anova, CodedDesign, ModelOrder};

/// Stage name.
pub const STAGE: &str = "screening";
/// Centre points of the screening design (seed 001 Table 6).
pub const CENTRE_POINTS: usize = 3;
/// Significance level (seed 001 Table 7: *).
pub const SIGNIFICANCE: f64 = 0.05;
/// Level at which a factor is carried on (seed 001 Table 7: **).
pub const CARRY_LEVEL: f64 = 0.01;
/// Fewest factors carried (a central composite design needs two).
pub const MIN_CARRIED: usize = 2;
/// Most factors carried (a three-factor central composite design has 8 + 6 + centre runs).
pub const MAX_CARRIED: usize = 3;

/// One factor's screening result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Effect {
    /// Label (x1…x9).
    pub label: String,
    /// Coded coefficient bⱼ, N per coded unit.
    pub coefficient: f64,
    /// Main effect 2bⱼ, N: mean force change from the low to the high level.
    pub effect: f64,
    /// ANOVA p-value.
    pub p: f64,
}

/// The screening stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Screening {
    /// Runs in standard order; `coded` holds the nine factors then the two dummies.
    pub runs: Vec<RunRecord>,
    /// The first-order ANOVA (with the curvature term).
    pub anova: Anova,
    /// Intercept b₀, N (the factorial-point mean).
    pub intercept: f64,
    /// Effects in factor order.
    pub effects: Vec<Effect>,
    /// Labels with p < [`SIGNIFICANCE`], smallest p first.
    pub significant: Vec<String>,
    /// Labels carried on to the path and the central composite design: the screening's
    /// choice, or the plan's named factors when it names them.
    pub carried: Vec<String>,
    /// What the screening alone chose (p ≤ the carry level, largest |effect| first, filled
    /// up or cut to 2–3), whatever the plan then carried.
    pub screening_choice: Vec<String>,
    /// Decisions the report must state.
    pub notes: Vec<String>,
    /// 2b₈₉/3, N: the main effect the x8·x9 interaction of F = σc·πRb² lends every other
    /// column (a 12-run Plackett–Burman design aliases each two-factor interaction onto the
    /// other columns with weight ±1/3); b₈₉ from σc·πRb² at the four (x8, x9) corners.
    pub x8_x9_alias_effect_n: f64,
}

/// 2b₈₉/3 of F = σc·πRb² over the plan's x8 and x9 ranges (seed 001 Table 5's for
/// [`Plan::seed001`]), N (see [`Screening::x8_x9_alias_effect_n`]).
pub fn x8_x9_alias_effect_n(plan: &Plan) -> f64 {
    let (s, r) = (&plan.factors[7], &plan.factors[8]);
    let f = |sigma: f64, radius: f64| sigma * core::f64::consts::PI * radius * radius;
    let b89 = (f(s.high, r.high) - f(s.high, r.low) - f(s.low, r.high) + f(s.low, r.low)) / 4.0;
    2.0 * b89 / 3.0
}

impl Screening {
    /// The effect row of `label`.
    pub fn effect(&self, label: &str) -> Option<&Effect> {
        self.effects.iter().find(|e| e.label == label)
    }
}

/// Runs stage 1.
pub fn run(
    sim: &PullOffSimulator,
    plan: &Plan,
    progress: &Progress,
) -> Result<Screening, PlantCalibrationError> {
    let design_err = |source| PlantCalibrationError::Design {
        stage: STAGE,
        source,
    };
    let factors = plan
        .factors
        .iter()
        .map(|f| f.factor())
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let size = plan.plackett_burman_runs().ok_or_else(|| {
        PlantCalibrationError::Plan(format!(
            "no {}-run Plackett–Burman design",
            plan.screening_runs
        ))
    })?;
    let design =
        plackett_burman(size, &factors, plan.screening_centre_points).map_err(design_err)?;
    let k = factors.len();
    let settings: Vec<[f64; 9]> = design
        .coded
        .iter()
        .map(|row| core::array::from_fn(|j| factors[j].to_actual(row[j])))
        .collect();
    let outcomes = sim.run_batch(STAGE, &settings, progress)?;
    let runs = RunRecord::list(&design.coded, &settings, &outcomes);
    let labels: Vec<String> = plan.factors.iter().map(|f| f.label.to_owned()).collect();
    let coded: Vec<Vec<f64>> = design.coded.iter().map(|r| r[..k].to_vec()).collect();
    let y: Vec<f64> = outcomes.iter().map(|o| o.detachment_force_n).collect();
    let stats_err = |source| PlantCalibrationError::Stats {
        stage: STAGE,
        source,
    };
    let anova = analyze(
        &CodedDesign::new(labels.clone(), coded, y).map_err(stats_err)?,
        ModelOrder::Linear,
    )
    .map_err(stats_err)?;
    let effects: Vec<Effect> = labels
        .iter()
        .enumerate()
        .map(|(j, label)| Effect {
            label: label.clone(),
            coefficient: anova.coefficients[j + 1].estimate,
            effect: 2.0 * anova.coefficients[j + 1].estimate,
            p: anova.terms[j].p,
        })
        .collect();
    let mut by_p: Vec<&Effect> = effects.iter().collect();
    by_p.sort_by(|a, b| a.p.total_cmp(&b.p));
    let significant = by_p
        .iter()
        .filter(|e| e.p < plan.significance)
        .map(|e| e.label.clone())
        .collect();
    let (carried, notes) = carry(&effects, plan.carry_level);
    Ok(Screening {
        runs,
        intercept: anova.coefficients[0].estimate,
        anova,
        effects,
        significant,
        screening_choice: carried.clone(),
        carried,
        notes,
        x8_x9_alias_effect_n: x8_x9_alias_effect_n(plan),
    })
}

/// The carried labels (largest |effect| first, p ≤ `carry_level`) and notes on any
/// fill-up or cut.
fn carry(effects: &[Effect], carry_level: f64) -> (Vec<String>, Vec<String>) {
    let mut by_size: Vec<&Effect> = effects.iter().collect();
    by_size.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    let passed: Vec<&Effect> = by_size
        .iter()
        .copied()
        .filter(|e| e.p <= carry_level)
        .collect();
    let mut notes = Vec::new();
    let n = passed.len().clamp(MIN_CARRIED, MAX_CARRIED);
    if passed.len() > MAX_CARRIED {
        notes.push(format!(
            "{} factors reached p ≤ {carry_level}; the {MAX_CARRIED} of largest |effect| go on",
            passed.len()
        ));
    }
    let mut carried: Vec<&Effect> = passed.into_iter().take(n).collect();
    if carried.len() < MIN_CARRIED {
        let fill: Vec<&Effect> = by_size
            .iter()
            .copied()
            .filter(|e| e.p > carry_level)
            .take(MIN_CARRIED - carried.len())
            .collect();
        notes.push(format!(
            "only {} factor(s) reached p ≤ {carry_level}; the central composite design needs \
             {MIN_CARRIED}, so the largest |effect| among the rest fill up: {}",
            carried.len(),
            fill.iter()
                .map(|e| e.label.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        ));
        carried.extend(fill);
    }
    (carried.iter().map(|e| e.label.clone()).collect(), notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn e(label: &str, effect: f64, p: f64) -> Effect {
        Effect {
            label: label.into(),
            coefficient: effect / 2.0,
            effect,
            p,
        }
    }

    #[test]
    fn carry_fills_up_and_cuts_by_effect() {
        let (c, notes) = carry(
            &[e("a", 1.0, 0.001), e("b", 3.0, 0.2), e("c", 2.0, 0.3)],
            CARRY_LEVEL,
        );
        assert_eq!(c, ["a", "b"]);
        assert!(notes[0].contains("fill up: b"), "{notes:?}");
        let all: Vec<Effect> = (0..5)
            .map(|i| e(&format!("f{i}"), f64::from(i), 0.001))
            .collect();
        let (c, notes) = carry(&all, CARRY_LEVEL);
        assert_eq!(c, ["f4", "f3", "f2"]);
        assert_eq!(notes.len(), 1);
    }
}
