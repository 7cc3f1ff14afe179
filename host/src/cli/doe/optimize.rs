//! `arachis optimize` (being built; see the issues).

/// Arguments of `arachis optimize`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `arachis optimize`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`optimize` is not available in this build yet")
}
