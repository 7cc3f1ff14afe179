//! What a study becomes for the calibration engine: the factors (with the values they are
//! held at), the plan's settings, and the problem of its target and validation
//! measurements on their rigs.

use super::plan::{
    ModelOrder as PlanOrder, PathExtension, DEFAULT_ORIGIN_CODED, DEFAULT_VALIDATION_REPLICATES,
};
use super::validate::ranges::measured_rig_parameters;
use super::{Measurement, Study};
use crate::calibration::settings::{
    Extension, NamedFactors, PathSettings, PlanSettings, ScreeningSettings, SurfaceDesign,
    SurfaceSettings, ValidationSettings,
};
use crate::calibration::{Factor, Objective, Problem, Rig};
use crate::doe::PlackettBurmanRuns;
use crate::rigs::{catalogue, pull_off};
use crate::stats::ModelOrder;

/// The objective of measurement `m` on `rig`.
pub fn objective<'a>(rig: &'a dyn Rig, m: &Measurement) -> Objective<'a> {
    Objective {
        rig,
        experiment: m.experiment.clone(),
        quantity: m.quantity.clone(),
        unit: m.unit.clone(),
        value: m.mean().unwrap_or(f64::NAN),
        condition: m.condition.clone(),
    }
}

impl Study {
    /// The calibration of this study: its factors and plan, the target measured on
    /// `target_rig` and the validation measurement on `validation_rig`. `None` for a study
    /// without a plan.
    pub fn problem<'a>(
        &self,
        target_rig: &'a dyn Rig,
        validation_rig: &'a dyn Rig,
    ) -> Option<Problem<'a>> {
        Some(Problem {
            factors: self.factors(),
            plan: self.plan_settings()?,
            target: objective(target_rig, self.target()?),
            validation: objective(validation_rig, self.validation()?),
        })
    }

    /// The varied parameters as calibration factors: the pod world's, in registry order
    /// (seed 000 Table 3's x1…x8), each held at the study's value or its range's centre;
    /// then the pull-off rig's, in seed 001 Table 5's order, held at their centres; then,
    /// in a study without a pod world, the `[parameters]` of its measured rigs.
    pub fn factors(&self) -> Vec<Factor> {
        let pods = self.varied().into_iter().map(|v| Factor {
            name: v.spec.name.to_owned(),
            label: v.label,
            unit: v.spec.unit.to_owned(),
            low: v.range.low,
            high: v.range.high,
            held: self.held_value(v.spec).unwrap_or(v.range.centre()),
            physical: v.spec.limits,
            admitted: v.range.limits(v.spec),
        });
        let pulls = pull_off::PARAMETERS.iter().filter_map(|p| {
            let levels = self.file().factors.get(p.label)?;
            Some(Factor {
                name: p.name.to_owned(),
                label: p.label.to_owned(),
                unit: p.unit.to_owned(),
                low: levels.low,
                high: levels.high,
                held: 0.5 * (levels.low + levels.high),
                physical: p.limits,
                admitted: p.limits,
            })
        });
        // Without a pod world, `[parameters]` ranges name the measured rigs' parameters.
        let rigs = if self.pod_world().is_some() {
            Vec::new()
        } else {
            measured_rig_parameters(self.file())
        };
        let others = self.file().parameters.iter().filter_map(|(name, range)| {
            let p = rigs.iter().find(|p| p.key == name)?;
            Some(Factor {
                name: name.clone(),
                label: range.label.clone().unwrap_or_else(|| name.clone()),
                unit: p.unit.to_owned(),
                low: range.low,
                high: range.high,
                held: range.centre(),
                physical: p.limits,
                admitted: p.limits,
            })
        });
        pods.chain(pulls).chain(others).collect()
    }

    /// The plan's settings (`None` without a plan). A path with `max_points` goes on as
    /// `extension` says, by default as its design's seed did: with doubling gaps before a
    /// Box–Behnken design (seed 000's study), one step at a time before a central
    /// composite one (seed 001's). Validation runs `replicates` times, by default three for
    /// a rig with random placement and once for a deterministic one.
    pub fn plan_settings(&self) -> Option<PlanSettings> {
        let plan = self.file().plan.as_ref()?;
        let composite = plan.central_composite.as_ref();
        let path = &plan.steepest_ascent;
        let extension = match (path.max_points, path.extension, composite) {
            (None, _, _) => Extension::None,
            (Some(m), Some(PathExtension::SingleSteps), _) | (Some(m), None, Some(_)) => {
                Extension::SingleSteps {
                    max_points: m as usize,
                }
            }
            (Some(m), _, _) => Extension::Doubling {
                max_points: m as usize,
            },
        };
        let random = self
            .target()
            .and_then(|t| catalogue::find(&t.experiment))
            .is_some_and(|k| k.random);
        Some(PlanSettings {
            screening: ScreeningSettings {
                runs: if plan.screening.design_runs() == 20 {
                    PlackettBurmanRuns::Twenty
                } else {
                    PlackettBurmanRuns::Twelve
                },
                centre_points: plan.screening.centre_points as usize,
                significance: plan.screening.significance,
                carry_level: plan.screening.carry_level,
                named: composite.and_then(|c| {
                    c.factors.clone().map(|labels| NamedFactors {
                        labels,
                        reason: format!(
                            "named by the study's [plan.central_composite] factors: {}",
                            c.why.as_deref().unwrap_or_default()
                        ),
                    })
                }),
            },
            path: PathSettings {
                points: path.points as usize,
                step_coded: path.step_coded,
                origin_coded: path.origin_coded.unwrap_or(DEFAULT_ORIGIN_CODED),
                extension,
            },
            surface: SurfaceSettings {
                design: match composite {
                    Some(c) => SurfaceDesign::CentralComposite { alpha: c.alpha },
                    None => SurfaceDesign::BoxBehnken,
                },
                centre_points: match (composite, &plan.box_behnken) {
                    (Some(c), _) => c.centre_points as usize,
                    (None, Some(b)) => b.centre_points as usize,
                    (None, None) => 0,
                },
                model: match plan.model.as_ref().map(|m| m.order) {
                    Some(PlanOrder::Linear) => ModelOrder::Linear,
                    Some(PlanOrder::Interaction) => ModelOrder::TwoFactorInteraction,
                    Some(PlanOrder::Quadratic) | None => ModelOrder::Quadratic,
                },
            },
            validation: ValidationSettings {
                replicates: plan.validation.replicates.unwrap_or(if random {
                    DEFAULT_VALIDATION_REPLICATES
                } else {
                    1
                }),
                max_relative_error_pct: plan.validation.max_relative_error_pct,
            },
        })
    }
}
