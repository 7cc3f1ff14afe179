//! Decoding and checking a plant study, collecting every error with its key instead of
//! stopping at the first: unknown or missing sections and keys, an unknown or missing
//! Table 5 factor, low ≥ high or levels outside physical limits, a missing or
//! non-positive measurement, an unreadable topology or a bond set it lacks, and plan
//! settings the designs cannot take.

use std::collections::BTreeMap;
use std::path::Path;

use super::file_format::{FactorLevels, PlantStudyFile, KIND_PULL_OFF, SECTIONS};
use super::{read_topology, ReadFile};
use crate::calibration::plan::central_composite::{MAX_FACTORS, MIN_FACTORS};
use crate::plant::topology::BondSet;
use crate::rigs::pull_off::{by_label, PARAMETERS};
use crate::study::decode::{map, root_sections, whole};
use crate::study::source::Source;
use crate::study::{nearest_name, KeyPath, StudyError};

/// The one quantity a pull-off study calibrates to.
pub const QUANTITY: &str = "detachment_force";
/// The one screening design.
pub const SCREENING_DESIGN: &str = "plackett_burman";
/// The one optimisation goal: desirability toward the measurement.
pub const GOAL: &str = "target";
/// Largest pull angle from the stalk axis, degrees (the rig pulls in the x–y plane).
pub const MAX_PULL_ANGLE_DEG: f64 = 90.0;
/// Most stalk spheres (the arenas are sized for the rig; more only slows every pull).
pub const MAX_STALK_SPHERES: u32 = 64;

/// Refuses a list of factors for the path and the central composite design that is not
/// 2–3 distinct Table 5 labels.
pub fn check_carry(carry: &[String]) -> Result<(), String> {
    if !(MIN_FACTORS..=MAX_FACTORS).contains(&carry.len()) {
        return Err(format!(
            "the central composite stage takes {MIN_FACTORS} to {MAX_FACTORS} factors, got {}",
            carry.len()
        ));
    }
    for (i, l) in carry.iter().enumerate() {
        if by_label(l).is_none() {
            return Err(format!("unknown factor '{l}' (seed 001 Table 5 has x1…x9)"));
        }
        if carry[..i].contains(l) {
            return Err(format!("factor '{l}' given twice"));
        }
    }
    Ok(())
}

/// Decodes every section, or returns every structural error found.
pub(crate) fn decode(src: &Source<'_>) -> Result<PlantStudyFile, Vec<StudyError>> {
    let (root, mut errors) = root_sections(src, &SECTIONS);
    let study = whole(src, root, "study", &mut errors);
    let rig = whole(src, root, "rig", &mut errors);
    let measurement = whole(src, root, "measurement", &mut errors);
    let factors: Option<BTreeMap<String, FactorLevels>> = map(src, root, "factors", &mut errors);
    let plan = whole(src, root, "plan", &mut errors);
    match (study, rig, measurement, factors, plan) {
        (Some(study), Some(rig), Some(measurement), Some(factors), Some(plan))
            if errors.is_empty() =>
        {
            Ok(PlantStudyFile {
                study,
                rig,
                measurement,
                factors,
                plan,
            })
        }
        _ => Err(errors),
    }
}

/// Checks a decoded file; returns the junction and stalk bond sets of its topology when
/// they could be read, and every error found.
pub(crate) fn validate(
    src: &Source<'_>,
    file: &PlantStudyFile,
    dir: &Path,
    read: ReadFile<'_>,
) -> (Option<(BondSet, BondSet)>, Vec<StudyError>) {
    let mut errors = Vec::new();
    let root = KeyPath::root();
    let mut err = |key: KeyPath, reason: String| errors.push(src.error(&key, reason));

    if file.study.kind != KIND_PULL_OFF {
        err(
            root.key("study").key("kind"),
            format!(
                "a plant study has kind '{KIND_PULL_OFF}', got '{}'",
                file.study.kind
            ),
        );
    }

    // [rig]
    let rig = &file.rig;
    let at = root.key("rig");
    if !(rig.pull_speed_m_s.is_finite() && rig.pull_speed_m_s > 0.0) {
        err(
            at.key("pull_speed_m_s"),
            format!(
                "must be a positive number of m/s, got {}",
                rig.pull_speed_m_s
            ),
        );
    }
    if !(rig.pull_angle_deg.is_finite() && rig.pull_angle_deg.abs() <= MAX_PULL_ANGLE_DEG) {
        err(
            at.key("pull_angle_deg"),
            format!(
                "must be between -{MAX_PULL_ANGLE_DEG} and {MAX_PULL_ANGLE_DEG} degrees, got {}",
                rig.pull_angle_deg
            ),
        );
    }
    if !(2..=MAX_STALK_SPHERES).contains(&rig.stalk_spheres) {
        err(
            at.key("stalk_spheres"),
            format!(
                "must be 2 to {MAX_STALK_SPHERES} (one clamped, one free at least), got {}",
                rig.stalk_spheres
            ),
        );
    }
    let sets = match read_topology(&dir.join(&rig.topology), read) {
        Err(reason) => {
            err(at.key("topology"), reason);
            None
        }
        Ok(t) => {
            let mut set = |key: &str, name: &str| match t.bonds.get(name) {
                None => {
                    let known: Vec<&str> = t.bonds.keys().map(String::as_str).collect();
                    err(
                        at.key(key),
                        format!(
                            "the topology {} has no bond set '{name}' (it has: {})",
                            rig.topology,
                            known.join(", ")
                        ),
                    );
                    None
                }
                Some(b) => {
                    let values = [b.kn_n_m3, b.kt_n_m3, b.sigma_c_pa, b.tau_c_pa, b.radius_m];
                    if values.iter().all(|v| v.is_finite() && *v > 0.0) {
                        Some(*b)
                    } else {
                        err(
                            at.key(key),
                            format!(
                                "bond set '{name}' of {} needs every stiffness, strength and \
                                 the radius > 0",
                                rig.topology
                            ),
                        );
                        None
                    }
                }
            };
            let junction = set("junction_bond_set", &rig.junction_bond_set);
            let stalk = set("stalk_bond_set", &rig.stalk_bond_set);
            junction.zip(stalk)
        }
    };

    // [measurement]
    let m = &file.measurement;
    let at = root.key("measurement");
    if m.quantity != QUANTITY {
        err(
            at.key("quantity"),
            format!(
                "a pull-off study calibrates to '{QUANTITY}', got '{}'",
                m.quantity
            ),
        );
    }
    if !(m.value_n.is_finite() && m.value_n > 0.0) {
        err(
            at.key("value_n"),
            format!("the measured force must be > 0 N, got {}", m.value_n),
        );
    }

    // [factors]
    let at = root.key("factors");
    let labels: Vec<&str> = PARAMETERS.iter().map(|f| f.label).collect();
    for (label, levels) in &file.factors {
        let Some(f) = by_label(label) else {
            let hint = nearest_name(label, &labels)
                .map_or(String::new(), |n| format!("; did you mean '{n}'?"));
            err(
                at.key(label),
                format!("unknown factor '{label}'{hint} (seed 001 Table 5 has x1…x9)"),
            );
            continue;
        };
        let here = at.key(label);
        let mut ok = true;
        for (key, v) in [("low", levels.low), ("high", levels.high)] {
            if let Err(reason) = f.limits.check(v) {
                err(
                    here.key(key),
                    format!("{} ({}): {reason}", f.label, f.description),
                );
                ok = false;
            }
        }
        if ok && levels.low >= levels.high {
            err(
                here.key("low"),
                format!(
                    "low {} must be below high {} ({} in {})",
                    levels.low, levels.high, f.description, f.unit
                ),
            );
        }
    }
    for f in &PARAMETERS {
        if !file.factors.contains_key(f.label) {
            err(
                at.key(f.label),
                format!(
                    "missing factor {} ({}): the screening needs all nine of seed 001 Table 5",
                    f.label, f.description
                ),
            );
        }
    }

    // [plan]
    let p = &file.plan;
    let at = root.key("plan");
    let s = at.key("screening");
    if p.screening.design != SCREENING_DESIGN {
        err(
            s.key("design"),
            format!(
                "the screening design is '{SCREENING_DESIGN}', got '{}'",
                p.screening.design
            ),
        );
    }
    if ![12, 20].contains(&p.screening.runs) {
        err(
            s.key("runs"),
            format!(
                "a Plackett–Burman design for nine factors has 12 or 20 runs, got {}",
                p.screening.runs
            ),
        );
    }
    for (key, v) in [
        ("significance", p.screening.significance),
        ("carry_level", p.screening.carry_level),
    ] {
        if !(v > 0.0 && v < 1.0) {
            err(
                s.key(key),
                format!("a significance level lies in (0, 1), got {v}"),
            );
        }
    }
    let sa = at.key("steepest_ascent");
    if !(p.steepest_ascent.step_coded.is_finite() && p.steepest_ascent.step_coded > 0.0) {
        err(
            sa.key("step_coded"),
            format!(
                "must be a positive coded step, got {}",
                p.steepest_ascent.step_coded
            ),
        );
    }
    if p.steepest_ascent.points < 3 {
        err(
            sa.key("points"),
            format!(
                "the path needs at least 3 points (a best one and its neighbours), got {}",
                p.steepest_ascent.points
            ),
        );
    }
    if p.steepest_ascent.max_points < p.steepest_ascent.points {
        err(
            sa.key("max_points"),
            format!(
                "must be at least points ({}), got {}",
                p.steepest_ascent.points, p.steepest_ascent.max_points
            ),
        );
    }
    let cc = at.key("central_composite");
    let c = &p.central_composite;
    if let Some(factors) = &c.factors {
        if let Err(reason) = check_carry(factors) {
            err(cc.key("factors"), reason);
        }
        if c.why.as_deref().is_none_or(|w| w.trim().is_empty()) {
            err(
                cc.key("why"),
                "a plan that names its factors says why (the report states it)".into(),
            );
        }
    }
    if !(c.alpha.is_finite() && c.alpha >= 1.0) {
        err(
            cc.key("alpha"),
            format!("α must be at least 1, got {}", c.alpha),
        );
    }
    if c.centre_points < 1 {
        err(
            cc.key("centre_points"),
            "the design needs at least one centre point".into(),
        );
    }
    if p.optimisation.goal != GOAL {
        err(
            at.key("optimisation").key("goal"),
            format!(
                "the optimisation goal is '{GOAL}' (desirability toward the measured \
                 force), got '{}'",
                p.optimisation.goal
            ),
        );
    }
    let limit = p.validation.max_relative_error_pct;
    if !(limit.is_finite() && limit > 0.0 && limit <= 100.0) {
        err(
            at.key("validation").key("max_relative_error_pct"),
            format!("must be in (0, 100] %, got {limit}"),
        );
    }
    (sets, errors)
}
