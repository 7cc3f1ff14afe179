//! Issue 17 must-show: the calibration and diagnosis commands write, byte for byte, what the
//! two former stacks wrote at commit c5d1f03 (`testdata/golden-c5d1f03/`, see its README).
//!
//! Cost: one surrogate calibration (milliseconds), one plant calibration (37 pulls, about
//! half a second), and the three diagnosis commands on the tutorial study (about 2 s).

use std::path::Path;

use crate::cli_support;
use cli_support::{arachis_at_root as arachis, REPO_ROOT};

/// A committed reference file.
fn golden(name: &str) -> Vec<u8> {
    let path = Path::new(REPO_ROOT)
        .join("testdata/golden-c5d1f03")
        .join(name);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// Fails with the first differing line when `actual` is not `expected`.
fn same_bytes(what: &str, actual: &[u8], expected: &[u8]) {
    if actual == expected {
        return;
    }
    let (a, e) = (
        String::from_utf8_lossy(actual),
        String::from_utf8_lossy(expected),
    );
    let line = a
        .lines()
        .zip(e.lines())
        .position(|(x, y)| x != y)
        .unwrap_or_else(|| a.lines().count().min(e.lines().count()));
    panic!(
        "{what} differs from c5d1f03 at line {}:\n  now: {:?}\n  was: {:?}",
        line + 1,
        a.lines().nth(line),
        e.lines().nth(line)
    );
}

fn stdout_of(args: &[&str]) -> Vec<u8> {
    let o = arachis(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o.stdout
}

#[test]
fn the_pod_study_on_the_surrogate_writes_the_c5d1f03_calibration() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cal");
    stdout_of(&[
        "calibrate",
        "testdata/peanut-pods-saline/study.toml",
        "--simulator",
        "surrogate",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    for file in ["calibration.json", "report.md"] {
        same_bytes(
            file,
            &std::fs::read(out.join(file)).unwrap(),
            &golden(&format!("pods-surrogate/{file}")),
        );
    }
}

#[test]
fn the_plant_study_writes_the_c5d1f03_calibration() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cal");
    stdout_of(&[
        "calibrate",
        "testdata/peanut-plant/study.toml",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    for file in ["plant-calibration.json", "report.md"] {
        same_bytes(
            file,
            &std::fs::read(out.join(file)).unwrap(),
            &golden(&format!("plant-study/{file}")),
        );
    }
}

#[test]
fn the_diagnosis_commands_print_what_they_printed_at_c5d1f03() {
    let study = "testdata/diagnosis-tutorial/measured.toml";
    for (args, file) in [
        (vec!["compare", study], "compare.stdout"),
        (vec!["diagnose", study], "diagnose.stdout"),
        (
            vec!["fit", study, "--with", "viscoelastic", "--no-loco"],
            "fit-noloco.stdout",
        ),
    ] {
        same_bytes(
            file,
            &stdout_of(&args),
            &golden(&format!("diagnosis/{file}")),
        );
    }
}

#[test]
fn study_check_prints_what_it_printed_at_c5d1f03() {
    for name in ["peanut-pods-saline", "peanut-plant"] {
        let study = format!("testdata/{name}/study.toml");
        same_bytes(
            &format!("study check {name}"),
            &stdout_of(&["study", "check", &study]),
            &golden(&format!("study-check/study-check-{name}.txt")),
        );
    }
    let pods = "testdata/peanut-pods-saline/study.toml";
    same_bytes(
        "study check --json (pods)",
        &stdout_of(&["study", "check", pods, "--json"]),
        &golden("study-check/study-check-peanut-pods-saline.json"),
    );
    // One study format (issue 17): the pull-off study's JSON is now the pod study's layout,
    // `{format, study, derived}`, its content the same as c5d1f03 printed.
    let plant = "testdata/peanut-plant/study.toml";
    let now: serde_json::Value =
        serde_json::from_slice(&stdout_of(&["study", "check", plant, "--json"])).unwrap();
    let was: serde_json::Value =
        serde_json::from_slice(&golden("study-check/study-check-peanut-plant.json")).unwrap();
    assert_eq!(now["study"], was, "the pull-off study's content changed");
    assert_eq!(now["format"], "arachis-study-1");
    assert_eq!(now["derived"]["varied"].as_array().unwrap().len(), 9);
}
