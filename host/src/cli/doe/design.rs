//! `arachis design` (being built; see the issues).

/// Arguments of `arachis design`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `arachis design`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`design` is not available in this build yet")
}
