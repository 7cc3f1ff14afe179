//! The record of a campaign's Slurm submissions, kept beside its run cache in `slurm/`:
//!
//! - `tasks/<spec hash>.json`: each run's task file ([`super::RunTask`]);
//! - `arrays/<tag>.json`: one file per submitted array, its job name, the spec hashes of
//!   its tasks in index order and, once `sbatch` answered, its job id;
//! - `arrays/<tag>.sh`: the array's batch script; `logs/<tag>_<index>.log`: each task's
//!   output.
//!
//! An array's record is written (atomically) *before* `sbatch` is called, then again with
//! the job id. A driver killed in between leaves a record without a job id; the array is
//! still found in the queue by its job name, which is unique to the campaign and the tag,
//! so no run is submitted twice. A run's attempts are the arrays that listed it.
//!
//! ```no_run
//! use arachis::cluster::ledger::Ledger;
//! let ledger = Ledger::open("calibration-out/slurm".as_ref())?;
//! for array in ledger.arrays()? {
//!     println!("{} job {:?}: {} runs", array.name, array.job, array.hashes.len());
//! }
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::path::{Path, PathBuf};

use anyhow::Context;
use serde::{Deserialize, Serialize};

use crate::calibration::spec_hash::fnv1a_64;

/// Prefix of every job name Arachis gives an array.
pub const JOB_PREFIX: &str = "arachis-";

/// One submitted array.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArrayRecord {
    /// Its tag, `a0001`, `a0002`, … in submission order.
    pub tag: String,
    /// Its job name.
    pub name: String,
    /// The spec hash of each task, by task index.
    pub hashes: Vec<String>,
    /// The job id `sbatch` gave it (`None`: submitted or about to be, id not yet known).
    pub job: Option<u64>,
}

/// The folder of records (module docs).
#[derive(Debug, Clone)]
pub struct Ledger {
    dir: PathBuf,
    campaign: String,
}

impl Ledger {
    /// Opens (creating) the record folder `dir`.
    pub fn open(dir: &Path) -> anyhow::Result<Self> {
        for sub in ["tasks", "arrays", "logs"] {
            let d = dir.join(sub);
            std::fs::create_dir_all(&d)
                .with_context(|| format!("cannot create {}", d.display()))?;
        }
        let dir = std::path::absolute(dir)?;
        // Job names are unique per campaign folder, so two campaigns never adopt each
        // other's arrays from the queue.
        let campaign = format!("{:08x}", fnv1a_64(dir.to_string_lossy().as_bytes()) as u32);
        Ok(Self { dir, campaign })
    }

    /// The folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The prefix of this campaign's job names.
    pub fn job_prefix(&self) -> String {
        format!("{JOB_PREFIX}{}-", self.campaign)
    }

    /// The task file of a run.
    pub fn task_path(&self, hash: &str) -> PathBuf {
        self.dir.join("tasks").join(format!("{hash}.json"))
    }

    /// The batch script of array `tag`.
    pub fn script_path(&self, tag: &str) -> PathBuf {
        self.dir.join("arrays").join(format!("{tag}.sh"))
    }

    /// The log of task `index` of array `tag` (`None`: the `%a` pattern `sbatch` fills).
    pub fn log_path(&self, tag: &str, index: Option<usize>) -> PathBuf {
        let index = index.map_or("%a".to_owned(), |i| i.to_string());
        self.dir.join("logs").join(format!("{tag}_{index}.log"))
    }

    /// Every array submitted so far, in submission order.
    pub fn arrays(&self) -> anyhow::Result<Vec<ArrayRecord>> {
        let dir = self.dir.join("arrays");
        let mut out = Vec::new();
        for entry in std::fs::read_dir(&dir).with_context(|| format!("{}", dir.display()))? {
            let path = entry?.path();
            if path.extension().and_then(|e| e.to_str()) != Some("json") {
                continue;
            }
            let text = crate::io::text::read_text(&path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            out.push(
                serde_json::from_str::<ArrayRecord>(&text)
                    .with_context(|| format!("{}: not an array record", path.display()))?,
            );
        }
        out.sort_by(|a, b| a.tag.cmp(&b.tag));
        Ok(out)
    }

    /// A new record for an array of `hashes`, written before it is submitted.
    pub fn begin(&self, hashes: Vec<String>) -> anyhow::Result<ArrayRecord> {
        let next = self.arrays()?.len() + 1;
        let tag = format!("a{next:04}");
        let record = ArrayRecord {
            name: format!("{}{tag}", self.job_prefix()),
            tag,
            hashes,
            job: None,
        };
        self.write(&record)?;
        Ok(record)
    }

    /// Writes `record` (atomically).
    pub fn write(&self, record: &ArrayRecord) -> anyhow::Result<()> {
        let path = self.dir.join("arrays").join(format!("{}.json", record.tag));
        let text = serde_json::to_string_pretty(record).expect("a record serialises");
        crate::io::write_string_atomic(&path, &(text + "\n"))
    }
}

/// How many arrays listed `hash`, and the log of its last task.
pub fn attempts(arrays: &[ArrayRecord], ledger: &Ledger, hash: &str) -> (usize, Option<PathBuf>) {
    let mut count = 0;
    let mut last = None;
    for a in arrays {
        if let Some(i) = a.hashes.iter().position(|h| h == hash) {
            count += 1;
            last = Some(ledger.log_path(&a.tag, Some(i)));
        }
    }
    (count, last)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrays_are_tagged_in_order_and_attempts_counted_per_run() {
        let dir = tempfile::tempdir().unwrap();
        let ledger = Ledger::open(dir.path()).unwrap();
        let mut first = ledger.begin(vec!["aa".into(), "bb".into()]).unwrap();
        first.job = Some(41);
        ledger.write(&first).unwrap();
        let second = ledger.begin(vec!["bb".into()]).unwrap();
        assert_eq!(
            (first.tag.as_str(), second.tag.as_str()),
            ("a0001", "a0002")
        );
        assert!(second.name.starts_with(&ledger.job_prefix()));
        let arrays = ledger.arrays().unwrap();
        assert_eq!(arrays, vec![first, second]);
        let (n, log) = attempts(&arrays, &ledger, "bb");
        assert_eq!(n, 2);
        assert_eq!(log.unwrap(), ledger.log_path("a0002", Some(0)));
        assert_eq!(attempts(&arrays, &ledger, "cc").0, 0);
    }

    #[test]
    fn two_campaign_folders_get_different_job_names() {
        let a = tempfile::tempdir().unwrap();
        let b = tempfile::tempdir().unwrap();
        let (la, lb) = (
            Ledger::open(a.path()).unwrap(),
            Ledger::open(b.path()).unwrap(),
        );
        assert_ne!(la.job_prefix(), lb.job_prefix());
    }
}
