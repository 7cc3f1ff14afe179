//! `arachis export liggghts STUDY --experiment NAME --out DIR`: the study's rig as a
//! LIGGGHTS 3.8 deck (`crate::export::liggghts`), each file written atomically:
//! - `repose`: `DIR/in.repose`, `DIR/particles.data` and `DIR/cylinder.stl`; run it with
//!   `cd DIR && liggghts -in in.repose`; it writes `final.dump`, which `arachis lab
//!   repose-pile DIR/final.dump` measures as the rig measures its own pile;
//! - `incline_slide`: `DIR/in.incline` and `DIR/particles.data`; it writes `incline.txt`
//!   with the slide angle read as the rig reads it.
//!
//! The seed, mode and `--set` values choose the run as for `arachis simulate`, so `simulate
//! --seed K` and `export --seed K` start from the same particles.

use std::path::PathBuf;

use anyhow::Context;
use clap::Subcommand;

use super::simulate::{pod_world, prepare, RunChoice, RunSelection};
use crate::export::liggghts::deck;
use crate::rigs::pod_world::setup::RunInputs;
use crate::rigs::pod_world::TemplateCache;

/// The `export` targets.
#[derive(Debug, Subcommand)]
pub enum Target {
    /// A LIGGGHTS 3.8 input deck of a study's rig (repose or incline_slide; studies of
    /// [spheres]).
    Liggghts(Args),
}

/// Arguments of `arachis export liggghts`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study file (TOML); its particles must be `[spheres]`.
    pub study: PathBuf,
    /// The experiment to export: repose or incline_slide.
    #[arg(long, default_value = "repose")]
    pub experiment: String,
    /// Folder to write the deck into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Mode, overrides and seed, as for `arachis simulate`.
    #[command(flatten)]
    pub choice: RunChoice,
}

/// Runs `arachis export`.
pub fn run(target: Target) -> anyhow::Result<()> {
    let Target::Liggghts(args) = target;
    let selection = RunSelection {
        experiment: args.experiment.clone(),
        study: args.study.clone(),
        choice: args.choice.clone(),
    };
    let (study, experiment, values, mode) = prepare(&selection)?;
    let world = pod_world(&study, &selection)?;
    let seed = args.choice.seed.unwrap_or(world.simulation.random_seed);
    let condition = study.condition_of(experiment.name());
    let inputs = RunInputs::resolve(
        &world,
        experiment,
        &condition,
        &values,
        mode,
        &TemplateCache::new(),
    )?;
    let source = format!("{} ({} mode)", args.study.display(), mode.as_str());
    let deck = deck(experiment, &inputs, seed, &source)
        .map_err(anyhow::Error::msg)
        .with_context(|| format!("cannot export {}", args.study.display()))?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    for file in &deck.files {
        crate::io::write_atomic(&args.out.join(file.name), |w| {
            w.write_all(file.text.as_bytes())?;
            Ok(())
        })?;
    }
    for w in &deck.warnings {
        eprintln!("warning: {w}");
    }
    let names: Vec<&str> = deck.files.iter().map(|f| f.name).collect();
    println!(
        "wrote {} ({}; dt {:e} s); run: cd {} && liggghts -in {}",
        args.out.display(),
        names.join(", "),
        deck.dt_s,
        args.out.display(),
        deck.input_name()
    );
    Ok(())
}
