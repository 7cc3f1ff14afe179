//! The cluster settings of a campaign command (`calibrate`, `plant-calibrate`): which
//! executor runs the simulations, and for Slurm the partition, account, time limit per run,
//! CPUs per run, extra `sbatch` arguments, retries and how often the queue is polled.
//!
//! ```
//! use arachis::cluster::{ClusterArgs, ExecutorKind};
//! let local = ClusterArgs::default();
//! assert_eq!(local.executor, ExecutorKind::Local);
//! ```

use std::time::Duration;

use crate::count_limits::count;

/// Where a campaign's runs execute.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ExecutorKind {
    /// This machine's cores (`--jobs` runs at once).
    #[default]
    Local,
    /// A Slurm cluster: each stage's missing runs become one job array.
    Slurm,
}

/// Time limit of a run when neither the command line nor the rig says, minutes.
pub const DEFAULT_TIME_PER_RUN_MIN: u32 = 60;
/// The longest time limit accepted, minutes (a week).
const MAX_TIME_PER_RUN_MIN: u64 = 7 * 24 * 60;
/// Failed runs are submitted again this many times by default.
pub const DEFAULT_RETRIES: u32 = 2;
/// Seconds between two looks at the queue by default.
pub const DEFAULT_POLL_S: u64 = 10;

/// The cluster flags (module docs).
#[derive(Debug, Clone, PartialEq, Eq, clap::Args)]
pub struct ClusterArgs {
    /// Where the simulations run: `local` (this machine) or `slurm` (one job array per
    /// stage; the results land in the same run cache, so the report is the same bytes).
    #[arg(long, value_enum, default_value = "local")]
    pub executor: ExecutorKind,
    /// Slurm partition (default: the cluster's default partition).
    #[arg(long)]
    pub partition: Option<String>,
    /// Slurm account to charge.
    #[arg(long)]
    pub account: Option<String>,
    /// Slurm time limit of each run, minutes (default: 3 × the longest run this campaign
    /// has measured, at least 5; 60 before its first run has finished).
    #[arg(long, value_name = "MIN", value_parser = count::<u32>(1, MAX_TIME_PER_RUN_MIN))]
    pub time_per_run: Option<u32>,
    /// CPUs of each run on the cluster (the threaded step uses them all).
    #[arg(long, default_value_t = 1, value_parser = count::<u32>(1, crate::stepping::MAX_THREADS as u64))]
    pub cpus_per_run: u32,
    /// Further `sbatch` arguments, separated by spaces (e.g. "--qos=short --mem=2G").
    #[arg(long, allow_hyphen_values = true, value_name = "ARGS")]
    pub sbatch_args: Option<String>,
    /// How many times a failed run is submitted again before the campaign stops.
    #[arg(long, default_value_t = DEFAULT_RETRIES, value_parser = count::<u32>(0, 100))]
    pub retries: u32,
    /// Seconds between two looks at the Slurm queue.
    #[arg(long, default_value_t = DEFAULT_POLL_S, value_parser = count::<u64>(1, 3600))]
    pub poll_seconds: u64,
}

impl Default for ClusterArgs {
    fn default() -> Self {
        Self {
            executor: ExecutorKind::Local,
            partition: None,
            account: None,
            time_per_run: None,
            cpus_per_run: 1,
            sbatch_args: None,
            retries: DEFAULT_RETRIES,
            poll_seconds: DEFAULT_POLL_S,
        }
    }
}

impl ClusterArgs {
    /// The extra `sbatch` arguments, one per word.
    pub fn extra_sbatch_args(&self) -> Vec<String> {
        self.sbatch_args
            .as_deref()
            .unwrap_or("")
            .split_whitespace()
            .map(str::to_owned)
            .collect()
    }

    /// The time between two looks at the queue.
    pub fn poll(&self) -> Duration {
        Duration::from_secs(self.poll_seconds)
    }
}
