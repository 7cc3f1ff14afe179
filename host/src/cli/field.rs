//! `arachis field FILE [--seed N] [--steps K] [--vtk FILE.vtk] [--picture FILE.svg]`: lay out
//! the field of a field file (`crate::field`: the plants of its variety in ridge rows, their
//! pods in a bed of soil grains), put it in one world, step it K steps (0: none) and print
//! one JSON line: plants, pods, grains, bonds and which of them broke (a count by bond set and
//! the first break: its step, set, criterion and stresses), where the pods lie, the time step
//! and the world's digest. `--vtk` writes every sphere for ParaView, `--picture` the plan view of the
//! plants. A bad field or variety file is refused with its path, line and key; nothing is
//! written.
//!
//! With `--harvester MACHINE.toml` (`crate::harvester`) the machine is mounted ahead of the
//! bed and the K steps move it along the ridge (`--pass`: as many steps as the whole bed
//! needs to pass the collector); the line then also holds the pods' ends so far
//! (`harvest`: collected, unpicked, lost and where) and the loss rate, and `--section`
//! draws a slice through the first row from the side.
//!
//! `--replicates N` (with a harvester) runs the seed's field trial
//! ([`crate::harvester::trial`]): N fields laid out from seeds `seed`, `seed + 1`, …, each
//! harvested the same way, then one JSON object: each replicate's line, the loss rate per
//! replicate (`loss_rate_pct`), the relative errors and the pooled t-test against the field's
//! losses (`--field-loss`, default seed 001 Table 12; `p_value`) and `pods_per_plant`.
//! Files named by `--vtk`, `--picture`, `--section` and `--pod-map` get `_rep<R>` before
//! their extension. `--pod-map` draws where every pod ended, from above.
//! `--output FILE` also writes the printed JSON to FILE, whole or not at all. `--report DIR`
//! writes the trial's report there (`crate::harvester::report`: `report.md` with seed 001
//! Table 12's comparison and where the pods went, `trial.json`, `where-lost.svg`, and each
//! replicate's pod map).
//!
//! The run starts with the field file's calm (`crate::field::calm`): for its first steps a
//! still, dense medium's drag takes out the ringing of the pegs the settled soil pressed on;
//! the line's `calm` says how many steps. A harvester must wait it out (its `settle_s`).
//!
//! `--frames DIR` writes VTK frames as the run goes (every `--frame-every` steps, and a
//! ParaView collection `particles.pvd`).
//!
//! `--checkpoint FILE.ckpt` keeps the run's state in FILE (`crate::checkpoint`, every
//! `--checkpoint-minutes` and at the end): the same command run again goes on from it, bit
//! for bit, so a pass of hours can stop and resume; a replicate already done is not run
//! again. A checkpoint of other inputs or another seed is refused, with its path.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::Context;
use arachis_core::prelude::*;
use arachis_core::units::LENGTH_M_TO_MM;
use serde::Serialize;

use crate::arena::{OwnedBonds, OwnedStorage};
use crate::checkpoint::{self, inputs_hash, Header};
use crate::count_limits::{count, MAX_REPLICATES};
use crate::field::calm::CalmPhase;
use crate::field::layout::holes;
use crate::field::picture::write_field_picture;
use crate::field::settle::Settled;
use crate::field::soil::fill_fraction;
use crate::field::speed_watch::SpeedWatch;
use crate::field::FieldSpec;
use crate::harvest::SEED001_FIELD_LOSS_PERCENT;
use crate::harvester::loss::LossTally;
use crate::harvester::picture::{write_pod_map, write_section_picture};
use crate::harvester::report::{self, Replicate, Trial};
use crate::harvester::rig::{Rig, CHUNK_STEPS};
use crate::harvester::trial::{summarise, TrialSummary};
use crate::harvester::HarvesterSpec;
use crate::io::write_string_atomic;
use crate::vtk::{write_frame, ParticleFrame, StepFrames};

/// Arguments of `arachis field`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Field file (TOML, see `arachis::field`).
    pub file: PathBuf,
    /// Seed of the layout (plants, their turns, the grains).
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Steps to run (gravity, cohesion, contacts between plants).
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u64).range(0..=MAX_STEPS))]
    pub steps: u64,
    /// Write every sphere after the steps as legacy VTK (ParaView).
    #[arg(long, value_name = "FILE.vtk")]
    pub vtk: Option<PathBuf>,
    /// Write VTK frames during the run into DIR (`frame_<step>.vtk`, every `--frame-every`
    /// steps and the last, plus `particles.pvd` for ParaView); with `--replicates`, one DIR
    /// per replicate (`_rep<R>`).
    #[arg(long, value_name = "DIR")]
    pub frames: Option<PathBuf>,
    /// Steps between VTK frames: a multiple of the machine's 250-step chunk, so that the
    /// frames change nothing in the run.
    #[arg(long, default_value_t = DEFAULT_FRAME_EVERY, requires = "frames",
        value_parser = frame_every)]
    pub frame_every: u64,
    /// Write the plan view of the laid-out field (plants from above), SVG.
    #[arg(long, value_name = "FILE.svg")]
    pub picture: Option<PathBuf>,
    /// Harvester file (TOML, see `arachis::harvester`): mount it and drive it along the ridge.
    #[arg(long, value_name = "MACHINE.toml")]
    pub harvester: Option<PathBuf>,
    /// With `--harvester`: write the side view of a slice through the first row after the
    /// steps (soil, plants, pods and the machine), SVG.
    #[arg(long, value_name = "FILE.svg", requires = "harvester")]
    pub section: Option<PathBuf>,
    /// With `--harvester`: write the plan view of where every pod ended (collected, unpicked,
    /// lost and where), SVG.
    #[arg(long, value_name = "FILE.svg", requires = "harvester")]
    pub pod_map: Option<PathBuf>,
    /// With `--harvester`: run the whole pass instead of `--steps`.
    #[arg(long, requires = "harvester", conflicts_with = "steps")]
    pub pass: bool,
    /// With `--harvester`: replicate fields (layout seeds seed, seed + 1, …; seed 001 uses
    /// four), compared with `--field-loss` by a pooled t-test.
    #[arg(long, default_value_t = 1, requires = "harvester",
        value_parser = count::<u32>(1, MAX_REPLICATES))]
    pub replicates: u32,
    /// Field loss rates to compare the replicates with, % (comma-separated; default seed 001
    /// Table 12: 4.01, 3.83, 4.04, 3.42).
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        requires = "harvester"
    )]
    pub field_loss: Option<Vec<f64>>,
    /// Also write the printed JSON to FILE (whole or not at all).
    #[arg(long, value_name = "FILE.json")]
    pub output: Option<PathBuf>,
    /// With `--harvester`: write the trial's report into DIR (`arachis::harvester::report`):
    /// `report.md` (seed 001 Table 12's comparison, where the pods went), `trial.json`,
    /// `where-lost.svg` and each replicate's pod map.
    #[arg(long, value_name = "DIR", requires = "harvester")]
    pub report: Option<PathBuf>,
    /// Keep the run's state in FILE (`arachis::checkpoint`), written every
    /// `--checkpoint-minutes` and when the steps are done; a run whose FILE exists goes on
    /// from it, bit for bit. With `--replicates`, one file per replicate (`_rep<R>`), so a
    /// trial stopped half-way resumes where each replicate was.
    #[arg(long, value_name = "FILE.ckpt")]
    pub checkpoint: Option<PathBuf>,
    /// Minutes of wall time between checkpoints.
    #[arg(long, default_value_t = 10, requires = "checkpoint",
        value_parser = clap::value_parser!(u64).range(1..=MAX_CHECKPOINT_MINUTES))]
    pub checkpoint_minutes: u64,
}

/// Most steps one call runs.
const MAX_STEPS: u64 = 100_000_000;
/// Steps between VTK frames by default: about 0.04 s of the field's time step, some 85
/// frames a pass.
const DEFAULT_FRAME_EVERY: u64 = 200 * CHUNK_STEPS;

/// `--frame-every`: a positive multiple of [`CHUNK_STEPS`].
fn frame_every(s: &str) -> Result<u64, String> {
    let n: u64 = s.parse().map_err(|e| format!("{e}"))?;
    if n == 0 || n % CHUNK_STEPS != 0 || n > MAX_STEPS {
        return Err(format!(
            "{n} is not a multiple of {CHUNK_STEPS} steps (the machine's chunk) from \
             {CHUNK_STEPS} to {MAX_STEPS}"
        ));
    }
    Ok(n)
}

/// Longest time between checkpoints, min (a day).
const MAX_CHECKPOINT_MINUTES: u64 = 24 * 60;
/// Seconds in a minute.
const SECONDS_PER_MINUTE: u64 = 60;

/// The printed line.
#[derive(Debug, Serialize)]
struct FieldLine {
    name: String,
    seed: u64,
    plants: usize,
    pods: usize,
    grains: usize,
    spheres: usize,
    bonds: usize,
    /// Bonds broken by the end of the steps (pod–stalk junctions, stalks, stems, leaves).
    bonds_broken: usize,
    /// The bonds broken, by bond set (`pod_stalk`, …).
    bonds_broken_by_set: BTreeMap<String, usize>,
    /// The first bond that broke, if any: when, of which set, and how.
    #[serde(skip_serializing_if = "Option::is_none")]
    first_break: Option<BreakLine>,
    /// Fraction of the bed the grains fill.
    soil_fill_fraction: f64,
    bed_min_m: [f64; 3],
    bed_max_m: [f64; 3],
    /// Pods whose centre lies inside the bed (below the surface, within its sides).
    pods_in_bed: usize,
    /// Shallowest and deepest pod centre below the surface, mm.
    pod_depth_mm: [f64; 2],
    /// The soil's settling around the held plants before the run (`crate::field::settle`).
    soil_settling: SettlingLine,
    /// The calm at the start of the run (`crate::field::calm`): its steps and medium.
    calm: CalmPhase,
    dt_s: f64,
    /// Field steps per step of the soil ([`crate::field::Soil::slow_stride`], as the soil's
    /// stable step allows it).
    soil_stride: u32,
    steps: u64,
    simulated_s: f64,
    wall_seconds: f64,
    /// CPU time of the steps, every thread, s (summed over the sessions of a resumed run;
    /// unlike the wall time, not inflated by a pause or by other programs).
    cpu_seconds: f64,
    threads: usize,
    digest: String,
    /// The fastest free body of the run and the first runaway, looked at after every chunk
    /// of [`CHUNK_STEPS`] steps (`crate::field::speed_watch`).
    speeds: SpeedWatch,
    /// With a harvester: where the pods are so far.
    #[serde(skip_serializing_if = "Option::is_none")]
    harvest: Option<HarvestLine>,
}

/// One bond's break, as printed.
#[derive(Debug, Serialize)]
struct BreakLine {
    /// The run's step in which it broke.
    step: u64,
    /// Its bond set (`pod_stalk`, …).
    set: String,
    /// The criterion that broke it (`Normal`: σmax, `Tangential`: τmax, `Both`).
    criterion: String,
    /// σmax and τmax at the break, MPa.
    sigma_max_mpa: f64,
    tau_max_mpa: f64,
    /// The bodies of its two spheres.
    bodies: [u32; 2],
}

/// The soil's settling, as printed.
#[derive(Debug, Serialize)]
struct SettlingLine {
    #[serde(flatten)]
    settled: Settled,
    /// Its wall time, s (not in the run's `wall_seconds`).
    wall_seconds: f64,
}

/// The printed object of a trial (`--replicates`).
#[derive(Debug, Serialize)]
struct TrialReport {
    name: String,
    machine: String,
    /// The comparison with the field: `loss_rate_pct`, `p_value`, `pods_per_plant`, ….
    #[serde(flatten)]
    summary: TrialSummary,
    replicates: Vec<FieldLine>,
    /// Wall time of all replicates, s.
    wall_seconds: f64,
    threads: usize,
}

/// The harvest part of the printed line.
#[derive(Debug, Serialize)]
struct HarvestLine {
    machine: String,
    /// Simulated time since the machine was mounted (its settling time included), s.
    machine_s: f64,
    /// Simulated time of the whole pass, s.
    pass_s: f64,
    roots_cut: usize,
    /// Loss rate so far, % (lost pods / all pods).
    loss_rate_pct: Option<f64>,
    /// Pods still on their plants, %.
    unpicked_pct: Option<f64>,
    pods: LossTally,
}

/// Runs `arachis field`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let spec = FieldSpec::read(&args.file)?;
    let machine = args
        .harvester
        .as_deref()
        .map(HarvesterSpec::read)
        .transpose()?;
    if let (Some(m), Some(path)) = (&machine, &args.harvester) {
        m.check_waits_for_calm(path, &spec.calm, &args.file)?;
    }
    let field_loss = args
        .field_loss
        .clone()
        .unwrap_or_else(|| SEED001_FIELD_LOSS_PERCENT.to_vec());
    if let Some(bad) = field_loss.iter().find(|v| !(0.0..=100.0).contains(*v)) {
        anyhow::bail!("--field-loss: {bad} is not a loss rate in % (0 to 100)");
    }
    if let Some(dir) = &args.report {
        // Now, not after hours of stepping: the runs write their pod maps there.
        std::fs::create_dir_all(dir)
            .with_context(|| format!("--report: cannot create {}", dir.display()))?;
    }
    let json = match (&machine, args.replicates) {
        (Some(m), n) if n > 1 || args.report.is_some() => {
            let started = Instant::now();
            let mut lines = Vec::new();
            for r in 0..n {
                let outputs = Outputs::of(&args, Some(r + 1));
                let label = format!("field, replicate {}/{n}", r + 1);
                let line = run_one(
                    &args,
                    &spec,
                    Some(m),
                    args.seed + r as u64,
                    &outputs,
                    &label,
                )?;
                // A pass takes hours: say each replicate's result as soon as it is known.
                eprintln!(
                    "field: replicate {}/{n} (seed {}) done in {:.0} s: {}",
                    r + 1,
                    line.seed,
                    line.wall_seconds,
                    serde_json::to_string(&line.harvest)?
                );
                lines.push(line);
            }
            let losses = lines
                .iter()
                .map(|l| {
                    l.harvest
                        .as_ref()
                        .and_then(|h| h.loss_rate_pct)
                        .ok_or_else(|| {
                            anyhow::anyhow!(
                                "{}: seed {} has no pods, so no loss rate",
                                args.file.display(),
                                l.seed
                            )
                        })
                })
                .collect::<anyhow::Result<Vec<f64>>>()?;
            let pods_per_plant = lines
                .iter()
                .map(|l| l.pods as f64 / l.plants.max(1) as f64)
                .sum::<f64>()
                / lines.len() as f64;
            let summary = summarise(&losses, &field_loss, pods_per_plant);
            if summary.significant_difference == Some(true) {
                eprintln!(
                    "field: the simulated mean loss {:.2} % differs from the field's {:.2} % (p = {:.3e} < {})",
                    summary.mean_simulated_pct,
                    summary.mean_field_pct,
                    summary.p_value.unwrap_or(f64::NAN),
                    summary.alpha
                );
            }
            let rows = lines
                .iter()
                .map(|l| Replicate {
                    seed: l.seed,
                    plants: l.plants,
                    tally: l.harvest.as_ref().map(|h| h.pods).unwrap_or_default(),
                    simulated_s: l.simulated_s,
                    pass_s: l.harvest.as_ref().map_or(0.0, |h| h.pass_s),
                    wall_seconds: l.wall_seconds,
                })
                .collect();
            let dt_s = lines.first().map_or(0.0, |l| l.dt_s);
            let threads = crate::stepping::run_threads();
            let json = serde_json::to_string(&TrialReport {
                name: spec.field.name.clone(),
                machine: m.harvester.name.clone(),
                summary: summary.clone(),
                replicates: lines,
                wall_seconds: started.elapsed().as_secs_f64(),
                threads,
            })?;
            if let Some(dir) = &args.report {
                let trial = Trial {
                    field: &spec.field.name,
                    field_file: &args.file.display().to_string(),
                    machine: &m.harvester.name,
                    machine_file: &args
                        .harvester
                        .as_ref()
                        .map_or(String::new(), |p| p.display().to_string()),
                    dt_s,
                    threads,
                    summary: &summary,
                    replicates: rows,
                };
                report::write(dir, &trial, &json)?;
            }
            json
        }
        _ => {
            let outputs = Outputs::of(&args, None);
            let line = run_one(&args, &spec, machine.as_ref(), args.seed, &outputs, "field")?;
            serde_json::to_string(&line)?
        }
    };
    if let Some(path) = &args.output {
        write_string_atomic(path, &format!("{json}\n"))?;
    }
    println!("{json}");
    Ok(())
}

/// Where one run writes its pictures and VTK file.
struct Outputs {
    vtk: Option<PathBuf>,
    picture: Option<PathBuf>,
    section: Option<PathBuf>,
    pod_map: Option<PathBuf>,
    /// The folder of VTK frames.
    frames: Option<PathBuf>,
    /// The pod map the report links to (in its folder).
    report_pods: Option<PathBuf>,
    checkpoint: Option<PathBuf>,
}

impl Outputs {
    /// The files of `args`, with `_rep<R>` before the extension for replicate R.
    fn of(args: &Args, replicate: Option<u32>) -> Self {
        let name = |p: &Option<PathBuf>| {
            p.as_ref().map(|p| match replicate {
                None => p.clone(),
                Some(r) => {
                    let stem = p
                        .file_stem()
                        .map(|s| s.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    let ext = p
                        .extension()
                        .map(|e| format!(".{}", e.to_string_lossy()))
                        .unwrap_or_default();
                    p.with_file_name(format!("{stem}_rep{r}{ext}"))
                }
            })
        };
        Outputs {
            vtk: name(&args.vtk),
            picture: name(&args.picture),
            section: name(&args.section),
            pod_map: name(&args.pod_map),
            frames: name(&args.frames),
            report_pods: name(&args.report.as_ref().map(|d| d.join("pods.svg"))),
            checkpoint: name(&args.checkpoint),
        }
    }
}

/// Lay out the field of `spec` from `seed`, mount `machine`, step, write `outputs` and return
/// the line.
fn run_one(
    args: &Args,
    spec: &FieldSpec,
    machine: Option<&HarvesterSpec>,
    seed: u64,
    outputs: &Outputs,
    label: &str,
) -> anyhow::Result<FieldLine> {
    let mut field = spec
        .lay_out(seed)
        .with_context(|| format!("{}: cannot lay out the field", args.file.display()))?;
    let settle_started = Instant::now();
    let settle_bar = super::steps_bar(&format!("{label} soil settling"), 0);
    let settled = field
        .settle(spec, |done, all| {
            settle_bar.set_length(all);
            settle_bar.set_position(done);
        })
        .map_err(|e| anyhow::anyhow!("{}: the soil's settling: {e}", args.file.display()))?;
    settle_bar.finish_and_clear();
    let soil_settling = SettlingLine {
        settled,
        wall_seconds: settle_started.elapsed().as_secs_f64(),
    };
    let (extra_bodies, extra_spheres) = machine.map_or((0, 0), Rig::extra_storage);
    let mut arena =
        OwnedStorage::<Fx>::new(field.storage_lengths_with(spec, extra_bodies, extra_spheres));
    let mut bonds = OwnedBonds::<Fx>::new(field.bond_count());
    let mut world = World::new(arena.storage()).map_err(|e| anyhow::anyhow!("{e}"))?;
    world
        .attach_bond_storage(bonds.storage())
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let loaded = field.load_into(spec, &mut world).map_err(|e| {
        anyhow::anyhow!(
            "{}: cannot build the field's world: {e}",
            args.file.display()
        )
    })?;
    let mut rig = match (machine, &args.harvester) {
        (Some(m), Some(path)) => {
            Some(Rig::mount(m, &field, &loaded, &mut world).map_err(|e| {
                anyhow::anyhow!("{}: cannot mount the harvester: {e}", path.display())
            })?)
        }
        _ => None,
    };
    let mut speeds = SpeedWatch::new(
        rig.as_ref()
            .map_or(0.0, |r| r.layout.fastest_point_m_s(r.travel.speed_m_s)),
    );
    let steps = match &rig {
        Some(r) if args.pass => r.pass_steps(world.timestep_s(), world.slow_stride()),
        _ => args.steps,
    };
    if steps % u64::from(world.slow_stride()) != 0 {
        anyhow::bail!(
            "--steps {steps}: the soil steps once every {} steps (soil.slow_stride), so the run must end between its steps: give a multiple of {}",
            world.slow_stride(),
            world.slow_stride()
        );
    }
    // No longer than the file's duration, which the machine waits out (checked in `run`).
    let calm = CalmPhase::of(&spec.calm, world.timestep_s());
    let wanted = Header::new(inputs_hash(spec, machine, seed), seed, 0, 0.0, None);
    let (mut done, wall_before, cpu_before) = match &outputs.checkpoint {
        Some(path) => checkpoint::resume(path, &wanted, steps, &mut world, rig.as_mut())?,
        None => (0, 0.0, 0.0),
    };
    let set_calm = |world: &mut World<'_, Fx>, done: u64| {
        calm.set(world, done)
            .map_err(|e| anyhow::anyhow!("{}: the calm: {e}", args.file.display()))
    };
    // The drag is set-up state, not in a checkpoint's words: set it from the steps done.
    set_calm(&mut world, done)?;
    let started = Instant::now();
    // The process's CPU clock counts every replicate run so far: this one's starts here.
    let cpu_started = super::simulate::process_cpu_seconds();
    let cpu_spent = || {
        let now = super::simulate::process_cpu_seconds();
        cpu_before + now.zip(cpu_started).map_or(0.0, |(n, s)| n - s)
    };
    let mut saved = Instant::now();
    let every = std::time::Duration::from_secs(args.checkpoint_minutes * SECONDS_PER_MINUTE);
    let bar = super::steps_bar(label, steps);
    bar.set_position(done);
    let frames = outputs
        .frames
        .as_deref()
        .map(|dir| StepFrames::new(dir, args.frame_every))
        .transpose()?;
    if let Some(f) = &frames {
        f.take(&world, done)?;
    }
    let save = |world: &mut World<'_, Fx>, rig: Option<&Rig>, done: u64| match &outputs.checkpoint {
        Some(path) => {
            let wall = wall_before + started.elapsed().as_secs_f64();
            let header = Header {
                steps_done: done,
                wall_seconds: wall,
                cpu_seconds: cpu_spent(),
                rig: rig.map(Rig::state),
                ..wanted.clone()
            };
            checkpoint::write(path, header, world)
        }
        None => Ok(()),
    };
    while done < steps {
        // Blocks end on frames; both are whole chunks, so the frames change nothing.
        let to_frame = frames.as_ref().map_or(u64::MAX, |f| f.steps_to_next(done));
        // A chunk at a time: the speed watch looks after each; the calm ends between two.
        let n = CHUNK_STEPS
            .min(steps - done)
            .min(to_frame)
            .min(calm.steps_to_switch(done));
        let stepped = match &mut rig {
            Some(r) => r.advance(&mut world, n),
            None => crate::stepping::run(&mut world, n).map_err(|e| e.to_string()),
        };
        stepped.map_err(|e| {
            anyhow::anyhow!(
                "{}: step failed at t = {} s: {e}",
                args.file.display(),
                world.time_s()
            )
        })?;
        done += n;
        if done == calm.steps {
            set_calm(&mut world, done)?;
        }
        bar.set_position(done);
        if let Some(f) = speeds.observe(&world, done) {
            bar.suspend(|| {
                eprintln!(
                    "{label}: warning: body {} moves at {:.1} m/s at step {} (at ({:.3}, {:.3}, {:.3}) m), faster than anything in the field can drive it ({:.1} m/s): its energy came from the numerics, and what it hits is wrong",
                    f.body, f.speed_m_s, f.step, f.position_m[0], f.position_m[1], f.position_m[2],
                    speeds.bound_m_s()
                )
            });
        }
        if let Some(f) = &frames {
            if f.due(done) || done == steps {
                f.take(&world, done)?;
            }
        }
        if saved.elapsed() >= every && done < steps {
            save(&mut world, rig.as_ref(), done)?;
            saved = Instant::now();
        }
    }
    bar.finish_and_clear();
    save(&mut world, rig.as_ref(), done)?;
    if let Some(f) = &frames {
        f.collect(world.timestep_s())?;
    }
    let wall_seconds = wall_before + started.elapsed().as_secs_f64();
    let cpu_seconds = cpu_spent();
    let harvest = match (&rig, machine) {
        (Some(r), Some(m)) => {
            let pods = r.tally(&world);
            Some(HarvestLine {
                machine: m.harvester.name.clone(),
                machine_s: r.elapsed_s(&world),
                pass_s: r.pass_steps(world.timestep_s(), world.slow_stride()) as f64
                    * world.timestep_s(),
                roots_cut: r.roots_let_go(),
                loss_rate_pct: pods.loss_percent(),
                unpicked_pct: pods.unpicked_percent(),
                pods,
            })
        }
        _ => None,
    };
    let pod_z_mm: Vec<f64> = loaded
        .pods
        .iter()
        .map(|&id| world.body(id).position.to_f64()[2])
        .collect();
    let pods_in_bed = loaded
        .pods
        .iter()
        .filter(|&&id| {
            let p = world.body(id).position.to_f64().map(|x| x / LENGTH_M_TO_MM);
            (0..3).all(|k| (field.bed_min_m[k]..=field.bed_max_m[k]).contains(&p[k]))
        })
        .count();
    // The plants of one field share their bond sets (`Field::load_into`).
    let set_name = |tag: u16| {
        field
            .plants
            .first()
            .and_then(|p| p.model.set_name(tag))
            .map_or_else(|| format!("tag {tag}"), str::to_owned)
    };
    let line = FieldLine {
        name: spec.field.name.clone(),
        seed,
        plants: field.plants.len(),
        pods: field.pods(),
        grains: field.grains.len(),
        spheres: field.spheres(),
        bonds: field.bond_count(),
        bonds_broken: field.bond_count() - world.bonds().bonds().len(),
        bonds_broken_by_set: world
            .bonds()
            .breaks()
            .iter()
            .fold(BTreeMap::new(), |mut by, b| {
                *by.entry(set_name(b.tag)).or_insert(0) += 1;
                by
            }),
        first_break: world.bonds().breaks().first().map(|b| BreakLine {
            step: b.step,
            set: set_name(b.tag),
            criterion: format!("{:?}", b.criterion),
            sigma_max_mpa: b.sigma_max_mpa.to_f64(),
            tau_max_mpa: b.tau_max_mpa.to_f64(),
            bodies: [
                world.spheres()[b.sphere_a as usize].body,
                world.spheres()[b.sphere_b as usize].body,
            ],
        }),
        soil_fill_fraction: fill_fraction(&field.grains, field.bed_min_m, field.bed_max_m),
        bed_min_m: field.bed_min_m,
        bed_max_m: field.bed_max_m,
        pods_in_bed,
        pod_depth_mm: [
            -pod_z_mm.iter().copied().fold(f64::MIN, f64::max),
            -pod_z_mm.iter().copied().fold(f64::MAX, f64::min),
        ],
        soil_settling,
        calm,
        dt_s: world.timestep_s(),
        soil_stride: world.slow_stride(),
        steps,
        simulated_s: world.time_s(),
        wall_seconds,
        cpu_seconds,
        threads: crate::stepping::run_threads(),
        digest: format!("{:016x}", world.digest()),
        speeds,
        harvest,
    };
    if let Some(path) = &outputs.vtk {
        write_frame(path, &ParticleFrame::from_world(&world))?;
    }
    if let (Some(path), Some(r)) = (&outputs.section, &rig) {
        let row_y = holes(spec).first().map_or(0.0, |h| h[1]);
        let title = format!("{}, seed {seed}", spec.field.name);
        write_section_picture(path, &world, &loaded.materials, r.steel, row_y, &title)?;
    }
    let pod_maps: Vec<&PathBuf> = [&outputs.pod_map, &outputs.report_pods]
        .into_iter()
        .flatten()
        .collect();
    if let (Some(r), false) = (&rig, pod_maps.is_empty()) {
        let title = format!("{}, seed {seed}", spec.field.name);
        let ends = r.ends(&world);
        for path in pod_maps {
            write_pod_map(
                path,
                &world,
                &ends,
                field.bed_min_m,
                field.bed_max_m,
                &title,
            )?;
        }
    }
    if let Some(path) = &outputs.picture {
        let title = format!("{}, seed {seed}", spec.field.name);
        write_field_picture(path, &field, &title)?;
    }
    Ok(line)
}
