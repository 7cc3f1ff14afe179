//! Runs the `arachis` binary the way the CLI tests need it.

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

/// Runs `arachis COMMAND STUDY --runs COPY ARGS` from the repository root on a copy of the
/// committed run cache `runs` (relative to the root), and fails if any run had to be
/// simulated instead of replayed. Returns what the command printed.
pub fn replay(command: &str, study: &str, runs: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let copy = dir.path().join("runs");
    std::fs::create_dir(&copy).unwrap();
    for e in std::fs::read_dir(std::path::Path::new(REPO_ROOT).join(runs)).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), copy.join(e.file_name())).unwrap();
    }
    let before = file_stamps(&copy);
    let mut all = vec![command, study, "--runs", copy.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = arachis_at_root(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        file_stamps(&copy),
        before,
        "a run was simulated instead of replayed: the committed cache no longer matches"
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// Runs `arachis args` and asserts it refused its input as a user should see it: exit 2, no
/// panic, `named` in the message, and no file at `unwritten`. Returns the message.
pub fn assert_refused(args: &[&str], named: &str, unwritten: &std::path::Path) -> String {
    let out = arachis(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(named), "{args:?}: {named} not named in: {err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        !unwritten.exists(),
        "{args:?}: {} was written",
        unwritten.display()
    );
    err
}

/// Runs `arachis simulate EXPERIMENT` on the shipped seed-000 study with one more
/// `[[measurements]]` block, `measurement` (its keys, without the header), and asserts it is
/// refused ([`assert_refused`]): exit 2, `named` in the message, and no VTK folder written.
pub fn assert_simulate_refuses_measurement(experiment: &str, measurement: &str, named: &str) {
    let dir = tempfile::tempdir().unwrap();
    let study = std::fs::read_to_string(
        std::path::Path::new(REPO_ROOT).join("testdata/peanut-pods-saline/study.toml"),
    )
    .unwrap();
    let path = dir.path().join("study.toml");
    std::fs::write(&path, format!("{study}\n[[measurements]]\n{measurement}\n")).unwrap();
    let vtk = dir.path().join("frames");
    let (study, frames) = (path.to_str().unwrap(), vtk.to_str().unwrap());
    assert_refused(
        &["simulate", experiment, "--study", study, "--vtk", frames],
        named,
        &vtk,
    );
}

/// A one-row, 0.2 m field with a narrow bed (one plant) and the shipped machine narrowed to
/// 0.24 m, written into `dir` with the shipped variety; returns the field and machine files.
/// Small enough for a test to step it thousands of times in seconds.
pub fn small_field_files(dir: &std::path::Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let data = std::path::Path::new(REPO_ROOT).join("testdata/peanut-plant");
    std::fs::copy(
        data.join("variety-huayu.toml"),
        dir.join("variety-huayu.toml"),
    )
    .unwrap();
    let mut field = std::fs::read_to_string(data.join("field-huayu.toml")).unwrap();
    for (from, to) in [
        ("ridge_length_m = 1.0", "ridge_length_m = 0.2"),
        ("rows = 2", "rows = 1"),
        ("margin_m = 0.25", "margin_m = 0.05"),
    ] {
        assert!(field.contains(from), "{from}");
        field = field.replacen(from, to, 1);
    }
    let machine = std::fs::read_to_string(data.join("harvester-digger.toml")).unwrap();
    let width = machine
        .lines()
        .find(|l| l.starts_with("width_m"))
        .expect("the machine has a width")
        .to_owned();
    let machine = machine.replacen(&width, "width_m = 0.24", 1);
    let (f, m) = (dir.join("field.toml"), dir.join("machine.toml"));
    std::fs::write(&f, field).unwrap();
    std::fs::write(&m, machine).unwrap();
    (f, m)
}
