//! The flags `compare`, `diagnose` and `fit` share for where their simulations run: a run
//! cache to store and replay them (`--runs DIR`), and the cluster settings
//! ([`ClusterArgs`]). Without either, simulations run on this machine's threads and nothing
//! is stored, as before.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::calibration::{Executor, Progress};
use crate::cluster::{ClusterArgs, ExecutorKind, RigRecipe, Simulator, SlurmExecutor};
use crate::diagnose::model::Model;
use crate::study::Study;

/// The shared flags (module docs).
#[derive(Debug, Clone, clap::Args)]
pub struct RunsArgs {
    /// Store every simulation in this run cache and replay those already there (default with
    /// `--executor slurm`: `runs-STUDYNAME/`, which also keeps the cluster's records in
    /// `runs-STUDYNAME/slurm/`).
    #[arg(long, value_name = "DIR")]
    pub runs: Option<PathBuf>,
    /// Where the simulations run (this machine or a Slurm cluster).
    #[command(flatten)]
    pub cluster: ClusterArgs,
}

impl RunsArgs {
    /// `model` with its simulations run as these flags say.
    pub fn attach<'a>(&self, model: Model<'a>, study: &Study) -> anyhow::Result<Model<'a>> {
        let slurm = self.cluster.executor == ExecutorKind::Slurm;
        let Some(runs) = self
            .runs
            .clone()
            .or_else(|| slurm.then(|| PathBuf::from(format!("runs-{}", study.name()))))
        else {
            return Ok(model);
        };
        let mut executor = Executor::new(None, Some(&runs), Progress::new(false))?;
        if slurm {
            let recipe = RigRecipe::new(study.path(), Simulator::Dem, study.plan_mode()?)
                .with_context(|| {
                    format!("{}: cannot make the path absolute", study.path().display())
                })?;
            let records = Path::new(&runs).join(crate::cluster::SLURM_DIR);
            let remote = SlurmExecutor::new(recipe, &self.cluster, &records, false)?;
            executor = executor.with_remote(Box::new(remote))?;
        }
        Ok(model.with_executor(executor))
    }
}
