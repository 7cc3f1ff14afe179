//! `arachis doe optimize` end to end on seed 000 eq. (22) written as a fit file
//! (`testdata/seed-tables/seed000_eq22_fit.json`), and its errors on bad fit files and goals.
//!
//! Tolerance: predicted stacking angles within 0.01° of the 31.06° target (the seed prints
//! angles to 0.01°).

use std::path::{Path, PathBuf};
use std::process::Output;

use crate::cli_support;
use cli_support::arachis;

fn fixture() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../testdata/seed-tables/seed000_eq22_fit.json")
}

fn optimize(fit: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["doe", "optimize", fit.to_str().unwrap()];
    args.extend_from_slice(extra);
    arachis(&args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Seed 000 Table 7 levels of coded −1 and +1.
const LEVELS: [(&str, f64, f64); 3] = [
    ("x3", 0.327, 0.340),
    ("x4", 0.848, 0.858),
    ("x5", 0.332, 0.350),
];

#[test]
fn eq22_fit_file_target_31_06_json() {
    let o = optimize(&fixture(), &["--goal", "angle_deg=target:31.06", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let goal = &v["goals"][0];
    assert_eq!(goal["goal"], "target");
    // Default limits: the predicted range over the box, 28.133 … 32.153 (see
    // optimize_seed000_eq22.rs for the corner arithmetic).
    assert!((goal["low"].as_f64().unwrap() - 28.133).abs() < 1e-6);
    assert!((goal["high"].as_f64().unwrap() - 32.153).abs() < 1e-6);
    let solutions = v["solutions"].as_array().unwrap();
    assert_eq!(solutions.len(), 100);
    for (i, s) in solutions.iter().enumerate() {
        assert_eq!(s["rank"], i + 1);
        let angle = s["predicted"]["angle_deg"].as_f64().unwrap();
        assert!((angle - 31.06).abs() < 0.01, "rank {}: {angle}", i + 1);
        for (name, low, high) in LEVELS {
            let c = s["coded"][name].as_f64().unwrap();
            let a = s["actual"][name].as_f64().unwrap();
            assert!((-1.0..=1.0).contains(&c), "{name} coded {c}");
            let expected = 0.5 * (low + high) + c * 0.5 * (high - low);
            assert!((a - expected).abs() < 1e-12, "{name}: {a} vs {expected}");
            assert!(a >= low - 1e-12 && a <= high + 1e-12);
        }
    }
}

#[test]
fn eq22_text_table_lists_coded_actual_and_prediction() {
    let o = optimize(
        &fixture(),
        &[
            "--goal",
            "angle_deg=target:31.06:29:32@3",
            "--solutions",
            "5",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(text.contains("limits 29 to 32, importance 3"), "{text}");
    let lines: Vec<&str> = text.lines().filter(|l| !l.starts_with('#')).collect();
    assert_eq!(
        lines[0],
        "rank,desirability,x3_coded,x4_coded,x5_coded,x3,x4,x5,angle_deg"
    );
    assert_eq!(lines.len(), 6);
    for l in &lines[1..] {
        let cells: Vec<f64> = l.split(',').map(|c| c.parse().unwrap()).collect();
        assert!((cells[8] - 31.06).abs() < 0.01, "{l}");
    }
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn bad_fit_files_and_goals_exit_2_with_clear_messages() {
    let dir = tempfile::tempdir().unwrap();
    let good = std::fs::read_to_string(fixture()).unwrap();
    let missing = write(
        dir.path(),
        "missing.json",
        r#"{"response": "y", "factors": [{"name": "A", "low": null, "high": null}]}"#,
    );
    let unknown = write(
        dir.path(),
        "unknown.json",
        &good.replace("\"x5^2\"", "\"x9^2\""),
    );
    let cubic = write(
        dir.path(),
        "cubic.json",
        &good.replace("\"x5^2\"", "\"x5^3\""),
    );
    let broken = write(
        dir.path(),
        "broken.json",
        "{\n  \"response\": \"y\",\n  oops\n}",
    );
    let levels = write(
        dir.path(),
        "levels.json",
        &good.replace(
            "\"low\": 0.327, \"high\": 0.340",
            "\"low\": 0.340, \"high\": 0.327",
        ),
    );
    // Issue 23: a key given twice was read as whichever came last.
    let twice = write(
        dir.path(),
        "twice.json",
        &good.replacen(
            "\"response\": \"angle_deg\"",
            "\"response\": \"force_n\", \"response\": \"angle_deg\"",
            1,
        ),
    );
    let target = "angle_deg=target:31.06";
    let eq22 = fixture();
    let cases: Vec<(&Path, &str, String)> = vec![
        (
            &missing,
            target,
            "missing.json: coefficients: missing key".into(),
        ),
        (
            &unknown,
            target,
            "unknown.json: coefficients[9].term: unknown term 'x9^2'".into(),
        ),
        (&cubic, target, "unknown term 'x5^3'".into()),
        (
            &twice,
            target,
            "twice.json: file: the key 'response' appears twice in one object".into(),
        ),
        (
            &broken,
            target,
            "broken.json: line 3 column 3: not valid JSON".into(),
        ),
        (
            &levels,
            target,
            "factors[0].low: low level 0.34 must be below high level 0.327".into(),
        ),
        (
            &eq22,
            "force_n=target:7.18",
            "no fit file has this response".into(),
        ),
        (&eq22, "angle_deg=aim:31", "unknown goal 'aim'".into()),
        (
            &eq22,
            "angle_deg=target:35",
            "target 35 lies outside the limits".into(),
        ),
        // Issue 23: the goal in words, the number readable, no Rust debug dump.
        (
            &eq22,
            "angle_deg=target:1e300",
            "goal 'target 1e300 within ".into(),
        ),
        (
            &eq22,
            "angle_deg=range:30",
            "give both limits LOW:HIGH or none".into(),
        ),
        (&eq22, "angle_deg=range", "range needs LOW:HIGH".into()),
        (
            &eq22,
            "angle_deg=max@0",
            "importance 0 must be positive".into(),
        ),
    ];
    for (path, goal, message) in cases {
        let o = optimize(path, &["--goal", goal]);
        assert_eq!(o.status.code(), Some(2), "{goal}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&message),
            "expected '{message}' in: {}",
            stderr(&o)
        );
        assert!(o.stdout.is_empty(), "no partial output");
    }
    let o = optimize(&fixture(), &["--goal", target, "--solutions", "101"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("between 1 and 100"), "{}", stderr(&o));
}
