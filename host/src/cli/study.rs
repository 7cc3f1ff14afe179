//! `arachis study check STUDY.toml [--json]`: parse and validate a study file (a pod, a
//! pull-off or a diagnosis study: one format) before any simulation runs, reporting every
//! problem with its file, key and line:column.

use std::path::PathBuf;

use clap::Subcommand;

use crate::study::Study;

/// Arguments of `arachis study`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// What to do with the study file.
    #[command(subcommand)]
    pub command: StudyCommand,
}

/// The `study` subcommands.
#[derive(Debug, Subcommand)]
pub enum StudyCommand {
    /// Validate a study file and print its summary (or the validated study as JSON).
    Check {
        /// The study file (TOML), e.g. testdata/peanut-pods-saline/study.toml or the plant
        /// pull-off study testdata/peanut-plant/study.toml.
        study: PathBuf,
        /// Print the validated study as one JSON object instead of the summary.
        #[arg(long)]
        json: bool,
    },
}

/// Runs `arachis study`.
pub fn run(args: Args) -> anyhow::Result<()> {
    match args.command {
        StudyCommand::Check { study, json } => {
            let study = Study::load(&study)?;
            if json {
                println!("{}", study.to_json());
            } else {
                println!("{}", study.summary().trim_end());
            }
            Ok(())
        }
    }
}
