//! Issue 20: a field pass is hours of stepping, so `arachis field --checkpoint FILE` keeps
//! its state and the same command run again goes on from it (`arachis::checkpoint`).
//!
//! - A run stopped after 1 000 steps and run on to 2 000 ends with the digest of a run of
//!   2 000 steps never stopped, on another thread count, with the harvester mounted.
//! - A trial's replicates each keep their own file and resume.
//! - A checkpoint of another seed, or a damaged one, is refused with its path; nothing is
//!   written.
//! - VTK frames taken as the run goes (`--frames`) change nothing in it, and a resumed run
//!   adds to them.

use std::path::Path;

use serde_json::Value;

use crate::cli_support::{arachis, small_field_files};

/// Steps of the reference run; the stopped run stops half-way (both whole numbers of the
/// machine's 250-step chunks).
const STEPS: u64 = 2_000;

/// The small field's files, as strings for the command line.
fn small_files(dir: &Path) -> (String, String) {
    let (f, m) = small_field_files(dir);
    (f.display().to_string(), m.display().to_string())
}

/// Runs `arachis --threads T field FIELD --harvester MACHINE ARGS…`; returns the printed
/// JSON and stderr, asserting success.
fn field(threads: &str, files: &(String, String), args: &[&str]) -> (Value, String) {
    let mut all = vec![
        "--threads",
        threads,
        "field",
        &files.0,
        "--harvester",
        &files.1,
    ];
    all.extend_from_slice(args);
    let out = arachis(&all);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(out.status.success(), "{stderr}");
    let json = serde_json::from_slice(&out.stdout).unwrap();
    (json, stderr)
}

#[test]
fn a_stopped_run_goes_on_to_the_bits_of_one_never_stopped() {
    let dir = tempfile::tempdir().unwrap();
    let files = small_files(dir.path());
    let steps = STEPS.to_string();
    let (whole, _) = field("1", &files, &["--steps", &steps]);

    let ckpt = dir.path().join("pass.ckpt");
    let ckpt_s = ckpt.to_str().unwrap();
    let half = (STEPS / 2).to_string();
    let (first, _) = field("2", &files, &["--steps", &half, "--checkpoint", ckpt_s]);
    assert_ne!(first["digest"], whole["digest"]);
    // The header line says how far the run got.
    let bytes = std::fs::read(&ckpt).unwrap();
    let line = bytes.split(|&b| b == b'\n').next().unwrap();
    let header: Value = serde_json::from_slice(line).unwrap();
    assert_eq!(header["steps_done"].as_u64(), Some(STEPS / 2));
    assert_eq!(header["seed"].as_u64(), Some(1));
    // It also counts the CPU time the steps took (Linux's process clock, in 10 ms ticks):
    // more than nothing, and no more than the run's threads could spend in its wall time.
    let cpu = |v: &Value| v["cpu_seconds"].as_f64().unwrap();
    assert!(cpu(&header) > 0.0, "{header}");
    assert!(cpu(&header) <= 2.0 * first["wall_seconds"].as_f64().unwrap() + 0.02);
    // The printed line is taken just after the last save.
    assert!(cpu(&header) <= cpu(&first) && cpu(&first) - cpu(&header) < 0.5);

    let (second, stderr) = field("2", &files, &["--steps", &steps, "--checkpoint", ckpt_s]);
    assert!(
        stderr.contains(&format!("at step {} of {STEPS}", STEPS / 2)),
        "{stderr}"
    );
    assert_eq!(second["digest"], whole["digest"], "resumed run");
    assert_eq!(second["harvest"], whole["harvest"]);
    // The bonds broken count from the field's bonds, so a resumed run counts them as one
    // never stopped: none here, 2 000 steps in with the machine still before the bed.
    assert_eq!(second["bonds_broken"], whole["bonds_broken"]);
    assert_eq!(whole["bonds_broken"].as_u64(), Some(0));
    let wall = |v: &Value| v["wall_seconds"].as_f64().unwrap();
    assert!(
        wall(&second) >= wall(&first),
        "the wall time counts both sessions"
    );
    assert!(
        cpu(&second) > cpu(&first),
        "the CPU time counts both sessions"
    );

    // Run again, it is done: nothing is stepped and the result is the same.
    let (again, stderr) = field("1", &files, &["--steps", &steps, "--checkpoint", ckpt_s]);
    assert!(
        stderr.contains(&format!("at step {STEPS} of {STEPS}")),
        "{stderr}"
    );
    assert_eq!(again["digest"], whole["digest"]);
}

#[test]
fn each_replicate_keeps_its_own_checkpoint_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let files = small_files(dir.path());
    let ckpt = dir.path().join("trial.ckpt");
    let args = [
        "--replicates",
        "2",
        "--steps",
        "500",
        "--checkpoint",
        ckpt.to_str().unwrap(),
    ];
    let (first, _) = field("2", &files, &args);
    for r in 1..=2 {
        assert!(dir.path().join(format!("trial_rep{r}.ckpt")).exists());
    }
    assert!(!ckpt.exists(), "no un-numbered checkpoint with replicates");
    let (again, stderr) = field("2", &files, &args);
    assert_eq!(stderr.matches("going on from").count(), 2, "{stderr}");
    let digests = |v: &Value| {
        v["replicates"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r["digest"].clone())
            .collect::<Vec<_>>()
    };
    assert_eq!(digests(&again), digests(&first));
    assert_eq!(again["loss_rate_pct"], first["loss_rate_pct"]);
}

#[test]
fn a_checkpoint_of_another_seed_or_a_damaged_one_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let files = small_files(dir.path());
    let ckpt = dir.path().join("pass.ckpt");
    let ckpt_s = ckpt.to_str().unwrap();
    field("2", &files, &["--steps", "250", "--checkpoint", ckpt_s]);
    let output = dir.path().join("out.json");
    let refused = |args: &[&str], why: &str| {
        let mut all = vec!["field", &files.0, "--harvester", &files.1];
        all.extend_from_slice(args);
        all.extend_from_slice(&["--checkpoint", ckpt_s, "--output", output.to_str().unwrap()]);
        let out = arachis(&all);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?} should be refused");
        assert!(
            stderr.contains(ckpt_s) && stderr.contains(why),
            "{args:?}: {stderr}"
        );
        assert!(!output.exists(), "{args:?} wrote its output");
    };
    refused(&["--steps", "500", "--seed", "2"], "layout seed 1");
    refused(&["--steps", "100"], "past the 100");
    // Cut short by a crash of the disk, not of arachis (whose writes are atomic).
    let bytes = std::fs::read(&ckpt).unwrap();
    std::fs::write(&ckpt, &bytes[..bytes.len() - 8]).unwrap();
    refused(&["--steps", "500"], "cut short");
    let mut flipped = bytes.clone();
    let last = flipped.len() - 1;
    flipped[last] ^= 1;
    std::fs::write(&ckpt, &flipped).unwrap();
    refused(&["--steps", "500"], "checksum");
}

#[test]
fn frames_taken_as_a_run_goes_change_nothing_and_go_on_after_a_resume() {
    let dir = tempfile::tempdir().unwrap();
    let files = small_files(dir.path());
    let (plain, _) = field("2", &files, &["--steps", "1000"]);
    let frames = dir.path().join("frames");
    let ckpt = dir.path().join("pass.ckpt");
    let with = |steps: &str| {
        let args = [
            "--steps",
            steps,
            "--frames",
            frames.to_str().unwrap(),
            "--frame-every",
            "250",
            "--checkpoint",
            ckpt.to_str().unwrap(),
        ];
        field("2", &files, &args).0
    };
    with("500");
    let framed = with("1000");
    assert_eq!(framed["digest"], plain["digest"], "frames changed the run");
    let pvd = std::fs::read_to_string(frames.join("particles.pvd")).unwrap();
    for step in [0, 250, 500, 750, 1000] {
        let name = format!("frame_{step:09}.vtk");
        assert!(frames.join(&name).exists(), "{name}");
        assert!(pvd.contains(&name), "{pvd}");
    }
    assert_eq!(pvd.matches("<DataSet").count(), 5, "{pvd}");
    let out = arachis(&[
        "field",
        &files.0,
        "--harvester",
        &files.1,
        "--frames",
        "f",
        "--frame-every",
        "100",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("multiple of 250"));
}
