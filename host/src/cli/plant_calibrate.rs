//! `arachis plant-calibrate`: seed 001's calibration of the pod–stalk junction bond on the
//! virtual tensile test (`crate::plant_calibration`), with a progress bar per stage.
//!
//! Writes `OUT/plant-calibration.json` and `OUT/report.md` atomically and prints one JSON
//! line: `{"validated_n":…,"target_n":…,"relative_error_pct":…,"passed":…,"runs":…,
//! "wall_seconds":…,"carried":[…]}`. Exit status 2 when the validation misses 5 %.
//!
//! ```text
//! arachis plant-calibrate --out DIR [--target 7.18] [--speed 0.1] [--angle 0]
//!                         [--carry x7,x8] [--jobs N] [--quiet]
//! ```

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, ensure, Context};
use arachis_core::scenario::PullOff;
use serde_json::json;

use crate::calibrate::Progress;
use crate::plant_calibration::{calibrate, report, PullOffSimulator, TARGET_DETACHMENT_N};

/// Arguments of `arachis plant-calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Target detachment force, N (seed 001 Table 8 implies 7.18).
    #[arg(long, default_value_t = TARGET_DETACHMENT_N, allow_hyphen_values = true)]
    pub target: f64,
    /// Gripper speed, m/s.
    #[arg(long, default_value_t = 0.1, allow_hyphen_values = true)]
    pub speed: f64,
    /// Pull direction from the stalk axis, degrees (0 = axial, the texture analyser).
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    pub angle: f64,
    /// Carry these factors (comma-separated, e.g. `x7,x8` as seed 001 did) to the path and
    /// the response surface instead of the screening's choice.
    #[arg(long, value_delimiter = ',')]
    pub carry: Option<Vec<String>>,
    /// Worker threads (default: every core).
    #[arg(long)]
    pub jobs: Option<usize>,
    /// No progress bars.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `arachis plant-calibrate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    super::pulloff::check_pull(args.speed, args.angle)?;
    ensure!(args.jobs != Some(0), "--jobs must be at least 1");
    let sim = PullOffSimulator {
        base: PullOff {
            pull_speed_m_s: args.speed,
            pull_angle_deg: args.angle,
            ..PullOff::default()
        },
    };
    let progress = Progress::new(args.quiet);
    let mut pool = rayon::ThreadPoolBuilder::new();
    if let Some(j) = args.jobs {
        pool = pool.num_threads(j);
    }
    let pool = pool.build().context("cannot start the worker threads")?;
    let started = Instant::now();
    let cal = pool.install(|| calibrate(&sim, args.target, args.carry.as_deref(), &progress))?;
    let wall = started.elapsed().as_secs_f64();
    report::write_all(&cal, wall, &args.out)
        .with_context(|| format!("cannot write the report into {}", args.out.display()))?;
    let o = &cal.optimum;
    println!(
        "{}",
        json!({
            "validated_n": o.validated_n,
            "target_n": cal.target_n,
            "relative_error_pct": o.relative_error_pct,
            "passed": o.passed,
            "runs": cal.runs,
            "wall_seconds": wall,
            "carried": cal.screening.carried,
        })
    );
    if !o.passed {
        bail!(
            "validation missed: {:.4} N is {:.2} % from the target {} N",
            o.validated_n,
            o.relative_error_pct,
            cal.target_n
        );
    }
    Ok(())
}
