//! `arachis pour`: the bench bed of DESIGN §8 — spheres poured into the steel cylinder and
//! left to settle — with its throughput figure.
//!
//! Prints one JSON line on stdout:
//! `{"particles":…,"steps":…,"wall_seconds":…,"particle_steps_per_second":…,
//! "kinetic_energy_j":…,"bed_height_m":…,"com_height_m":…,"digest":"…","scalar":…,"dt_s":…,
//! "threads":…,"list_builds":…}`.
//! `particle_steps_per_second` is particles × steps / wall seconds "over the whole run,
//! insertion and settling included" (DESIGN §8); writing VTK files comes after the clock
//! stops. `bed_height_m` is the 95th percentile of z + R, `com_height_m` the mean z (issue 2),
//! `digest` the core's state digest as 16 hex digits, `list_builds` how often the
//! neighbour list was built (a cost, not a result). A progress bar goes to stderr when it
//! is a terminal. The global `--threads N` steps on N threads (default: every core); in fixed
//! point the digest is the same for any N.
//!
//! ```text
//! arachis pour --particles 2000 --steps 20000 --dt 2e-5 [--f64] [--threads N] [--vtk DIR] [--frames 20]
//!     [--rolling-convention edem|liggghts-cdt] [--friction-convention edem|liggghts] [--no-rolling-friction]
//! ```
//!
//! The conventions and `--no-rolling-friction` make the LIGGGHTS cross-check of the bed one
//! command (`scripts/cross-check-bed.sh`, `docs/conventions.md`); the JSON line names them.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{anyhow, ensure, Context};
use arachis_core::prelude::*;
use arachis_core::scenario::bench_bed::{self, BenchBed};
use arachis_core::scenario::materials::{POD, POD_POD, POD_STEEL};
use arachis_core::scenario::measure::{bed_height_mm, com_height_mm};
use arachis_core::timestep::{max_stable_dt_s, rayleigh_time_s, MAX_RAYLEIGH_FRACTION};
use arachis_core::units::{ENERGY_J_TO_MJ, LENGTH_M_TO_MM, TIME_S_TO_MS};
use serde::Serialize;

use crate::arena::OwnedStorage;
use crate::stepping::{default_threads, Stepper};
use crate::vtk::{write_series, ParticleFrame};

/// Steps between progress-bar updates: often enough to look live, rarely enough to cost
/// nothing next to a step of thousands of spheres.
const PROGRESS_EVERY_STEPS: u64 = 100;
/// VTK frames written by default with `--vtk`.
const DEFAULT_FRAMES: u32 = 20;

/// Arguments of `arachis pour`. Numbers may be written with a sign (`--dt -2e-5`), so that
/// a negative value is reported as an invalid value rather than as an unknown flag.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Number of spheres (R 4 mm pods) to insert; DESIGN §8 uses 2 000.
    #[arg(long, default_value_t = bench_bed::DESIGN_PARTICLES, allow_hyphen_values = true)]
    pub particles: u32,
    /// Number of time steps to run; DESIGN §8 settles by 20 000.
    #[arg(long, default_value_t = bench_bed::DESIGN_SETTLE_STEPS, allow_hyphen_values = true)]
    pub steps: u64,
    /// Time step in seconds; must be positive and within the stable bound.
    #[arg(long, default_value_t = bench_bed::TIMESTEP_S, allow_hyphen_values = true)]
    pub dt: f64,
    /// Step in the f64 reference arithmetic instead of Q32.32 fixed point.
    #[arg(long)]
    pub f64: bool,
    /// Write VTK frames (`frame_NNNNNN.vtk` plus `particles.pvd` for ParaView) into DIR.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Number of VTK frames, evenly spaced from the initial to the final state.
    #[arg(long, default_value_t = DEFAULT_FRAMES, allow_hyphen_values = true)]
    pub frames: u32,
    /// Seed of the random insertion.
    #[arg(long, default_value_t = bench_bed::DEFAULT_SEED)]
    pub seed: u64,
    /// How both pairs read rolling friction: EDEM's (each body's own spin, the total normal
    /// force), LIGGGHTS' `rolling_friction cdt` (relative spin, R*, elastic force) or
    /// LIGGGHTS' `rolling_friction epsd2` (a spring torque on the relative spin, capped).
    #[arg(
        long,
        value_name = "edem|liggghts-cdt|liggghts-epsd2",
        default_value = "edem"
    )]
    pub rolling_convention: RollingConvention,
    /// How both pairs apply the Coulomb limit: EDEM's (spring plus damping capped) or
    /// LIGGGHTS' `tangential history` (the spring alone tested, no damping while sliding).
    #[arg(long, value_name = "edem|liggghts", default_value = "edem")]
    pub friction_convention: FrictionConvention,
    /// Rolling friction off (μr = 0 for both pairs).
    #[arg(long)]
    pub no_rolling_friction: bool,
}

/// The JSON line printed by `arachis pour` (SI units).
#[derive(Debug, Serialize)]
struct PourReport {
    particles: u32,
    steps: u64,
    wall_seconds: f64,
    particle_steps_per_second: f64,
    kinetic_energy_j: f64,
    bed_height_m: f64,
    com_height_m: f64,
    digest: String,
    scalar: &'static str,
    dt_s: f64,
    threads: usize,
    rolling_convention: &'static str,
    friction_convention: &'static str,
    rolling_friction: bool,
    list_builds: u64,
}

/// Runs `arachis pour`.
pub fn run(args: Args) -> anyhow::Result<()> {
    check_args(&args)?;
    let (report, frames) = if args.f64 {
        pour::<f64>(&args)?
    } else {
        pour::<Fx>(&args)?
    };
    if let Some(dir) = &args.vtk {
        write_series(dir, &frames)?;
    }
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}

/// Refuse bad arguments before the (possibly long) insertion starts.
fn check_args(args: &Args) -> anyhow::Result<()> {
    ensure!(
        args.particles >= 1,
        "--particles must be at least 1, got {}",
        args.particles
    );
    let max = BenchBed::max_particles();
    ensure!(
        args.particles <= max,
        "--particles {} does not fit the DESIGN §8 insertion region (r <= 45 mm, \
         10 mm <= z <= 400 mm) without overlap; at most {max} can be inserted",
        args.particles
    );
    ensure!(args.steps >= 1, "--steps must be at least 1");
    ensure!(
        args.dt.is_finite() && args.dt > 0.0,
        "--dt must be a positive number of seconds, got {}",
        args.dt
    );
    let radius_m = bench_bed::SPHERE_RADIUS_UM as f64 * 1e-6;
    let rayleigh_s = rayleigh_time_s(
        radius_m,
        POD.density_kg_m3,
        POD.youngs_modulus_pa,
        POD.poisson,
    );
    let max_dt = max_stable_dt_s(rayleigh_s);
    ensure!(
        args.dt <= max_dt,
        "--dt {:e} s is above the stable bound {max_dt:.3e} s ({MAX_RAYLEIGH_FRACTION} x the \
         Rayleigh time {rayleigh_s:.3e} s of a 4 mm pod sphere)",
        args.dt
    );
    if args.vtk.is_some() {
        ensure!(args.frames >= 1, "--frames must be at least 1");
        ensure!(
            u64::from(args.frames) <= args.steps + 1,
            "--frames {} exceeds the {} states of a {}-step run",
            args.frames,
            args.steps + 1,
            args.steps
        );
    }
    Ok(())
}

/// Steps after which a VTK frame is taken: `frames` states evenly spaced over `0..=steps`
/// (only the final state for one frame). Empty without `--vtk`.
fn frame_steps(args: &Args) -> Vec<u64> {
    if args.vtk.is_none() {
        return Vec::new();
    }
    let k = u64::from(args.frames);
    if k == 1 {
        return vec![args.steps];
    }
    (0..k).map(|i| i * args.steps / (k - 1)).collect()
}

/// DESIGN §8's pod–pod and pod–steel pairs in the requested conventions, with or without
/// rolling friction.
fn pairs(args: &Args) -> (PairSpec, PairSpec) {
    let conventions = Conventions {
        rolling: args.rolling_convention,
        friction: args.friction_convention,
    };
    let adapt = |p: PairSpec| PairSpec {
        rolling_friction: if args.no_rolling_friction {
            0.0
        } else {
            p.rolling_friction
        },
        ..p.with_conventions(conventions)
    };
    (adapt(POD_POD), adapt(POD_STEEL))
}

/// Build the bed, run it, and measure it.
fn pour<S: Scalar>(args: &Args) -> anyhow::Result<(PourReport, Vec<ParticleFrame>)> {
    let bed = BenchBed {
        particles: args.particles,
        seed: args.seed,
    };
    let (pod_pod, pod_steel) = pairs(args);
    let lengths = bed
        .storage_lengths()
        .with_effects_for(&[pod_pod, pod_steel]);
    let mut arenas = OwnedStorage::<S>::new(lengths);
    let mut stepper = Stepper::<S>::new(default_threads())?;
    let bar = super::steps_bar("pour", args.steps);
    bar.set_message("inserting");
    let started = Instant::now();
    let mut world = bed
        .build_with_timestep(arenas.storage(), args.dt)
        .context("cannot set up the bench bed")?;
    BenchBed::set_pairs(&mut world, pod_pod, pod_steel)
        .context("cannot set the bench bed's pairs")?;
    bar.set_message(format!("dt {:.3e} ms, {}", args.dt * TIME_S_TO_MS, S::NAME));
    let wanted = frame_steps(args);
    let mut frames = Vec::with_capacity(wanted.len());
    let mut next_frame = wanted.iter().copied().peekable();
    let mut done = 0;
    loop {
        while next_frame.peek() == Some(&done) {
            frames.push(ParticleFrame::from_world(&world));
            next_frame.next();
        }
        if done == args.steps {
            break;
        }
        let until = (done + PROGRESS_EVERY_STEPS)
            .min(args.steps)
            .min(next_frame.peek().copied().unwrap_or(u64::MAX));
        stepper
            .run(&mut world, until - done)
            .map_err(|e| anyhow!("the pour failed between steps {done} and {until}: {e}"))?;
        done = until;
        bar.set_position(done);
    }
    let wall_seconds = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let mut scratch = vec![0.0; world.spheres().len()];
    let bed_height_mm =
        bed_height_mm(&world, &mut scratch).context("the bed has no spheres to measure")?;
    let com_height_mm = com_height_mm(&world).context("the bed has no bodies to measure")?;
    let report = PourReport {
        particles: args.particles,
        steps: args.steps,
        wall_seconds,
        particle_steps_per_second: f64::from(args.particles) * args.steps as f64 / wall_seconds,
        kinetic_energy_j: world.kinetic_energy_mj() / ENERGY_J_TO_MJ,
        bed_height_m: bed_height_mm / LENGTH_M_TO_MM,
        com_height_m: com_height_mm / LENGTH_M_TO_MM,
        digest: format!("{:016x}", world.digest()),
        scalar: S::NAME,
        dt_s: args.dt,
        threads: stepper.threads(),
        rolling_convention: args.rolling_convention.name(),
        friction_convention: args.friction_convention.name(),
        rolling_friction: !args.no_rolling_friction,
        list_builds: world.neighbour_list_builds(),
    };
    Ok((report, frames))
}
