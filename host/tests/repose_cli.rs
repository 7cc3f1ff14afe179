//! `arachis lab repose PHOTO.png` on the shipped synthetic picture
//! `testdata/repose/synthetic_pile_31.06deg.png` (a 31.06° pile, seed 000's bench mean),
//! through the command's clap arguments as `arachis lab` will parse them.
//!
//! The picture is drawn by `repose_support::shipped_pile`; `shipped_png_is_the_generators`
//! checks the committed file against it, and rewrites it when run with
//! `ARACHIS_REGENERATE_REPOSE_PNG=1`.

use crate::repose_support;

use std::path::PathBuf;

use arachis::cli::lab_repose::{execute, Args};
use arachis::cli::{lab, Cli, Command};
use clap::Parser;
use repose_support::{shipped_pile, SHIPPED_ANGLE_DEG, SHIPPED_PNG};
use serde_json::Value;

/// The must-show tolerance (degrees).
const TOLERANCE_DEG: f64 = 0.5;

fn shipped() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/repose")
        .join(SHIPPED_PNG)
}

/// Parses `arachis lab repose ARGS` with the real command line; returns the repose
/// arguments and the lab-wide `--json` flag.
fn parse(args: &[&str]) -> anyhow::Result<(Args, bool)> {
    let mut argv = vec!["arachis", "lab", "repose"];
    argv.extend_from_slice(args);
    match Cli::try_parse_from(argv)?.command {
        Command::Lab(lab::Args {
            test: lab::LabTest::Repose(a),
            json,
        }) => Ok((a, json)),
        other => anyhow::bail!("parsed as another command: {other:?}"),
    }
}

/// The kind of a command-line parse error.
fn clap_kind(err: anyhow::Error) -> clap::error::ErrorKind {
    err.downcast::<clap::Error>()
        .expect("a command-line parse error")
        .kind()
}

fn run(args: &[&str]) -> anyhow::Result<String> {
    let (args, json) = parse(args)?;
    let mut out = Vec::new();
    execute(args, json, &mut out)?;
    Ok(String::from_utf8(out)?)
}

#[test]
fn shipped_png_is_the_generators() {
    let expected = shipped_pile();
    if std::env::var_os("ARACHIS_REGENERATE_REPOSE_PNG").is_some() {
        expected.save(shipped()).unwrap();
    }
    let stored = image::open(shipped()).unwrap().to_luma8();
    assert_eq!(stored.dimensions(), expected.dimensions());
    assert!(stored.as_raw() == expected.as_raw(), "shipped PNG differs");
}

#[test]
fn json_on_the_shipped_picture() {
    let file = shipped();
    let text = run(&[file.to_str().unwrap(), "--json", "--mm-per-px", "0.5"]).unwrap();
    let json: Value = serde_json::from_str(&text).unwrap();
    let angle = json["angle_deg"].as_f64().unwrap();
    let (left, right) = (
        json["left"]["angle_deg"].as_f64().unwrap(),
        json["right"]["angle_deg"].as_f64().unwrap(),
    );
    eprintln!("shipped 31.06° picture: {angle:.3}° (left {left:.3}°, right {right:.3}°)");
    for a in [angle, left, right] {
        assert!((a - SHIPPED_ANGLE_DEG).abs() < TOLERANCE_DEG, "{a}°");
    }
    assert_eq!(json["polarity"], "dark-pile");
    assert_eq!(json["otsu_threshold"], true);
    assert_eq!(json["band"]["low"], 0.2);
    let height_px = json["height_px"].as_f64().unwrap();
    assert_eq!(json["height_mm"].as_f64(), Some(0.5 * height_px));
    assert!(json["left"]["line"]["r_squared"].as_f64().unwrap() > 0.999);
}

#[test]
fn text_and_svg_on_the_shipped_picture() {
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("pile.svg");
    let file = shipped();
    let text = run(&[
        file.to_str().unwrap(),
        "--svg",
        svg.to_str().unwrap(),
        "--fit-band",
        "0.3:0.7",
        "--dark-pile",
        "--threshold",
        "140",
    ])
    .unwrap();
    assert!(text.starts_with("repose angle of "), "{text}");
    assert!(text.contains("threshold 140 (given), dark pile"), "{text}");
    assert!(text.contains("between 30% and 70%"), "{text}");
    let printed: f64 = text
        .split(": ")
        .nth(1)
        .and_then(|s| s.split('°').next())
        .unwrap()
        .parse()
        .unwrap();
    assert!(
        (printed - SHIPPED_ANGLE_DEG).abs() < TOLERANCE_DEG,
        "{text}"
    );
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(picture.starts_with("<svg"), "not an SVG");
    assert!(picture.contains(&format!("repose angle {printed:.2}°")));
    assert!(picture.contains("left ") && picture.contains("right "));
}

#[test]
fn bad_arguments_and_files_are_clear_errors() {
    let file = shipped();
    let path = file.to_str().unwrap();
    let conflict = parse(&[path, "--dark-pile", "--light-pile"]).unwrap_err();
    assert_eq!(
        clap_kind(conflict),
        clap::error::ErrorKind::ArgumentConflict
    );
    let band = parse(&[path, "--fit-band", "0.9:0.1"])
        .unwrap_err()
        .to_string();
    assert!(band.contains("low < high"), "{band}");
    let threshold = parse(&[path, "--threshold", "300"]).unwrap_err();
    assert_eq!(
        clap_kind(threshold),
        clap::error::ErrorKind::ValueValidation
    );

    // A missing photograph: the error names it, and no SVG is left behind.
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.png");
    let svg = dir.path().join("out.svg");
    let err = run(&[missing.to_str().unwrap(), "--svg", svg.to_str().unwrap()]).unwrap_err();
    let message = format!("{err:#}");
    assert!(
        message.contains("cannot read image") && message.contains("missing.png"),
        "{message}"
    );
    assert!(!svg.exists());
}
