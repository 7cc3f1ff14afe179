//! `arachis plant [--topology FILE]`: generate a plant from its topology and print its
//! summary as one JSON line (`crate::plant::PlantSummary`): parts by kind, spheres,
//! bodies, the bond count of every set, the pod–stalk, stalk–stem and stem–leaf counts,
//! and seed 001's 191 / 201 / 150 beside them. A bad topology is a clear error.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::plant::{generate, PlantModel, Topology};

/// Arguments of `arachis plant`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Plant topology (TOML, see `arachis::plant`); default: the shipped small plant.
    #[arg(long, value_name = "FILE")]
    pub topology: Option<PathBuf>,
}

/// Runs `arachis plant`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let model = load_plant(args.topology.as_deref())?;
    println!("{}", serde_json::to_string(&model.summary())?);
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
