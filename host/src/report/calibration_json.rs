//! `calibration.json` (format [`CALIBRATION_FORMAT`]): every number of a calibration, the
//! stages' decisions phrased as notes. The field names and order are those of the first
//! (seed 000) calibration, so files of every rig read alike and the shipped study's file is
//! unchanged byte for byte.

use std::collections::BTreeMap;

use serde::Serialize;

use super::notes;
use crate::calibration::plan::optimum::Optimum;
use crate::calibration::plan::response_surface::ResponseSurface;
use crate::calibration::plan::screening::Screening;
use crate::calibration::plan::steepest_ascent::SteepestAscent;
use crate::calibration::plan::validation::Validation;
use crate::calibration::settings::SurfaceDesign;
use crate::calibration::{Factor, Objective, Problem, RunRecord, Stages};
use crate::rigs::pod_world::Mode;
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
    /// The size of each pile (the mode's pods and spheres per pod), for a calibration that
    /// simulates pod piles (the DEM repose rig); `None` for any other rig, which keeps its
    /// file as it was.
    pub pile: Option<Mode>,
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

/// Stage 1: the engine's numbers, then the screening's decisions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScreeningJson {
    /// Design, factors, runs, ANOVA and effects.
    #[serde(flatten)]
    pub stage: Screening,
    /// Labels with p < α, largest |effect| first.
    pub significant: Vec<String>,
    /// Labels carried on.
    pub selected: Vec<String>,
    /// Decisions in words.
    pub notes: Vec<String>,
}

/// Stage 2: the engine's numbers, then how the path ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PathJson {
    /// Factors, direction, points and their errors.
    #[serde(flatten)]
    pub stage: SteepestAscent,
    /// The best point is the last.
    pub best_at_path_end: bool,
    /// Decisions in words.
    pub notes: Vec<String>,
}

/// Stage 3.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceJson {
    /// The factors with the box's levels.
    pub factors: Vec<Factor>,
    /// How the box was chosen, in words.
    pub range_rule: String,
    /// Path points of coded −1 and +1.
    pub path_points: [i64; 2],
    /// Centre points.
    pub centre_points: usize,
    /// The runs.
    pub runs: Vec<RunRecord>,
    /// The model fitted.
    pub model: String,
    /// Its ANOVA.
    pub anova: Anova,
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

/// Stage 4: the engine's optimum, then the whole calibrated set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OptimumJson {
    /// Goal, point, desirability and prediction.
    #[serde(flatten)]
    pub stage: Optimum,
    /// Every varied parameter at the calibrated set.
    pub parameters: Vec<ParameterRow>,
}

/// Stage 5: the measurement validated against, then the engine's numbers.
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
    /// Measured and simulated values, error and runs.
    #[serde(flatten)]
    pub stage: Validation,
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
    /// Pods per simulated pile (a DEM pile calibration only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pods: Option<u32>,
    /// Spheres per pod (a DEM pile calibration only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub spheres_per_pod: Option<u32>,
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
        stage: s.clone(),
        significant: by_size.iter().map(|e| e.label.clone()).collect(),
        selected: s.choice.carried.clone(),
        notes: notes::screening(s, design),
    }
}

fn surface(s: &ResponseSurface) -> SurfaceJson {
    SurfaceJson {
        factors: s.factors.clone(),
        range_rule: notes::box_rule(s),
        path_points: s.path_points,
        centre_points: s.centre_points,
        runs: s.runs.clone(),
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
        let fitted = surface(&stages.surface);
        let (box_behnken, central_composite) = match design {
            SurfaceDesign::BoxBehnken => (Some(fitted), None),
            SurfaceDesign::CentralComposite { .. } => (None, Some(fitted)),
        };
        Self {
            format: CALIBRATION_FORMAT,
            study: provenance.study.clone(),
            mode: provenance.mode.clone(),
            pods: provenance.pile.as_ref().map(|p| p.pods),
            spheres_per_pod: provenance.pile.as_ref().map(|p| p.spheres_per_pod),
            simulator: rig.id(),
            simulator_description: rig.description(),
            target: target(&problem.target),
            screening: screening(&stages.screening, design),
            steepest_ascent: PathJson {
                stage: stages.path.clone(),
                best_at_path_end: stages.path.best_at_path_end(),
                notes: notes::path(&stages.path, design),
            },
            box_behnken,
            central_composite,
            optimum: OptimumJson {
                stage: stages.optimum.clone(),
                parameters: parameter_rows(stages),
            },
            validation: ValidationJson {
                experiment: problem.validation.experiment.clone(),
                quantity: problem.validation.quantity.clone(),
                unit: problem.validation.unit.clone(),
                condition: problem.validation.condition.clone(),
                stage: stages.validation.clone(),
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
