//! `arachis doe analyze` end to end: a JSON run on a seed table, and bad input that must
//! exit with status 2 and a message naming the file (and line and column where they apply).

use std::path::PathBuf;
use std::process::Output;

use serde_json::Value;

use crate::cli_support;
use cli_support::arachis;

fn seed_table(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/seed-tables")
        .join(file)
}

/// Runs `doe analyze` on `text` written to `name` in a temporary directory; returns the
/// output and the file's path as passed.
fn analyze_text(name: &str, text: &str, extra: &[&str]) -> (Output, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, text).unwrap();
    let path = path.to_str().unwrap().to_owned();
    let mut args = vec!["doe", "analyze", path.as_str(), "--response", "y"];
    args.extend_from_slice(extra);
    (arachis(&args), path)
}

fn assert_fails_with(output: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    assert!(
        stderr.contains(needle),
        "stderr {stderr:?} lacks {needle:?}"
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
}

const SEED_001_LEVELS: &str = "X1=0.61:0.82,X2=0.45:0.76,X3=0.16:0.33,X4=0.42:0.68,\
X5=0.32:0.54,X6=0.18:0.39,X7=3:7,X8=6:14,X9=1:1.2";

#[test]
fn json_for_seed_001_table_6() {
    let file = seed_table("seed001_table6_plackett_burman.csv");
    let output = arachis(&[
        "doe",
        "analyze",
        file.to_str().unwrap(),
        "--response",
        "force_n",
        "--model",
        "linear",
        "--levels",
        SEED_001_LEVELS,
        "--json",
    ]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let v: Value = serde_json::from_slice(&output.stdout).unwrap();
    let num = |pointer: &str| v.pointer(pointer).and_then(Value::as_f64).unwrap();
    // Seed 001 Table 7, to the printed digits.
    assert!((num("/model/ss") - 55.67).abs() <= 0.005);
    assert_eq!(v["model"]["df"], 9);
    assert_eq!(v["residual"]["df"], 4);
    assert!((num("/residual/ss") - 0.7053).abs() <= 0.00005);
    assert!((num("/lack_of_fit/f") - 0.8947).abs() <= 0.00005);
    assert!((num("/pure_error/ss") - 0.3723).abs() <= 0.00005);
    assert_eq!(v["curvature"]["df"], 1);
    assert!((num("/r2") - 0.9875).abs() <= 0.00005);
    assert_eq!(v["terms"][7]["name"], "X8");
    assert!((num("/terms/7/f") - 192.84).abs() <= 0.005);
    assert_eq!(v["coefficients"][0]["term"], "Intercept");
    assert!((num("/coefficients/8/estimate") + 1.68).abs() <= 0.005);
    assert!(num("/coefficients/8/se") > 0.0);
    for key in ["adj_r2", "pred_r2", "adeq_precision", "cv_percent"] {
        assert!(v[key].is_f64(), "{key}");
    }
    assert_eq!(v["response"], "force_n");
    assert_eq!(v["factors"][0]["name"], "X1");
    assert_eq!(v["factors"][0]["low"], 0.61);
    assert_eq!(v["factors"][8]["high"], 1.2);
}

#[test]
fn json_nulls_without_replicates_or_centre_points() {
    // A coded 2³ factorial without replicates: no pure error, lack of fit or curvature, and
    // the factors carry no actual levels.
    let text = "run,A,B,C,y\n1,-1,-1,-1,10.1\n2,1,-1,-1,12.3\n3,-1,1,-1,9.2\n4,1,1,-1,11.9\n\
                5,-1,-1,1,10.8\n6,1,-1,1,13.5\n7,-1,1,1,9.9\n8,1,1,1,12.2\n";
    let (output, _) = analyze_text("coded.csv", text, &["--model", "linear", "--json"]);
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let v: Value = serde_json::from_slice(&output.stdout).unwrap();
    assert!(v["lack_of_fit"].is_null() && v["pure_error"].is_null() && v["curvature"].is_null());
    assert!(v["factors"][2]["low"].is_null() && v["factors"][2]["high"].is_null());
    assert_eq!(v["residual"]["df"], 4);
}

#[test]
fn human_table_has_design_expert_rows() {
    let file = seed_table("seed001_table6_plackett_burman.csv");
    let output = arachis(&[
        "doe",
        "analyze",
        file.to_str().unwrap(),
        "--response",
        "force_n",
        "--model",
        "linear",
        "--levels",
        SEED_001_LEVELS,
    ]);
    let text = String::from_utf8(output.stdout).unwrap();
    for needle in [
        "Sum of Squares",
        "Curvature",
        "Lack of Fit",
        "not significant",
        "Pure Error",
        "Cor Total",
        "R²",
        "Final equation in terms of coded factors",
    ] {
        assert!(text.contains(needle), "missing {needle:?} in\n{text}");
    }
}

#[test]
fn ragged_csv_names_file_and_line() {
    let (output, path) = analyze_text("ragged.csv", "A,y\n-1,1\n1\n", &["--model", "linear"]);
    assert_fails_with(
        &output,
        &format!("{path}:3: row has 1 cells but the header has 2"),
    );
}

#[test]
fn non_numeric_cell_names_file_line_and_column() {
    let text = "# a comment line\nA,B,y\n-1,-1,1\n1,abc,2\n-1,1,3\n1,1,4\n";
    let (output, path) = analyze_text("cells.csv", text, &["--model", "linear"]);
    assert_fails_with(
        &output,
        &format!("{path}:4: column 'B': 'abc' is not a finite number"),
    );
}

#[test]
fn factor_with_one_level_is_refused() {
    let text = "A,B,y\n-1,0.5,1\n1,0.5,2\n-1,0.5,3\n1,0.5,5\n";
    let (output, path) = analyze_text("one_level.csv", text, &["--model", "linear"]);
    assert_fails_with(
        &output,
        &format!("{path}: column 'B': factor has a single level (0.5)"),
    );
}

#[test]
fn saturated_model_is_refused() {
    // A 2² factorial and the 2FI model: four parameters for four runs.
    let text = "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,3\n1,1,5\n";
    let (output, path) = analyze_text("saturated.csv", text, &["--model", "2fi"]);
    assert_fails_with(&output, &path);
    assert_fails_with(&output, "no residual degrees of freedom (saturated model)");
}

#[test]
fn aliased_term_is_named() {
    // A replicated 2^(3−1) fraction with C = A·B: the 2FI model cannot separate A*B from C.
    let text = "A,B,C,y\n-1,-1,1,1\n1,-1,-1,2\n-1,1,-1,3\n1,1,1,5\n\
                -1,-1,1,1.2\n1,-1,-1,2.1\n-1,1,-1,2.8\n1,1,1,5.3\n";
    let (output, _) = analyze_text("aliased.csv", text, &["--model", "2fi"]);
    assert_fails_with(&output, "term 'A*B' is aliased with 'C'");
}

#[test]
fn actual_units_need_levels() {
    let file = seed_table("seed000_table4_plackett_burman.csv");
    let output = arachis(&[
        "doe",
        "analyze",
        file.to_str().unwrap(),
        "--response",
        "angle_deg",
        "--model",
        "linear",
    ]);
    assert_fails_with(&output, "column 'x1' is not in coded units");
    assert_fails_with(&output, "--levels x1=LOW:HIGH");
}

#[test]
fn level_off_the_printed_table_names_line_and_column() {
    let text = "A,y\n0.327,1\n0.335,2\n0.340,3\n0.327,1.5\n";
    let (output, path) = analyze_text(
        "levels.csv",
        text,
        &["--model", "linear", "--levels", "A=0.327:0.334:0.340"],
    );
    assert_fails_with(
        &output,
        &format!("{path}:3: column 'A': 0.335 is none of the printed levels"),
    );
}

/// Issue 23: a factor given twice in --levels was read at its first levels.
#[test]
fn a_factor_given_twice_in_levels_is_refused() {
    let text = "A,y\n0.327,1\n0.340,2\n0.327,1.5\n0.340,2.5\n";
    let (output, _) = analyze_text(
        "twice.csv",
        text,
        &[
            "--model",
            "linear",
            "--levels",
            "A=0.327:0.340",
            "--levels",
            "A=0:1",
        ],
    );
    assert_fails_with(
        &output,
        "--levels gives factor 'A' twice ('A=0.327:0.340' and 'A=0:1')",
    );
}

#[test]
fn missing_file_is_an_error() {
    let output = arachis(&[
        "doe",
        "analyze",
        "/nonexistent/d.csv",
        "--response",
        "y",
        "--model",
        "linear",
    ]);
    assert_fails_with(&output, "/nonexistent/d.csv: cannot read");
}
