//! `arachis lab` (being built; see the issues).

/// Arguments of `arachis lab`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `arachis lab`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`lab` is not available in this build yet")
}
