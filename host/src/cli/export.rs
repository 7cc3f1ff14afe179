//! `arachis export liggghts STUDY --experiment repose --out DIR`: the study's rig as a
//! LIGGGHTS 3.8 deck (`crate::export::liggghts`): `DIR/in.repose`, `DIR/particles.data` and
//! `DIR/cylinder.stl`, each written atomically. Run it with `cd DIR && liggghts -in
//! in.repose`; it writes `final.dump`, which `arachis lab repose-pile DIR/final.dump`
//! measures as the rig measures its own pile. The seed, mode and `--set` values choose the
//! run as for `arachis simulate`, so `simulate --seed K` and `export --seed K` start from the
//! same particles.

use std::path::PathBuf;

use anyhow::{bail, Context};
use clap::Subcommand;

use super::simulate::{pod_world, prepare, RunChoice, RunSelection};
use crate::export::liggghts::repose_deck;
use crate::rigs::pod_world::setup::RunInputs;
use crate::rigs::pod_world::{Experiment, TemplateCache};

/// The `export` targets.
#[derive(Debug, Subcommand)]
pub enum Target {
    /// A LIGGGHTS 3.8 input deck of a study's rig (the repose rig; studies of [spheres]).
    Liggghts(Args),
}

/// Arguments of `arachis export liggghts`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The study file (TOML); its particles must be `[spheres]`.
    pub study: PathBuf,
    /// The experiment to export (today: repose).
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
    if experiment != Experiment::Repose {
        bail!(
            "export liggghts writes the repose rig only (asked for {})",
            experiment.name()
        );
    }
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
    let deck = repose_deck(&inputs, seed, &source)
        .map_err(anyhow::Error::msg)
        .with_context(|| format!("cannot export {}", args.study.display()))?;
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("cannot create {}", args.out.display()))?;
    for (name, text) in [
        ("in.repose", &deck.input),
        ("particles.data", &deck.data),
        ("cylinder.stl", &deck.cylinder_stl),
    ] {
        crate::io::write_atomic(&args.out.join(name), |w| {
            w.write_all(text.as_bytes())?;
            Ok(())
        })?;
    }
    for w in &deck.warnings {
        eprintln!("warning: {w}");
    }
    println!(
        "wrote {} (in.repose, particles.data, cylinder.stl; dt {:e} s); run: cd {} && liggghts -in in.repose",
        args.out.display(),
        deck.dt_s,
        args.out.display()
    );
    Ok(())
}
