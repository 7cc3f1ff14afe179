//! `arachis plant [--topology FILE]`: generate a plant from its topology and print its
//! summary as one JSON line (`crate::plant::PlantSummary`): parts by kind, spheres,
//! bodies, the bond count of every set, the pod–stalk, stalk–stem and stem–leaf counts,
//! and seed 001's 191 / 201 / 150 beside them. A bad topology is a clear error.

use std::path::PathBuf;

use anyhow::Context;

use crate::plant::{generate, Topology};

/// Arguments of `arachis plant`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Plant topology (TOML, see `arachis::plant`); default: the shipped small plant.
    #[arg(long, value_name = "FILE")]
    pub topology: Option<PathBuf>,
}

/// Runs `arachis plant`.
pub fn run(args: Args) -> anyhow::Result<()> {
    let text = match &args.topology {
        Some(p) => crate::io::text::read_text(p)
            .with_context(|| format!("cannot read the topology {}", p.display()))?,
        None => crate::plant::SHIPPED_TOPOLOGY.to_owned(),
    };
    let topology = Topology::from_toml(&text).context("bad plant topology")?;
    let model = generate(&topology).context("cannot generate the plant")?;
    println!("{}", serde_json::to_string(&model.summary())?);
    Ok(())
}
