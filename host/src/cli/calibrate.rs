//! `arachis calibrate STUDY [--quick|--full|--mode NAME] [--jobs N] [--out DIR] [--quiet]
//! [--strict] [--simulator dem|surrogate]`: the calibration plan of any study — screening,
//! steepest ascent, a Box–Behnken or central composite design, desirability optimum,
//! validation — on the study's rig, writing the report into the output folder with one
//! `runs/<spec hash>.json` per run.
//!
//! The study is loaded and validated before anything runs, so a bad file stops with its
//! file, key and reason. Rerunning into the same folder replays finished runs from
//! `runs/`, so an interrupted calibration resumes and ends with the same bytes. A study
//! writes `calibration.json`, except a pull-off study (seed 001's, with `[rig]`), which
//! writes seed 001's `plant-calibration.json` for one release.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, ensure, Context};

use crate::calibration::{calibrate, Executor, Outcome, Problem, Progress};
use crate::cluster::recipe::ShippedPull;
use crate::cluster::{on_cluster_if_chosen, ClusterArgs, RigRecipe};
use crate::report::{pull_off, write_calibration, Provenance};
use crate::rigs::pod_world::ModeName;
use crate::rigs::pull_off::PullOffRig;
use crate::study::Study;

/// Which simulator answers the runs (the name the command line has known it by).
pub use crate::cluster::Simulator as SimulatorChoice;

/// Arguments of `arachis calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study file (TOML), e.g. testdata/peanut-pods-saline/study.toml or the plant
    /// pull-off study testdata/peanut-plant/study.toml.
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
    /// Simulations run at once (default: every core; at most `count_limits::MAX_JOBS`).
    #[arg(long, short, value_parser = crate::count_limits::count::<u32>(1, crate::count_limits::MAX_JOBS))]
    pub jobs: Option<u32>,
    /// Output folder (default: `calibration-STUDYNAME-MODE`, or `calibration-STUDYNAME`
    /// for a study without modes).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Exit with status 2 when the validation misses its limit (for scripts and CI).
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
    /// Where the simulations run (this machine or a Slurm cluster).
    #[command(flatten)]
    pub cluster: ClusterArgs,
    /// Set by `plant-calibrate`: the study is the built-in pull-off study with this pull.
    #[arg(skip)]
    pub shipped_pull_off: Option<ShippedPull>,
}

impl Args {
    /// The mode the flags ask for, if any.
    fn mode(&self) -> Option<String> {
        if self.quick {
            Some(ModeName::Quick.as_str().to_owned())
        } else if self.full {
            Some(ModeName::Full.as_str().to_owned())
        } else {
            self.mode.clone()
        }
    }

    /// The recipe of this command's rigs.
    fn recipe(&self, mode: Option<ModeName>) -> anyhow::Result<RigRecipe> {
        let mut recipe = RigRecipe::new(&self.study, self.simulator, mode)
            .with_context(|| format!("{}: cannot make the path absolute", self.study.display()))?;
        recipe.surrogate_delay_ms = self.surrogate_delay_ms;
        recipe.shipped_pull_off = self.shipped_pull_off;
        Ok(recipe)
    }

    fn executor(&self, out: &Path, recipe: RigRecipe) -> anyhow::Result<Executor> {
        let local = Executor::new(
            self.jobs.map(|j| j as usize),
            Some(&out.join(crate::calibration::RUNS_DIR)),
            Progress::new(self.quiet),
        )?;
        on_cluster_if_chosen(
            local,
            &self.cluster,
            || Ok(recipe),
            &out.join(crate::cluster::SLURM_DIR),
            self.quiet,
        )
    }
}

/// Runs `arachis calibrate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    calibrate_study(&args, &Study::load(&args.study)?)
}

/// The run mode of `study` the flags ask for (checked against its `[plan.modes]`), `None`
/// for a study whose rigs have no modes.
fn mode(args: &Args, study: &Study) -> anyhow::Result<Option<(String, ModeName)>> {
    let plan = study.file().plan.as_ref();
    let Some(modes) = plan.map(|p| &p.modes).filter(|m| !m.is_empty()) else {
        ensure!(
            args.mode().is_none(),
            "{}: a study without [plan.modes] (a pull-off study: every pull is the same rig) \
             has no run modes (--quick, --full, --mode)",
            args.study.display()
        );
        return Ok(None);
    };
    let name = args
        .mode()
        .or_else(|| plan.and_then(|p| p.mode.clone()))
        .unwrap_or_else(|| ModeName::Quick.as_str().to_owned());
    if !modes.contains_key(&name) {
        let known: Vec<&String> = modes.keys().collect();
        bail!(
            "calibrating {}: the study cannot be calibrated: no mode '{name}' in \
             [plan.modes] (the study has {known:?})",
            args.study.display()
        );
    }
    let parsed = name.parse()?;
    Ok(Some((name, parsed)))
}

/// Calibrates `study` as `args` say, writes its report and prints its summary.
pub fn calibrate_study(args: &Args, study: &Study) -> anyhow::Result<()> {
    let mode = mode(args, study)?;
    let (Some(target), Some(validation)) = (study.target(), study.validation()) else {
        bail!(
            "{}: the study has no [plan]: nothing to calibrate",
            args.study.display()
        );
    };
    let modal = mode.as_ref().map(|(_, m)| *m);
    let recipe = args.recipe(modal)?;
    let target_rig = recipe.build(study, &target.experiment)?;
    let other_rig = (validation.experiment != target.experiment)
        .then(|| recipe.build(study, &validation.experiment))
        .transpose()?;
    let problem = study
        .problem(
            target_rig.as_ref(),
            other_rig.as_deref().unwrap_or(target_rig.as_ref()),
        )
        .with_context(|| format!("{}: the study has no [plan]", args.study.display()))?;
    let name = study.name();
    let out = args.out.clone().unwrap_or_else(|| {
        PathBuf::from(match &mode {
            Some((m, _)) => format!("calibration-{name}-{m}"),
            None => format!("calibration-{name}"),
        })
    });
    let started = Instant::now();
    let executor = args.executor(&out, recipe)?;
    let outcome = run_problem(args, &problem, &executor)?;
    if let Some(base) = study.pull_off_setup() {
        let rig = PullOffRig { base };
        return report_pull_off(args, &problem, &outcome, name, &rig, &out, started);
    }
    // A DEM pile calibration states its piles' size; the surrogate simulates no pile.
    let pile = match (&mode, args.simulator) {
        (Some((m, _)), SimulatorChoice::Dem) => study
            .file()
            .plan
            .as_ref()
            .and_then(|p| p.modes.get(m))
            .cloned(),
        _ => None,
    };
    let provenance = Provenance {
        study: name.to_owned(),
        mode: mode.map_or("-".to_owned(), |(m, _)| m),
        pile,
    };
    let c = write_calibration(&problem, &outcome.stages, &provenance, &out)?;
    let strongest = outcome
        .stages
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
        c.steepest_ascent.stage.direction.name(),
        c.steepest_ascent.stage.best,
        c.steepest_ascent.stage.runs.len()
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
        c.optimum.stage.desirability,
        c.optimum.stage.predicted,
        c.target.unit
    );
    let (v, unit) = (&c.validation.stage, &c.validation.unit);
    println!(
        "validation: simulated {:.3} {unit} vs measured {} {unit}: relative error {:.3} % (limit \
         {} %)",
        v.simulated, v.measured, v.relative_error_pct, v.max_relative_error_pct
    );
    // The thread count is printed, not written: calibration.json is the same bytes for any.
    println!(
        "{} runs simulated, {} replayed from {}, in {:.1} s ({} threads)",
        outcome.simulated,
        outcome.replayed,
        out.join(crate::calibration::RUNS_DIR).display(),
        started.elapsed().as_secs_f64(),
        crate::stepping::default_threads()
    );
    println!("report: {}", out.join(crate::report::REPORT_FILE).display());
    validation_verdict(
        args,
        v.passed,
        v.relative_error_pct,
        v.max_relative_error_pct,
    )
}

/// Runs `problem`, naming the study in the error.
fn run_problem(args: &Args, problem: &Problem<'_>, executor: &Executor) -> anyhow::Result<Outcome> {
    calibrate(problem, executor).with_context(|| format!("calibrating {}", args.study.display()))
}

/// Prints a missed validation, or fails with it under `--strict`.
fn validation_verdict(args: &Args, passed: bool, psi: f64, limit: f64) -> anyhow::Result<()> {
    if passed {
        return Ok(());
    }
    let miss = format!("validation failed: relative error {psi:.3} % exceeds {limit} %");
    if args.strict {
        bail!(miss);
    }
    println!("{miss} (see the report; --strict makes this an error)");
    Ok(())
}

/// Writes seed 001's pull-off report and prints its summary.
fn report_pull_off(
    args: &Args,
    problem: &Problem<'_>,
    outcome: &Outcome,
    name: &str,
    rig: &PullOffRig,
    out: &Path,
    started: Instant,
) -> anyhow::Result<()> {
    let wall = started.elapsed().as_secs_f64();
    let cal = pull_off::PlantCalibration::new(problem, &outcome.stages, name, rig);
    pull_off::write_files(&cal, out)
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
    println!(
        "{} pulls ({} simulated, {} replayed) in {wall:.2} s",
        cal.runs, outcome.simulated, outcome.replayed
    );
    println!("report: {}", out.join(pull_off::MARKDOWN_FILE).display());
    validation_verdict(
        args,
        o.passed,
        o.relative_error_pct,
        o.max_relative_error_pct,
    )
}
