//! The flags `compare`, `diagnose`, `fit` and `harvest` share for where their simulations
//! run: a run cache to store and replay them (`--runs DIR`), and the cluster settings
//! ([`ClusterArgs`]). Without either, simulations run on this machine's threads and nothing
//! is stored, as before. [`PredictionArgs`]: how many placements the diagnosis commands
//! average for a rig with a random placement.

use std::path::PathBuf;

use anyhow::Context;

use crate::calibration::{Executor, Progress};
use crate::cluster::{on_cluster_if_chosen, ClusterArgs, ExecutorKind, RigRecipe, Simulator};
use crate::diagnose::model::{Model, DEFAULT_RANDOM_REPLICATES};
use crate::study::Study;

/// The shared flags (module docs).
#[derive(Debug, Clone, clap::Args)]
pub struct RunsArgs {
    /// Store every simulation in this run cache and replay those already there (default with
    /// `--executor slurm`: `runs-NAME/`, NAME the study's or `harvest`, which also keeps the
    /// cluster's records in its `slurm/`).
    #[arg(long, value_name = "DIR")]
    pub runs: Option<PathBuf>,
    /// Where the simulations run (this machine or a Slurm cluster).
    #[command(flatten)]
    pub cluster: ClusterArgs,
}

impl RunsArgs {
    /// Whether these flags ask for an executor (a run cache or a cluster).
    pub fn wanted(&self) -> bool {
        self.runs.is_some() || self.cluster.executor == ExecutorKind::Slurm
    }

    /// The executor these flags ask for (`None`: neither a run cache nor a cluster), its
    /// cache in `--runs` or `runs-NAME/`; `recipe` rebuilds its rigs on the cluster.
    pub fn executor(
        &self,
        name: &str,
        recipe: impl FnOnce() -> anyhow::Result<RigRecipe>,
    ) -> anyhow::Result<Option<Executor>> {
        if !self.wanted() {
            return Ok(None);
        }
        let runs = self
            .runs
            .clone()
            .unwrap_or_else(|| PathBuf::from(format!("runs-{name}")));
        let executor = Executor::new(None, Some(&runs), Progress::new(false))?;
        let records = runs.join(crate::cluster::SLURM_DIR);
        on_cluster_if_chosen(executor, &self.cluster, recipe, &records, false).map(Some)
    }

    /// `model` with its simulations run as these flags say.
    pub fn attach<'a>(&self, model: Model<'a>, study: &Study) -> anyhow::Result<Model<'a>> {
        let recipe = || {
            RigRecipe::new(study.path(), Simulator::Dem, study.plan_mode()?).with_context(|| {
                format!("{}: cannot make the path absolute", study.path().display())
            })
        };
        Ok(match self.executor(study.name(), recipe)? {
            Some(executor) => model.with_executor(executor),
            None => model,
        })
    }
}

/// Most simulated replicates per prediction `--replicates` accepts: a typo cannot ask for a
/// million piles.
pub const MAX_PREDICTION_REPLICATES: u32 = 1000;

/// `compare`, `diagnose` and `fit`: simulated replicates per prediction of a random rig.
#[derive(Debug, Clone, clap::Args)]
pub struct PredictionArgs {
    /// Simulated replicates per prediction of a rig with a random placement (a pod pile):
    /// every parameter set is simulated at the same placements, so differences between
    /// them are paired (common random numbers). Deterministic rigs run once.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_RANDOM_REPLICATES,
          value_parser = clap::value_parser!(u32).range(1..=MAX_PREDICTION_REPLICATES as i64))]
    pub replicates: u32,
}

impl PredictionArgs {
    /// `model` with these replicates, and a progress bar over its simulations on a terminal.
    pub fn apply<'a>(&self, model: Model<'a>) -> Model<'a> {
        model
            .with_replicates(self.replicates)
            .with_progress(crate::calibration::Progress::new(false))
    }
}
