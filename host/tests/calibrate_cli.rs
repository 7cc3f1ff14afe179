//! `arachis calibrate` through the real binary: bad studies stop before any simulation,
//! and killing the process part-way then rerunning gives a byte-identical final JSON.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use crate::cli_support;
use cli_support::{arachis_at_root as arachis, REPO_ROOT as ROOT};
const STUDY: &str = "testdata/peanut-pods-saline/study.toml";

fn calibrate_args<'a>(study: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "calibrate",
        study,
        "--simulator",
        "surrogate",
        "--quiet",
        "--out",
        out,
    ]
}

/// Rejects `file` with its path, `key` and `reason` on stderr, exit status 2, and no
/// output folder (nothing was simulated).
fn rejected(file: &str, key: &str, reason: &str) {
    let out_dir = tempfile::tempdir().unwrap();
    let out = out_dir.path().join("out");
    let path = format!("testdata/bad-studies/{file}");
    let o = arachis(&calibrate_args(&path, out.to_str().unwrap()));
    assert_eq!(o.status.code(), Some(2), "{file}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&path), "{file}: no file in {err}");
    assert!(err.contains(key), "{file}: no key {key} in {err}");
    assert!(
        err.contains(reason),
        "{file}: no reason '{reason}' in {err}"
    );
    assert!(!out.exists(), "{file}: an output folder was made");
}

#[test]
fn an_unknown_parameter_is_rejected_before_any_simulation() {
    rejected(
        "unknown_parameter.toml",
        r#"parameters."pod-pod.static_fricton""#,
        "unknown parameter 'pod-pod.static_fricton'",
    );
}

#[test]
fn a_reversed_range_is_rejected_before_any_simulation() {
    rejected(
        "range_reversed.toml",
        r#"parameters."pod-pod.static_friction".low"#,
        "low 0.878 > high 0.837",
    );
}

#[test]
fn a_missing_measurement_is_rejected_before_any_simulation() {
    rejected(
        "missing_measurement.toml",
        "plan.target.experiment",
        "missing measurement",
    );
}

#[test]
fn an_unreadable_stl_is_rejected_before_any_simulation() {
    rejected(
        "missing_stl.toml",
        "pods.stl.normal",
        "unreadable STL 'scans/no-such-pod.stl'",
    );
    rejected(
        "not_an_stl.toml",
        "pods.stl.cocoon",
        "fewer than the 84-byte binary header",
    );
}

#[test]
fn the_surrogate_run_prints_its_results_and_no_bar_when_piped() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    // No --quiet: stderr is a pipe here, so the bar must hide itself.
    let o = arachis(&[
        "calibrate",
        STUDY,
        "--quick",
        "--simulator",
        "surrogate",
        "--jobs",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("most significant x4 (pod-pod.static_friction)"),
        "{text}"
    );
    assert!(text.contains("relative error"), "{text}");
    assert!(out.join("calibration.json").is_file() && out.join("report.md").is_file());
}

fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .map(|d| {
            d.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

#[test]
fn killing_the_calibration_and_rerunning_gives_a_byte_identical_json() {
    let dir = tempfile::tempdir().unwrap();
    let reference = dir.path().join("reference");
    let o = arachis(&calibrate_args(STUDY, reference.to_str().unwrap()));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let expected = std::fs::read(reference.join("calibration.json")).unwrap();
    // Kill points: pseudo-random (the clock's nanoseconds), printed so a failure can be
    // replayed. 81 runs × 10 ms on 2 threads take about 0.4 s plus start-up.
    let nanos = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap()
        .subsec_nanos();
    for (i, base_ms) in [60_u64, 200, 350].into_iter().enumerate() {
        let kill_ms = base_ms + u64::from(nanos >> (4 * i)) % 100;
        println!("kill after {kill_ms} ms");
        let out = dir.path().join(format!("killed{i}"));
        let mut child = Command::new(env!("CARGO_BIN_EXE_arachis"))
            .args(calibrate_args(STUDY, out.to_str().unwrap()))
            .args(["--jobs", "2", "--surrogate-delay-ms", "10"])
            .current_dir(ROOT)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(kill_ms));
        let _ = child.kill();
        let status = child.wait().unwrap();
        let finished = status.success();
        let kept = files(&out.join("runs")).len();
        println!("killed run {i}: finished = {finished}, {kept} run files kept");
        let o = arachis(&calibrate_args(STUDY, out.to_str().unwrap()));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = String::from_utf8_lossy(&o.stdout);
        if !finished {
            assert!(text.contains(" replayed from "), "{text}");
        }
        assert!(
            std::fs::read(out.join("calibration.json")).unwrap() == expected,
            "kill after {kill_ms} ms: the resumed JSON differs"
        );
        assert_eq!(
            files(&out.join("runs")),
            files(&reference.join("runs")),
            "no temporary file is left"
        );
    }
}

#[test]
fn jobs_zero_is_refused() {
    let o = arachis(&[
        "calibrate",
        STUDY,
        "--simulator",
        "surrogate",
        "--jobs",
        "0",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

/// A target far outside what the model gives in the seed's ranges (60° instead of 31.06°),
/// with the path held to seed 000's five points (no `max_points`), completes the
/// calibration and reports the missed validation: exit status 0 by default, 2 with
/// `--strict`.
#[test]
fn a_missed_validation_is_reported_and_fails_only_with_strict() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(Path::new(ROOT).join(STUDY)).unwrap();
    let unreachable = text.replacen("mean = 31.06 ", "mean = 60.0 ", 1).replacen(
        "max_points = ",
        "# max_points = ",
        1,
    );
    assert_eq!(
        unreachable.len(),
        text.len() - 1 + 2,
        "the study's target or max_points line moved"
    );
    let study = dir.path().join("study.toml");
    std::fs::write(&study, unreachable).unwrap();
    let study = study.to_str().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let o = arachis(&calibrate_args(study, out));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("validation failed"), "{stdout}");
    let mut strict = calibrate_args(study, out);
    strict.push("--strict");
    let o = arachis(&strict);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("validation failed"));
}
