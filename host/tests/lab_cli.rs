//! `arachis lab <test> FILE.csv` end to end: the shipped example files work out of the box,
//! `--json` prints one object that agrees with the library, and bad input exits with
//! status 2 and a message naming file, line and column.

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::cli_support;
use cli_support::arachis;

fn testdata(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/lab")
        .join(name)
}

fn stdout(o: &Output) -> String {
    String::from_utf8(o.stdout.clone()).unwrap()
}

#[test]
fn every_test_runs_on_its_shipped_example() {
    let tests = [
        "density",
        "poisson",
        "hertz-modulus",
        "shear-modulus",
        "tensile-modulus",
        "restitution-plate",
        "restitution-camera",
        "static-friction",
        "rolling-friction",
        "bond",
    ];
    for test in tests {
        let file = testdata(&format!("{}.csv", test.replace('-', "_")));
        let out = arachis(&["lab", test, file.to_str().unwrap()]);
        assert!(
            out.status.success(),
            "{test}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let text = stdout(&out);
        assert!(text.contains("95% CI low"), "{test}: {text}");
    }
}

#[test]
fn hertz_modulus_table_and_json() {
    let file = testdata("hertz_modulus.csv");
    let out = arachis(&["lab", "hertz-modulus", file.to_str().unwrap()]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert!(
        text.lines()
            .any(|l| l.starts_with("apparent_modulus  MPa   10")),
        "{text}"
    );

    let out = arachis(&["lab", "hertz-modulus", file.to_str().unwrap(), "--json"]);
    assert!(out.status.success());
    let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(json["test"], "hertz-modulus");
    let q = &json["quantities"][0];
    assert_eq!(q["name"], "apparent_modulus");
    assert_eq!(q["unit"], "Pa");
    assert_eq!(q["n"], 10);
    // The JSON mean is the library's mean on the same file.
    let table = arachis::io::CsvTable::read(&file).unwrap();
    let report = arachis::lab::hertz_modulus::analyze(&table, Default::default()).unwrap();
    let mean = report.quantity("apparent_modulus").unwrap().summary.mean;
    assert!((q["mean"].as_f64().unwrap() - mean).abs() <= 1e-9 * mean);
    // And the mean is the mean of the replicates listed.
    let reps = q["replicates"].as_array().unwrap();
    let by_hand = reps
        .iter()
        .map(|r| r["value"].as_f64().unwrap())
        .sum::<f64>()
        / reps.len() as f64;
    assert!((by_hand - mean).abs() <= 1e-9 * mean);
}

#[test]
fn static_friction_json_is_one_object() {
    let file = testdata("static_friction.csv");
    let out = arachis(&["lab", "static-friction", "--json", file.to_str().unwrap()]);
    assert!(out.status.success());
    let text = stdout(&out);
    assert_eq!(text.trim().lines().count(), 1);
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["quantities"][0]["name"], "static_friction");
}

#[test]
fn negative_deformation_exits_2_naming_file_line_column() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("pods.csv");
    std::fs::write(
        &file,
        "# two pods\nforce_n,deformation_mm,upper_r1_mm,upper_r2_mm,poisson\n15,1.0,8,16,0.386\n15,-0.5,8,16,0.386\n",
    )
    .unwrap();
    let out = arachis(&["lab", "hertz-modulus", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        err.trim_end(),
        format!(
            "error: {}:4: column 'deformation_mm': deformation must be positive, got -0.5",
            file.display()
        )
    );
}

#[test]
fn ragged_csv_exits_2() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("angles.csv");
    std::fs::write(&file, "pod,angle_deg\n1,30.5\n2\n").unwrap();
    let out = arachis(&["lab", "static-friction", file.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(
        err.trim_end(),
        format!(
            "error: {}:3: row has 1 cells but the header has 2",
            file.display()
        )
    );
}

#[test]
fn help_lists_the_columns_with_units() {
    let out = arachis(&["lab", "restitution-plate", "--help"]);
    assert!(out.status.success());
    let text = stdout(&out);
    for col in ["drop_height_mm", "h1_mm", "s1_mm", "h2_mm", "s2_mm"] {
        assert!(text.contains(col), "{col} missing from:\n{text}");
    }
}
