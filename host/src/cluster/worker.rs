//! The worker: one task ([`RunTask`]) simulated and stored in the run cache, what every
//! Slurm array task runs (`arachis run TASK.json --cache DIR`) and useful on its own to
//! re-run a single point of a campaign.
//!
//! The worker builds the rig from the task's recipe, recomputes the run's specification and
//! refuses to run when its hash is not the task's (the study or the program changed since
//! the campaign was planned). A run already stored is not simulated again. The result is
//! stored atomically ([`RunCache::store`]), so a killed worker leaves no partial file.
//!
//! Two test hooks, read from the environment (a Slurm task inherits the submitter's), make
//! failures reproducible for the executor's tests: `ARACHIS_TEST_FAIL_RUN=<spec hash>`
//! fails that run every time; `ARACHIS_TEST_KILL_ONCE=<folder>` aborts the process (as a
//! killed worker) on the first attempt at each run, leaving a marker in the folder.
//!
//! ```no_run
//! use arachis::cluster::{worker::run_task, RunTask};
//! let task = RunTask::read("out/slurm/tasks/00d0c0ffee15bad5.json".as_ref())?;
//! let done = run_task(&task, "out/runs".as_ref())?;
//! println!("{} = {}", done.quantity, done.response);
//! # Ok::<(), anyhow::Error>(())
//! ```

use std::path::Path;
use std::time::Instant;

use anyhow::{bail, Context};
use serde::Serialize;

use super::task::RunTask;
use crate::calibration::rig::response;
use crate::calibration::run_cache::RunCache;
use crate::calibration::{RunRequest, SpecHash};

/// Environment variable: a spec hash whose run fails every time (test hook).
pub const FAIL_RUN_ENV: &str = "ARACHIS_TEST_FAIL_RUN";
/// Environment variable: a folder; the first attempt at each run aborts (test hook).
pub const KILL_ONCE_ENV: &str = "ARACHIS_TEST_KILL_ONCE";

/// What a worker did, printed as one JSON line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Done {
    /// The run's spec hash.
    pub spec_hash: String,
    /// The campaign stage and run that asked for it.
    pub stage: String,
    /// See `stage`.
    pub run: usize,
    /// The response the campaign reads, and its value.
    pub quantity: String,
    /// See `quantity`.
    pub response: f64,
    /// Whether the run was found already stored (nothing simulated).
    pub already_stored: bool,
    /// Wall time of the worker, s.
    pub wall_seconds: f64,
}

/// Runs `task` and stores it in the run cache `cache_dir` (module docs).
pub fn run_task(task: &RunTask, cache_dir: &Path) -> anyhow::Result<Done> {
    let started = Instant::now();
    crate::plausible::allow_extreme(task.recipe.allow_extreme);
    let (study, pass, boxed);
    let rig: &dyn crate::calibration::Rig = match &task.recipe.harvest {
        Some(harvest) => {
            pass = harvest.build()?;
            &pass
        }
        None => {
            study = task.recipe.load_study()?;
            boxed = task.recipe.build(&study, &task.experiment)?;
            boxed.as_ref()
        }
    };
    let request = RunRequest {
        values: &task.values,
        condition: &task.condition,
        replicate: task.replicate,
    };
    let spec = rig.specification(&request)?;
    let hash = SpecHash::of(&spec);
    if hash.to_string() != task.spec_hash {
        bail!(
            "the run's specification now hashes to {hash}, not the task's {}: the study {} or \
             the program changed since the campaign was planned; plan it again",
            task.spec_hash,
            task.recipe.study.display()
        );
    }
    let cache = RunCache::open(cache_dir)?;
    let rig_id = rig.id();
    let done = |response: f64, already_stored: bool| Done {
        spec_hash: task.spec_hash.clone(),
        stage: task.stage.clone(),
        run: task.run,
        quantity: task.quantity.clone(),
        response,
        already_stored,
        wall_seconds: started.elapsed().as_secs_f64(),
    };
    if let Some(stored) = cache.load(&spec, hash, &rig_id, &task.quantity) {
        return Ok(done(response(&stored, &task.quantity)?, true));
    }
    test_hooks(&task.spec_hash)?;
    let responses = rig
        .run(&request)
        .with_context(|| format!("{} run {} (spec {hash})", task.stage, task.run))?;
    let value = response(&responses, &task.quantity)?;
    cache.store(&spec, hash, &rig_id, &responses)?;
    Ok(done(value, false))
}

/// The failures the environment asks for (module docs).
fn test_hooks(hash: &str) -> anyhow::Result<()> {
    if std::env::var(FAIL_RUN_ENV).is_ok_and(|h| h == hash) {
        bail!("{FAIL_RUN_ENV} asks this run ({hash}) to fail");
    }
    if let Ok(dir) = std::env::var(KILL_ONCE_ENV) {
        let marker = Path::new(&dir).join(hash);
        if !marker.exists() {
            std::fs::write(&marker, b"")
                .with_context(|| format!("cannot write {}", marker.display()))?;
            eprintln!("{KILL_ONCE_ENV}: aborting the first attempt at {hash}");
            std::process::abort();
        }
    }
    Ok(())
}
