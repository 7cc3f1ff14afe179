//! `arachis analyze` (being built; see the issues).

/// Arguments of `arachis analyze`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `arachis analyze`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`analyze` is not available in this build yet")
}
