//! Campaigns that outgrow one machine (issue 21): the runs of a calibration, a diagnosis
//! (`compare`, `diagnose`, `fit`) or a harvest executed as Slurm job arrays, with the same
//! bytes as a local run.
//!
//! Every run of a campaign is named by the hash of its specification and stored in the run
//! cache, which is exactly the unit a job array wants:
//! - [`RigRecipe`]: how to build the campaign's rig again on any node;
//! - [`RunTask`]: one run written to a task file; [`worker`] simulates it and stores it
//!   (`arachis run TASK.json --cache DIR`);
//! - [`SlurmExecutor`]: the calibration engine's [`crate::calibration::Remote`] backend:
//!   each stage's missing runs become one array, then the stage replays them from the cache;
//! - [`ledger`]: the record of submitted arrays beside the cache, so that a restarted
//!   driver submits nothing twice; [`scheduler`]: the `sbatch` and `squeue` calls.
//!
//! `scripts/slurm-local.sh` starts a one-node cluster on this machine for the tests.
//!
//! ```no_run
//! use arachis::calibration::{Executor, Progress};
//! use arachis::cluster::{ClusterArgs, RigRecipe, Simulator, SlurmExecutor};
//! let recipe = RigRecipe::new("study.toml".as_ref(), Simulator::Dem, None)?;
//! let slurm = SlurmExecutor::new(recipe, &ClusterArgs::default(), "out/slurm".as_ref(), true)?;
//! let executor = Executor::new(None, Some("out/runs".as_ref()), Progress::hidden())?
//!     .with_remote(Box::new(slurm))?;
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod ledger;
pub mod recipe;
pub mod scheduler;
pub mod settings;
pub mod slurm;
pub mod task;
pub mod worker;

pub use recipe::{RigRecipe, Simulator};
pub use settings::{ClusterArgs, ExecutorKind};
pub use slurm::{on_cluster_if_chosen, SlurmExecutor};
pub use task::RunTask;

/// Folder of a campaign's Slurm records inside its output folder, beside `runs/`.
pub const SLURM_DIR: &str = "slurm";
