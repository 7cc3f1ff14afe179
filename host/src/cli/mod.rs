//! The `arachis` command line: one module per subcommand, each a thin face over the library.
//!
//! Every subcommand returns `anyhow::Result`; `main` prints the error chain and exits with
//! status 2, so bad input is always a clear message and never a panic.

pub mod calibrate;
pub mod compare;
pub mod diagnose;
pub mod doe;
pub mod export;
pub mod field;
pub mod fit;
pub mod harvest;
pub mod lab;
pub mod lab_repose;
pub mod lab_repose_pile;
pub mod plant;
pub mod plant_calibrate;
pub mod pour;
pub mod pulloff;
pub mod run;
pub mod runs_args;
pub mod simulate;
pub mod study;
pub mod synth;

use clap::{Parser, Subcommand};

/// Arachis: calibrated, bit-reproducible DEM models of peanut pods and plants.
#[derive(Debug, Parser)]
#[command(name = "arachis", version, about)]
pub struct Cli {
    /// Threads each simulation steps on (default: every core; a campaign that runs several
    /// simulations at once gives each its share). In fixed point the results do not depend
    /// on it.
    #[arg(long, global = true, value_name = "N", allow_hyphen_values = true)]
    pub threads: Option<usize>,
    /// Accept study values outside their plausible ranges (`arachis::plausible`: densities,
    /// moduli, friction, gravity, measured angles), with a warning for each.
    #[arg(long, global = true)]
    pub allow_extreme: bool,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Pour spheres into the steel bench-bed cylinder and let them settle.
    Pour(pour::Args),
    /// Analyse bench-test measurements (density, Poisson, Hertz modulus, restitution, friction).
    Lab(lab::Args),
    /// Designs of experiments: make a design, analyse a response, optimise a fitted surface.
    Doe(doe::Args),
    /// Study files: validate one before any simulation runs.
    Study(study::Args),
    /// Virtual tensile test: pull a bonded pod off its stalk, print the detachment force.
    Pulloff(pulloff::Args),
    /// Diagnosis: simulate a study's experiments and test the misfit per experiment.
    Compare(compare::Args),
    /// Diagnosis: rank the optional effects that could explain the misfit.
    Diagnose(diagnose::Args),
    /// Diagnosis: recalibrate with an effect on; nested tests, AIC/BIC, held-out error.
    Fit(fit::Args),
    /// Diagnosis: write synthetic measurements with a hidden effect.
    Synth(synth::Args),
    /// Run one virtual bench experiment of a study (repose, plate_drop, incline_slide,
    /// rolling, compression).
    Simulate(simulate::Args),
    /// Calibrate any study end to end: screen, steepest ascent, response surface, optimise,
    /// validate.
    Calibrate(calibrate::Args),
    /// Simulate one run of a campaign from its task file into the run cache (what each
    /// Slurm array task runs).
    Run(run::Args),
    /// Alias (this release only) of `calibrate` on seed 001's built-in pull-off study.
    PlantCalibrate(plant_calibrate::Args),
    /// Generate a plant from its topology and print its parts and bond-set counts.
    Plant(plant::Args),
    /// Lay out a field (plants of a variety in ridge rows, pods in a soil bed) and step it.
    Field(field::Args),
    /// Virtual harvest: plants through a toothed picking drum; loss rate and t-test against
    /// the field (seed 001 Table 12).
    Harvest(harvest::Args),
    /// Write a study's rig for another engine (a LIGGGHTS 3.8 deck of the repose rig).
    #[command(subcommand)]
    Export(export::Target),
}

impl Cli {
    /// Runs the chosen subcommand.
    pub fn run(self) -> anyhow::Result<()> {
        if let Some(threads) = self.threads {
            crate::stepping::set_default_threads(threads)?;
        }
        crate::plausible::allow_extreme(self.allow_extreme);
        match self.command {
            Command::Pour(args) => pour::run(args),
            Command::Lab(args) => lab::run(args),
            Command::Doe(args) => doe::run(args),
            Command::Study(args) => study::run(args),
            Command::Pulloff(args) => pulloff::run(args),
            Command::Compare(args) => compare::run(args),
            Command::Diagnose(args) => diagnose::run(args),
            Command::Fit(args) => fit::run(args),
            Command::Synth(args) => synth::run(args),
            Command::Simulate(args) => simulate::run(args),
            Command::Calibrate(args) => calibrate::run(args),
            Command::Run(args) => run::run(args),
            Command::PlantCalibrate(args) => plant_calibrate::run(args),
            Command::Harvest(args) => harvest::run(args),
            Command::Plant(args) => plant::run(args),
            Command::Field(args) => field::run(args),
            Command::Export(target) => export::run(target),
        }
    }
}

/// A progress bar over `steps` steps, labelled `label`, with rate, time left and a message.
/// Its default draw target is stderr, hidden when stderr is not a terminal.
pub(crate) fn steps_bar(label: &str, steps: u64) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(steps);
    let template =
        format!("{label} {{bar:40}} {{pos}}/{{len}} steps  {{per_sec}}  eta {{eta}}  {{msg}}");
    if let Ok(style) = indicatif::ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    bar
}
