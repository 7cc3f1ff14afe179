//! A worker task: one run of a campaign written to a file, `tasks/<spec hash>.json`, that
//! `arachis run` reads on any machine that sees the study and the run cache. It holds the
//! rig's [`RigRecipe`], the experiment and the run's values, condition and replicate, and
//! the hash of the specification the planner computed: the worker builds the rig again,
//! recomputes the specification and refuses to run when the hash differs (the study file or
//! the program changed since the campaign was planned), so a cached result always belongs
//! to the run that was asked for.
//!
//! ```no_run
//! use arachis::cluster::RunTask;
//! let task = RunTask::read("calibration-out/slurm/tasks/00d0c0ffee15bad5.json".as_ref())?;
//! println!("{} replicate {}", task.experiment, task.replicate);
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::path::Path;

use anyhow::{bail, Context};
use serde::{Deserialize, Serialize};

use super::recipe::RigRecipe;
use crate::calibration::{Condition, ParameterValues, RemoteRun};

/// Format tag of a task file.
pub const TASK_FORMAT: &str = "arachis-task-1";

/// One run for a worker (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunTask {
    /// [`TASK_FORMAT`].
    pub format: String,
    /// The hash of the run's specification, 16 hex digits (its file in the run cache).
    pub spec_hash: String,
    /// The stage and 1-based run number that asked for it (for messages).
    pub stage: String,
    /// See `stage`.
    pub run: usize,
    /// How to build the rig.
    pub recipe: RigRecipe,
    /// The study experiment whose rig runs it.
    pub experiment: String,
    /// The response the campaign reads from it.
    pub quantity: String,
    /// Every parameter the run sets (name → value in the name's unit).
    pub values: ParameterValues,
    /// The measurement's condition.
    pub condition: Condition,
    /// Replicate index.
    pub replicate: u32,
}

impl RunTask {
    /// The task of `run`, built by `recipe`.
    pub fn new(recipe: &RigRecipe, run: &RemoteRun<'_>) -> Self {
        Self {
            format: TASK_FORMAT.to_owned(),
            spec_hash: run.spec_hash.to_string(),
            stage: run.stage.to_owned(),
            run: run.run,
            recipe: recipe.clone(),
            experiment: run.experiment.to_owned(),
            quantity: run.quantity.to_owned(),
            values: run.request.values.clone(),
            condition: run.request.condition.clone(),
            replicate: run.request.replicate,
        }
    }

    /// Reads and checks a task file.
    pub fn read(path: &Path) -> anyhow::Result<Self> {
        let text = crate::io::text::read_text(path)?;
        let task: Self = serde_json::from_str(&text)
            .with_context(|| format!("{}: not a task file", path.display()))?;
        if task.format != TASK_FORMAT {
            bail!(
                "{}: format '{}', expected '{TASK_FORMAT}'",
                path.display(),
                task.format
            );
        }
        Ok(task)
    }

    /// Writes the task to `path` atomically.
    pub fn write(&self, path: &Path) -> anyhow::Result<()> {
        let text = serde_json::to_string_pretty(self).expect("a task serialises");
        crate::io::write_string_atomic(path, &(text + "\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calibration::{RunRequest, SpecHash};
    use crate::cluster::Simulator;

    #[test]
    fn a_task_reads_back_as_written_and_a_foreign_format_is_refused() {
        let values = ParameterValues::from([("pod-pod.restitution".to_owned(), 0.335)]);
        let condition = Condition::from([("lift_speed_m_s".to_owned(), 0.01)]);
        let recipe = RigRecipe {
            study: "/data/study.toml".into(),
            shipped_pull_off: None,
            harvest: None,
            simulator: Simulator::Dem,
            mode: Some("quick".into()),
            allow_extreme: false,
            surrogate_delay_ms: 0,
        };
        let run = RemoteRun {
            stage: "screening",
            run: 7,
            spec_hash: SpecHash(0x00d0_c0ff_ee15_bad5),
            spec: &serde_json::Value::Null,
            rig_id: "rig",
            experiment: "repose",
            quantity: "repose_angle",
            request: RunRequest {
                values: &values,
                condition: &condition,
                replicate: 2,
            },
        };
        let task = RunTask::new(&recipe, &run);
        assert_eq!(task.spec_hash, "00d0c0ffee15bad5");
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.json");
        task.write(&path).unwrap();
        assert_eq!(RunTask::read(&path).unwrap(), task);

        let foreign = std::fs::read_to_string(&path)
            .unwrap()
            .replace(TASK_FORMAT, "arachis-task-0");
        std::fs::write(&path, foreign).unwrap();
        let err = RunTask::read(&path).unwrap_err().to_string();
        assert!(err.contains("format 'arachis-task-0'"), "{err}");
    }
}
