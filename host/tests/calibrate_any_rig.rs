//! `arachis calibrate` on a study of a rig that neither seed calibrated: the single-sphere
//! rebound, with a central composite box. The engine knows only the rig's parameters and
//! responses, so this study runs the same five stages as the pod and plant studies.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use crate::cli_support;
use cli_support::arachis;

/// A restitution calibration from a 0.2 m drop (three measured rebound ratios).
const REBOUND_STUDY: &str = r#"
[study]
name = "rebound-restitution"
description = "restitution of a pod sphere calibrated to its rebound from 0.2 m"
citation = "a test study"

[[measurements]]
experiment = "rebound"
quantity = "rebound_ratio"
unit = "-"
condition = { drop_height_m = 0.2 }
values = [0.52, 0.53, 0.515]

[parameters.restitution]
low = 0.3
high = 0.7

[parameters.youngs_modulus_pa]
low = 5e6
high = 1.2e7

[plan.screening]
design = "pb12"
significance = 0.05

[plan.steepest_ascent]
points = 5
step_coded = 0.5
max_points = 9

[plan.central_composite]
alpha = 1.414
centre_points = 3

[plan.validation]
max_relative_error_pct = 2.0
"#;

const MEASURED_MEAN: f64 = (0.52 + 0.53 + 0.515) / 3.0;
const ALPHA: f64 = 1.414;

/// Writes `study` into `dir` and runs `arachis calibrate` on it into `dir/out`; the
/// command's output and the output folder.
fn calibrate(dir: &Path, study: &str) -> (Output, PathBuf) {
    let path = dir.join("study.toml");
    fs::write(&path, study).unwrap();
    let out = dir.join("out");
    let o = arachis(&[
        "calibrate",
        path.to_str().unwrap(),
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    (o, out)
}

#[test]
fn a_rebound_study_calibrates_restitution_through_all_five_stages() {
    let dir = tempfile::tempdir().unwrap();
    let (o, out) = calibrate(dir.path(), REBOUND_STUDY);
    assert!(
        o.status.success(),
        "calibrate failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_slice(&fs::read(out.join("calibration.json")).unwrap()).unwrap();

    assert_eq!(json["target"]["experiment"], "rebound");
    assert!((json["target"]["value"].as_f64().unwrap() - MEASURED_MEAN).abs() < 1e-12);

    // Screening: restitution moves the rebound ratio far more than stiffness does.
    let effects = json["screening"]["effects"].as_array().unwrap();
    let effect_of = |name: &str| {
        effects
            .iter()
            .find(|e| e["name"] == name)
            .unwrap_or_else(|| panic!("no screening effect for {name}"))["effect"]
            .as_f64()
            .unwrap()
            .abs()
    };
    assert!(effect_of("restitution") > 100.0 * effect_of("youngs_modulus_pa"));

    // The box is the study's central composite: axial points at ±alpha, 3 centre points.
    let runs = json["central_composite"]["runs"].as_array().unwrap();
    let coded: Vec<Vec<f64>> = runs
        .iter()
        .map(|r| {
            r["coded"]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let axial = coded
        .iter()
        .filter(|c| c.iter().any(|x| (x.abs() - ALPHA).abs() < 1e-9))
        .count();
    let centre = coded.iter().filter(|c| c.iter().all(|x| *x == 0.0)).count();
    assert_eq!((coded.len(), axial, centre), (4 + 4 + 3, 4, 3));

    // The optimum lies inside the screening range, and a fresh run there meets the target.
    let restitution = json["optimum"]["actual"]["restitution"].as_f64().unwrap();
    assert!(restitution > 0.3 && restitution < 0.7, "{restitution}");
    let validation = &json["validation"];
    assert_eq!(validation["passed"], true);
    let simulated = validation["simulated"].as_f64().unwrap();
    assert!((simulated - MEASURED_MEAN).abs() / MEASURED_MEAN < 0.02);
    assert!(out.join("report.md").is_file());
}

#[test]
fn a_parameter_no_measured_rig_has_is_rejected_with_the_nearest_name() {
    let dir = tempfile::tempdir().unwrap();
    let misspelt = REBOUND_STUDY.replace("[parameters.restitution]", "[parameters.restitutio]");
    let (o, out) = calibrate(dir.path(), &misspelt);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("parameters.restitutio"), "{err}");
    assert!(err.contains("did you mean 'restitution'"), "{err}");
    assert!(!out.exists(), "an output folder was made");
}

#[test]
fn study_check_summarises_a_study_of_another_rig() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    fs::write(&study, REBOUND_STUDY).unwrap();
    let o = arachis(&["study", "check", study.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    for line in [
        "Study: rebound-restitution",
        "rebound rebound_ratio: 0.5216666666666666 - (n = 3, replicates) at drop_height_m = 0.2",
        "restitution                  0.3 … 0.7 -",
        "youngs_modulus_pa            5000000 … 12000000 Pa",
        "central composite: α = 1.414, 3 centre points; quadratic model",
        "validation: rebound rebound_ratio, relative error ≤ 2 %",
    ] {
        assert!(text.contains(line), "no '{line}' in\n{text}");
    }
}
