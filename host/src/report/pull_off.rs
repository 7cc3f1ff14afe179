//! Seed 001's pull-off calibration report, `plant-calibration.json` (format
//! [`FORMAT`]) and `report.md`: the tables of seed 001 §3 for the pull-off rig and how they
//! compare with the seed. A pull-off study writes it instead of `calibration.json` for one
//! release, so its output stays byte for byte what the former plant calibration wrote;
//! the numbers are the engine's, only their layout and words are this format's.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use super::{prepare_dir, write};
use crate::calibration::plan::screening::{Adjustment, Screening as Screened};
use crate::calibration::plan::steepest_ascent::SteepestAscent;
use crate::calibration::settings::{Extension, SurfaceDesign};
use crate::calibration::{CalibrateError, Factor, Problem, RunRecord, Stages};
use crate::rigs::pull_off::{
    by_name, PullOffRig, Setting, PREDICTED_AXIAL_FORCE, SEED_CARRIED, SEED_SIGNIFICANT,
};
use crate::stats::{relative_error_percent, Anova};

/// Format tag of `plant-calibration.json`.
pub const FORMAT: &str = "arachis-plant-calibration-1";
/// JSON file name.
pub const JSON_FILE: &str = "plant-calibration.json";
/// Markdown file name.
pub const MARKDOWN_FILE: &str = "report.md";

/// A screening factor with seed 001's words.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantFactor {
    /// Seed 001 Table 5 label (x1…x9).
    pub label: String,
    /// What it is, in words.
    pub description: &'static str,
    /// Unit of `low` and `high` (SI).
    pub unit: String,
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
    /// What it sets in the rig.
    pub setting: Setting,
}

/// The plan that ran.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// The nine factors.
    pub factors: Vec<PlantFactor>,
    /// Runs of the Plackett–Burman design.
    pub screening_runs: usize,
    /// Centre points of the screening design.
    pub screening_centre_points: usize,
    /// Screening significance level.
    pub significance: f64,
    /// Level at which a screened factor is carried on (p at or below it).
    pub carry_level: Option<f64>,
    /// Coded step of the largest-|b| factor per path point.
    pub path_step_coded: f64,
    /// Path points run at once.
    pub path_first_points: usize,
    /// Longest path.
    pub path_max_points: usize,
    /// Axial distance α of the central composite design, coded.
    pub ccd_alpha: f64,
    /// Centre points of the central composite design.
    pub ccd_centre_points: usize,
    /// Factors the plan names for the path and the design.
    pub carry: Option<Vec<String>>,
    /// Where `carry` comes from and why.
    pub carry_reason: Option<String>,
    /// Pass mark of the validation pull, % relative error.
    pub max_relative_error_pct: f64,
}

/// The rig's test conditions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RigInfo {
    /// Gripper speed, m/s.
    pub pull_speed_m_s: f64,
    /// Pull direction from the stalk axis, degrees.
    pub pull_angle_deg: f64,
    /// Spheres in the stalk.
    pub stalk_spheres: u32,
    /// Junction normal stiffness per unit area (held), N/m³.
    pub junction_normal_stiffness_n_m3: f64,
}

/// One pull-off run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Run {
    /// Coded settings in the stage's coding.
    pub coded: Vec<f64>,
    /// The nine factors x1…x9 (SI).
    pub settings: Vec<f64>,
    /// Detachment force, N.
    pub detachment_force_n: f64,
    /// σc·πRb² of the run, N.
    pub predicted_axial_n: f64,
}

/// One factor's screening result.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Effect {
    /// Label.
    pub label: String,
    /// Coded coefficient bⱼ, N per coded unit.
    pub coefficient: f64,
    /// Main effect 2bⱼ, N.
    pub effect: f64,
    /// ANOVA p-value (null without an ANOVA).
    pub p: f64,
}

/// Stage 1.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Screening {
    /// Runs in standard order.
    pub runs: Vec<Run>,
    /// The first-order ANOVA (with the curvature term).
    pub anova: Option<Anova>,
    /// Intercept b₀, N.
    pub intercept: f64,
    /// Effects in factor order.
    pub effects: Vec<Effect>,
    /// Labels with p < α, smallest p first.
    pub significant: Vec<String>,
    /// Labels carried on.
    pub carried: Vec<String>,
    /// What the screening alone chose, passed factors first, largest |effect| first.
    pub screening_choice: Vec<String>,
    /// Decisions in words.
    pub notes: Vec<String>,
    /// 2b₈₉/3, N: the main effect the x8·x9 interaction of F = σc·πRb² lends every other
    /// column of a 12-run Plackett–Burman design.
    pub x8_x9_alias_effect_n: f64,
}

/// Stage 2.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteepestPath {
    /// Carried labels.
    pub factors: Vec<String>,
    /// Their screening coefficients.
    pub coefficients: Vec<f64>,
    /// "ascent" or "descent".
    pub direction: String,
    /// Coded start.
    pub origin_coded: Vec<f64>,
    /// Coded change per point.
    pub step_coded: Vec<f64>,
    /// The points.
    pub runs: Vec<Run>,
    /// |F − T|/T × 100 % of each point.
    pub relative_error_pct: Vec<f64>,
    /// 1-based best point.
    pub best: usize,
    /// Decisions in words.
    pub notes: Vec<String>,
}

/// A factor of the central composite design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CcdFactor {
    /// Label.
    pub label: String,
    /// Unit.
    pub unit: String,
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
}

/// Stage 3.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CentralComposite {
    /// The factors.
    pub factors: Vec<CcdFactor>,
    /// α, coded.
    pub alpha: f64,
    /// Runs in standard order.
    pub runs: Vec<Run>,
    /// The quadratic ANOVA.
    pub anova: Anova,
}

/// Stages 4 and 5.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Optimum {
    /// Coded point (the central composite coding).
    pub coded: Vec<f64>,
    /// The carried factors' calibrated values (label, value).
    pub calibrated: Vec<(String, f64)>,
    /// All nine factors at the optimum.
    pub settings: Vec<f64>,
    /// Overall desirability D.
    pub desirability: f64,
    /// Surface prediction there, N.
    pub predicted_n: f64,
    /// The validation pull's detachment force, N.
    pub validated_n: f64,
    /// σc·πRb² at the optimum, N.
    pub predicted_axial_n: f64,
    /// ψ of the validation, %.
    pub relative_error_pct: f64,
    /// The pass mark, %.
    pub max_relative_error_pct: f64,
    /// ψ within the pass mark.
    pub passed: bool,
}

/// Everything `plant-calibration.json` holds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlantCalibration {
    /// [`FORMAT`].
    pub format: &'static str,
    /// The study's name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub study: Option<String>,
    /// Target detachment force, N.
    pub target_n: f64,
    /// The plan.
    pub plan: Plan,
    /// The rig.
    pub rig: RigInfo,
    /// Stage 1.
    pub screening: Screening,
    /// Stage 2.
    pub path: SteepestPath,
    /// Stage 3.
    pub central_composite: CentralComposite,
    /// Stages 4–5.
    pub optimum: Optimum,
    /// Pull-off runs in all.
    pub runs: usize,
    /// Largest |F − σc·πRb²|/σc·πRb² over every run before validation, %.
    pub axial_check_max_deviation_pct: f64,
}

/// The nine settings of a run setting `values`, the other factors held.
fn settings(all: &[Factor], values: &crate::calibration::ParameterValues) -> Vec<f64> {
    all.iter()
        .map(|f| values.get(&f.name).copied().unwrap_or(f.held))
        .collect()
}

fn axial(r: &RunRecord) -> f64 {
    r.responses
        .get(PREDICTED_AXIAL_FORCE)
        .copied()
        .unwrap_or(f64::NAN)
}

fn runs(all: &[Factor], rs: &[RunRecord]) -> Vec<Run> {
    rs.iter()
        .map(|r| Run {
            coded: r.coded.clone(),
            settings: settings(all, &r.values),
            detachment_force_n: r.response,
            predicted_axial_n: axial(r),
        })
        .collect()
}

/// 2b₈₉/3 of F = σc·πRb² over the x8 and x9 ranges, N (see
/// [`Screening::x8_x9_alias_effect_n`]).
pub fn x8_x9_alias_effect_n(all: &[Factor]) -> f64 {
    let level = |label: &str| all.iter().find(|f| f.label == label);
    let (Some(s), Some(r)) = (level("x8"), level("x9")) else {
        return f64::NAN;
    };
    let f = |sigma: f64, radius: f64| sigma * core::f64::consts::PI * radius * radius;
    let b89 = (f(s.high, r.high) - f(s.high, r.low) - f(s.low, r.high) + f(s.low, r.low)) / 4.0;
    2.0 * b89 / 3.0
}

fn screening(all: &[Factor], s: &Screened) -> Screening {
    let level = s.choice.carry_level;
    let passes = |p: Option<f64>| match level {
        None => p.is_some_and(|p| p < s.significance),
        Some(l) => p.is_some_and(|p| p <= l),
    };
    let mut by_p: Vec<_> = s.effects.iter().filter(|e| e.significant).collect();
    by_p.sort_by(|a, b| a.p.unwrap_or(f64::NAN).total_cmp(&b.p.unwrap_or(f64::NAN)));
    let mut by_size: Vec<_> = s
        .effects
        .iter()
        .filter(|e| s.choice.screening.contains(&e.label))
        .collect();
    by_size.sort_by(|a, b| b.effect.abs().total_cmp(&a.effect.abs()));
    let choice: Vec<String> = by_size
        .iter()
        .filter(|e| passes(e.p))
        .chain(by_size.iter().filter(|e| !passes(e.p)))
        .map(|e| e.label.clone())
        .collect();
    let rule = level.map_or(format!("p < {}", s.significance), |l| format!("p ≤ {l}"));
    let (min, max) = (
        crate::calibration::plan::central_composite::MIN_FACTORS,
        crate::calibration::plan::central_composite::MAX_FACTORS,
    );
    let mut notes = Vec::new();
    match &s.choice.adjustment {
        Some(Adjustment::Capped { passed, .. }) => notes.push(format!(
            "{passed} factors reached {rule}; the {max} of largest |effect| go on"
        )),
        Some(Adjustment::Filled { passed, fill, .. }) => notes.push(format!(
            "only {passed} factor(s) reached {rule}; the central composite design needs \
             {min}, so the largest |effect| among the rest fill up: {}",
            fill.join(", ")
        )),
        None => {}
    }
    if let Some(reason) = &s.choice.named_reason {
        notes.push(format!(
            "the path and the central composite design take {} ({reason}); the screening \
             alone would have carried {}",
            s.choice.carried.join(", "),
            choice.join(", ")
        ));
    }
    Screening {
        runs: runs(all, &s.runs),
        anova: s.anova.clone(),
        intercept: s.intercept,
        effects: s
            .effects
            .iter()
            .map(|e| Effect {
                label: e.label.clone(),
                coefficient: e.coefficient,
                effect: e.effect,
                p: e.p.unwrap_or(f64::NAN),
            })
            .collect(),
        significant: by_p.iter().map(|e| e.label.clone()).collect(),
        carried: s.choice.carried.clone(),
        screening_choice: choice,
        notes,
        x8_x9_alias_effect_n: x8_x9_alias_effect_n(all),
    }
}

fn path(all: &[Factor], p: &SteepestAscent) -> SteepestPath {
    let mut notes = Vec::new();
    if let Some(reason) = &p.stopped_at_limit {
        notes.push(format!("the path stops: the next point has {reason}"));
    }
    if p.runs.len() > p.planned {
        notes.push(format!(
            "the force was still approaching the target after the plan's {} points, so the \
             path went on to {} points",
            p.planned,
            p.runs.len()
        ));
    }
    if p.best_at_path_end() {
        notes.push("the best point is the path's last: the target may lie beyond it".into());
    }
    SteepestPath {
        factors: p.factors.iter().map(|f| f.label.clone()).collect(),
        coefficients: p.coefficients.clone(),
        direction: p.direction.name().to_owned(),
        origin_coded: p.origin_coded.clone(),
        step_coded: p.step_coded.clone(),
        runs: runs(all, &p.runs),
        relative_error_pct: p.relative_error_pct.clone(),
        best: p.best,
        notes,
    }
}

impl PlantCalibration {
    /// The report of a pull-off calibration of study `study` on `rig`.
    pub fn new(problem: &Problem<'_>, stages: &Stages, study: &str, rig: &PullOffRig) -> Self {
        let all = &problem.factors;
        let plan = &problem.plan;
        let (first_points, max_points) = match plan.path.extension {
            Extension::SingleSteps { max_points } => (plan.path.points, max_points),
            _ => (plan.path.points, plan.path.points),
        };
        let alpha = match plan.surface.design {
            SurfaceDesign::CentralComposite { alpha } => alpha,
            SurfaceDesign::BoxBehnken => 1.0,
        };
        let fitted = &stages.surface;
        let o = &stages.optimum;
        let v = &stages.validation;
        let before: Vec<&RunRecord> = stages
            .screening
            .runs
            .iter()
            .chain(&stages.path.runs)
            .chain(&fitted.runs)
            .collect();
        Self {
            format: FORMAT,
            study: Some(study.to_owned()),
            target_n: problem.target.value,
            plan: Plan {
                factors: all
                    .iter()
                    .map(|f| PlantFactor {
                        label: f.label.clone(),
                        description: by_name(&f.name).map_or("", |p| p.description),
                        unit: f.unit.clone(),
                        low: f.low,
                        high: f.high,
                        setting: by_name(&f.name).map_or(Setting::JunctionStrength, |p| p.sets),
                    })
                    .collect(),
                screening_runs: plan.screening.runs.runs(),
                screening_centre_points: plan.screening.centre_points,
                significance: plan.screening.significance,
                carry_level: plan.screening.carry_level,
                path_step_coded: plan.path.step_coded,
                path_first_points: first_points,
                path_max_points: max_points,
                ccd_alpha: alpha,
                ccd_centre_points: plan.surface.centre_points,
                carry: plan.screening.named.as_ref().map(|n| n.labels.clone()),
                carry_reason: plan.screening.named.as_ref().map(|n| n.reason.clone()),
                max_relative_error_pct: plan.validation.max_relative_error_pct,
            },
            rig: RigInfo {
                pull_speed_m_s: rig.base.pull_speed_m_s,
                pull_angle_deg: rig.base.pull_angle_deg,
                stalk_spheres: rig.base.stalk_spheres,
                junction_normal_stiffness_n_m3: rig.base.junction.normal_stiffness_n_m3,
            },
            screening: screening(all, &stages.screening),
            path: path(all, &stages.path),
            central_composite: CentralComposite {
                factors: fitted
                    .factors
                    .iter()
                    .map(|f| CcdFactor {
                        label: f.label.clone(),
                        unit: f.unit.clone(),
                        low: f.low,
                        high: f.high,
                    })
                    .collect(),
                alpha,
                runs: runs(all, &fitted.runs),
                anova: fitted.anova.clone(),
            },
            optimum: Optimum {
                coded: o.coded.clone(),
                calibrated: fitted
                    .factors
                    .iter()
                    .map(|f| (f.label.clone(), o.values[&f.name]))
                    .collect(),
                settings: settings(all, &o.values),
                desirability: o.desirability,
                predicted_n: o.predicted,
                validated_n: v.simulated,
                predicted_axial_n: v.runs.first().map_or(f64::NAN, axial),
                relative_error_pct: v.relative_error_pct,
                max_relative_error_pct: v.max_relative_error_pct,
                passed: v.passed,
            },
            runs: before.len() + v.runs.len(),
            axial_check_max_deviation_pct: before
                .iter()
                .map(|r| relative_error_percent(r.response, axial(r)))
                .fold(0.0_f64, f64::max),
        }
    }
}

/// Writes `plant-calibration.json` and `report.md` into `dir` (created if missing).
pub fn write_files(cal: &PlantCalibration, dir: &Path) -> Result<(), CalibrateError> {
    prepare_dir(dir)?;
    let json = serde_json::to_string_pretty(cal).expect("a calibration serialises");
    write(&dir.join(JSON_FILE), &(json + "\n"))?;
    write(&dir.join(MARKDOWN_FILE), &markdown(cal))
}

/// `v` with 4 significant digits.
fn g(v: f64) -> String {
    format!("{v:.4e}")
}

/// The markdown report.
pub fn markdown(cal: &PlantCalibration) -> String {
    let mut s = String::new();
    let s8 = &cal.screening;
    let _ = writeln!(s, "# Plant calibration: pod–stalk junction (seed 001 §3)\n");
    let _ = writeln!(
        s,
        "Target detachment force {} N (seed 001 Table 8). Rig: axial-pull tensile test at \
         {} m/s, pull angle {}°, {} stalk spheres, junction kn {} N/m³ (held). {} pull-off \
         runs.\n",
        cal.target_n,
        cal.rig.pull_speed_m_s,
        cal.rig.pull_angle_deg,
        cal.rig.stalk_spheres,
        g(cal.rig.junction_normal_stiffness_n_m3),
        cal.runs
    );
    let _ = writeln!(s, "## 1. Plackett–Burman screening (Tables 5–7)\n");
    let _ = writeln!(
        s,
        "| factor | what | low | high | effect / N | p | seed p < 0.05 |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for (f, e) in cal.plan.factors.iter().zip(&s8.effects) {
        let _ = writeln!(
            s,
            "| {} | {} ({}) | {} | {} | {:.4} | {:.3e} | {} |",
            f.label,
            f.description,
            f.unit,
            g(f.low),
            g(f.high),
            e.effect,
            e.p,
            if SEED_SIGNIFICANT.contains(&f.label.as_str()) {
                "yes"
            } else {
                ""
            }
        );
    }
    let _ = writeln!(
        s,
        "\nR² {:.4}; curvature p {}; significant here (p < {}): {:?}; seed: {:?}. The \
         screening's choice (p ≤ {}): {:?}; seed's: {:?}. Carried to the path and the central \
         composite design: {:?} — {}.",
        s8.anova.as_ref().map_or(f64::NAN, |a| a.fit.r2),
        s8.anova
            .as_ref()
            .and_then(|a| a.curvature.as_ref())
            .map_or("-".into(), |c| format!("{:.3e}", c.p)),
        cal.plan.significance,
        s8.significant,
        SEED_SIGNIFICANT,
        cal.plan.carry_level.unwrap_or(cal.plan.significance),
        s8.screening_choice,
        SEED_CARRIED,
        s8.carried,
        cal.plan
            .carry_reason
            .as_deref()
            .unwrap_or("the screening's choice")
    );
    for n in &s8.notes {
        let _ = writeln!(s, "\nNote: {n}");
    }
    let _ = writeln!(
        s,
        "\nEvery run's force against the criterion's pure-tension break force σc·πRb²: largest \
         deviation {:.3} %. In an axial pull the junction is in tension, so its break force \
         is σc·πRb² whatever its shear stiffness (x7) and the unbonded contacts (x1–x6, which \
         touch nothing before the break); the seed's EDEM test evidently loaded the junction \
         otherwise. What x1–x7 show instead is aliasing: F = σc·πRb² has an x8·x9 \
         interaction, which a 12-run Plackett–Burman design lends every other column with \
         weight ±1/3, an effect of ±{:.4} N (2b₈₉/3 from σc·πRb²); the dummy columns carry \
         the same, so these effects are not significant. Centre replicates of a \
         deterministic simulator are identical: pure error 0, so no lack-of-fit test.",
        cal.axial_check_max_deviation_pct, s8.x8_x9_alias_effect_n
    );
    let p = &cal.path;
    let _ = writeln!(s, "\n## 2. Steepest {} (Table 8)\n", p.direction);
    let _ = writeln!(
        s,
        "| point | {} | F / N | error / % |",
        p.factors.join(" | ")
    );
    let _ = writeln!(s, "|---|{}---|---|", "---|".repeat(p.factors.len()));
    for (i, (r, e)) in p.runs.iter().zip(&p.relative_error_pct).enumerate() {
        let vals: Vec<String> = p
            .factors
            .iter()
            .map(|l| g(r.settings[label_index(cal, l)]))
            .collect();
        let _ = writeln!(
            s,
            "| {}{} | {} | {:.3} | {:.2} |",
            i + 1,
            if i + 1 == p.best { " (best)" } else { "" },
            vals.join(" | "),
            r.detachment_force_n,
            e
        );
    }
    for n in &p.notes {
        let _ = writeln!(s, "\nNote: {n}");
    }
    let c = &cal.central_composite;
    let _ = writeln!(
        s,
        "\n## 3. Central composite design, α = {} (Tables 9–11)\n",
        c.alpha
    );
    for f in &c.factors {
        let _ = writeln!(
            s,
            "- {}: −1 = {}, +1 = {} {}",
            f.label,
            g(f.low),
            g(f.high),
            f.unit
        );
    }
    let _ = writeln!(s, "\n| term | coefficient / N | p |\n|---|---|---|");
    for (i, coef) in c.anova.coefficients.iter().enumerate() {
        let pv = if i == 0 {
            "-".into()
        } else {
            format!("{:.3e}", c.anova.terms[i - 1].p)
        };
        let _ = writeln!(s, "| {} | {:.5} | {} |", coef.term, coef.estimate, pv);
    }
    let _ = writeln!(
        s,
        "\nModel p {:.3e}, R² {:.5}, {} runs, forces {:.3}–{:.3} N.",
        c.anova.model.p,
        c.anova.fit.r2,
        c.runs.len(),
        c.runs
            .iter()
            .map(|r| r.detachment_force_n)
            .fold(f64::INFINITY, f64::min),
        c.runs
            .iter()
            .map(|r| r.detachment_force_n)
            .fold(f64::NEG_INFINITY, f64::max)
    );
    let o = &cal.optimum;
    let _ = writeln!(s, "\n## 4. Optimum and validation\n");
    for (l, v) in &o.calibrated {
        let _ = writeln!(s, "- {l} = {}", g(*v));
    }
    let _ = writeln!(
        s,
        "\nDesirability {:.4}; surface prediction {:.4} N; validation pull {:.4} N \
         (σc·πRb² = {:.4} N) against the target {} N: error {:.3} % — {} (limit {} %).",
        o.desirability,
        o.predicted_n,
        o.validated_n,
        o.predicted_axial_n,
        cal.target_n,
        o.relative_error_pct,
        if o.passed { "passed" } else { "FAILED" },
        o.max_relative_error_pct
    );
    s
}

/// Column of `label` among x1…x9.
fn label_index(cal: &PlantCalibration, label: &str) -> usize {
    cal.plan
        .factors
        .iter()
        .position(|f| f.label == label)
        .unwrap_or(0)
}
