//! Runs the `arachis` binary the way the CLI tests need it.
#![allow(dead_code)]

use std::process::{Command, Output};

/// The repository root (where `testdata/` lies).
pub const REPO_ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// Runs `arachis ARGS` in the test's working directory (the `host` package).
pub fn arachis(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_arachis"))
        .args(args)
        .output()
        .expect("cannot start the arachis binary")
}

/// Runs `arachis ARGS` from the repository root, so paths like `testdata/…` resolve.
pub fn arachis_at_root(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_arachis"))
        .args(args)
        .current_dir(REPO_ROOT)
        .output()
        .expect("cannot start the arachis binary")
}

/// Each file of `dir` with its modification time, sorted by name: equal before and after a
/// command when the command rewrote nothing there.
pub fn file_stamps(dir: &std::path::Path) -> Vec<(std::ffi::OsString, std::time::SystemTime)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            (e.file_name(), e.metadata().unwrap().modified().unwrap())
        })
        .collect();
    v.sort();
    v
}
