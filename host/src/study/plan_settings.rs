//! What a pod study's `[plan]` and `[parameters]` become for the calibration engine: the
//! factors (with the values they are held at), the plan's settings, and the problem of its
//! target and validation measurements.

use super::plan::{ModelOrder as PlanOrder, ScreeningDesign};
use super::{Measurement, Study};
use crate::calibration::settings::{
    Extension, PathSettings, PlanSettings, ScreeningSettings, SurfaceDesign, SurfaceSettings,
    ValidationSettings,
};
use crate::calibration::{Factor, Objective, Problem, Rig};
use crate::doe::PlackettBurmanRuns;
use crate::stats::ModelOrder;

/// The objective of measurement `m` on `rig`.
pub fn objective<'a>(rig: &'a dyn Rig, m: &Measurement) -> Objective<'a> {
    Objective {
        rig,
        experiment: m.experiment.name().to_owned(),
        quantity: m.quantity.clone(),
        unit: m.unit.clone(),
        value: m.mean().expect("a validated measurement has a mean"),
        condition: m.condition.clone(),
    }
}

impl Study {
    /// The calibration of this study: its factors and plan, the target measured on
    /// `target_rig` and the validation measurement on `validation_rig`.
    pub fn problem<'a>(&self, target_rig: &'a dyn Rig, validation_rig: &'a dyn Rig) -> Problem<'a> {
        Problem {
            factors: self.factors(),
            plan: self.plan_settings(),
            target: objective(target_rig, self.target()),
            validation: objective(validation_rig, self.validation()),
        }
    }

    /// The varied parameters as calibration factors, in registry order (seed 000 Table 3's
    /// x1…x8), each held at the study's value or its range's centre.
    pub fn factors(&self) -> Vec<Factor> {
        self.varied()
            .into_iter()
            .map(|v| Factor {
                name: v.spec.name.to_owned(),
                label: v.label,
                unit: v.spec.unit.to_owned(),
                low: v.range.low,
                high: v.range.high,
                held: self.held_value(v.spec).unwrap_or(v.range.centre()),
                physical: v.spec.limits,
                admitted: v.range.limits(v.spec),
            })
            .collect()
    }

    /// The plan's settings: seed 000's sequence (a path going on with doubling gaps when
    /// `max_points` allows, a Box–Behnken response surface).
    pub fn plan_settings(&self) -> PlanSettings {
        let plan = &self.file().plan;
        PlanSettings {
            screening: ScreeningSettings {
                runs: match plan.screening.design {
                    ScreeningDesign::Pb12 => PlackettBurmanRuns::Twelve,
                    ScreeningDesign::Pb20 => PlackettBurmanRuns::Twenty,
                },
                centre_points: plan.screening.centre_points as usize,
                significance: plan.screening.significance,
                carry_level: None,
                named: None,
            },
            path: PathSettings {
                points: plan.steepest_ascent.points as usize,
                step_coded: plan.steepest_ascent.step_coded,
                origin_coded: plan.steepest_ascent.origin_coded,
                extension: plan
                    .steepest_ascent
                    .max_points
                    .map_or(Extension::None, |m| Extension::Doubling {
                        max_points: m as usize,
                    }),
            },
            surface: SurfaceSettings {
                design: SurfaceDesign::BoxBehnken,
                centre_points: plan.box_behnken.centre_points as usize,
                model: match plan.model.order {
                    PlanOrder::Linear => ModelOrder::Linear,
                    PlanOrder::Interaction => ModelOrder::TwoFactorInteraction,
                    PlanOrder::Quadratic => ModelOrder::Quadratic,
                },
            },
            validation: ValidationSettings {
                replicates: plan.validation.replicates(),
                max_relative_error_pct: plan.validation.max_relative_error_pct,
            },
        }
    }
}
