//! The stages' decisions in words, as `calibration.json` and `report.md` state them: why
//! other factors than those that passed screening go on, how the path went on and why it
//! stopped, how the response-surface box was chosen.

use crate::calibration::plan::response_surface::{BoxChoice, ResponseSurface};
use crate::calibration::plan::screening::{Adjustment, Screening};
use crate::calibration::plan::steepest_ascent::SteepestAscent;
use crate::calibration::settings::{Extension, SurfaceDesign};

/// The response-surface stage's name in a sentence.
pub fn stage_name(design: SurfaceDesign) -> &'static str {
    match design {
        SurfaceDesign::BoxBehnken => "the Box–Behnken stage",
        SurfaceDesign::CentralComposite { .. } => "the central composite stage",
    }
}

/// The response-surface box's name in a sentence.
fn box_name(design: SurfaceDesign) -> &'static str {
    match design {
        SurfaceDesign::BoxBehnken => "the Box–Behnken box",
        SurfaceDesign::CentralComposite { .. } => "the central composite box",
    }
}

/// "p < α" or "p ≤ level": what passing screening meant.
pub fn pass_rule(s: &Screening) -> String {
    match s.choice.carry_level {
        None => format!("p < {}", s.significance),
        Some(level) => format!("p ≤ {level}"),
    }
}

/// The screening's notes.
pub fn screening(s: &Screening, design: SurfaceDesign) -> Vec<String> {
    let stage = stage_name(design);
    let range = crate::calibration::plan::response_surface::factor_range(design);
    let mut notes = Vec::new();
    match &s.choice.adjustment {
        None => {}
        Some(Adjustment::Capped { passed, dropped }) => notes.push(format!(
            "{passed} factors passed screening; {stage} takes at most {max}, so the {max} of \
             largest |effect| go on and {} are held",
            dropped.join(", "),
            max = range.end()
        )),
        Some(Adjustment::Filled {
            passed,
            tested,
            fill,
        }) => {
            let why = if !tested {
                "the ANOVA is undefined, so no factor could be tested".to_owned()
            } else if *passed == 0 {
                format!("no factor reached {}", pass_rule(s))
            } else {
                format!("only {passed} factor(s) reached {}", pass_rule(s))
            };
            notes.push(format!(
                "{why}; {stage} needs {} factors, so the largest |effect| among the rest fill \
                 up: {}",
                range.start(),
                fill.join(", ")
            ));
        }
    }
    if let Some(reason) = &s.choice.named_reason {
        notes.push(format!(
            "the path and {stage} take {} ({reason}); the screening alone would have carried {}",
            s.choice.carried.join(", "),
            s.choice.screening.join(", ")
        ));
    }
    notes
}

/// The path's notes.
pub fn path(p: &SteepestAscent, design: SurfaceDesign) -> Vec<String> {
    let mut notes = Vec::new();
    let n = p.runs.len();
    if n > p.planned {
        notes.push(match p.extension {
            Extension::SingleSteps { .. } => format!(
                "the response was still approaching the target after the planned {} points, so \
                 the path went on one step at a time to {n} points",
                p.planned
            ),
            _ => format!(
                "the planned {} points did not reach the target, so the path went on with \
                 doubling gaps to {n} points (positions {:?})",
                p.planned,
                &p.positions[p.planned..]
            ),
        });
    }
    if p.held_at_limits {
        notes.push(
            "the path stopped where every factor is held by a physical limit or its screened \
             level"
                .to_owned(),
        );
    }
    if let Some(reason) = &p.stopped_at_limit {
        notes.push(format!("the path stopped: the next point has {reason}"));
    }
    if p.best_at_path_end() {
        notes.push(format!(
            "the best point is the path's last (point {}): the target may lie beyond the path, \
             so {} reaches one step past it",
            p.best,
            box_name(design)
        ));
    }
    if p.best == 1 {
        notes.push(
            "the best point is the path's first: the response moved away from the target \
             along the whole path"
                .to_owned(),
        );
    }
    notes
}

/// How the response-surface box was chosen.
pub fn box_rule(s: &ResponseSurface) -> String {
    let [a, b] = s.path_points;
    match (s.choice, s.design) {
        (BoxChoice::Bracketing, _) => {
            format!("path points {a} and {b} bracket the target (seed 000 §3.4)")
        }
        (BoxChoice::AroundBest, SurfaceDesign::BoxBehnken) => format!(
            "no neighbour of the best path point {} brackets the target, so the box spans \
             one step either side of it",
            s.best_path_point
        ),
        (BoxChoice::AroundBest, SurfaceDesign::CentralComposite { .. }) => format!(
            "path points {a} and {b}, the neighbours of the best point {}, are −1 and +1 \
             (seed 001 Table 9)",
            s.best_path_point
        ),
    }
}
