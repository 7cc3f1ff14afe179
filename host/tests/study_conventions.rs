//! Contact conventions in study files (issue 18): `rolling_convention` and
//! `friction_convention` of a `[pairs."a-b"]` table reach the run's pair, name the run (so a
//! cached EDEM run is not reused for a LIGGGHTS one), and a misspelt name is refused with the
//! accepted names, the file and the line.

use std::collections::BTreeMap;
use std::path::Path;

use arachis::rigs::pod_world::experiment::Experiment;
use arachis::study::Study;

/// The shipped seed-000 study.
fn seed_study_text() -> String {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-pods-saline/study.toml");
    std::fs::read_to_string(path).unwrap()
}

/// The shipped study with `lines` added to its pod–steel pair.
fn with_pod_steel(lines: &str) -> String {
    seed_study_text().replace(
        "[pairs.\"pod-steel\"]\n",
        &format!("[pairs.\"pod-steel\"]\n{lines}\n"),
    )
}

fn load(text: &str) -> Result<Study, String> {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-pods-saline/study.toml");
    Study::from_toml(text, &path).map_err(|e| e.to_string())
}

/// The canonical run-spec JSON of the repose test at the study's own values.
fn spec_json(study: &Study) -> String {
    let values = study.current_values();
    study
        .run_spec(Experiment::Repose, &BTreeMap::new(), &values, "quick")
        .unwrap()
        .canonical_json()
}

#[test]
fn a_pair_in_liggghts_conventions_is_named_in_its_run() {
    let edem = load(&seed_study_text()).unwrap();
    let liggghts = load(&with_pod_steel(
        "rolling_convention = \"liggghts-cdt\"\nfriction_convention = \"liggghts\"",
    ))
    .unwrap();
    let pair = &liggghts.pod_world().unwrap().pairs["pod-steel"];
    assert_eq!(
        pair.conventions(),
        arachis_core::contact::Conventions::LIGGGHTS
    );
    let (a, b) = (spec_json(&edem), spec_json(&liggghts));
    assert!(
        !a.contains("convention"),
        "EDEM runs keep their old spec: {a}"
    );
    assert!(b.contains("\"rolling_convention\":\"liggghts-cdt\""), "{b}");
    assert!(b.contains("\"friction_convention\":\"liggghts\""), "{b}");
    // Naming EDEM's conventions explicitly is the same run as naming none.
    let explicit = load(&with_pod_steel(
        "rolling_convention = \"edem\"\nfriction_convention = \"edem\"",
    ))
    .unwrap();
    assert_eq!(spec_json(&explicit), a);
}

#[test]
fn a_misspelt_convention_is_refused_with_the_accepted_names_and_line() {
    let text = with_pod_steel("rolling_convention = \"liggghts\"");
    let line = text
        .lines()
        .position(|l| l.starts_with("rolling_convention"))
        .unwrap()
        + 1;
    let err = load(&text).unwrap_err();
    assert!(err.contains("'liggghts'"), "{err}");
    assert!(
        err.contains("accepted: edem, liggghts-cdt, liggghts-epsd2"),
        "{err}"
    );
    assert!(
        err.contains(&format!(":{line}:")),
        "line {line} not in {err}"
    );
}

/// Issue 23: a value the DEM core cannot hold is reported with the study key it came from
/// and the value as written (μs = 1e300 once read "pair constant = 15.07 (internal units)",
/// which named the pair's 8G* and no key). `study check` refuses it as implausible first;
/// `--allow-extreme` lets it through to the core, which must still say what it refuses.
#[test]
fn a_value_the_core_refuses_is_named_by_its_key_and_value() {
    let text = seed_study_text().replace(
        "static_friction = 0.589       # seed 000 §3.4: x7 = 0.589",
        "static_friction = 1e300",
    );
    assert!(text.contains("static_friction = 1e300"));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("study.toml");
    std::fs::write(&path, text).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_arachis"))
        .args([
            "simulate",
            "--allow-extreme",
            "--study",
            path.to_str().unwrap(),
            "incline_slide",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the study's pairs.\"pod-steel\": sliding friction μs = 1e300"),
        "{err}"
    );
}
