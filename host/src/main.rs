//! The `arachis` command-line program.

use clap::Parser;

fn main() {
    let cli = arachis::cli::Cli::parse();
    if let Err(err) = cli.run() {
        eprintln!("error: {err:#}");
        std::process::exit(2);
    }
}
