//! `arachis run TASK.json --cache DIR`: simulate one run of a campaign from its task file
//! and store it in the run cache (what each Slurm array task runs; `crate::cluster::worker`).
//! Prints one JSON line: the spec hash, the stage and run, the response and the wall time.

use std::path::PathBuf;

use crate::cluster::worker::run_task;
use crate::cluster::RunTask;

/// Arguments of `arachis run`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The task file (`slurm/tasks/<spec hash>.json` of a campaign's output folder).
    pub task: PathBuf,
    /// The run cache to store the result in (`runs/` of the campaign's output folder).
    #[arg(long, value_name = "DIR")]
    pub cache: PathBuf,
}

/// Runs `arachis run`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let task = RunTask::read(&args.task)?;
    let done = run_task(&task, &args.cache)?;
    println!("{}", serde_json::to_string(&done)?);
    Ok(())
}
