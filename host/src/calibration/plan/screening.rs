//! Stage 1: Plackett–Burman screening (seed 000 §3.3, Tables 3–5; seed 001 §3.1, Tables
//! 5–7).
//!
//! Every factor is a column of the design at its range's low and high levels; the unused
//! columns are dummies, left out of the model so their sums of squares form the error
//! estimate (seed 000 Table 5: residual df 3 = 12 − 1 − 8). Centre points, when the plan
//! has them, are replicated runs that split off a curvature term (seed 001 Table 7). A
//! first-order model is fitted and tested by ANOVA (`stats::analyze`, Type III SS). A
//! factor is significant when p < α.
//!
//! The factors carried on ([`choose`]) are those at the plan's carry level (the
//! significant ones by default), at least and at most what the response-surface design
//! takes: when fewer pass, the largest |effect| among the rest fill up — including when
//! none passes, or when the ANOVA is undefined (an exact fit); when more pass, the largest
//! |effect| go on. A plan may name the carried factors instead; the screening's own choice
//! is kept for the report.

use nalgebra::DVector;
use serde::Serialize;

use super::super::executor::{replicate_indices, Executor, PlannedRun, RunRecord};
use super::super::settings::ScreeningSettings;
use super::super::{CalibrateError, Factor, Objective};
use crate::doe::plackett_burman;
use crate::stats::{self, analyze, Anova, CodedDesign, ModelOrder};

/// Stage name in messages and the progress bar.
pub const STAGE: &str = "screening";

/// One factor's screening effect.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Effect {
    /// Report label.
    pub label: String,
    /// Parameter name.
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

/// Why the carried factors are not simply those that passed.
#[derive(Debug, Clone, PartialEq)]
pub enum Adjustment {
    /// More passed than the design takes; these (smallest |effect|) are held.
    Capped {
        /// How many passed.
        passed: usize,
        /// The labels held back.
        dropped: Vec<String>,
    },
    /// Fewer passed than the design needs; these (largest |effect| of the rest) fill up.
    Filled {
        /// How many passed (0 when none did).
        passed: usize,
        /// Whether an ANOVA tested the factors at all.
        tested: bool,
        /// The labels that fill up.
        fill: Vec<String>,
    },
}

/// The factors that go on, and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// What the screening alone carries, in factor order.
    pub screening: Vec<String>,
    /// What the later stages take: the plan's named factors (in their order) or
    /// `screening`.
    pub carried: Vec<String>,
    /// The screening's cap or fill-up, if any.
    pub adjustment: Option<Adjustment>,
    /// The carry level used (p ≤ it passes), `None` for "significant" (p < α).
    pub carry_level: Option<f64>,
    /// The plan's named factors and why, when it named them.
    pub named_reason: Option<String>,
}

/// The screening stage's numbers (serialised without the choice, which a report words).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Screening {
    /// Design name.
    pub design: String,
    /// The factors, in study order, in the screening coding.
    pub factors: Vec<Factor>,
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
    pub effects: Vec<Effect>,
    /// The factors that go on.
    #[serde(skip)]
    pub choice: Choice,
}

impl Screening {
    /// The carried factors and their coded coefficients, in carried order.
    pub fn carried_factors(&self) -> Vec<(&Factor, f64)> {
        self.choice
            .carried
            .iter()
            .filter_map(|label| {
                let j = self.factors.iter().position(|f| &f.label == label)?;
                Some((&self.factors[j], self.effects[j].coefficient))
            })
            .collect()
    }

    /// The most significant factor: smallest p, else largest |effect|.
    pub fn strongest(&self) -> Option<&Effect> {
        self.effects.iter().min_by(|a, b| match (a.p, b.p) {
            (Some(pa), Some(pb)) if pa != pb => pa.total_cmp(&pb),
            _ => b.effect.abs().total_cmp(&a.effect.abs()),
        })
    }

    /// The effect row of `label`.
    pub fn effect(&self, label: &str) -> Option<&Effect> {
        self.effects.iter().find(|e| e.label == label)
    }
}

/// Runs stage 1 over `factors`; `carried` is the range of factors the next stages take.
pub fn run(
    executor: &Executor,
    target: &Objective<'_>,
    factors: &[Factor],
    settings: &ScreeningSettings,
    carried: std::ops::RangeInclusive<usize>,
) -> Result<Screening, CalibrateError> {
    let design_err = |source| CalibrateError::Design {
        stage: STAGE,
        source,
    };
    if factors.len() < *carried.start() {
        return Err(CalibrateError::Plan(format!(
            "{} varied parameters; the response-surface stage needs at least {}",
            factors.len(),
            carried.start()
        )));
    }
    let doe_factors = factors
        .iter()
        .map(Factor::doe)
        .collect::<Result<Vec<_>, _>>()
        .map_err(design_err)?;
    let design =
        plackett_burman(settings.runs, &doe_factors, settings.centre_points).map_err(design_err)?;
    let k = factors.len();
    let planned: Vec<PlannedRun> = design
        .coded
        .iter()
        .zip(replicate_indices(&design.coded))
        .map(|(row, replicate)| PlannedRun {
            coded: row.clone(),
            values: factors
                .iter()
                .zip(&doe_factors)
                .zip(row)
                .map(|((info, f), &x)| (info.name.clone(), f.to_actual(x)))
                .collect(),
            replicate,
        })
        .collect();
    let runs = executor.run_batch(STAGE, target, factors, &planned)?;

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
    let effects: Vec<Effect> = factors
        .iter()
        .enumerate()
        .map(|(j, f)| {
            let p = anova.as_ref().map(|a| a.terms[j].p);
            Effect {
                label: f.label.clone(),
                name: f.name.clone(),
                coefficient: coefficients[j + 1],
                effect: 2.0 * coefficients[j + 1],
                p,
                significant: p.is_some_and(|p| p < settings.significance),
            }
        })
        .collect();
    let mut choice = choose(&effects, settings.carry_level, anova.is_some(), carried);
    if let Some(named) = &settings.named {
        choice.carried = named.labels.clone();
        choice.named_reason = Some(named.reason.clone());
    }
    Ok(Screening {
        design: design.kind.clone(),
        factors: factors.to_vec(),
        dummy_columns: design.dummy_columns.clone(),
        significance: settings.significance,
        runs,
        anova,
        anova_unavailable,
        intercept: coefficients[0],
        effects,
        choice,
    })
}

/// The screening's choice: the factors at `carry_level` (p ≤ it; `None`: the significant
/// ones), cut or filled up by |effect| to the range `carried`, in factor order.
pub fn choose(
    effects: &[Effect],
    carry_level: Option<f64>,
    tested: bool,
    carried: std::ops::RangeInclusive<usize>,
) -> Choice {
    let passes = |e: &Effect| match carry_level {
        None => e.significant,
        Some(level) => e.p.is_some_and(|p| p <= level),
    };
    let mut by_size: Vec<&Effect> = effects.iter().collect();
    // Stable sort: equal |effect| keep factor order.
    by_size.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    let mut chosen: Vec<&Effect> = by_size.iter().copied().filter(|e| passes(e)).collect();
    let passed = chosen.len();
    let mut adjustment = None;
    if passed > *carried.end() {
        let dropped = chosen[*carried.end()..]
            .iter()
            .map(|e| e.label.clone())
            .collect();
        adjustment = Some(Adjustment::Capped { passed, dropped });
        chosen.truncate(*carried.end());
    }
    if passed < *carried.start() {
        let fill: Vec<&Effect> = by_size
            .iter()
            .copied()
            .filter(|e| !passes(e))
            .take(carried.start() - passed)
            .collect();
        adjustment = Some(Adjustment::Filled {
            passed,
            tested,
            fill: fill.iter().map(|e| e.label.clone()).collect(),
        });
        chosen.extend(fill);
    }
    let screening = effects
        .iter()
        .filter(|e| chosen.iter().any(|c| c.label == e.label))
        .map(|e| e.label.clone())
        .collect::<Vec<_>>();
    Choice {
        carried: screening.clone(),
        screening,
        adjustment,
        carry_level,
        named_reason: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(label: &str, effect: f64, p: Option<f64>) -> Effect {
        Effect {
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
        let c = choose(&effects, None, true, 3..=7);
        assert_eq!(c.carried, ["b", "d", "e"]);
        assert_eq!(
            c.adjustment,
            Some(Adjustment::Filled {
                passed: 0,
                tested: true,
                fill: vec!["b".into(), "d".into(), "e".into()]
            })
        );
    }

    #[test]
    fn too_many_significant_are_capped_by_effect() {
        let effects: Vec<Effect> = (0..9)
            .map(|i| row(&format!("f{i}"), f64::from(i) + 1.0, Some(0.001)))
            .collect();
        let c = choose(&effects, None, true, 3..=7);
        assert_eq!(c.carried, ["f2", "f3", "f4", "f5", "f6", "f7", "f8"]);
        let Some(Adjustment::Capped { passed, dropped }) = c.adjustment else {
            panic!("{c:?}")
        };
        assert_eq!((passed, dropped), (9, vec!["f1".into(), "f0".into()]));
    }

    #[test]
    fn a_carry_level_is_inclusive_and_fills_up_by_effect() {
        let effects = [
            row("a", 1.0, Some(0.01)),
            row("b", 3.0, Some(0.2)),
            row("c", 2.0, Some(0.3)),
        ];
        let c = choose(&effects, Some(0.01), true, 2..=3);
        assert_eq!(c.carried, ["a", "b"]);
        assert!(matches!(
            c.adjustment,
            Some(Adjustment::Filled { passed: 1, .. })
        ));
    }

    #[test]
    fn untested_screening_says_so() {
        let effects = [
            row("a", 1.0, None),
            row("b", 2.0, None),
            row("c", 3.0, None),
        ];
        let c = choose(&effects, None, false, 3..=7);
        assert_eq!(c.carried, ["a", "b", "c"]);
        assert!(matches!(
            c.adjustment,
            Some(Adjustment::Filled { tested: false, .. })
        ));
    }
}
