//! `arachis doe`: designs of experiments, response-surface analysis and optimisation.

pub mod analyze;
pub mod design;
pub mod optimize;

use clap::Subcommand;

/// Arguments of `arachis doe`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// What to do with designs.
    #[command(subcommand)]
    pub command: DoeCommand,
}

/// The `doe` subcommands.
#[derive(Debug, Subcommand)]
pub enum DoeCommand {
    /// Write a design matrix (coded and actual units) as CSV.
    Design(design::Args),
    /// Fit a model to one response and print a Design-Expert-style ANOVA table.
    Analyze(analyze::Args),
    /// Find factor settings on a fitted surface that meet desirability goals.
    Optimize(optimize::Args),
}

/// Runs `arachis doe`.
pub fn run(args: Args) -> anyhow::Result<()> {
    match args.command {
        DoeCommand::Design(a) => design::run(a),
        DoeCommand::Analyze(a) => analyze::run(a),
        DoeCommand::Optimize(a) => optimize::run(a),
    }
}
