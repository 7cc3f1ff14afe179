//! `calibration.json` (format [`CALIBRATION_FORMAT`]): every number of a calibration, the
//! stages' decisions phrased as notes. The field names and order are those of the first
//! (seed 000) calibration, so files of every rig read alike and the shipped study's file is
//! unchanged byte for byte.

use std::collections::BTreeMap;

use serde::Serialize;

use super::notes;
use crate::calibration::plan::response_surface::ResponseSurface;
use crate::calibration::plan::screening::Screening;
use crate::calibration::plan::steepest_ascent::SteepestAscent;
use crate::calibration::settings::SurfaceDesign;
use crate::calibration::{Factor, Objective, Problem, RunRecord, Stages};
use crate::stats::Anova;

/// Format tag of `calibration.json`.
pub const CALIBRATION_FORMAT: &str = "arachis-calibration-1";

/// Who ran the calibration: the study, the mode and the rig.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// The study's name.
    pub study: String,
    /// The run mode (`-` for a rig without modes).
    pub mode: String,
}

/// A factor of a design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FactorJson {
    /// Parameter name.
    pub name: String,
    /// Report label.
    pub label: String,
    /// Unit of `low` and `high`.
    pub unit: String,
    /// Actual level at coded −1.
    pub low: f64,
    /// Actual level at coded +1.
    pub high: f64,
}

impl From<&Factor> for FactorJson {
    fn from(f: &Factor) -> Self {
        Self {
            name: f.name.clone(),
            label: f.label.clone(),
            unit: f.unit.clone(),
            low: f.low,
            high: f.high,
        }
    }
}

fn factors(fs: &[Factor]) -> Vec<FactorJson> {
    fs.iter().map(FactorJson::from).collect()
}

/// One finished run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunJson {
    /// 1-based run number within the stage.
    pub run: usize,
    /// Coded settings.
    pub coded: Vec<f64>,
    /// The parameters the run set.
    pub actual: BTreeMap<String, f64>,
    /// Replicate index.
    pub replicate: u32,
    /// Hash of the run's specification (its file under `runs/`).
    pub spec_hash: String,
    /// The response, in the target's unit.
    pub response: f64,
}

fn runs(rs: &[RunRecord]) -> Vec<RunJson> {
    rs.iter()
        .map(|r| RunJson {
            run: r.run,
            coded: r.coded.clone(),
            actual: r.values.clone(),
            replicate: r.replicate,
            spec_hash: r.spec_hash.to_string(),
            response: r.response,
        })
        .collect()
}

/// A measured quantity and its condition.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TargetJson {
    /// The experiment.
    pub experiment: String,
    /// The quantity.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The measured mean, in `unit`.
    pub value: f64,
    /// The measurement's condition.
    pub condition: BTreeMap<String, f64>,
}

/// One factor's screening effect.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EffectJson {
    /// Report label.
    pub label: String,
    /// Parameter name.
    pub name: String,
    /// Coded coefficient bⱼ.
    pub coefficient: f64,
    /// Main effect 2bⱼ.
    pub effect: f64,
    /// ANOVA p-value, when defined.
    pub p: Option<f64>,
    /// p < α.
    pub significant: bool,
}

/// Stage 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScreeningJson {
    /// Design name.
    pub design: String,
    /// The factors.
    pub factors: Vec<FactorJson>,
    /// Dummy columns.
    pub dummy_columns: Vec<String>,
    /// α.
    pub significance: f64,
    /// The runs.
    pub runs: Vec<RunJson>,
    /// The first-order ANOVA, when defined.
    pub anova: Option<Anova>,
    /// Why there is none.
    pub anova_unavailable: Option<String>,
    /// Intercept b₀.
    pub intercept: f64,
    /// Effects, in factor order.
    pub effects: Vec<EffectJson>,
    /// Labels with p < α, largest |effect| first.
    pub significant: Vec<String>,
    /// Labels carried on.
    pub selected: Vec<String>,
    /// Decisions in words.
    pub notes: Vec<String>,
}

/// Stage 2.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathJson {
    /// The carried factors.
    pub factors: Vec<FactorJson>,
    /// Their screening coefficients.
    pub coefficients: Vec<f64>,
    /// "ascent" or "descent".
    pub direction: String,
    /// Screening-fit prediction at the origin.
    pub predicted_at_origin: f64,
    /// Coded start.
    pub origin_coded: Vec<f64>,
    /// Coded step.
    pub step_coded: Vec<f64>,
    /// Path positions of the runs.
    pub positions: Vec<f64>,
    /// The path points.
    pub runs: Vec<RunJson>,
    /// ψ of each point, %.
    pub relative_error_pct: Vec<f64>,
    /// 1-based best point.
    pub best: usize,
    /// The best point is the last.
    pub best_at_path_end: bool,
    /// Decisions in words.
    pub notes: Vec<String>,
}

/// Stage 3.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceJson {
    /// The factors with the box's levels.
    pub factors: Vec<FactorJson>,
    /// How the box was chosen, in words.
    pub range_rule: String,
    /// Path points of coded −1 and +1.
    pub path_points: [i64; 2],
    /// Centre points.
    pub centre_points: usize,
    /// The runs.
    pub runs: Vec<RunJson>,
    /// The model fitted.
    pub model: String,
    /// Its ANOVA.
    pub anova: Anova,
}

/// The desirability goal.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GoalJson {
    /// Target T.
    pub target: f64,
    /// T − w.
    pub low: f64,
    /// T + w.
    pub high: f64,
}

/// One parameter of the calibrated set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterRow {
    /// Parameter name.
    pub name: String,
    /// Report label.
    pub label: String,
    /// Unit.
    pub unit: String,
    /// Calibrated or held value.
    pub value: f64,
    /// "calibrated" or "held".
    pub role: String,
    /// Screening range.
    pub low: f64,
    /// Screening range.
    pub high: f64,
}

/// Stage 4.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptimumJson {
    /// The goal.
    pub goal: GoalJson,
    /// Coded point.
    pub coded: Vec<f64>,
    /// The calibrated factors' values.
    pub actual: BTreeMap<String, f64>,
    /// Overall desirability D.
    pub desirability: f64,
    /// Surface prediction there.
    pub predicted: f64,
    /// Distinct solutions found with D > 0.
    pub solutions_found: usize,
    /// Every varied parameter at the calibrated set.
    pub parameters: Vec<ParameterRow>,
}

/// Stage 5.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ValidationJson {
    /// The experiment.
    pub experiment: String,
    /// The quantity.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The condition.
    pub condition: BTreeMap<String, f64>,
    /// Measured mean ζ.
    pub measured: f64,
    /// Simulated mean ζ′.
    pub simulated: f64,
    /// SD of the replicates.
    pub simulated_sd: f64,
    /// Surface prediction at the optimum.
    pub predicted: f64,
    /// ψ, %.
    pub relative_error_pct: f64,
    /// Largest accepted ψ, %.
    pub max_relative_error_pct: f64,
    /// ψ within the limit.
    pub passed: bool,
    /// The validation runs.
    pub runs: Vec<RunJson>,
}

/// Everything `calibration.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CalibrationJson {
    /// [`CALIBRATION_FORMAT`].
    pub format: &'static str,
    /// The study's name.
    pub study: String,
    /// The run mode.
    pub mode: String,
    /// The rig's id.
    pub simulator: String,
    /// The rig in words.
    pub simulator_description: String,
    /// The target measurement.
    pub target: TargetJson,
    /// Stage 1.
    pub screening: ScreeningJson,
    /// Stage 2.
    pub steepest_ascent: PathJson,
    /// Stage 3 with a Box–Behnken design.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub box_behnken: Option<SurfaceJson>,
    /// Stage 3 with a central composite design.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub central_composite: Option<SurfaceJson>,
    /// Stage 4.
    pub optimum: OptimumJson,
    /// Stage 5.
    pub validation: ValidationJson,
}

fn target(o: &Objective<'_>) -> TargetJson {
    TargetJson {
        experiment: o.experiment.clone(),
        quantity: o.quantity.clone(),
        unit: o.unit.clone(),
        value: o.value,
        condition: o.condition.clone(),
    }
}

fn screening(s: &Screening, design: SurfaceDesign) -> ScreeningJson {
    let mut by_size: Vec<_> = s.effects.iter().filter(|e| e.significant).collect();
    by_size.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    ScreeningJson {
        design: s.design.clone(),
        factors: factors(&s.factors),
        dummy_columns: s.dummy_columns.clone(),
        significance: s.significance,
        runs: runs(&s.runs),
        anova: s.anova.clone(),
        anova_unavailable: s.anova_unavailable.clone(),
        intercept: s.intercept,
        effects: s
            .effects
            .iter()
            .map(|e| EffectJson {
                label: e.label.clone(),
                name: e.name.clone(),
                coefficient: e.coefficient,
                effect: e.effect,
                p: e.p,
                significant: e.significant,
            })
            .collect(),
        significant: by_size.iter().map(|e| e.label.clone()).collect(),
        selected: s.choice.carried.clone(),
        notes: notes::screening(s, design),
    }
}

fn path(p: &SteepestAscent, design: SurfaceDesign) -> PathJson {
    PathJson {
        factors: factors(&p.factors),
        coefficients: p.coefficients.clone(),
        direction: p.direction.name().to_owned(),
        predicted_at_origin: p.predicted_at_origin,
        origin_coded: p.origin_coded.clone(),
        step_coded: p.step_coded.clone(),
        positions: p.positions.clone(),
        runs: runs(&p.runs),
        relative_error_pct: p.relative_error_pct.clone(),
        best: p.best,
        best_at_path_end: p.best_at_path_end(),
        notes: notes::path(p, design),
    }
}

fn surface(s: &ResponseSurface) -> SurfaceJson {
    SurfaceJson {
        factors: factors(&s.factors),
        range_rule: notes::box_rule(s),
        path_points: s.path_points,
        centre_points: s.centre_points,
        runs: runs(&s.runs),
        model: s.model.clone(),
        anova: s.anova.clone(),
    }
}

/// The calibrated value of every screened factor (the optimum's, else the held one).
pub fn parameter_rows(stages: &Stages) -> Vec<ParameterRow> {
    stages
        .screening
        .factors
        .iter()
        .map(|f| {
            let (value, role) = match stages.optimum.values.get(&f.name) {
                Some(v) => (*v, "calibrated"),
                None => (f.held, "held"),
            };
            ParameterRow {
                name: f.name.clone(),
                label: f.label.clone(),
                unit: f.unit.clone(),
                value,
                role: role.to_owned(),
                low: f.low,
                high: f.high,
            }
        })
        .collect()
}

impl CalibrationJson {
    /// The file's content for `problem`'s `stages`.
    pub fn new(problem: &Problem<'_>, stages: &Stages, provenance: &Provenance) -> Self {
        let rig = problem.target.rig;
        let design = problem.plan.surface.design;
        let o = &stages.optimum;
        let v = &stages.validation;
        let fitted = surface(&stages.surface);
        let (box_behnken, central_composite) = match design {
            SurfaceDesign::BoxBehnken => (Some(fitted), None),
            SurfaceDesign::CentralComposite { .. } => (None, Some(fitted)),
        };
        Self {
            format: CALIBRATION_FORMAT,
            study: provenance.study.clone(),
            mode: provenance.mode.clone(),
            simulator: rig.id(),
            simulator_description: rig.description(),
            target: target(&problem.target),
            screening: screening(&stages.screening, design),
            steepest_ascent: path(&stages.path, design),
            box_behnken,
            central_composite,
            optimum: OptimumJson {
                goal: GoalJson {
                    target: o.goal.target,
                    low: o.goal.low,
                    high: o.goal.high,
                },
                coded: o.coded.clone(),
                actual: o.values.clone(),
                desirability: o.desirability,
                predicted: o.predicted,
                solutions_found: o.solutions_found,
                parameters: parameter_rows(stages),
            },
            validation: ValidationJson {
                experiment: problem.validation.experiment.clone(),
                quantity: problem.validation.quantity.clone(),
                unit: problem.validation.unit.clone(),
                condition: problem.validation.condition.clone(),
                measured: v.measured,
                simulated: v.simulated,
                simulated_sd: v.simulated_sd,
                predicted: v.predicted,
                relative_error_pct: v.relative_error_pct,
                max_relative_error_pct: v.max_relative_error_pct,
                passed: v.passed,
                runs: runs(&v.runs),
            },
        }
    }

    /// The response surface stage, whichever design it used.
    pub fn surface(&self) -> &SurfaceJson {
        self.box_behnken
            .as_ref()
            .or(self.central_composite.as_ref())
            .expect("a calibration has one response-surface stage")
    }
}
