//! The Slurm executor: a stage's runs that are not in the run cache become one job array,
//! one task per run, each task `arachis run tasks/<hash>.json --cache runs/`. The driver
//! polls the queue until none of its tasks is left, resubmits the runs that left the queue
//! without a stored result (up to the retry count), and returns when every run is stored;
//! the stage then replays them from the cache, exactly as a resumed local calibration does.
//!
//! What it guarantees:
//! - **Same bytes.** Results come only from the cache, which stores the worker's responses
//!   as the local executor would; where a run executed cannot change a number.
//! - **A restarted driver submits nothing twice.** Before it submits, it asks the queue for
//!   the campaign's tasks (by job name, [`super::ledger`]) and waits for those instead.
//! - **Failures are named.** A run that failed more often than the retries allow stops the
//!   campaign with its stage, run, spec hash and the log of its last attempt.
//! - **No torn result is read.** The worker writes a run by renaming a complete temporary
//!   file, and a run is read only when it parses and its specification is the one asked
//!   for ([`crate::calibration::run_cache`]), also over a network file system.
//!
//! ```no_run
//! use arachis::cluster::{ClusterArgs, RigRecipe, Simulator, SlurmExecutor};
//! let recipe = RigRecipe::new("study.toml".as_ref(), Simulator::Dem, None)?;
//! let slurm = SlurmExecutor::new(recipe, &ClusterArgs::default(),
//!                                "calibration-out/slurm".as_ref(), false)?;
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use indicatif::ProgressBar;

use super::ledger::{attempts, ArrayRecord, Ledger};
use super::recipe::RigRecipe;
use super::scheduler::{queued_tasks, Submission};
use super::settings::{ClusterArgs, ExecutorKind, DEFAULT_TIME_PER_RUN_MIN};
use super::task::RunTask;
use crate::calibration::run_cache::RunCache;
use crate::calibration::{CalibrateError, Executor, Remote, RemoteRun};

/// Runs a campaign's stages on Slurm (module docs).
pub struct SlurmExecutor {
    recipe: RigRecipe,
    settings: ClusterArgs,
    ledger: Ledger,
    /// The program each task runs (this very binary; on a cluster it must lie on a file
    /// system the nodes see).
    program: PathBuf,
    quiet: bool,
}

impl SlurmExecutor {
    /// An executor that builds its rigs by `recipe`, submits as `settings` say and keeps
    /// its records in `dir`; `quiet` silences the notes on stderr.
    pub fn new(
        recipe: RigRecipe,
        settings: &ClusterArgs,
        dir: &Path,
        quiet: bool,
    ) -> anyhow::Result<Self> {
        Ok(Self {
            recipe,
            settings: settings.clone(),
            ledger: Ledger::open(dir)?,
            program: std::env::current_exe()?,
            quiet,
        })
    }

    /// This executor with `program` as the worker each task runs (library use, where this
    /// process is not `arachis`).
    pub fn with_program(mut self, program: PathBuf) -> Self {
        self.program = program;
        self
    }

    /// The batch script of an array: task i runs the i-th of `hashes`.
    fn script(&self, hashes: &[String], cache: &RunCache) -> String {
        let quote = |p: &Path| format!("'{}'", p.display().to_string().replace('\'', r"'\''"));
        format!(
            "#!/bin/sh\n\
             # Written by arachis: task i of this array runs the i-th run below.\n\
             set -eu\n\
             set -- {hashes}\n\
             shift \"$SLURM_ARRAY_TASK_ID\"\n\
             exec {program} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\" {extreme}run \
             {tasks}/\"$1\".json --cache {cache}\n",
            hashes = hashes.join(" "),
            program = quote(&self.program),
            extreme = if self.recipe.allow_extreme {
                "--allow-extreme "
            } else {
                ""
            },
            tasks = quote(&self.ledger.dir().join("tasks")),
            cache = quote(&std::path::absolute(cache.dir()).unwrap_or(cache.dir().into())),
        )
    }

    /// Submits one array of `hashes`.
    fn submit(&self, hashes: Vec<String>, cache: &RunCache, stage: &str) -> anyhow::Result<()> {
        let count = hashes.len();
        let script = self.script(&hashes, cache);
        let mut record = self.ledger.begin(hashes)?;
        let script_path = self.ledger.script_path(&record.tag);
        crate::io::write_string_atomic(&script_path, &script)?;
        let log = self.ledger.log_path(&record.tag, None);
        let extra = self.settings.extra_sbatch_args();
        let job = Submission {
            name: &record.name,
            script: &script_path,
            count,
            log_pattern: &log,
            partition: self.settings.partition.as_deref(),
            account: self.settings.account.as_deref(),
            time_limit_min: self.time_limit_min(),
            cpus_per_task: self.settings.cpus_per_run,
            extra: &extra,
        }
        .submit()
        .map_err(anyhow::Error::msg)?;
        record.job = Some(job);
        self.ledger.write(&record)?;
        if !self.quiet {
            eprintln!(
                "{stage}: submitted Slurm array job {job} ({count} runs); logs in {}",
                self.ledger.dir().join("logs").display()
            );
        }
        Ok(())
    }

    /// The time limit of each task, minutes: `--time-per-run` when given; else
    /// [`TIME_MARGIN`] times the longest run this campaign has measured so far (the
    /// workers' logs), at least [`MIN_TIME_PER_RUN_MIN`]; else, before any run has finished,
    /// [`DEFAULT_TIME_PER_RUN_MIN`].
    fn time_limit_min(&self) -> u32 {
        if let Some(t) = self.settings.time_per_run {
            return t;
        }
        let longest = longest_run_s(&self.ledger.dir().join("logs"));
        longest.map_or(DEFAULT_TIME_PER_RUN_MIN, |s| {
            ((s * TIME_MARGIN / 60.0).ceil() as u32).max(MIN_TIME_PER_RUN_MIN)
        })
    }

    /// The spec hashes of this campaign's tasks (the arrays `arrays`) still in the queue.
    fn in_flight(&self, arrays: &[ArrayRecord]) -> anyhow::Result<BTreeSet<String>> {
        let queued = queued_tasks(&self.ledger.job_prefix()).map_err(anyhow::Error::msg)?;
        Ok(queued
            .iter()
            .filter_map(|q| {
                let a = arrays.iter().find(|a| a.name == q.name)?;
                a.hashes.get(q.index).cloned()
            })
            .collect())
    }
}

/// `executor` with its missing runs sent to Slurm when `settings` choose it (records in
/// `records`, rigs rebuilt by `recipe`), else `executor` as it is.
pub fn on_cluster_if_chosen(
    executor: Executor,
    settings: &ClusterArgs,
    recipe: impl FnOnce() -> anyhow::Result<RigRecipe>,
    records: &Path,
    quiet: bool,
) -> anyhow::Result<Executor> {
    Ok(match settings.executor {
        ExecutorKind::Local => executor,
        ExecutorKind::Slurm => {
            let slurm = SlurmExecutor::new(recipe()?, settings, records, quiet)?;
            executor.with_remote(Box::new(slurm))?
        }
    })
}

/// A measured run's time limit is this many times its wall time: runs of one campaign
/// differ in their settling time, and a killed run costs a whole retry.
pub const TIME_MARGIN: f64 = 3.0;
/// The shortest time limit a measured campaign gets, minutes (a task's start-up and a
/// loaded node's slowness must fit too).
pub const MIN_TIME_PER_RUN_MIN: u32 = 5;

/// The longest wall time, s, of the runs the workers whose logs are in `logs` simulated
/// (the JSON line `arachis run` prints; runs found already stored do not count).
fn longest_run_s(logs: &Path) -> Option<f64> {
    let entries = std::fs::read_dir(logs).ok()?;
    entries
        .filter_map(|e| std::fs::read_to_string(e.ok()?.path()).ok())
        .flat_map(|text| {
            text.lines()
                .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
                .filter(|v| v["already_stored"] == false)
                .filter_map(|v| v["wall_seconds"].as_f64())
                .collect::<Vec<_>>()
        })
        .reduce(f64::max)
}

/// The last non-empty line of a log, for the message that names it.
fn last_line(path: &Path) -> String {
    std::fs::read_to_string(path)
        .ok()
        .and_then(|t| {
            t.lines()
                .rev()
                .find(|l| !l.trim().is_empty())
                .map(str::to_owned)
        })
        .unwrap_or_else(|| "(the log is empty or missing)".to_owned())
}

impl Remote for SlurmExecutor {
    fn run_all(
        &self,
        runs: &[RemoteRun<'_>],
        cache: &RunCache,
        bar: &ProgressBar,
    ) -> Result<(), CalibrateError> {
        let io = |e: anyhow::Error| CalibrateError::Io {
            path: self.ledger.dir().to_owned(),
            reason: format!("{e:#}"),
        };
        for r in runs {
            let task = RunTask::new(&self.recipe, r);
            task.write(&self.ledger.task_path(&task.spec_hash))
                .map_err(io)?;
        }
        let start = bar.position();
        // A run once found stored stays stored: only the others are looked up again.
        let mut pending: Vec<&RemoteRun<'_>> = runs.iter().collect();
        loop {
            pending.retain(|r| {
                cache
                    .load(r.spec, r.spec_hash, r.rig_id, r.quantity)
                    .is_none()
            });
            bar.set_position(start + (runs.len() - pending.len()) as u64);
            let Some(stage) = pending.first().map(|r| r.stage) else {
                return Ok(());
            };
            let arrays = self.ledger.arrays().map_err(io)?;
            let flying = self.in_flight(&arrays).map_err(io)?;
            let mut submit = Vec::new();
            for r in &pending {
                let hash = r.spec_hash.to_string();
                if flying.contains(&hash) {
                    continue;
                }
                // Looked up again after the queue was read: a task that stored its run and
                // left the queue between the lookup above and `squeue` is neither stored
                // there nor in flight here, and would run twice. A worker stores before its
                // task ends, so a run whose task has left the queue is stored by now (a CI
                // run caught a task finishing in that window, and its run twice).
                if cache
                    .load(r.spec, r.spec_hash, r.rig_id, r.quantity)
                    .is_some()
                {
                    continue;
                }
                let (tries, log) = attempts(&arrays, &self.ledger, &hash);
                if tries > self.settings.retries as usize {
                    let log = log.unwrap_or_default();
                    return Err(CalibrateError::Simulation {
                        stage: r.stage,
                        run: r.run,
                        hash,
                        reason: format!(
                            "failed on the cluster {tries} times (--retries {}); the log of \
                             its last attempt, {}, ends: {}",
                            self.settings.retries,
                            log.display(),
                            last_line(&log)
                        ),
                    });
                }
                submit.push(hash);
            }
            if submit.is_empty() {
                std::thread::sleep(self.settings.poll());
            } else {
                self.submit(submit, cache, stage).map_err(io)?;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_simulated_run_is_read_from_the_workers_logs() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(longest_run_s(dir.path()), None);
        let line = |s: f64, stored: bool| {
            format!("{{\"spec_hash\":\"ab\",\"already_stored\":{stored},\"wall_seconds\":{s}}}\n")
        };
        std::fs::write(dir.path().join("a0001_0.log"), line(120.5, false)).unwrap();
        let other = format!("starting\n{}", line(999.0, true));
        std::fs::write(dir.path().join("a0001_1.log"), other).unwrap();
        std::fs::write(dir.path().join("a0001_2.log"), line(300.0, false)).unwrap();
        std::fs::write(dir.path().join("a0001_3.log"), "error: killed\n").unwrap();
        assert_eq!(longest_run_s(dir.path()), Some(300.0));
    }
}
