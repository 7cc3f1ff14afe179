//! `arachis pulloff`: the virtual tensile test of issue 6 (core scenario
//! [`arachis_core::scenario::PullOff`]): a bonded pod stalk clamped at one end, a pod clump
//! bonded to the other end and pulled at constant speed until the pod–stalk junction breaks.
//!
//! Prints one JSON line on stdout:
//! `{"detachment_force_n":…,"detachment_displacement_m":…,"detached":…,"break_time_s":…,
//! "predicted_axial_detachment_n":…,"stalk_broke_first":…,"steps":…,"wall_seconds":…,
//! "digest":"…","scalar":…,"dt_s":…}`. The detachment force is the largest pull force before
//! the junction broke. `--curve FILE` writes the force–displacement curve as CSV
//! (`displacement_m,force_n`, every step), `--vtk DIR` writes particle frames.
//!
//! ```text
//! arachis pulloff [--speed 0.1] [--angle 0] [--stalk-spheres 8] [--kn N/m3] [--kt N/m3]
//!                 [--sigma-c Pa] [--tau-c Pa] [--bond-radius m] [--max-steps 100000]
//!                 [--f64] [--curve FILE] [--vtk DIR] [--frame-every 200]
//! ```

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{ensure, Context};
use arachis_core::prelude::*;
use arachis_core::scenario::pull_off::{self, PullOff};
use arachis_core::units::LENGTH_M_TO_MM;
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;

use crate::io::write_atomic;
use crate::rigs::pull_off::{PullOffArenas, MAX_PULL_SPEED_M_S};
use crate::vtk::{write_series, ParticleFrame};

/// Steps between VTK frames by default with `--vtk` (the default run breaks after about
/// 4 200 steps: about 20 frames).
const DEFAULT_FRAME_EVERY: u64 = 200;
/// Default step budget: 50 ms of pulling at dt 5e-7 s (25 mm at 0.5 m/s, far beyond any
/// junction stretch).
const DEFAULT_MAX_STEPS: u64 = 100_000;
/// Steps between progress-bar updates.
const PROGRESS_EVERY_STEPS: u64 = 500;

/// Arguments of `arachis pulloff` (SI units). Defaults are those of the core scenario.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Gripper speed, m/s.
    #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
    pub speed: f64,
    /// Pull direction from the stalk axis, degrees (0 = axial, like a texture analyser).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub angle: f64,
    /// Spheres in the stalk (the first is clamped).
    #[arg(long, default_value_t = 8, allow_hyphen_values = true)]
    pub stalk_spheres: u32,
    /// Junction normal stiffness per unit area, N/m³ (default E/L of the scenario).
    #[arg(long, allow_hyphen_values = true)]
    pub kn: Option<f64>,
    /// Junction tangential stiffness per unit area, N/m³.
    #[arg(long, allow_hyphen_values = true)]
    pub kt: Option<f64>,
    /// Junction normal critical stress, Pa.
    #[arg(long, allow_hyphen_values = true)]
    pub sigma_c: Option<f64>,
    /// Junction tangential critical stress, Pa.
    #[arg(long, allow_hyphen_values = true)]
    pub tau_c: Option<f64>,
    /// Junction bond radius, m.
    #[arg(long, allow_hyphen_values = true)]
    pub bond_radius: Option<f64>,
    /// Largest number of steps before giving up (the junction held).
    #[arg(long, default_value_t = DEFAULT_MAX_STEPS, allow_hyphen_values = true)]
    pub max_steps: u64,
    /// Step in the f64 reference arithmetic instead of Q32.32 fixed point.
    #[arg(long)]
    pub f64: bool,
    /// Write the force–displacement curve (CSV: displacement_m,force_n) to FILE.
    #[arg(long, value_name = "FILE")]
    pub curve: Option<PathBuf>,
    /// Write VTK frames (`frame_NNNNNN.vtk` plus `particles.pvd`) into DIR.
    #[arg(long, value_name = "DIR")]
    pub vtk: Option<PathBuf>,
    /// Steps between VTK frames (the initial and the final state are always written).
    #[arg(long, default_value_t = DEFAULT_FRAME_EVERY, allow_hyphen_values = true)]
    pub frame_every: u64,
}

/// The JSON line printed by `arachis pulloff` (SI units).
#[derive(Debug, Serialize)]
struct Report {
    detachment_force_n: f64,
    detachment_displacement_m: f64,
    detached: bool,
    break_time_s: Option<f64>,
    predicted_axial_detachment_n: f64,
    stalk_broke_first: bool,
    steps: u64,
    wall_seconds: f64,
    digest: String,
    scalar: &'static str,
    dt_s: f64,
}

/// Runs `arachis pulloff`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let scenario = scenario(&args)?;
    let (report, curve, frames) = if args.f64 {
        pull::<f64>(&args, &scenario)?
    } else {
        pull::<Fx>(&args, &scenario)?
    };
    if let Some(path) = &args.curve {
        write_atomic(path, |w| {
            let mut csv = csv::Writer::from_writer(w);
            csv.write_record(["displacement_m", "force_n"])?;
            for (d, f) in &curve {
                csv.write_record([d.to_string(), f.to_string()])?;
            }
            csv.flush()?;
            Ok(())
        })
        .with_context(|| format!("cannot write the curve {}", path.display()))?;
    }
    if let Some(dir) = &args.vtk {
        write_series(dir, &frames)?;
    }
    println!("{}", serde_json::to_string(&report)?);
    Ok(())
}

/// Refuses a `--speed` (m/s) that is not positive or an `--angle` (degrees) beyond ±90.
pub fn check_pull(speed_m_s: f64, angle_deg: f64) -> anyhow::Result<()> {
    ensure!(
        speed_m_s.is_finite() && speed_m_s > 0.0,
        "--speed must be a positive number of m/s, got {speed_m_s}"
    );
    ensure!(
        speed_m_s <= MAX_PULL_SPEED_M_S,
        "--speed {speed_m_s} m/s is beyond the rig's {} m/s: the pull would no longer be \
         quasi-static (rigs::pull_off::MAX_PULL_SPEED_M_S says why)",
        MAX_PULL_SPEED_M_S
    );
    ensure!(
        angle_deg.is_finite() && angle_deg.abs() <= 90.0,
        "--angle must be between -90 and 90 degrees, got {angle_deg}"
    );
    Ok(())
}

/// The scenario the arguments describe; bad numbers are refused here with the flag's name.
fn scenario(args: &Args) -> anyhow::Result<PullOff> {
    check_pull(args.speed, args.angle)?;
    ensure!(
        args.stalk_spheres >= 2,
        "--stalk-spheres must be at least 2 (one clamped, one free), got {}",
        args.stalk_spheres
    );
    ensure!(
        args.stalk_spheres <= crate::study::pull_off::MAX_STALK_SPHERES,
        "--stalk-spheres is {}; at most {} are accepted (the pull-off rig's limit, \
         study::pull_off::MAX_STALK_SPHERES)",
        args.stalk_spheres,
        crate::study::pull_off::MAX_STALK_SPHERES
    );
    ensure!(args.max_steps >= 1, "--max-steps must be at least 1");
    if args.vtk.is_some() {
        ensure!(args.frame_every >= 1, "--frame-every must be at least 1");
    }
    let mut s = PullOff {
        stalk_spheres: args.stalk_spheres,
        pull_speed_m_s: args.speed,
        pull_angle_deg: args.angle,
        ..PullOff::default()
    };
    let positive = |v: Option<f64>, flag: &str, into: &mut f64| -> anyhow::Result<()> {
        if let Some(x) = v {
            ensure!(x.is_finite() && x > 0.0, "{flag} must be > 0, got {x}");
            *into = x;
        }
        Ok(())
    };
    positive(args.kn, "--kn", &mut s.junction.normal_stiffness_n_m3)?;
    positive(args.kt, "--kt", &mut s.junction.tangential_stiffness_n_m3)?;
    positive(
        args.sigma_c,
        "--sigma-c",
        &mut s.junction.normal_strength_pa,
    )?;
    positive(
        args.tau_c,
        "--tau-c",
        &mut s.junction.tangential_strength_pa,
    )?;
    positive(args.bond_radius, "--bond-radius", &mut s.junction.radius_m)?;
    Ok(s)
}

type Outcome = (Report, Vec<(f64, f64)>, Vec<ParticleFrame>);

fn pull<S: Scalar>(args: &Args, scenario: &PullOff) -> anyhow::Result<Outcome> {
    let mut a = PullOffArenas::<S>::new(scenario);
    let started = Instant::now();
    let mut world = a
        .world(scenario)
        .context("cannot set up the pull-off test")?;
    let bar = ProgressBar::new(args.max_steps);
    if let Ok(style) = ProgressStyle::with_template("pulloff {bar:40} {pos}/{len} steps  {msg}") {
        bar.set_style(style);
    }
    let mut curve = Vec::new();
    let mut frames = Vec::new();
    let frame_every = args.frame_every.max(1);
    if args.vtk.is_some() {
        frames.push(ParticleFrame::from_world(&world));
    }
    // Run in chunks so the bar moves and frames are taken; the scenario stops at the break.
    let mut result = None;
    let mut done = 0;
    while done < args.max_steps {
        let chunk = PROGRESS_EVERY_STEPS
            .min(frame_every)
            .min(args.max_steps - done);
        let r = scenario
            .run(&mut world, chunk, |d, f| {
                curve.push((d / LENGTH_M_TO_MM, f))
            })
            .context("the pull-off run failed")?;
        done = world.step_count();
        bar.set_position(done);
        let last = r.break_step.is_some() || done == args.max_steps;
        if args.vtk.is_some() && (done % frame_every == 0 || last) {
            frames.push(ParticleFrame::from_world(&world));
        }
        let finished = r.break_step.is_some();
        result = Some(match result {
            None => r,
            Some(prev) => merge(prev, r),
        });
        if finished {
            break;
        }
    }
    let wall_seconds = started.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let r = result.context("no step was run")?;
    let report = Report {
        detachment_force_n: r.detachment_force_n,
        detachment_displacement_m: r.detachment_displacement_mm / LENGTH_M_TO_MM,
        detached: r.break_step.is_some(),
        break_time_s: r.break_step.map(|s| s as f64 * pull_off::TIMESTEP_S),
        predicted_axial_detachment_n: scenario.predicted_axial_detachment_n(),
        stalk_broke_first: r.stalk_broke_first,
        steps: world.step_count(),
        wall_seconds,
        digest: format!("{:016x}", world.digest()),
        scalar: S::NAME,
        dt_s: pull_off::TIMESTEP_S,
    };
    Ok((report, curve, frames))
}

/// Combine the results of two consecutive run chunks.
fn merge(a: pull_off::PullOffResult, b: pull_off::PullOffResult) -> pull_off::PullOffResult {
    let (peak, disp) = if b.detachment_force_n > a.detachment_force_n {
        (b.detachment_force_n, b.detachment_displacement_mm)
    } else {
        (a.detachment_force_n, a.detachment_displacement_mm)
    };
    pull_off::PullOffResult {
        detachment_force_n: peak,
        detachment_displacement_mm: disp,
        break_step: b.break_step,
        stalk_broke_first: a.stalk_broke_first || b.stalk_broke_first,
    }
}
