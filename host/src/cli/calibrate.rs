//! `arachis calibrate STUDY [--quick|--full|--mode NAME] [--jobs N] [--out DIR] [--quiet]`:
//! seed 000's calibration plan end to end (issue 4 §4–§5) — screening, steepest ascent,
//! Box–Behnken, desirability optimum, validation — writing `report.md`, `figures/*.svg`,
//! `calibration.json` and one `runs/<spec hash>.json` per simulation into the output folder.
//!
//! The study is loaded and validated before anything runs, so a bad file stops with its
//! file, key and reason. Rerunning into the same folder replays finished runs from
//! `runs/`, so an interrupted calibration resumes and ends with the same bytes.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::Context;
use clap::ValueEnum;

use crate::calibrate::{
    calibrate, CalibrateOptions, DemExperiment, Progress, RunResult, Seed000Surrogate,
    SimulationError, Simulator,
};
use crate::study::{RunSpec, Study};

/// Which simulator answers the runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SimulatorChoice {
    /// The repose DEM experiment (cylinder lifting, seed 000 §2.7).
    Dem,
    /// Seed 000's closed-form surrogate: a test stand-in, NOT a DEM simulation.
    Surrogate,
}

/// Arguments of `arachis calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study file (TOML), e.g. testdata/peanut-pods-saline/study.toml; a plant pull-off
    /// study (`[study] kind = "pull_off"`, e.g. testdata/peanut-plant/study.toml) runs seed
    /// 001's junction calibration instead.
    pub study: PathBuf,
    /// Quick mode (`[plan.modes.quick]`: fewer pods, coarser filling).
    #[arg(long, conflicts_with_all = ["full", "mode"])]
    pub quick: bool,
    /// Full, seed-scale mode (`[plan.modes.full]`).
    #[arg(long, conflicts_with = "mode")]
    pub full: bool,
    /// Any mode of `[plan.modes]` (default: the plan's `mode`).
    #[arg(long)]
    pub mode: Option<String>,
    /// Simulations run at once (default: every core).
    #[arg(long, short, value_parser = clap::value_parser!(u32).range(1..))]
    pub jobs: Option<u32>,
    /// Output folder (default: `calibration-STUDYNAME-MODE`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Exit with status 2 when the validation run misses its limit (for scripts and CI).
    /// Without it the miss is printed and written to the report, and the exit status is 0:
    /// a completed calibration that misses its target is a finding, not a crash.
    #[arg(long)]
    pub strict: bool,
    /// Which simulator answers the runs.
    #[arg(long, value_enum, default_value = "dem")]
    pub simulator: SimulatorChoice,
    /// Test hook: sleep this long in each surrogate run, so tests can interrupt a
    /// calibration part-way (milliseconds).
    #[arg(long, hide = true, default_value_t = 0)]
    pub surrogate_delay_ms: u64,
}

/// The surrogate with a sleep per run (the results, and so the id, are the surrogate's).
struct Delayed {
    inner: Seed000Surrogate,
    delay: Duration,
}

impl Simulator for Delayed {
    fn id(&self) -> String {
        self.inner.id()
    }
    fn description(&self) -> String {
        self.inner.description()
    }
    fn simulate(&self, spec: &RunSpec) -> Result<RunResult, SimulationError> {
        std::thread::sleep(self.delay);
        self.inner.simulate(spec)
    }
}

/// The simulator `choice` names, for `study`.
fn simulator<'a>(
    choice: SimulatorChoice,
    args: &Args,
    study: &'a Study,
) -> anyhow::Result<Box<dyn Simulator + 'a>> {
    match choice {
        SimulatorChoice::Surrogate => Ok(Box::new(Delayed {
            inner: Seed000Surrogate::default(),
            delay: Duration::from_millis(args.surrogate_delay_ms),
        })),
        SimulatorChoice::Dem => Ok(Box::new(DemExperiment::new(study))),
    }
}

/// Runs `arachis calibrate`. A plant pull-off study (`[study] kind = "pull_off"`) goes to
/// [`super::calibrate_plant`]; every other file is a seed 000 study.
pub fn run(args: Args) -> anyhow::Result<()> {
    if crate::plant_study::is_plant_study(&args.study) {
        return super::calibrate_plant::run(&args);
    }
    let study = Study::load(&args.study)?;
    let mode = if args.quick {
        Some("quick".to_owned())
    } else if args.full {
        Some("full".to_owned())
    } else {
        args.mode.clone()
    };
    let mode_name = mode
        .clone()
        .unwrap_or_else(|| study.file().plan.mode.clone());
    let out = args.out.clone().unwrap_or_else(|| {
        PathBuf::from(format!(
            "calibration-{}-{mode_name}",
            study.file().study.name
        ))
    });
    let sim = simulator(args.simulator, &args, &study)?;
    let options = CalibrateOptions {
        mode,
        jobs: args.jobs.map(|j| j as usize),
        out_dir: out.clone(),
        progress: Progress::new(args.quiet),
    };
    let started = std::time::Instant::now();
    let outcome = calibrate(&study, sim.as_ref(), &options)
        .with_context(|| format!("calibrating {}", args.study.display()))?;
    let c = &outcome.calibration;
    let strongest = c
        .screening
        .strongest()
        .map_or("-".to_owned(), |e| format!("{} ({})", e.label, e.name));
    println!(
        "study {} (mode {}), simulator {}",
        c.study, c.mode, c.simulator
    );
    println!(
        "screening: most significant {strongest}; significant [{}]; carried [{}]",
        c.screening.significant.join(", "),
        c.screening.selected.join(", ")
    );
    for note in c.screening.notes.iter().chain(&c.steepest_ascent.notes) {
        println!("note: {note}");
    }
    println!(
        "steepest {}: best point {} of {}",
        c.steepest_ascent.direction,
        c.steepest_ascent.best,
        c.steepest_ascent.runs.len()
    );
    let params: Vec<String> = c
        .optimum
        .parameters
        .iter()
        .filter(|p| p.role == "calibrated")
        .map(|p| format!("{} = {:.4}", p.name, p.value))
        .collect();
    println!(
        "optimum: {} (D = {:.4}, predicted {:.3} {})",
        params.join(", "),
        c.optimum.desirability,
        c.optimum.predicted,
        c.target.unit
    );
    let v = &c.validation;
    println!(
        "validation: simulated {:.3} {} vs measured {} {}: relative error {:.3} % (limit {} %)",
        v.simulated, v.unit, v.measured, v.unit, v.relative_error_pct, v.max_relative_error_pct
    );
    println!(
        "{} runs simulated, {} replayed from {}, in {:.1} s",
        outcome.simulated,
        outcome.replayed,
        out.join(crate::calibrate::RUNS_DIR).display(),
        started.elapsed().as_secs_f64()
    );
    println!(
        "report: {}",
        out.join(crate::calibrate::report::REPORT_FILE).display()
    );
    if !v.passed {
        let miss = format!(
            "validation failed: relative error {:.3} % exceeds {} %",
            v.relative_error_pct, v.max_relative_error_pct
        );
        if args.strict {
            anyhow::bail!(miss);
        }
        println!("{miss} (see the report; --strict makes this an error)");
    }
    Ok(())
}
