//! The plant calibration's report folder: `plant-calibration.json` (every number) and
//! `report.md` (the tables of seed 001 §3 for this rig, and how they compare with the
//! seed), both written atomically.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use super::factors::{SEED_CARRIED, SEED_SIGNIFICANT};
use super::PlantCalibration;
use crate::io::write_string_atomic;

/// JSON file name.
pub const JSON_FILE: &str = "plant-calibration.json";
/// Markdown file name.
pub const MARKDOWN_FILE: &str = "report.md";

/// What the JSON file holds: the calibration and, when asked, its wall-clock time.
#[derive(Serialize)]
struct Written<'a> {
    #[serde(flatten)]
    calibration: &'a PlantCalibration,
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_seconds: Option<f64>,
}

/// Writes both files into `dir` (created if missing), with the wall-clock time in each.
pub fn write_all(cal: &PlantCalibration, wall_seconds: f64, dir: &Path) -> anyhow::Result<()> {
    write_files(cal, Some(wall_seconds), dir)
}

/// Writes both files into `dir` (created if missing); `wall_seconds` `None` leaves the
/// run time out, so the same calibration always writes the same bytes (the simulation is
/// bit-reproducible; only the clock is not).
pub fn write_files(
    cal: &PlantCalibration,
    wall_seconds: Option<f64>,
    dir: &Path,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)?;
    let json = serde_json::to_string_pretty(&Written {
        calibration: cal,
        wall_seconds,
    })?;
    write_string_atomic(&dir.join(JSON_FILE), &(json + "\n"))?;
    write_string_atomic(&dir.join(MARKDOWN_FILE), &render(cal, wall_seconds))
}

/// `v` with 4 significant digits.
fn g(v: f64) -> String {
    format!("{v:.4e}")
}

/// The markdown report.
pub fn markdown(cal: &PlantCalibration, wall_seconds: f64) -> String {
    render(cal, Some(wall_seconds))
}

/// The markdown report; the wall-clock time only when given.
fn render(cal: &PlantCalibration, wall_seconds: Option<f64>) -> String {
    let mut s = String::new();
    let s8 = &cal.screening;
    let _ = writeln!(s, "# Plant calibration: pod–stalk junction (seed 001 §3)\n");
    let _ = writeln!(
        s,
        "Target detachment force {} N (seed 001 Table 8). Rig: axial-pull tensile test at \
         {} m/s, pull angle {}°, {} stalk spheres, junction kn {} N/m³ (held). {} pull-off \
         runs{}.\n",
        cal.target_n,
        cal.rig.pull_speed_m_s,
        cal.rig.pull_angle_deg,
        cal.rig.stalk_spheres,
        g(cal.rig.junction_normal_stiffness_n_m3),
        cal.runs,
        wall_seconds.map_or(String::new(), |w| format!(" in {w:.2} s wall-clock"))
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
            if SEED_SIGNIFICANT.contains(&f.label) {
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
        s8.anova.fit.r2,
        s8.anova
            .curvature
            .as_ref()
            .map_or("-".into(), |c| format!("{:.3e}", c.p)),
        cal.plan.significance,
        s8.significant,
        SEED_SIGNIFICANT,
        cal.plan.carry_level,
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
