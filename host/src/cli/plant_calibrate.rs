//! `arachis plant-calibrate`: an alias, for this release only, of `arachis calibrate` on
//! seed 001's pull-off study (`testdata/peanut-plant/study.toml`, built into the program),
//! with the former command's flags applied to the study. It says so on stderr, runs the
//! same engine and writes the same files as `calibrate`, then prints one JSON line:
//! `{"validated_n":…,"target_n":…,"relative_error_pct":…,"passed":…,"runs":…,
//! "carried":[…]}`. Exit status 2 when the validation misses its limit.
//!
//! ```text
//! arachis plant-calibrate --out DIR [--target 7.18] [--speed 0.1] [--angle 0]
//!                         [--carry x7,x8] [--jobs N] [--quiet]
//! ```

use std::path::PathBuf;

use anyhow::{ensure, Context};
use serde_json::json;

use super::calibrate::{calibrate_study, SimulatorChoice};
use crate::report::pull_off::JSON_FILE;
use crate::study::Study;

/// What the alias prints on stderr.
pub const ALIAS_NOTICE: &str = "note: `arachis plant-calibrate` is an alias, kept for this \
     release only, of `arachis calibrate testdata/peanut-plant/study.toml` (seed 001's \
     pull-off study, built in); use `arachis calibrate STUDY`";

/// Arguments of `arachis plant-calibrate`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Target detachment force, N (default: the study's measured 7.18 N).
    #[arg(long, allow_hyphen_values = true)]
    pub target: Option<f64>,
    /// Gripper speed, m/s (default: the study's).
    #[arg(long, allow_hyphen_values = true)]
    pub speed: Option<f64>,
    /// Pull direction from the stalk axis, degrees (default: the study's, 0 = axial).
    #[arg(long, allow_hyphen_values = true)]
    pub angle: Option<f64>,
    /// Carry these factors (comma-separated, e.g. `x8,x9`) to the path and the response
    /// surface instead of the study's (x7, x8, as seed 001 did).
    #[arg(long, value_delimiter = ',')]
    pub carry: Option<Vec<String>>,
    /// Worker threads (default: every core; at most `count_limits::MAX_JOBS`).
    #[arg(long, value_parser = crate::count_limits::count::<usize>(1, crate::count_limits::MAX_JOBS))]
    pub jobs: Option<usize>,
    /// No progress bars.
    #[arg(long)]
    pub quiet: bool,
    /// Where the simulations run (this machine or a Slurm cluster).
    #[command(flatten)]
    pub cluster: crate::cluster::ClusterArgs,
}

/// Runs `arachis plant-calibrate`.
pub fn run(args: Args) -> anyhow::Result<()> {
    eprintln!("{ALIAS_NOTICE}");
    let mut study = Study::shipped_pull_off();
    let rig = study
        .file()
        .rig
        .as_ref()
        .context("the built-in study has its [rig]")?;
    let (speed, angle) = (
        args.speed.unwrap_or(rig.pull_speed_m_s),
        args.angle.unwrap_or(rig.pull_angle_deg),
    );
    super::pulloff::check_pull(speed, angle)?;
    study.set_pull(speed, angle);
    if let Some(target) = args.target {
        ensure!(
            target.is_finite() && target > 0.0,
            "--target: the target detachment force must be a positive number of N, got \
             {target}"
        );
        study.set_target_n(target);
    }
    if let Some(carry) = args.carry.clone() {
        study
            .set_named_factors(Some(carry), "asked for on the command line (--carry)")
            .map_err(|e| anyhow::anyhow!("--carry: {e}"))?;
    }
    ensure!(args.jobs != Some(0), "--jobs must be at least 1");
    let calibrate = super::calibrate::Args {
        study: study.path().to_owned(),
        quick: false,
        full: false,
        mode: None,
        jobs: args.jobs.map(|j| u32::try_from(j).unwrap_or(u32::MAX)),
        out: Some(args.out.clone()),
        quiet: args.quiet,
        strict: true,
        simulator: SimulatorChoice::Dem,
        surrogate_delay_ms: 0,
        cluster: args.cluster.clone(),
        shipped_pull_off: Some(crate::cluster::recipe::ShippedPull {
            speed_m_s: speed,
            angle_deg: angle,
        }),
    };
    let verdict = calibrate_study(&calibrate, &study);
    let path = args.out.join(JSON_FILE);
    if !path.exists() {
        return verdict;
    }
    let written: serde_json::Value = serde_json::from_str(
        &crate::io::text::read_text(&path)
            .with_context(|| format!("cannot read back {}", path.display()))?,
    )
    .with_context(|| format!("{} is not JSON", path.display()))?;
    let o = &written["optimum"];
    println!(
        "{}",
        json!({
            "validated_n": o["validated_n"],
            "target_n": written["target_n"],
            "relative_error_pct": o["relative_error_pct"],
            "passed": o["passed"],
            "runs": written["runs"],
            "carried": written["screening"]["carried"],
        })
    );
    verdict
}
