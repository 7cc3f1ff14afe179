//! `arachis calibrate STUDY` for a plant pull-off study (`[study] kind = "pull_off"`,
//! `crate::plant_study`): seed 001's calibration of the pod–stalk junction as the study
//! states it — Plackett–Burman screening, steepest ascent, central composite design,
//! optimisation to the measured force, validation pull.
//!
//! The study is loaded and checked before any pull, so a bad file stops with its file, key
//! and reason. Writes `OUT/plant-calibration.json` and `OUT/report.md` atomically; neither
//! holds the wall-clock time (printed instead), so a rerun writes the same bytes. Seed
//! 000's options that a pull-off study has no use for (`--quick`, `--full`, `--mode`,
//! `--simulator surrogate`) are refused rather than ignored.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, ensure, Context};

use super::calibrate::{Args, SimulatorChoice};
use crate::calibrate::Progress;
use crate::plant_calibration::{calibrate_plan, report};
use crate::plant_study::PlantStudy;

/// Runs the plant calibration of the study `args.study`.
pub fn run(args: &Args) -> anyhow::Result<()> {
    ensure!(
        !(args.quick || args.full || args.mode.is_some()),
        "{}: a pull-off study has no run modes (--quick, --full, --mode): every pull is the \
         same rig",
        args.study.display()
    );
    ensure!(
        args.simulator == SimulatorChoice::Dem,
        "{}: the surrogate stands in for seed 000's repose runs only; a pull-off study runs \
         the DEM tensile test",
        args.study.display()
    );
    let study = PlantStudy::load(&args.study)?;
    let name = &study.file().study.name;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("calibration-{name}")));
    let sim = study.simulator();
    let plan = study.plan();
    let progress = Progress::new(args.quiet);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(j) = args.jobs {
        pool = pool.num_threads(j as usize);
    }
    let pool = pool.build().context("cannot start the worker threads")?;
    let started = Instant::now();
    let mut cal = pool
        .install(|| calibrate_plan(&sim, study.target_n(), &plan, &progress))
        .with_context(|| format!("calibrating {}", args.study.display()))?;
    let wall = started.elapsed().as_secs_f64();
    cal.study = Some(name.clone());
    report::write_files(&cal, None, &out)
        .with_context(|| format!("cannot write the report into {}", out.display()))?;

    let s = &cal.screening;
    println!("study {name} (pull-off), {} pulls", cal.runs);
    println!(
        "screening: significant [{}]; the screening's choice [{}]; carried [{}]",
        s.significant.join(", "),
        s.screening_choice.join(", "),
        s.carried.join(", ")
    );
    for note in s.notes.iter().chain(&cal.path.notes) {
        println!("note: {note}");
    }
    let c = &cal.central_composite;
    println!(
        "steepest {}: best point {} of {}; central composite on [{}], α = {}, {} runs",
        cal.path.direction,
        cal.path.best,
        cal.path.runs.len(),
        cal.path.factors.join(", "),
        c.alpha,
        c.runs.len()
    );
    let o = &cal.optimum;
    let params: Vec<String> = o
        .calibrated
        .iter()
        .map(|(l, v)| format!("{l} = {v:.5e}"))
        .collect();
    println!(
        "optimum: {} (D = {:.4}, predicted {:.4} N)",
        params.join(", "),
        o.desirability,
        o.predicted_n
    );
    println!(
        "validation: pulled {:.5} N vs measured {} N: relative error {:.3} % (limit {} %)",
        o.validated_n, cal.target_n, o.relative_error_pct, o.max_relative_error_pct
    );
    println!("{} pulls in {wall:.2} s", cal.runs);
    println!("report: {}", out.join(report::MARKDOWN_FILE).display());
    if !o.passed {
        let miss = format!(
            "validation failed: relative error {:.3} % exceeds {} %",
            o.relative_error_pct, o.max_relative_error_pct
        );
        if args.strict {
            bail!(miss);
        }
        println!("{miss} (see the report; --strict makes this an error)");
    }
    Ok(())
}
