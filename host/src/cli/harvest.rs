//! `arachis harvest`: the virtual harvest of issue 6 ([`crate::harvest`]). Plants of a
//! topology (default: the shipped `testdata/peanut-plant/topology-small.toml`) pass through a
//! toothed picking drum, replicate by replicate; prints one JSON report on stdout with the
//! loss rate of every replicate and the pooled t-test against the field losses (default:
//! seed 001 Table 12), and shows a progress bar on stderr.
//!
//! ```text
//! arachis harvest [--topology FILE] [--plants 4] [--replicates 4] [--seed 1]
//!                 [--machine FILE] [--forward-speed 1.0] [--drum-rpm 500] [--tip-radius 0.15]
//!                 [--drum-length 0.12] [--teeth-per-ring 6] [--reach 0.03]
//!                 [--field 4.01,3.83,4.04,3.42] [--f64] [--vtk DIR] [--frame-every 2000]
//!                 [--output FILE]
//! ```

use crate::count_limits::{count, MAX_PLANTS, MAX_REPLICATES};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

use anyhow::Context;
use arachis_core::prelude::*;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use crate::calibration::BatchRun;
use crate::cluster::recipe::HarvestRecipe;
use crate::cluster::RigRecipe;
use crate::harvest::{
    assemble, plan_passes, run_harvest, HarvestConfig, HarvestOutcome, Machine, Progress,
    SEED001_FIELD_LOSS_PERCENT,
};
use crate::io::write_atomic;
use crate::rigs::harvest_pass::{self, layout_condition, pass_result, HarvestPassRig};
use crate::stats::relative_error_percent;
use crate::vtk::write_series;

/// Steps between VTK frames by default with `--vtk`.
const DEFAULT_FRAME_EVERY: u64 = 2000;
/// Significance level of the t-test (seed 001 §3.3: t < t0.05).
const ALPHA: f64 = 0.05;

/// Arguments of `arachis harvest` (SI units).
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Plant topology (TOML, see `arachis::plant`); default: the shipped small plant.
    #[arg(long, value_name = "FILE")]
    pub topology: Option<PathBuf>,
    /// Plants per replicate (at most `count_limits::MAX_PLANTS`).
    #[arg(long, default_value_t = HarvestConfig::default().plants,
        value_parser = count::<u32>(1, MAX_PLANTS))]
    pub plants: u32,
    /// Replicates (different plant layouts; seed 001 uses four; at most
    /// `count_limits::MAX_REPLICATES`).
    #[arg(long, default_value_t = HarvestConfig::default().replicates,
        value_parser = count::<u32>(1, MAX_REPLICATES))]
    pub replicates: u32,
    /// Seed of the first replicate (replicate r uses seed + r).
    #[arg(long, default_value_t = HarvestConfig::default().seed)]
    pub seed: u64,
    /// Machine file (TOML, the fields of `arachis::harvest::Machine`; missing fields take
    /// their defaults), e.g. testdata/peanut-plant/harvest-machine.toml. Flags override it.
    #[arg(long, value_name = "FILE")]
    pub machine: Option<PathBuf>,
    /// Forward (clamp-conveyor) speed, m/s [default 1.0].
    #[arg(long, allow_hyphen_values = true)]
    pub forward_speed: Option<f64>,
    /// Drum speed, r/min [default 500].
    #[arg(long, allow_hyphen_values = true)]
    pub drum_rpm: Option<f64>,
    /// Radius of the tooth centres, m [default 0.15].
    #[arg(long, allow_hyphen_values = true)]
    pub tip_radius: Option<f64>,
    /// Drum length, m [default 0.12].
    #[arg(long, allow_hyphen_values = true)]
    pub drum_length: Option<f64>,
    /// Teeth per ring [default 6].
    #[arg(long)]
    pub teeth_per_ring: Option<u32>,
    /// Height of the tooth circle's top above the stem root, m [default 0.03].
    #[arg(long, allow_hyphen_values = true)]
    pub reach: Option<f64>,
    /// Field loss rates to compare with, % (comma-separated; default seed 001 Table 12).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub field: Option<Vec<f64>>,
    /// Step in the f64 reference arithmetic instead of Q32.32 fixed point.
    #[arg(long)]
    pub f64: bool,
    /// Write VTK frames of every pass into DIR/rep<R>_plant<P>/.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Steps between VTK frames.
    #[arg(long, default_value_t = DEFAULT_FRAME_EVERY)]
    pub frame_every: u64,
    /// Also write the JSON report to FILE.
    #[arg(long, value_name = "FILE")]
    pub output: Option<PathBuf>,
    /// Where the passes run, and the run cache that keeps them.
    #[command(flatten)]
    pub runs: super::runs_args::RunsArgs,
}

/// The t-test block of the report.
#[derive(Debug, Serialize)]
struct TTestReport {
    mean_simulated_percent: f64,
    mean_field_percent: f64,
    pooled_sd_percent: f64,
    t: f64,
    df: usize,
    p: f64,
    alpha: f64,
    significant_difference: bool,
}

/// The JSON report of `arachis harvest`.
#[derive(Debug, Serialize)]
struct Report<'a> {
    machine: Machine,
    tip_speed_m_s: f64,
    plants_per_replicate: u32,
    pods_per_plant: usize,
    /// Bonds of every named set in one plant (pod_stalk, stalk_stem, stem_leaf, …).
    bond_sets_per_plant: std::collections::BTreeMap<&'static str, usize>,
    loss_percent: Vec<f64>,
    field_loss_percent: &'a [f64],
    relative_error_percent: Vec<Option<f64>>,
    t_test: Option<TTestReport>,
    replicates: &'a [crate::harvest::Replicate],
    steps: u64,
    dt_s: f64,
    pass_time_s: f64,
    /// Wall time of the run, s: printed, never written into `--output`, whose bytes must be
    /// the same for every run of the same command.
    #[serde(skip_serializing_if = "Option::is_none")]
    wall_seconds: Option<f64>,
    scalar: &'static str,
    /// Threads each pass could step on (`--threads` shared among the passes run at once);
    /// printed only, like the wall time (the results do not depend on it).
    #[serde(skip_serializing_if = "Option::is_none")]
    threads: Option<usize>,
}

/// Runs `arachis harvest`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let model = super::plant::load_plant(args.topology.as_deref())?;
    let mut machine = match &args.machine {
        Some(p) => {
            let text = crate::io::text::read_text(p)
                .with_context(|| format!("cannot read the machine file {}", p.display()))?;
            toml::from_str::<Machine>(&text)
                .with_context(|| format!("bad machine file {}", p.display()))?
        }
        None => Machine::default(),
    };
    let set = |v: Option<f64>, into: &mut f64| {
        if let Some(x) = v {
            *into = x;
        }
    };
    set(args.forward_speed, &mut machine.forward_speed_m_s);
    set(args.drum_rpm, &mut machine.drum_speed_rpm);
    set(args.tip_radius, &mut machine.tip_radius_m);
    set(args.drum_length, &mut machine.drum_length_m);
    set(args.reach, &mut machine.reach_above_root_m);
    if let Some(n) = args.teeth_per_ring {
        machine.teeth_per_ring = n;
    }
    let config = HarvestConfig {
        machine,
        plants: args.plants,
        replicates: args.replicates,
        seed: args.seed,
        field_loss_percent: args
            .field
            .clone()
            .unwrap_or_else(|| SEED001_FIELD_LOSS_PERCENT.to_vec()),
        frame_every: args.vtk.as_ref().map(|_| args.frame_every),
    };
    let bar = ProgressBar::new(0);
    if let Ok(style) = ProgressStyle::with_template("harvest {bar:40} {pos}/{len} steps  {msg}") {
        bar.set_style(style);
    }
    let passes = AtomicU64::new(0);
    let total = u64::from(config.plants) * u64::from(config.replicates);
    let progress = |p: Progress| match p {
        Progress::Started(n) => {
            bar.inc_length(n);
            let k = passes.fetch_add(1, Ordering::Relaxed) + 1;
            bar.set_message(format!("pass {k}/{total}"));
        }
        Progress::Stepped(n) => bar.inc(n),
    };
    let started = Instant::now();
    let outcome = match passes_executor(&args, &config.machine)? {
        Some((executor, rig)) => run_through(&executor, &rig, &config)?,
        None => if args.f64 {
            run_harvest::<f64>(&config, &model, &progress)
        } else {
            run_harvest::<Fx>(&config, &model, &progress)
        }
        .context("the harvest simulation failed")?,
    };
    let wall_seconds = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    if let Some(dir) = &args.vtk {
        write_frames(dir, &config, &outcome)?;
    }
    let scalar = if args.f64 {
        <f64 as Scalar>::NAME
    } else {
        Fx::NAME
    };
    let mut report = report(&config, &model, &outcome, wall_seconds, scalar);
    let json = serde_json::to_string(&report)?;
    if let Some(path) = &args.output {
        report.wall_seconds = None;
        report.threads = None;
        let file = serde_json::to_string(&report)?;
        write_atomic(path, |w| {
            w.write_all(file.as_bytes())?;
            w.write_all(b"\n")?;
            Ok(())
        })
        .with_context(|| format!("cannot write the report {}", path.display()))?;
    }
    println!("{json}");
    Ok(())
}

/// The executor and pass rig `--runs` or `--executor slurm` ask for, if any.
fn passes_executor(
    args: &Args,
    machine: &Machine,
) -> anyhow::Result<Option<(crate::calibration::Executor, HarvestPassRig)>> {
    if !args.runs.wanted() {
        return Ok(None);
    }
    anyhow::ensure!(
        args.vtk.is_none(),
        "--vtk: frames come from passes run here without a run cache; drop --runs and \
         --executor slurm to write them"
    );
    let harvest = HarvestRecipe {
        topology: args
            .topology
            .as_deref()
            .map(std::path::absolute)
            .transpose()?,
        machine: *machine,
        f64: args.f64,
    };
    let rig = harvest.build()?;
    let executor = args
        .runs
        .executor("harvest", || Ok(RigRecipe::for_harvest(harvest)))?
        .expect("an executor was asked for");
    Ok(Some((executor, rig)))
}

/// The harvest with its passes run (or replayed) by `executor`.
fn run_through(
    executor: &crate::calibration::Executor,
    rig: &HarvestPassRig,
    config: &HarvestConfig,
) -> anyhow::Result<HarvestOutcome> {
    let passes = plan_passes(config)?;
    let conditions: Vec<_> = passes.iter().map(|p| layout_condition(&p.layout)).collect();
    let batch: Vec<BatchRun<'_>> = conditions
        .iter()
        .map(|condition| BatchRun {
            rig,
            experiment: harvest_pass::NAME,
            quantity: harvest_pass::QUANTITY,
            values: Default::default(),
            condition,
            replicate: 0,
        })
        .collect();
    let results = executor
        .run_requests("harvest", &batch)?
        .iter()
        .map(|run| pass_result(&run.responses))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(assemble(config, &passes, results)?)
}

fn write_frames(
    dir: &std::path::Path,
    config: &HarvestConfig,
    outcome: &HarvestOutcome,
) -> anyhow::Result<()> {
    let per = config.plants as usize;
    for (i, frames) in outcome.frames.iter().enumerate() {
        let sub = dir.join(format!("rep{}_plant{}", i / per + 1, i % per + 1));
        write_series(&sub, frames)
            .with_context(|| format!("cannot write VTK frames into {}", sub.display()))?;
    }
    Ok(())
}

fn report<'a>(
    config: &'a HarvestConfig,
    model: &crate::plant::PlantModel,
    outcome: &'a HarvestOutcome,
    wall_seconds: f64,
    scalar: &'static str,
) -> Report<'a> {
    let loss: Vec<f64> = outcome.replicates.iter().map(|r| r.loss_percent).collect();
    // Seed 001 Table 12 pairs replicate i of the simulation with field trial i and takes the
    // simulation as the reference (undefined, null, for a simulated loss of zero).
    let rel = loss
        .iter()
        .zip(&config.field_loss_percent)
        .map(|(s, f)| (*s != 0.0).then(|| relative_error_percent(*f, *s)))
        .collect();
    Report {
        machine: config.machine,
        tip_speed_m_s: config.machine.tip_speed_m_s(),
        plants_per_replicate: config.plants,
        pods_per_plant: model
            .bodies
            .iter()
            .filter(|b| b.kind == crate::plant::topology::Kind::Pod)
            .count(),
        bond_sets_per_plant: model.bond_counts(),
        loss_percent: loss,
        field_loss_percent: &config.field_loss_percent,
        relative_error_percent: rel,
        t_test: outcome.t_test.map(|t| TTestReport {
            mean_simulated_percent: t.mean_1,
            mean_field_percent: t.mean_2,
            pooled_sd_percent: t.pooled_sd,
            t: t.t,
            df: t.df,
            p: t.p,
            alpha: ALPHA,
            significant_difference: t.p < ALPHA,
        }),
        replicates: &outcome.replicates,
        steps: outcome.steps,
        dt_s: outcome.dt_s,
        pass_time_s: outcome.pass_time_s,
        wall_seconds: Some(wall_seconds),
        scalar,
        threads: Some(crate::stepping::default_threads()),
    }
}
