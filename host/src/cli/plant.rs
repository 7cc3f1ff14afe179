//! `arachis plant [--topology FILE]`: generate a plant from its topology and print its
//! summary as one JSON line (`crate::plant::PlantSummary`): parts by kind, spheres,
//! bodies, the bond count of every set, the pod–stalk, stalk–stem and stem–leaf counts,
//! seed 001's 191 / 201 / 150 beside them, and the organ sizes as built. A bad topology is
//! a clear error.
//!
//! `arachis plant --variety FILE [--seed N] [--plants K]`: grow K plants of a variety
//! (`crate::variety`) from seeds N, N+1, … and print one line per plant, its seed
//! first. A bad variety file is refused with its path, line and key.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::plant::picture::write_plant_picture;
use crate::plant::{generate, PlantModel, Topology};
use crate::variety::Variety;

/// Arguments of `arachis plant`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Plant topology (TOML, see `arachis::plant`); default: the shipped small plant.
    #[arg(long, value_name = "FILE", conflicts_with = "variety")]
    pub topology: Option<PathBuf>,
    /// Grow plants of this variety (TOML, see `arachis::variety`) instead.
    #[arg(long, value_name = "FILE")]
    pub variety: Option<PathBuf>,
    /// Seed of the first plant grown from `--variety`.
    #[arg(long, default_value_t = 1, requires = "variety")]
    pub seed: u64,
    /// Write a side view of the (first) plant, SVG.
    #[arg(long, value_name = "FILE.svg")]
    pub picture: Option<PathBuf>,
    /// Plants to grow from `--variety` (seeds N, N+1, …).
    #[arg(long, default_value_t = 1, requires = "variety", value_parser = clap::value_parser!(u64).range(1..=MAX_PLANTS))]
    pub plants: u64,
}

/// One printed line of `arachis plant --variety`: the seed, then the plant's summary.
#[derive(serde::Serialize)]
struct PlantLine {
    seed: u64,
    #[serde(flatten)]
    summary: crate::plant::PlantSummary,
}

/// Most plants one `arachis plant --variety` call grows.
const MAX_PLANTS: u64 = 10_000;

/// Runs `arachis plant`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let Some(path) = args.variety.as_deref() else {
        let model = load_plant(args.topology.as_deref())?;
        if let Some(picture) = &args.picture {
            write_plant_picture(picture, &model, "plant")?;
        }
        println!("{}", serde_json::to_string(&model.summary())?);
        return Ok(());
    };
    let variety = Variety::read(path)?;
    let mut lines = Vec::new();
    let mut first = None;
    for seed in (0..args.plants).map(|k| args.seed.wrapping_add(k)) {
        let (_, model) = variety
            .grow(seed)
            .with_context(|| format!("{}: cannot grow plant {seed}", path.display()))?;
        let line = PlantLine {
            seed,
            summary: model.summary(),
        };
        lines.push(serde_json::to_string(&line)?);
        first.get_or_insert(model);
    }
    // Written only once every plant has grown: a refused plant writes and prints nothing.
    if let (Some(picture), Some(model)) = (&args.picture, &first) {
        let title = format!("{}, plant of seed {}", variety.variety.name, args.seed);
        write_plant_picture(picture, model, &title)?;
    }
    println!("{}", lines.join("\n"));
    Ok(())
}

/// The plant generated from the topology at `path` (the shipped small plant when `None`);
/// every error names the file.
pub(crate) fn load_plant(path: Option<&Path>) -> anyhow::Result<PlantModel> {
    let (text, name) = crate::plant::topology_text(path).with_context(|| {
        format!(
            "cannot read the topology {}",
            path.map_or(String::new(), |p| p.display().to_string())
        )
    })?;
    let topology =
        Topology::from_toml(&text).with_context(|| format!("{name}: bad plant topology"))?;
    generate(&topology).with_context(|| format!("{name}: cannot generate the plant"))
}
