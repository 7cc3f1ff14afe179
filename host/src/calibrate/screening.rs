//! Stage 1: Plackett–Burman screening (seed 000 §3.3, Tables 3–5).
//!
//! Every varied parameter is a column of the study's Plackett–Burman design at its range's
//! low and high levels; the unused columns are dummies, left out of the model so their
//! sums of squares form the error estimate (seed 000 Table 5: residual df 3 = 12 − 1 − 8).
//! A first-order model is fitted and tested by ANOVA (`stats::analyze`, Type III SS; with
//! centre points a curvature term is split off). A factor passes when p < α
//! (`[plan.screening] significance`).
//!
//! The factors carried on are the passed ones, at least [`MIN_CARRIED`] and at most
//! [`MAX_CARRIED`] (the Box–Behnken design's limits): when fewer pass, the largest |effect|
//! among the rest fill up — including when none passes, or when the ANOVA is undefined
//! (an exact fit) — and the report says so instead of failing.

use std::collections::BTreeMap;

use nalgebra::DVector;
use serde::Serialize;

use super::{replicate_indices, CalibrateError, PlannedRun, RunRecord, Runner, TargetInfo};
use crate::doe::{self, plackett_burman, Factor, PlackettBurmanRuns};
use crate::stats::{self, analyze, Anova, CodedDesign, ModelOrder};
use crate::study::plan::ScreeningDesign;

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "screening";
/// Fewest factors carried to the response-surface stages (a Box–Behnken design needs 3).
pub const MIN_CARRIED: usize = doe::box_behnken::MIN_FACTORS;
/// Most factors carried (the largest Box–Behnken design available).
pub const MAX_CARRIED: usize = doe::box_behnken::MAX_FACTORS;

/// A factor of a design, in the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FactorInfo {
    /// Registry name of the parameter.
    pub name: String,
    /// Report label (seed 000 Table 3's x1…x8).
    pub label: String,
    /// Unit of `low` and `high`.
    pub unit: String,
    /// Actual level at coded −1.
    pub low: f64,
    /// Actual level at coded +1.
    pub high: f64,
}

impl FactorInfo {
    /// The `doe` factor (named by its label).
    pub fn factor(&self) -> Result<Factor, crate::doe::DesignError> {
        Factor::new(&self.label, &self.unit, self.low, self.high)
    }
}

/// One factor's screening effect.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectRow {
    /// Report label.
    pub label: String,
    /// Registry name.
    pub name: String,
    /// Coded coefficient bⱼ of the first-order fit (response units per coded unit).
    pub coefficient: f64,
    /// Main effect 2bⱼ: the mean response change from the low to the high level.
    pub effect: f64,
    /// ANOVA p-value, when the ANOVA is defined.
    pub p: Option<f64>,
    /// p < α.
    pub significant: bool,
}

/// The screening stage's numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Screening {
    /// Design name.
    pub design: String,
    /// The factors, in registry order.
    pub factors: Vec<FactorInfo>,
    /// Names of the dummy columns (coded columns after the factors in each run).
    pub dummy_columns: Vec<String>,
    /// Significance level α.
    pub significance: f64,
    /// The runs, standard order; `coded` holds the factor then the dummy columns.
    pub runs: Vec<RunRecord>,
    /// The first-order ANOVA, when defined.
    pub anova: Option<Anova>,
    /// Why there is no ANOVA, when there is none.
    pub anova_unavailable: Option<String>,
    /// Intercept b₀ of the first-order fit (response units).
    pub intercept: f64,
    /// Effects, in factor order.
    pub effects: Vec<EffectRow>,
    /// Labels of the factors with p < α, largest |effect| first.
    pub significant: Vec<String>,
    /// Labels of the factors carried on, in factor order.
    pub selected: Vec<String>,
    /// Decisions the report must state (fill-ups, caps).
    pub notes: Vec<String>,
}

impl Screening {
    /// The carried factors' infos and coded coefficients, in factor order.
    pub fn selected_factors(&self) -> Vec<(&FactorInfo, f64)> {
        self.factors
            .iter()
            .zip(&self.effects)
            .filter(|(f, _)| self.selected.contains(&f.label))
            .map(|(f, e)| (f, e.coefficient))
            .collect()
    }

    /// The most significant factor: smallest p, else largest |effect|.
    pub fn strongest(&self) -> Option<&EffectRow> {
        self.effects.iter().min_by(|a, b| match (a.p, b.p) {
            (Some(pa), Some(pb)) if pa != pb => pa.total_cmp(&pb),
            _ => b.effect.abs().total_cmp(&a.effect.abs()),
        })
    }
}

/// Runs stage 1.
pub fn run(runner: &Runner<'_>, target: &TargetInfo) -> Result<Screening, CalibrateError> {
    let study = runner.study();
    let plan = &study.file().plan.screening;
    let design_err = |source| CalibrateError::Design {
        stage: STAGE,
        source,
    };
    let factors: Vec<FactorInfo> = study
        .varied()
        .into_iter()
        .map(|v| FactorInfo {
            name: v.spec.name.to_owned(),
            label: v.label,
            unit: v.spec.unit.to_owned(),
            low: v.range.low,
            high: v.range.high,
        })
        .collect();
    if factors.len() < MIN_CARRIED {
        return Err(CalibrateError::Plan(format!(
            "{} varied parameters; the Box–Behnken stage needs at least {MIN_CARRIED}",
            factors.len()
        )));
    }
    let doe_factors = factors
        .iter()
        .map(FactorInfo::factor)
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let runs_kind = match plan.design {
        ScreeningDesign::Pb12 => PlackettBurmanRuns::Twelve,
        ScreeningDesign::Pb20 => PlackettBurmanRuns::Twenty,
    };
    let design = plackett_burman(runs_kind, &doe_factors, plan.centre_points as usize)
        .map_err(design_err)?;
    let k = factors.len();
    let replicates = replicate_indices(&design.coded);
    let planned: Vec<PlannedRun> = design
        .coded
        .iter()
        .zip(replicates)
        .map(|(row, replicate)| PlannedRun {
            coded: row.clone(),
            values: factors
                .iter()
                .zip(&doe_factors)
                .zip(row)
                .map(|((info, f), &x)| (info.name.clone(), f.to_actual(x)))
                .collect::<BTreeMap<_, _>>(),
            replicate,
        })
        .collect();
    let runs = runner.run_batch(STAGE, target.experiment, &target.condition, &planned)?;

    let labels: Vec<String> = factors.iter().map(|f| f.label.clone()).collect();
    let coded: Vec<Vec<f64>> = design.coded.iter().map(|r| r[..k].to_vec()).collect();
    let y: Vec<f64> = runs.iter().map(|r| r.response).collect();
    let stats_err = |source| CalibrateError::Stats {
        stage: STAGE,
        source,
    };
    let coded_design =
        CodedDesign::new(labels.clone(), coded.clone(), y.clone()).map_err(stats_err)?;
    let (anova, anova_unavailable, coefficients) = match analyze(&coded_design, ModelOrder::Linear)
    {
        Ok(a) => {
            let b: Vec<f64> = a.coefficients.iter().map(|c| c.estimate).collect();
            (Some(a), None, b)
        }
        Err(e) => {
            // No F-tests (e.g. an exact fit); the effects still rank the factors.
            let terms = stats::model_terms(&labels, ModelOrder::Linear);
            let x = stats::model_matrix(&terms, &coded);
            let names: Vec<&str> = terms.iter().map(|t| t.name.as_str()).collect();
            let fit = stats::least_squares(&x, &DVector::from_column_slice(&y), &names)
                .map_err(stats_err)?;
            (
                None,
                Some(e.to_string()),
                fit.coefficients.iter().copied().collect(),
            )
        }
    };
    let effects: Vec<EffectRow> = factors
        .iter()
        .enumerate()
        .map(|(j, f)| {
            let p = anova.as_ref().map(|a| a.terms[j].p);
            EffectRow {
                label: f.label.clone(),
                name: f.name.clone(),
                coefficient: coefficients[j + 1],
                effect: 2.0 * coefficients[j + 1],
                p,
                significant: p.is_some_and(|p| p < plan.significance),
            }
        })
        .collect();
    let (significant, selected, notes) = select(&effects, plan.significance, anova.is_some());
    Ok(Screening {
        design: design.kind.clone(),
        factors,
        dummy_columns: design.dummy_columns.clone(),
        significance: plan.significance,
        runs,
        anova,
        anova_unavailable,
        intercept: coefficients[0],
        effects,
        significant,
        selected,
        notes,
    })
}

/// The significant labels (largest |effect| first), the carried labels (factor order) and
/// the notes explaining any fill-up or cap.
fn select(
    effects: &[EffectRow],
    alpha: f64,
    tested: bool,
) -> (Vec<String>, Vec<String>, Vec<String>) {
    let mut by_size: Vec<&EffectRow> = effects.iter().collect();
    // Stable sort: equal |effect| keep factor order.
    by_size.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    let significant: Vec<String> = by_size
        .iter()
        .filter(|e| e.significant)
        .map(|e| e.label.clone())
        .collect();
    let mut carried: Vec<&EffectRow> = by_size.iter().copied().filter(|e| e.significant).collect();
    let mut notes = Vec::new();
    if carried.len() > MAX_CARRIED {
        let dropped: Vec<&str> = carried[MAX_CARRIED..]
            .iter()
            .map(|e| e.label.as_str())
            .collect();
        notes.push(format!(
            "{} factors passed screening; the Box–Behnken stage takes at most {MAX_CARRIED}, so \
             the {MAX_CARRIED} of largest |effect| go on and {} are held",
            carried.len(),
            dropped.join(", ")
        ));
        carried.truncate(MAX_CARRIED);
    }
    if carried.len() < MIN_CARRIED {
        let before = carried.len();
        let fill: Vec<&EffectRow> = by_size
            .iter()
            .copied()
            .filter(|e| !e.significant)
            .take(MIN_CARRIED - before)
            .collect();
        let names: Vec<&str> = fill.iter().map(|e| e.label.as_str()).collect();
        let why = if !tested {
            "the ANOVA is undefined, so no factor could be tested".to_owned()
        } else if before == 0 {
            format!("no factor reached p < {alpha}")
        } else {
            format!("only {before} factor(s) reached p < {alpha}")
        };
        notes.push(format!(
            "{why}; the Box–Behnken stage needs {MIN_CARRIED} factors, so the largest |effect| \
             among the rest fill up: {}",
            names.join(", ")
        ));
        carried.extend(fill);
    }
    let selected = effects
        .iter()
        .filter(|e| carried.iter().any(|c| c.label == e.label))
        .map(|e| e.label.clone())
        .collect();
    (significant, selected, notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(label: &str, effect: f64, p: Option<f64>) -> EffectRow {
        EffectRow {
            label: label.into(),
            name: label.into(),
            coefficient: effect / 2.0,
            effect,
            p,
            significant: p.is_some_and(|p| p < 0.05),
        }
    }

    #[test]
    fn nothing_significant_carries_the_largest_effects() {
        let effects = [
            row("a", 1.0, Some(0.5)),
            row("b", -4.0, Some(0.2)),
            row("c", 0.5, Some(0.9)),
            row("d", 3.0, Some(0.1)),
            row("e", 2.0, Some(0.3)),
        ];
        let (sig, sel, notes) = select(&effects, 0.05, true);
        assert!(sig.is_empty());
        assert_eq!(sel, ["b", "d", "e"]);
        assert!(notes[0].contains("no factor reached p < 0.05"), "{notes:?}");
    }

    #[test]
    fn too_many_significant_are_capped_by_effect() {
        let effects: Vec<EffectRow> = (0..9)
            .map(|i| row(&format!("f{i}"), f64::from(i) + 1.0, Some(0.001)))
            .collect();
        let (sig, sel, notes) = select(&effects, 0.05, true);
        assert_eq!(sig.len(), 9);
        assert_eq!(sel, ["f2", "f3", "f4", "f5", "f6", "f7", "f8"]);
        assert!(notes[0].contains("f1, f0"), "{notes:?}");
    }

    #[test]
    fn untested_screening_says_why() {
        let effects = [
            row("a", 1.0, None),
            row("b", 2.0, None),
            row("c", 3.0, None),
        ];
        let (_, sel, notes) = select(&effects, 0.05, false);
        assert_eq!(sel, ["a", "b", "c"]);
        assert!(notes[0].contains("ANOVA is undefined"));
    }
}
