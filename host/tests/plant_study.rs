//! Issue 6 §4: seed 001's calibration plan run by `arachis calibrate` from the shipped study
//! `testdata/peanut-plant/study.toml` (37 pulls, about 2 s), and bad plant studies rejected
//! before any pull with file, key and reason.
//!
//! The bad studies are the shipped study with one edit each (so they stay in step with it),
//! written next to a copy of its topology.

use std::path::{Path, PathBuf};
use std::process::Output;

use arachis::study::Study;

use crate::cli_support;
use cli_support::arachis;

fn study_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-plant")
}

fn shipped() -> PathBuf {
    study_dir().join("study.toml")
}

fn calibrate_into(out: &Path) -> (Output, serde_json::Value, Vec<u8>) {
    let o = arachis(&[
        "calibrate",
        shipped().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--strict",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let bytes = std::fs::read(out.join("plant-calibration.json")).unwrap();
    let json = serde_json::from_slice(&bytes).unwrap();
    (o, json, bytes)
}

#[test]
fn shipped_study_calibrates_through_the_cli_and_reruns_bit_identically() {
    let dir = tempfile::tempdir().unwrap();
    let (o, json, first) = calibrate_into(&dir.path().join("a"));
    let stdout = String::from_utf8_lossy(&o.stdout);

    // The plan ran as the study states it: 12 + 3 screening runs, then a central composite
    // design on x7 and x8 with α = 1.414 and five centre points (seed 001 Tables 6, 9, 10).
    assert_eq!(json["study"], "peanut-plant-pull-off");
    assert_eq!(json["screening"]["runs"].as_array().unwrap().len(), 15);
    let ccd = &json["central_composite"];
    assert_eq!(ccd["alpha"], 1.414);
    let labels: Vec<&str> = ccd["factors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["x7", "x8"]);
    let runs = ccd["runs"].as_array().unwrap();
    let coded = |r: &serde_json::Value| -> Vec<f64> {
        r["coded"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let at_centre = runs
        .iter()
        .filter(|r| coded(r).iter().all(|&x| x == 0.0))
        .count();
    assert_eq!(at_centre, 5);
    // 4 cube + 4 axial + 5 centre runs; the axial ones at ±1.414.
    assert_eq!(runs.len(), 13);
    let axial = runs
        .iter()
        .filter(|r| coded(r).iter().any(|x| (x.abs() - 1.414).abs() < 1e-12))
        .count();
    assert_eq!(axial, 4);

    // What our screening flagged and what the design used are both reported.
    assert_eq!(
        json["screening"]["screening_choice"],
        serde_json::json!(["x8", "x9"])
    );
    assert_eq!(
        json["screening"]["carried"],
        serde_json::json!(["x7", "x8"])
    );
    let md = std::fs::read_to_string(dir.path().join("a/report.md")).unwrap();
    assert!(md.contains("seed 001 §3.1 carries X7 and X8"), "{md}");
    assert!(
        md.contains(r#"The screening's choice (p ≤ 0.01): ["x8", "x9"]"#),
        "{md}"
    );

    // The must-show: the validation pull within 5 % of the measured 7.18 N.
    let target = 7.18;
    assert_eq!(json["target_n"], target);
    let validated = json["optimum"]["validated_n"].as_f64().unwrap();
    assert!(
        (validated - target).abs() / target <= 0.05,
        "validated {validated} N"
    );
    assert_eq!(json["optimum"]["passed"], true);
    // Independent check: an axial pull breaks the junction in pure tension at σc·πRb²
    // (DESIGN §2), computed here from the optimum's x8 (σc) and x9 (Rb). Tolerance 1 %.
    let s = json["optimum"]["settings"].as_array().unwrap();
    let (sigma, rb) = (s[7].as_f64().unwrap(), s[8].as_f64().unwrap());
    let axial = sigma * std::f64::consts::PI * rb * rb;
    assert!(
        (validated - axial).abs() / axial < 0.01,
        "{validated} N vs σc·πRb² {axial} N"
    );
    assert!(stdout.contains("validation: pulled"), "{stdout}");

    // A rerun into another folder writes the same bytes.
    let (_, _, second) = calibrate_into(&dir.path().join("b"));
    assert!(
        first == second,
        "plant-calibration.json differs between runs"
    );
}

/// The shipped study with `edit` applied, written beside a copy of its topology.
fn bad_study(dir: &Path, name: &str, edit: impl Fn(&str) -> String) -> PathBuf {
    let topology = "topology-small.toml";
    std::fs::copy(study_dir().join(topology), dir.join(topology)).unwrap();
    let text = std::fs::read_to_string(shipped()).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "{name}: the edit changed nothing");
    let path = dir.join(name);
    std::fs::write(&path, edited).unwrap();
    path
}

/// 1-based line of the first line of `path` containing `text`.
fn line_of(path: &Path, text: &str) -> usize {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .position(|l| l.contains(text))
        .unwrap()
        + 1
}

/// One bad study: file name, the edit, the key and reason expected, and the text on the
/// line the error must point at (when the file has the key).
type Case = (
    &'static str,
    Box<dyn Fn(&str) -> String>,
    &'static str,
    &'static str,
    Option<&'static str>,
);

#[test]
fn bad_plant_studies_are_rejected_before_any_pull() {
    let dir = tempfile::tempdir().unwrap();
    let cases: Vec<Case> = vec![
        (
            "unknown_factor.toml",
            Box::new(|t| t.replace("[factors.x9]", "[factors.x10]")),
            "factors.x10",
            "unknown factor 'x10'",
            Some("[factors.x10]"),
        ),
        (
            "missing_factor.toml",
            Box::new(|t| t.replace("[factors.x9]", "[factors.x10]")),
            "factors.x9",
            "missing factor x9",
            None,
        ),
        (
            "low_above_high.toml",
            Box::new(|t| t.replace("low = 3.0e5", "low = 8.0e5")),
            "factors.x7.low",
            "low 800000 must be below high 700000",
            Some("low = 8.0e5"),
        ),
        (
            "missing_measurement.toml",
            Box::new(|t| {
                let start = t.find("[measurement]").unwrap();
                let end = t.find("# The nine factors").unwrap();
                format!("{}{}", &t[..start], &t[end..])
            }),
            "measurement",
            "missing section [measurement]",
            None,
        ),
        (
            "negative_force.toml",
            Box::new(|t| t.replace("value_n = 7.18", "value_n = -7.18")),
            "measurement.value_n",
            "must be > 0 N",
            Some("value_n = -7.18"),
        ),
        (
            "unknown_ccd_factor.toml",
            Box::new(|t| t.replace(r#"factors = ["x7", "x8"]"#, r#"factors = ["x7", "x12"]"#)),
            "plan.central_composite.factors",
            "unknown factor 'x12'",
            Some(r#"factors = ["x7", "x12"]"#),
        ),
        (
            "unknown_bond_set.toml",
            Box::new(|t| {
                t.replace(
                    r#"junction_bond_set = "pod_stalk""#,
                    r#"junction_bond_set = "pod_stem""#,
                )
            }),
            "rig.junction_bond_set",
            "no bond set 'pod_stem'",
            Some("junction_bond_set"),
        ),
        (
            "misspelt_key.toml",
            Box::new(|t| t.replace("alpha = 1.414", "alfa = 1.414")),
            "plan.central_composite.alfa",
            "unknown key 'alfa'",
            Some("alfa = 1.414"),
        ),
    ];
    for (name, edit, key, reason, line_text) in &cases {
        let path = bad_study(dir.path(), name, edit);
        // Library: every error names file, key, line and reason.
        let errors = Study::load(&path).expect_err(name);
        let e = errors
            .errors()
            .iter()
            .find(|e| e.key.to_string() == *key)
            .unwrap_or_else(|| panic!("{name}: no error at {key}:\n{errors}"));
        assert!(e.reason.contains(reason), "{name}: {}", e.reason);
        assert_eq!(e.file, path);
        if let Some(text) = line_text {
            assert_eq!(
                e.position.map(|p| p.0),
                Some(line_of(&path, text)),
                "{name}: {e}"
            );
        }
        // CLI: exit status 2, the message on stderr, nothing written.
        let out = dir.path().join(format!("out-{name}"));
        let o = arachis(&[
            "calibrate",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(
            err.contains("rejected before any simulation"),
            "{name}: {err}"
        );
        assert!(
            err.contains(name) && err.contains(key) && err.contains(reason),
            "{name}: {err}"
        );
        assert!(!out.exists(), "{name}: an output folder was written");
    }
}

#[test]
fn seed000_options_are_refused_for_a_plant_study() {
    for (flag, says) in [
        ("--quick", "no run modes"),
        ("--simulator=surrogate", "surrogate"),
    ] {
        let o = arachis(&["calibrate", shipped().to_str().unwrap(), flag, "--quiet"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag}: {err}");
        assert!(err.contains(says), "{flag}: {err}");
    }
}

#[test]
fn study_check_validates_a_plant_study() {
    let o = arachis(&["study", "check", shipped().to_str().unwrap()]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.contains("central composite on x7, x8 (α = 1.414, 5 centre points)"),
        "{out}"
    );
    let o = arachis(&["study", "check", shipped().to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["study"]["measurement"]["value_n"], 7.18);
    assert_eq!(v["study"]["factors"]["x8"]["high"], 1.4e6);
    assert_eq!(v["derived"]["target_value"], 7.18);
}
