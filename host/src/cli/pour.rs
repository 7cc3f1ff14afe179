//! `arachis pour` (being built; see the issues).

/// Arguments of `arachis pour`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Runs `arachis pour`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`pour` is not available in this build yet")
}
