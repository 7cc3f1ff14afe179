//! `report.md`: the story of a calibration with its tables, in the words of
//! `calibration.json`, linking the figures of [`super::figures`].

use std::fmt::Write as _;

use super::calibration_json::CalibrationJson;
use super::{FIGURES_DIR, PILE_SCHEMATIC};
use crate::calibration::RunRecord;
use crate::stats::report::{format_number, format_p, text_report};

/// What the figures folder holds, for the report's links.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Figures {
    /// Response-surface maps, file names inside the figures folder.
    pub surfaces: Vec<String>,
    /// The measured and simulated pile drawn as cone profiles (a repose angle only).
    pub pile_schematic: bool,
    /// The rig's own picture of the optimum, relative to the output folder.
    pub picture: Option<String>,
}

/// The Markdown report.
pub fn markdown(c: &CalibrationJson, strongest: Option<(&str, &str)>, figures: &Figures) -> String {
    let mut s = String::new();
    let unit = &c.target.unit;
    let _ = writeln!(s, "# Calibration of `{}`\n", c.study);
    let _ = writeln!(
        s,
        "- Simulator: {} (`{}`)",
        c.simulator_description, c.simulator
    );
    let _ = writeln!(s, "- Mode: `{}`", c.mode);
    let _ = writeln!(
        s,
        "- Target: {} {} = {} {unit} (measured mean)",
        c.target.experiment, c.target.quantity, c.target.value
    );
    let v = &c.validation.stage;
    let _ = writeln!(
        s,
        "- Result: simulated {} {unit} at the optimum, relative error ψ = {:.3} % (limit {} %): **{}**\n",
        format_number(v.simulated),
        v.relative_error_pct,
        v.max_relative_error_pct,
        if v.passed { "passed" } else { "FAILED" }
    );

    let sc = &c.screening.stage;
    let _ = writeln!(s, "## 1. Screening ({}, seed 000 §3.3)\n", sc.design);
    let _ = writeln!(
        s,
        "{} runs; dummy columns {} left out of the model as the error estimate; α = {}.\n",
        sc.runs.len(),
        if sc.dummy_columns.is_empty() {
            "none".to_owned()
        } else {
            sc.dummy_columns.join(", ")
        },
        sc.significance
    );
    let _ = writeln!(
        s,
        "| factor | parameter | low | high | effect ({unit}) | p | significant |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for (f, e) in sc.factors.iter().zip(&sc.effects) {
        let _ = writeln!(
            s,
            "| {} | {} ({}) | {} | {} | {} | {} | {} |",
            f.label,
            f.name,
            f.unit,
            f.low,
            f.high,
            format_number(e.effect),
            e.p.map_or("–".to_owned(), format_p),
            if e.significant { "yes" } else { "no" }
        );
    }
    let strongest = strongest.map_or("–".to_owned(), |(label, name)| {
        format!("{label} ({name})")
    });
    let _ = writeln!(
        s,
        "\nMost significant factor: **{strongest}**. Significant: {}. Carried on: {}.\n",
        if c.screening.significant.is_empty() {
            "none".to_owned()
        } else {
            c.screening.significant.join(", ")
        },
        c.screening.selected.join(", ")
    );
    for note in &c.screening.notes {
        let _ = writeln!(s, "> Note: {note}\n");
    }
    if let Some(why) = &sc.anova_unavailable {
        let _ = writeln!(s, "> No ANOVA: {why}\n");
    }
    let _ = writeln!(
        s,
        "![Pareto chart of screening effects]({FIGURES_DIR}/pareto.svg)\n"
    );
    if let Some(a) = &sc.anova {
        let _ = writeln!(s, "```text\n{}```\n", text_report(a, unit));
    }
    runs_table(&mut s, "Screening runs", &sc.runs, unit);

    let p = &c.steepest_ascent.stage;
    let _ = writeln!(
        s,
        "## 2. Path of steepest {} (seed 000 §3.4)\n",
        p.direction.name()
    );
    let _ =
        writeln!(
        s,
        "Factors {} move along the screening gradient (coded coefficients {}); the rest are held. \
         The screening fit predicts {} {unit} at the start.\n",
        p.factors.iter().map(|f| f.label.as_str()).collect::<Vec<_>>().join(", "),
        p.coefficients.iter().map(|b| format_number(*b)).collect::<Vec<_>>().join(", "),
        format_number(p.predicted_at_origin)
    );
    let _ = write!(s, "| point | position (steps) |");
    for f in &p.factors {
        let _ = write!(s, " {} |", f.label);
    }
    let _ = writeln!(s, " response ({unit}) | ψ (%) |");
    let _ = writeln!(s, "|{}", "---|".repeat(p.factors.len() + 4));
    for ((r, e), m) in p.runs.iter().zip(&p.relative_error_pct).zip(&p.positions) {
        let _ = write!(
            s,
            "| {}{} | {m} |",
            r.run,
            if r.run == p.best { " (best)" } else { "" }
        );
        for f in &p.factors {
            let _ = write!(s, " {} |", fmt_value(r.values[&f.name]));
        }
        let _ = writeln!(s, " {} | {:.2} |", format_number(r.response), e);
    }
    let _ = writeln!(s);
    for note in &c.steepest_ascent.notes {
        let _ = writeln!(s, "> Note: {note}\n");
    }

    let b = c.surface();
    let (design, source) = if c.box_behnken.is_some() {
        ("Box–Behnken", "seed 000 §3.5")
    } else {
        ("Central composite", "seed 001 §3.2")
    };
    let _ = writeln!(s, "## 3. {design} design and {} fit ({source})\n", b.model);
    let _ = writeln!(
        s,
        "Box: {}. {} runs, {} centre points.\n",
        b.range_rule,
        b.runs.len(),
        b.centre_points
    );
    let _ = writeln!(s, "| factor | parameter | −1 | +1 |");
    let _ = writeln!(s, "|---|---|---|---|");
    for f in &b.factors {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} |",
            f.label,
            f.name,
            fmt_value(f.low),
            fmt_value(f.high)
        );
    }
    let _ = writeln!(s, "\n```text\n{}```\n", text_report(&b.anova, unit));
    for name in &figures.surfaces {
        let _ = writeln!(s, "![Response surface]({FIGURES_DIR}/{name})\n");
    }
    runs_table(&mut s, &format!("{design} runs"), &b.runs, unit);

    let o = &c.optimum.stage;
    let _ = writeln!(s, "## 4. Optimum (desirability, seed 000 §3.6.1)\n");
    let _ = writeln!(
        s,
        "Goal: {} = {} {unit}, desirability falling to 0 at {} and {}. Chosen: D = {:.6}, \
         predicted {} {unit} ({} distinct solutions found; the one nearest the box centre among the best).\n",
        c.target.quantity,
        o.goal.target,
        format_number(o.goal.low),
        format_number(o.goal.high),
        o.desirability,
        format_number(o.predicted),
        o.solutions_found
    );
    let _ = writeln!(
        s,
        "| factor | parameter | unit | value | role | study range |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for r in &c.optimum.parameters {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} – {} |",
            r.label,
            r.name,
            r.unit,
            fmt_value(r.value),
            r.role,
            r.low,
            r.high
        );
    }

    let _ = writeln!(s, "\n## 5. Validation (seed 000 eq. (21), §3.6.2)\n");
    let _ = writeln!(
        s,
        "Measured {} {unit}; simulated {} ± {} {unit} (mean ± SD of {} replicates; surface \
         predicted {}); ψ = {:.3} % against the limit {} %: **{}**.\n",
        v.measured,
        format_number(v.simulated),
        format_number(v.simulated_sd),
        v.runs.len(),
        format_number(v.predicted),
        v.relative_error_pct,
        v.max_relative_error_pct,
        if v.passed { "passed" } else { "FAILED" },
    );
    runs_table(&mut s, "Validation runs", &v.runs, unit);
    if figures.pile_schematic {
        let _ = writeln!(
            s,
            "![Measured vs simulated pile]({FIGURES_DIR}/{PILE_SCHEMATIC})\n"
        );
    }
    if let Some(pic) = &figures.picture {
        let what = if figures.pile_schematic {
            "pile"
        } else {
            "run"
        };
        let _ = writeln!(s, "![Simulated {what} at the optimum]({pic})\n");
    }
    s
}

/// Four significant digits past the leading ones, without float noise (0.8540, 3.04e6).
fn fmt_value(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e4 || v.abs() < 1e-3) {
        format!("{v:.4e}")
    } else {
        format!("{v:.4}")
    }
}

fn runs_table(s: &mut String, title: &str, runs: &[RunRecord], unit: &str) {
    let Some(first) = runs.first() else { return };
    let names: Vec<&String> = first.values.keys().collect();
    let _ = writeln!(s, "<details><summary>{title}</summary>\n");
    let _ = write!(s, "| run |");
    for n in &names {
        let _ = write!(s, " {n} |");
    }
    let _ = writeln!(s, " replicate | response ({unit}) | spec |");
    let _ = writeln!(s, "|{}", "---|".repeat(names.len() + 4));
    for r in runs {
        let _ = write!(s, "| {} |", r.run);
        for n in &names {
            let _ = write!(s, " {} |", fmt_value(r.values[*n]));
        }
        let _ = writeln!(
            s,
            " {} | {} | `{}` |",
            r.replicate,
            format_number(r.response),
            r.spec_hash
        );
    }
    let _ = writeln!(s, "\n</details>\n");
}
