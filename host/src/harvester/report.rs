//! The field trial's report (`arachis field --replicates N --report DIR`): `report.md`, the
//! trial in words and tables laid out as seed 001 Table 12 (loss per replicate against the
//! field's, the relative errors, the pooled t-test), where the pods went in each replicate,
//! and `where-lost.svg`, a stacked bar per replicate of where every pod ended. The printed
//! JSON is kept beside it as `trial.json`, and each replicate's pod map as
//! `pods_rep<R>.svg`. Every file is written whole or not at all.
//!
//! ```
//! use arachis::harvester::loss::{LossTally, PodEnd, Where};
//! use arachis::harvester::report::{markdown, Replicate, Trial};
//! use arachis::harvester::trial::summarise;
//! let mut tally = LossTally::default();
//! for _ in 0..24 { tally.add(PodEnd::Collected); }
//! tally.add(PodEnd::Lost(Where::Chain));
//! let reps: Vec<Replicate> = (1..=2)
//!     .map(|seed| Replicate { seed, plants: 3, tally, simulated_s: 3.5, pass_s: 3.5,
//!         wall_seconds: 1.0 })
//!     .collect();
//! let summary = summarise(&[4.0, 4.0], &[4.01, 3.83, 4.04, 3.42], 25.0 / 3.0);
//! let trial = Trial { field: "ridge", field_file: "field.toml", machine: "digger",
//!     machine_file: "digger.toml", dt_s: 8e-7, threads: 2, summary: &summary, replicates: reps };
//! let md = markdown(&trial);
//! assert!(md.contains("| 1 | 4.00 | 4.01 |"));
//! ```

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;

use super::loss::LossTally;
use super::trial::TrialSummary;
use crate::io::write_string_atomic;
use crate::stats::report::format_p;

/// The report's file names in its folder.
pub const MARKDOWN_FILE: &str = "report.md";
/// The trial's JSON (as printed).
pub const JSON_FILE: &str = "trial.json";
/// The stacked bars of where the pods ended.
pub const WHERE_LOST_FILE: &str = "where-lost.svg";

/// A run whose simulated time reaches this fraction of its pass's has done the pass (the
/// pass ends on a whole step).
const PASS_DONE: f64 = 0.999_999;
/// Room above the tallest bar for its label, as a fraction of its height.
const HEADROOM: f64 = 0.15;
/// Figure size, pixels.
const SIZE: (u32, u32) = (720, 440);
/// Margin and label room, pixels.
const MARGIN: u32 = 12;
const LABEL_AREA: u32 = 44;
/// Bar width as a fraction of its slot.
const BAR_FILL: f64 = 0.6;
/// Room on the right of the bars for the legend, in bar slots.
const LEGEND_SLOTS: f64 = 1.6;
/// Font sizes.
const CAPTION_FONT: u32 = 18;
const LEGEND_FONT: u32 = 13;

/// One replicate's outcome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Replicate {
    /// Layout seed.
    pub seed: u64,
    /// Plants in the field.
    pub plants: usize,
    /// Where its pods ended.
    pub tally: LossTally,
    /// Simulated time, s.
    pub simulated_s: f64,
    /// Simulated time of the whole pass, s.
    pub pass_s: f64,
    /// Wall time, s (summed over sessions when it was resumed).
    pub wall_seconds: f64,
}

/// A finished trial.
#[derive(Debug, Clone)]
pub struct Trial<'a> {
    /// The field's name.
    pub field: &'a str,
    /// The field file, as given.
    pub field_file: &'a str,
    /// The machine's name.
    pub machine: &'a str,
    /// The harvester file, as given (its settings and their sources are there).
    pub machine_file: &'a str,
    /// Time step, s.
    pub dt_s: f64,
    /// Threads each simulation stepped on.
    pub threads: usize,
    /// The comparison with the field.
    pub summary: &'a TrialSummary,
    /// The replicates, in order.
    pub replicates: Vec<Replicate>,
}

/// Where a pod can end, the tally's count of it and its colour in the figure.
fn places(t: &LossTally) -> [(&'static str, u32, RGBColor); 8] {
    [
        ("collected", t.collected, RGBColor(46, 139, 87)),
        (
            "unpicked (on the vines)",
            t.unpicked,
            RGBColor(150, 190, 90),
        ),
        ("lost in the soil", t.in_soil, RGBColor(120, 80, 40)),
        ("lost off the shovel", t.shovel, RGBColor(200, 120, 40)),
        ("lost through the chain", t.chain, RGBColor(220, 60, 50)),
        (
            "lost behind the collector",
            t.behind,
            RGBColor(160, 40, 120),
        ),
        ("lost beside the machine", t.beside, RGBColor(90, 90, 200)),
        (
            "lost on the machine (run ended)",
            t.on_machine,
            RGBColor(120, 120, 120),
        ),
    ]
}

/// `x` with two decimals, or "—".
fn pct(x: Option<f64>) -> String {
    x.map_or("—".into(), |v| format!("{v:.2}"))
}

/// The report's text.
pub fn markdown(t: &Trial<'_>) -> String {
    let s = t.summary;
    let mut md = String::new();
    let _ = writeln!(md, "# Field trial in simulation: {}\n", t.field);
    let _ = writeln!(
        md,
        "{} replicate fields of `{}`, each laid out from its own seed and harvested by \
         \"{}\" (`{}`, whose settings cite their sources), compared with the field's losses \
         as seed 001 Table 12 compares them. Loss rate = pods neither collected nor left on \
         their plants, over all pods (`arachis::harvester::loss`). Time step {:.3e} s, {} \
         threads per simulation.\n",
        t.replicates.len(),
        t.field_file,
        t.machine,
        t.machine_file,
        t.dt_s,
        t.threads
    );
    let short: Vec<String> = t
        .replicates
        .iter()
        .enumerate()
        .filter(|(_, r)| r.simulated_s < r.pass_s * PASS_DONE)
        .map(|(i, _)| (i + 1).to_string())
        .collect();
    if !short.is_empty() {
        let _ = writeln!(
            md,
            "**Not a field trial's result:** replicate(s) {} stopped before the end of the \
             pass (see the runs below), and pods not yet lifted count as lost in the soil. \
             Run with `--pass` for the trial.\n",
            short.join(", ")
        );
    }
    let _ = writeln!(md, "## Loss rate against the field (seed 001 Table 12)\n");
    let _ = writeln!(
        md,
        "| Replicate | Simulated loss (%) | Field loss (%) | Relative error (%) | Seed | Pods |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    let rows = t.replicates.len().max(s.field_loss_rate_pct.len());
    for i in 0..rows {
        let r = t.replicates.get(i);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} |",
            i + 1,
            pct(s.loss_rate_pct.get(i).copied()),
            pct(s.field_loss_rate_pct.get(i).copied()),
            pct(s.relative_error_pct.get(i).copied().flatten()),
            r.map_or("—".into(), |r| r.seed.to_string()),
            r.map_or("—".into(), |r| r.tally.pods.to_string()),
        );
    }
    let _ = writeln!(
        md,
        "| mean | {:.2} | {:.2} | | | |\n",
        s.mean_simulated_pct, s.mean_field_pct
    );
    let _ = writeln!(
        md,
        "Relative error = |field − simulated| / simulated × 100, as Table 12 takes the \
         simulation as the reference. Pods per plant: {:.1}.\n",
        s.pods_per_plant
    );
    let _ = writeln!(md, "{}\n", verdict(s));
    let _ = writeln!(md, "## Where the pods went\n");
    let names = places(&LossTally::default()).map(|p| p.0);
    let _ = writeln!(md, "| Replicate | {} |", names.join(" | "));
    let _ = writeln!(md, "|---{}|", "|---".repeat(names.len()));
    for (i, r) in t.replicates.iter().enumerate() {
        let counts = places(&r.tally).map(|p| p.1.to_string());
        let _ = writeln!(md, "| {} | {} |", i + 1, counts.join(" | "));
    }
    let _ = writeln!(
        md,
        "\n![Where every pod ended, per replicate]({WHERE_LOST_FILE})\n"
    );
    for i in 1..=t.replicates.len() {
        let _ = writeln!(
            md,
            "![Replicate {i}: where each pod ended, from above](pods_rep{i}.svg)\n"
        );
    }
    let _ = writeln!(md, "## The runs\n");
    let _ = writeln!(
        md,
        "| Replicate | Seed | Plants | Simulated (s) | Pass (s) | Wall (s) |"
    );
    let _ = writeln!(md, "|---|---|---|---|---|---|");
    for (i, r) in t.replicates.iter().enumerate() {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.4} | {:.4} | {:.0} |",
            i + 1,
            r.seed,
            r.plants,
            r.simulated_s,
            r.pass_s,
            r.wall_seconds
        );
    }
    md
}

/// The t-test in words, as seed 001 states it, and what follows when it rejects.
fn verdict(s: &TrialSummary) -> String {
    match (s.t, s.df, s.p_value, s.significant_difference) {
        (Some(t), Some(df), Some(p), Some(rejects)) => {
            // format_p gives "< 0.0001" below its last digit.
            let p = format_p(p);
            let p = if p.starts_with('<') {
                p
            } else {
                format!("= {p}")
            };
            let test =
                format!("Pooled two-sample t-test of equal means: t = {t:.3}, df = {df}, p {p}.");
            if rejects {
                format!(
                    "{test} **The test rejects** at α = {}: the simulated mean loss \
                     ({:.2} %) differs from the field's ({:.2} %). The model does not \
                     reproduce the field trial; the report states it as it is, and the \
                     harvester's settings were fixed before this comparison.",
                    s.alpha, s.mean_simulated_pct, s.mean_field_pct
                )
            } else {
                format!(
                    "{test} At α = {} the test does not reject: the simulated mean loss \
                     ({:.2} %) and the field's ({:.2} %) do not differ significantly.",
                    s.alpha, s.mean_simulated_pct, s.mean_field_pct
                )
            }
        }
        _ => format!(
            "No t-test: {}.",
            s.no_test.as_deref().unwrap_or("it could not be made")
        ),
    }
}

/// Stacked bars: each replicate's pods by where they ended.
pub fn where_lost(t: &Trial<'_>) -> Result<String, String> {
    let err = |e: &dyn std::fmt::Display| format!("cannot draw {WHERE_LOST_FILE}: {e}");
    let n = t.replicates.len() as f64;
    let top = t
        .replicates
        .iter()
        .map(|r| r.tally.pods)
        .max()
        .unwrap_or(1)
        .max(1) as f64
        * (1.0 + HEADROOM);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("{}: where the pods ended", t.field),
                ("sans-serif", CAPTION_FONT),
            )
            .margin(MARGIN)
            .x_label_area_size(LABEL_AREA / 2)
            .y_label_area_size(LABEL_AREA)
            .build_cartesian_2d(0.0..n + LEGEND_SLOTS, 0.0..top)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(0)
            .y_desc("pods")
            .draw()
            .map_err(|e| err(&e))?;
        for (i, r) in t.replicates.iter().enumerate() {
            let x0 = i as f64 + 0.5 * (1.0 - BAR_FILL);
            let mut y = 0.0;
            for (_, count, colour) in places(&r.tally) {
                let h = f64::from(count);
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(x0, y), (x0 + BAR_FILL, y + h)],
                        colour.filled(),
                    )))
                    .map_err(|e| err(&e))?;
                y += h;
            }
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("rep {} (seed {})", i + 1, r.seed),
                    (x0, y + 0.06 * top),
                    ("sans-serif", LEGEND_FONT).into_font(),
                )))
                .map_err(|e| err(&e))?;
        }
        for (k, (name, _, colour)) in places(&LossTally::default()).into_iter().enumerate() {
            let y = top * (1.0 - 0.07 * (k as f64 + 1.0));
            let x = n + 0.1;
            chart
                .draw_series([Rectangle::new(
                    [(x, y), (x + 0.12, y + 0.04 * top)],
                    colour.filled(),
                )
                .into_dyn()])
                .map_err(|e| err(&e))?;
            chart
                .draw_series(std::iter::once(Text::new(
                    name,
                    (x + 0.18, y + 0.035 * top),
                    ("sans-serif", LEGEND_FONT).into_font(),
                )))
                .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    Ok(svg)
}

/// Writes `report.md`, `trial.json` (`json`, as printed) and `where-lost.svg` into `dir`
/// (created if missing); the pod maps are written by the runs themselves.
pub fn write(dir: &Path, t: &Trial<'_>, json: &str) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)
        .map_err(|e| anyhow::anyhow!("cannot create {}: {e}", dir.display()))?;
    let svg = where_lost(t).map_err(|e| anyhow::anyhow!("{e}"))?;
    write_string_atomic(&dir.join(WHERE_LOST_FILE), &svg)?;
    write_string_atomic(&dir.join(JSON_FILE), &format!("{json}\n"))?;
    write_string_atomic(&dir.join(MARKDOWN_FILE), &markdown(t))
}
