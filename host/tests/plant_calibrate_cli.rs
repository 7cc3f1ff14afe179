//! `arachis plant-calibrate`, the alias of `arachis calibrate` on seed 001's built-in
//! study: it says it is an alias, writes `calibrate`'s report files and the summary line,
//! and refuses bad input with clear errors (exit status 2, no report written).

use crate::cli_support;
use cli_support::arachis;

#[test]
fn writes_the_report_and_prints_the_validation() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cal");
    let o = arachis(&[
        "plant-calibrate",
        "--out",
        out.to_str().unwrap(),
        "--quiet",
        "--jobs",
        "2",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("is an alias"));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let line: serde_json::Value = serde_json::from_str(stdout.lines().last().unwrap()).unwrap();
    assert_eq!(line["passed"], true);
    assert_eq!(line["carried"], serde_json::json!(["x7", "x8"]));
    assert!(line["relative_error_pct"].as_f64().unwrap() <= 5.0);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plant-calibration.json")).unwrap())
            .unwrap();
    assert_eq!(json["format"], "arachis-plant-calibration-1");
    assert_eq!(json["optimum"]["validated_n"], line["validated_n"]);
    // The alias writes what `calibrate` writes on the shipped study, as c5d1f03 did.
    let golden = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../testdata/golden-c5d1f03/plant-study/plant-calibration.json"
    );
    assert!(
        std::fs::read(out.join("plant-calibration.json")).unwrap()
            == std::fs::read(golden).unwrap(),
        "plant-calibrate wrote other bytes than calibrate on the shipped study"
    );
    let md = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(md.contains("passed"), "{md}");
}

#[test]
fn bad_input_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cal");
    let o = out.to_str().unwrap();
    for (args, says) in [
        (vec!["--speed", "0"], "--speed"),
        (vec!["--angle", "120"], "--angle"),
        (vec!["--target", "-1"], "target detachment force"),
        (vec!["--jobs", "0"], "--jobs"),
        (vec!["--carry", "x7,x7"], "given twice"),
        (vec!["--carry", "x7"], "2 to 3 factors"),
        (vec!["--carry", "x7,x10"], "unknown factor 'x10'"),
    ] {
        let mut all = vec!["plant-calibrate", "--out", o, "--quiet"];
        all.extend(args);
        let r = arachis(&all);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(2), "{all:?}: {err}");
        assert!(err.contains(says), "{all:?}: {err}");
        assert!(!out.join("plant-calibration.json").exists());
    }
}
