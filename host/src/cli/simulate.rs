//! `arachis simulate`: one virtual bench experiment of a study, from the command line.
//!
//! ```text
//! arachis simulate repose --study testdata/peanut-pods-saline/study.toml \
//!     [--mode quick|full] [--set pod-pod.static_friction=0.854 ...] [--seed N] \
//!     [--vtk DIR] [--picture pile.svg|pile.png] [--json]
//! ```
//!
//! Experiments: the pod rigs `repose`, `plate_drop`, `incline_slide`, `rolling`,
//! `compression`, `pod_bulk_density`, `pod_drum`, `pod_hopper` (`crate::rigs`). `--set KEY=VALUE` overrides a registry parameter (SI, e.g.
//! `pod.shear_modulus_pa=3.04e6`); parameters not set take the study's held values. The
//! study and every `--set` are checked before anything is simulated. Prints the observable
//! (with `--json`: the whole [`crate::rigs::pod_world::Observation`] plus the run's spec hash
//! and its CPU time, one JSON object).

use std::path::PathBuf;

use anyhow::{bail, Context};
use serde::Serialize;

use crate::rigs::pod_world::{
    check_values, parse_assignment, parse_experiment, Experiment, ModeName, Observation,
    ObservationDetails, ParameterValues, PodWorld, RunOptions,
};
use crate::rigs::repose_picture::write_pile_picture;
use crate::study::Study;

/// Which run: mode, parameter overrides and seed, as `simulate` and `export liggghts` take
/// them.
#[derive(Debug, Clone, clap::Args)]
pub struct RunChoice {
    /// Run mode: quick (fewer pods, coarser filling) or full (seed scale); default: the
    /// study's `[plan] mode`.
    #[arg(long)]
    pub mode: Option<String>,
    /// Override a parameter, KEY=VALUE in SI (repeatable), e.g.
    /// pod-pod.static_friction=0.854.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Placement seed; default: the study's `[plan.simulation] random_seed`.
    #[arg(long)]
    pub seed: Option<u64>,
}

/// Which run of which study.
#[derive(Debug, clap::Args)]
pub struct RunSelection {
    /// The experiment: repose, plate_drop, incline_slide, rolling, compression,
    /// pod_bulk_density, pod_drum or pod_hopper.
    pub experiment: String,
    /// The study file (TOML).
    #[arg(long, value_name = "STUDY.toml")]
    pub study: PathBuf,
    /// Mode, overrides and seed.
    #[command(flatten)]
    pub choice: RunChoice,
}

/// Arguments of `arachis simulate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The run.
    #[command(flatten)]
    pub run: RunSelection,
    /// Write VTK frames (`frame_NNNNNN.vtk` plus `particles.pvd`) into DIR.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Write a picture of the result (repose: the pile's silhouette and fitted flanks),
    /// SVG or PNG by the file's extension.
    #[arg(long, value_name = "FILE")]
    pub picture: Option<PathBuf>,
    /// Print the full observation as JSON.
    #[arg(long)]
    pub json: bool,
}

#[derive(Serialize)]
struct Printed<'a> {
    format: &'static str,
    study: String,
    mode: &'static str,
    seed: u64,
    values: &'a ParameterValues,
    spec_hash: String,
    /// CPU seconds of the run, every thread of the process (a figure of this machine; not
    /// part of the deterministic observation).
    cpu_seconds: Option<f64>,
    /// Threads the simulation stepped on (`--threads`; the observation does not depend on it).
    threads: usize,
    observation: &'a Observation,
}

/// Checks everything that can be checked before simulating.
pub fn prepare(
    args: &RunSelection,
) -> anyhow::Result<(Study, Experiment, ParameterValues, ModeName)> {
    let experiment = parse_experiment(&args.experiment)?;
    let study = Study::load(&args.study)?;
    let world = pod_world(&study, args)?;
    let mode: ModeName = match (
        &args.choice.mode,
        study.file().plan.as_ref().and_then(|p| p.mode.as_ref()),
    ) {
        (Some(m), _) | (None, Some(m)) => m.parse()?,
        (None, None) => ModeName::Quick,
    };
    let mut values = ParameterValues::new();
    for text in &args.choice.set {
        let (key, value) = parse_assignment(text).with_context(|| format!("--set {text}"))?;
        if values.insert(key.clone(), value).is_some() {
            bail!("--set {key} is given twice");
        }
    }
    check_values(&world, &values).context("--set")?;
    Ok((study, experiment, values, mode))
}

/// Refuses a `--picture` that cannot be drawn before the (possibly long) run.
fn check_picture(args: &Args, experiment: Experiment) -> anyhow::Result<()> {
    if let Some(p) = &args.picture {
        let ext = p
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        if !matches!(ext.as_deref(), Some("svg") | Some("png")) {
            bail!(
                "--picture {}: the file name must end in .svg or .png",
                p.display()
            );
        }
        if experiment != Experiment::Repose {
            bail!("--picture is drawn for the repose experiment only");
        }
    }
    Ok(())
}

/// The study's pod world, or the error saying it has none.
pub fn pod_world<'a>(study: &'a Study, args: &RunSelection) -> anyhow::Result<PodWorld<'a>> {
    study.pod_world().with_context(|| {
        format!(
            "{}: `simulate` runs the pod rigs, and the study has no pod world ([materials], \
             [pods], [pairs], [plan.modes], [plan.simulation])",
            args.study.display()
        )
    })
}

/// Runs `arachis simulate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let (study, experiment, values, mode) = prepare(&args.run)?;
    check_picture(&args, experiment)?;
    let world = pod_world(&study, &args.run)?;
    let seed = args.run.choice.seed.unwrap_or(world.simulation.random_seed);
    let condition = study.condition_of(experiment.name());
    let spec_hash = world
        .run_spec(experiment, &condition, &values, mode.as_str())
        .map_err(anyhow::Error::msg)?
        .spec_hash();
    let options = RunOptions {
        vtk_dir: args.vtk.clone(),
        templates: None,
    };
    let cpu_start = process_cpu_seconds();
    let observation = study.run_experiment(experiment, &values, mode, seed, &options)?;
    let cpu_seconds = process_cpu_seconds()
        .zip(cpu_start)
        .map(|(end, start)| end - start);
    if let (Some(path), ObservationDetails::Repose(details)) = (&args.picture, &observation.details)
    {
        let title = format!("{} ({} mode, seed {seed})", study.name(), mode);
        write_pile_picture(path, details, &title)?;
    }
    if args.json {
        let printed = Printed {
            format: "arachis-simulate-1",
            study: study.path().display().to_string(),
            mode: mode.as_str(),
            seed,
            values: &values,
            spec_hash: spec_hash.to_string(),
            cpu_seconds,
            threads: crate::stepping::run_threads(),
            observation: &observation,
        };
        println!("{}", serde_json::to_string_pretty(&printed)?);
    } else {
        println!(
            "{} {} = {:.4} {} (mode {}, seed {seed}, spec {spec_hash}, digest {}{})",
            experiment,
            observation.quantity,
            observation.value,
            observation.unit,
            mode,
            observation.digest,
            cpu_seconds
                .map(|c| format!(", {c:.1} s CPU"))
                .unwrap_or_default()
        );
    }
    Ok(())
}

/// CPU time of this process, every thread included (also threads that have ended, such as a
/// finished run's stepping pool), s: fields 14 and 15 of Linux's `/proc/self/stat` (user and
/// system time in clock ticks); `None` elsewhere. std has no CPU clock, and this figure is
/// only printed, never used in a result. The calling thread's own clock would miss the
/// stepping threads (it reported 0.19 s for a 315 s run on 2 threads).
pub fn process_cpu_seconds() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/stat").ok()?;
    cpu_seconds_of_stat(&text)
}

/// Clock ticks per second of `/proc/*/stat` times: Linux's USER_HZ, 100 on every
/// architecture it exports to user space.
const USER_HZ: f64 = 100.0;

/// User plus system time, s, of a `/proc/PID/stat` line. The command name (field 2) is in
/// parentheses and may hold spaces, so fields are counted after its closing parenthesis.
fn cpu_seconds_of_stat(text: &str) -> Option<f64> {
    let rest = &text[text.rfind(')')? + 1..];
    let mut fields = rest.split_whitespace().skip(11); // fields 3..=13
    let user: u64 = fields.next()?.parse().ok()?;
    let system: u64 = fields.next()?.parse().ok()?;
    Some((user + system) as f64 / USER_HZ)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stat_times_are_read_after_the_command_name() {
        // A command name with spaces and a parenthesis; utime 1234, stime 66 ticks.
        let line = "4242 (a (b) c) R 1 2 3 4 5 6 7 8 9 10 1234 66 0 0 20 0 3 0 99";
        assert_eq!(cpu_seconds_of_stat(line), Some(13.0));
        assert_eq!(cpu_seconds_of_stat("4242 (x) R 1"), None);
    }

    #[test]
    fn the_process_clock_counts_other_threads() {
        let before = process_cpu_seconds().expect("Linux /proc");
        std::thread::spawn(|| {
            let t = std::time::Instant::now();
            let mut x = 0u64;
            while t.elapsed().as_millis() < 300 {
                x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            }
            std::hint::black_box(x);
        })
        .join()
        .unwrap();
        let spent = process_cpu_seconds().unwrap() - before;
        // 0.3 s of spinning on another thread, read at a 0.01 s tick; a loaded machine may
        // give the thread less than all of the 0.3 s of wall time, hence the margin.
        assert!(spent >= 0.1, "{spent} s");
    }
}
