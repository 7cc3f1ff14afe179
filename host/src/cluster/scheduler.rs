//! The Slurm commands the cluster executor uses, and nothing else of Slurm: `sbatch` to
//! submit a job array, `squeue` to see which of its tasks are still queued or running.
//! Accounting (`sacct`) is not needed: a task that left the queue either stored its run in
//! the cache or failed, and the cache says which.
//!
//! ```no_run
//! use arachis::cluster::scheduler::{queued_tasks, Submission};
//! let tasks = queued_tasks("arachis-")?;
//! println!("{} tasks of Arachis in the queue", tasks.len());
//! # Ok::<(), String>(())
//! ```

use std::path::Path;
use std::process::Command;

/// A job array to submit.
#[derive(Debug, Clone, PartialEq)]
pub struct Submission<'a> {
    /// The job name (`--job-name`): how a restarted driver finds the array in the queue.
    pub name: &'a str,
    /// The batch script each task runs.
    pub script: &'a Path,
    /// Array tasks 0..count.
    pub count: usize,
    /// Where each task writes its output; `%a` is the task index.
    pub log_pattern: &'a Path,
    /// `--partition`, when set.
    pub partition: Option<&'a str>,
    /// `--account`, when set.
    pub account: Option<&'a str>,
    /// `--time`, minutes per task.
    pub time_limit_min: u32,
    /// `--cpus-per-task`.
    pub cpus_per_task: u32,
    /// Further `sbatch` arguments, passed as they are.
    pub extra: &'a [String],
}

impl Submission<'_> {
    /// The `sbatch` arguments.
    pub fn arguments(&self) -> Vec<String> {
        let mut args = vec![
            "--parsable".to_owned(),
            format!("--job-name={}", self.name),
            format!("--array=0-{}", self.count.saturating_sub(1)),
            format!("--output={}", self.log_pattern.display()),
            format!("--time={}", self.time_limit_min),
            format!("--cpus-per-task={}", self.cpus_per_task),
        ];
        args.extend(self.partition.map(|p| format!("--partition={p}")));
        args.extend(self.account.map(|a| format!("--account={a}")));
        args.extend(self.extra.iter().cloned());
        args.push(self.script.display().to_string());
        args
    }

    /// Submits the array; returns its job id.
    pub fn submit(&self) -> Result<u64, String> {
        let out = run("sbatch", &self.arguments())?;
        // `--parsable` prints "jobid" or "jobid;cluster".
        let id = out.trim().split(';').next().unwrap_or("");
        id.parse()
            .map_err(|_| format!("sbatch printed '{}', not a job id", out.trim()))
    }
}

/// One array task in the queue (pending or running).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct QueuedTask {
    /// The array's job name.
    pub name: String,
    /// The array's job id.
    pub job: u64,
    /// The task index.
    pub index: usize,
}

/// Every queued or running array task whose job name starts with `prefix`.
pub fn queued_tasks(prefix: &str) -> Result<Vec<QueuedTask>, String> {
    let args = ["-h", "-r", "-o", "%F %K %j"].map(str::to_owned);
    let out = run("squeue", &args)?;
    Ok(parse_queue(&out, prefix))
}

/// The lines `squeue -h -r -o "%F %K %j"` prints, those named `prefix…` kept. A job that is
/// not an array prints `N/A` as its index and is skipped.
fn parse_queue(text: &str, prefix: &str) -> Vec<QueuedTask> {
    text.lines()
        .filter_map(|line| {
            let mut f = line.split_whitespace();
            let (job, index, name) = (f.next()?, f.next()?, f.next()?);
            Some(QueuedTask {
                name: name.starts_with(prefix).then(|| name.to_owned())?,
                job: job.parse().ok()?,
                index: index.parse().ok()?,
            })
        })
        .collect()
}

/// Runs a Slurm client command and returns its standard output, or why it failed.
fn run(program: &str, args: &[String]) -> Result<String, String> {
    let out = Command::new(program).args(args).output().map_err(|e| {
        format!(
            "cannot run {program} ({e}): is this a Slurm login node? (scripts/slurm-local.sh \
             starts a one-node cluster for testing)"
        )
    })?;
    if !out.status.success() {
        return Err(format!(
            "{program} {} failed ({}): {}",
            args.join(" "),
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_queue_is_read_per_task_and_other_jobs_are_left_out() {
        let text = "12 0 arachis-ab-a0001\n12 3 arachis-ab-a0001\n13 N/A other\n14 1 other\n";
        let tasks = parse_queue(text, "arachis-ab-");
        assert_eq!(
            tasks,
            vec![
                QueuedTask {
                    name: "arachis-ab-a0001".into(),
                    job: 12,
                    index: 0
                },
                QueuedTask {
                    name: "arachis-ab-a0001".into(),
                    job: 12,
                    index: 3
                },
            ]
        );
    }

    #[test]
    fn the_array_arguments_carry_every_setting() {
        let extra = ["--qos=short".to_owned()];
        let s = Submission {
            name: "arachis-ab-a0002",
            script: Path::new("/c/slurm/a0002.sh"),
            count: 3,
            log_pattern: Path::new("/c/slurm/logs/a0002_%a.log"),
            partition: Some("long"),
            account: Some("agri"),
            time_limit_min: 25,
            cpus_per_task: 2,
            extra: &extra,
        };
        assert_eq!(
            s.arguments().join(" "),
            "--parsable --job-name=arachis-ab-a0002 --array=0-2 \
             --output=/c/slurm/logs/a0002_%a.log --time=25 --cpus-per-task=2 \
             --partition=long --account=agri --qos=short /c/slurm/a0002.sh"
        );
    }
}
