//! Every file in `testdata/bad-studies/` is rejected before any simulation, with the file,
//! the key path, the line:column and the reason (issue 4 must-show: an unknown parameter, a
//! range with low > high, a missing measurement, an unreadable STL; and the other checks).
//!
//! Expected positions are not typed in: each test finds the line of the offending text in
//! the file itself, so the test checks the loader's line numbers against the file.

use std::path::{Path, PathBuf};

use arachis::study::{Study, StudyError, StudyErrors};

fn bad(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/bad-studies")
        .join(name)
}

fn rejected(name: &str) -> StudyErrors {
    match Study::load(&bad(name)) {
        Ok(_) => panic!("{name} was accepted"),
        Err(e) => e,
    }
}

/// The error at `key`; fails listing every error if there is none.
fn at<'a>(errors: &'a StudyErrors, key: &str) -> &'a StudyError {
    errors
        .errors()
        .iter()
        .find(|e| e.key.to_string() == key)
        .unwrap_or_else(|| panic!("no error at {key}; got:\n{errors}"))
}

/// 1-based line of the first line of `name` containing `text` at or after line `from`.
fn line_of(name: &str, text: &str, from: usize) -> usize {
    let content = std::fs::read_to_string(bad(name)).unwrap();
    content
        .lines()
        .enumerate()
        .skip(from.saturating_sub(1))
        .find(|(_, l)| l.contains(text))
        .map(|(i, _)| i + 1)
        .unwrap_or_else(|| panic!("'{text}' not in {name}"))
}

/// Asserts the common shape of a rejection: the file is named, the key is given, the
/// message line is `file:line:col: key: reason`.
fn check(e: &StudyError, name: &str, line: usize, reason: &str) {
    assert!(e.file.ends_with(name), "file {:?}", e.file);
    assert_eq!(e.position.map(|p| p.0), Some(line), "line of {e}");
    assert!(e.reason.contains(reason), "reason of {e}\nlacks: {reason}");
    let text = e.to_string();
    assert!(
        text.contains(&format!("{name}:{line}:")),
        "message lacks file:line: {text}"
    );
    assert!(
        text.contains(&e.key.to_string()),
        "message lacks key: {text}"
    );
}

#[test]
fn the_valid_base_loads() {
    let study = Study::load(&bad("valid.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(study.varied().len(), 4);
}

#[test]
fn unknown_parameter_names_the_nearest_known_one() {
    let name = "unknown_parameter.toml";
    let errors = rejected(name);
    let e = at(&errors, r#"parameters."pod-pod.static_fricton""#);
    let line = line_of(name, "static_fricton", 1);
    check(e, name, line, "unknown parameter 'pod-pod.static_fricton'");
    assert!(e.reason.contains("did you mean 'pod-pod.static_friction'?"));
    // The key name starts after `[parameters.` on that line: column 13.
    assert_eq!(e.position, Some((line, 13)));
}

#[test]
fn reversed_range_is_rejected_at_low() {
    let name = "range_reversed.toml";
    let errors = rejected(name);
    assert_eq!(errors.errors().len(), 1, "{errors}");
    let e = at(&errors, r#"parameters."pod-pod.static_friction".low"#);
    check(
        e,
        name,
        line_of(name, "low = 0.878", 1),
        "low 0.878 > high 0.837",
    );
}

#[test]
fn empty_range_is_rejected() {
    let name = "range_empty.toml";
    let errors = rejected(name);
    let e = at(&errors, r#"parameters."pod-pod.static_friction".low"#);
    check(e, name, line_of(name, "low = 0.85", 1), "low = high = 0.85");
}

#[test]
fn ranges_outside_physical_limits_are_rejected() {
    let name = "friction_negative.toml";
    let e = rejected(name);
    let e = at(&e, r#"parameters."pod-steel.static_friction".low"#);
    check(
        e,
        name,
        line_of(name, "low = -0.1", 1),
        "friction coefficient must be ≥ 0",
    );

    let name = "effect_negative.toml";
    let e = rejected(name);
    let e = at(&e, r#"pairs."pod-pod".cohesion_j_m3"#);
    check(
        e,
        name,
        line_of(name, "cohesion_j_m3 = -500.0", 1),
        "must be ≥ 0",
    );

    let name = "restitution_above_one.toml";
    let e = rejected(name);
    let e = at(&e, r#"parameters."pod-pod.restitution".high"#);
    check(
        e,
        name,
        line_of(name, "high = 1.2", 1),
        "restitution coefficient must lie in (0, 1]",
    );

    let name = "poisson_above_half.toml";
    let e = rejected(name);
    let e = at(&e, r#"parameters."pod.poisson".high"#);
    check(
        e,
        name,
        line_of(name, "high = 0.586", 1),
        "Poisson ratio must lie in (−1, 0.5)",
    );
    assert!(e.reason.contains("poisson_above_half = true"), "{e}");
}

#[test]
fn missing_target_measurement_is_rejected() {
    let name = "missing_measurement.toml";
    let errors = rejected(name);
    let target_line = line_of(name, "[plan.target]", 1) + 1;
    let e = at(&errors, "plan.target.experiment");
    check(e, name, target_line, "missing measurement");
    assert!(e.reason.contains("repose repose_angle"), "{e}");
    let e = at(&errors, "plan.validation.experiment");
    check(
        e,
        name,
        line_of(name, "[plan.validation]", 1) + 1,
        "missing measurement",
    );
}

#[test]
fn missing_and_non_stl_files_are_rejected() {
    let name = "missing_stl.toml";
    let errors = rejected(name);
    let e = at(&errors, "pods.stl.normal");
    check(
        e,
        name,
        line_of(name, "no-such-pod.stl", 1),
        "unreadable STL 'scans/no-such-pod.stl'",
    );
    // Resolved against the study's folder, not the working directory.
    assert!(
        e.reason.contains("bad-studies/scans/no-such-pod.stl"),
        "{e}"
    );

    let name = "not_an_stl.toml";
    let errors = rejected(name);
    let e = at(&errors, "pods.stl.cocoon");
    check(
        e,
        name,
        line_of(name, "not-an-stl.stl", 1),
        "the file has 51 bytes, fewer than the 84-byte binary header, and does not start with 'solid'",
    );
}

#[test]
fn shape_mix_must_sum_to_one() {
    let name = "shape_mix_sum.toml";
    let errors = rejected(name);
    let e = at(&errors, "pods.shape_mix");
    check(
        e,
        name,
        line_of(name, "[pods.shape_mix]", 1),
        "sum to 1.1, not 1",
    );
}

#[test]
fn unknown_key_suggests_the_accepted_one() {
    let name = "unknown_key.toml";
    let errors = rejected(name);
    let e = at(&errors, "materials.pod.densty_kg_m3");
    check(
        e,
        name,
        line_of(name, "densty_kg_m3", 1),
        "unknown key 'densty_kg_m3'",
    );
    assert!(e.reason.contains("did you mean 'density_kg_m3'?"), "{e}");
}

#[test]
fn wrong_type_is_rejected_at_the_value() {
    let name = "wrong_type.toml";
    let errors = rejected(name);
    let e = at(&errors, r#"parameters."pod-pod.static_friction".low"#);
    let line = line_of(name, r#"low = "0.837""#, 1);
    check(
        e,
        name,
        line,
        r#"invalid type: string "0.837", expected a number"#,
    );
    // The value starts after `low = `: column 7.
    assert_eq!(e.position, Some((line, 7)));
}

#[test]
fn unknown_section_is_rejected() {
    let name = "unknown_section.toml";
    let errors = rejected(name);
    let e = at(&errors, "plna");
    check(
        e,
        name,
        line_of(name, "[plna.model]", 1),
        "unknown section 'plna'",
    );
    assert!(e.reason.contains("did you mean 'plan'?"), "{e}");
    // The missing [plan.model] is reported too.
    assert!(at(&errors, "plan.model")
        .reason
        .contains("missing key 'model'"));
}

#[test]
fn syntax_error_names_line_and_column() {
    let name = "syntax_error.toml";
    let errors = rejected(name);
    let e = &errors.errors()[0];
    check(
        e,
        name,
        line_of(name, "name = \"bad-study", 1),
        "not valid TOML",
    );
}

#[test]
fn every_independent_error_is_reported_at_once() {
    let name = "many_errors.toml";
    let errors = rejected(name);
    let expected = [
        ("materials.steel.density_kg_m3", "must be > 0"),
        ("pods.shape_mix", "sum to 1.1"),
        ("pods.stl.normal", "unreadable STL"),
        (
            r#"parameters."pod-pod.static_fricton""#,
            "unknown parameter",
        ),
        (r#"parameters."pod-pod.rolling_friction".low"#, "reversed"),
        ("plan.modes.quick.pods", "pods must be ≥ 1"),
    ];
    for (key, reason) in expected {
        let e = at(&errors, key);
        assert!(e.reason.contains(reason), "{e}");
    }
    // The misspelt x4 is reported once, not again as a missing pod-pod static friction.
    assert!(
        !errors
            .errors()
            .iter()
            .any(|e| e.reason.contains("no static_friction")),
        "{errors}"
    );
    // Sorted top to bottom for the reader.
    let lines: Vec<usize> = errors
        .errors()
        .iter()
        .filter_map(|e| e.position.map(|p| p.0))
        .collect();
    assert!(lines.windows(2).all(|w| w[0] <= w[1]), "{lines:?}");
    assert!(errors
        .to_string()
        .starts_with("study rejected before any simulation: 6 errors"));
}

#[test]
fn a_missing_study_file_is_an_error_naming_it() {
    let errors = rejected("no-such-study.toml");
    let e = &errors.errors()[0];
    assert!(e.file.ends_with("no-such-study.toml"));
    assert!(e.reason.contains("cannot read the study file"), "{e}");
}

/// Issue 23: a study name that holds a path (`x/../../../escaped`) is refused where it is
/// written, before `calibrate` could make `calibration-NAME-MODE` three folders up.
#[test]
fn a_name_with_a_path_is_refused() {
    let name = "name_escapes.toml";
    let errors = rejected(name);
    let e = at(&errors, "study.name");
    check(e, name, line_of(name, "escaped", 1), "may not hold '/'");
}

/// Issue 23: counts beyond their limits are refused by the loader (so by `study check`), at
/// their keys, before `calibrate` could try to allocate them.
#[test]
fn counts_beyond_their_limits_are_refused_at_their_keys() {
    let name = "counts_too_large.toml";
    let errors = rejected(name);
    for (key, text) in [
        ("plan.steepest_ascent.points", "points = 1000000000"),
        (
            "plan.box_behnken.centre_points",
            "centre_points = 100000000",
        ),
        ("plan.modes.quick.pods", "pods = 4000000000"),
    ] {
        let e = at(&errors, key);
        check(e, name, line_of(name, text, 1), "at most");
    }
}

/// Issue 23: a study that is not UTF-8 text is refused with the line of its first bad byte.
#[test]
fn a_file_that_is_not_utf8_is_refused_at_its_line() {
    let errors = rejected("not_utf8.toml").to_string();
    assert!(errors.contains("not_utf8.toml"), "{errors}");
    assert!(errors.contains("not UTF-8 text"), "{errors}");
    assert!(errors.contains("line 3"), "{errors}");
}

/// Issue 23: values the contact model admits but no agricultural study has (a density or a
/// gravity of 1e300, a shear modulus of 1e-300, a friction of 1e300, a repose angle of
/// −31.06°) are refused at their keys, naming the plausible range (`src/plausible.rs`).
#[test]
fn implausible_values_are_refused_at_their_keys() {
    let name = "implausible_values.toml";
    let errors = rejected(name);
    for (key, text) in [
        ("materials.pod.density_kg_m3", "density_kg_m3 = 1e300"),
        (
            "materials.steel.shear_modulus_pa",
            "shear_modulus_pa = 1e-300",
        ),
        (
            r#"pairs."pod-steel".static_friction"#,
            "static_friction = 1e300",
        ),
        ("measurements[1].mean", "mean = -31.06"),
        ("plan.simulation.gravity_m_s2", "gravity_m_s2 = 1e300"),
    ] {
        let e = at(&errors, key);
        check(e, name, line_of(name, text, 1), "outside the plausible");
    }
}

/// Issue 23: a `[parameters]` range is held to the same plausible range as the value it
/// varies (friction up to 1e300 was accepted).
#[test]
fn an_implausible_parameter_range_is_rejected() {
    let name = "range_implausible.toml";
    let errors = rejected(name);
    let e = at(&errors, "parameters.\"pod-pod.static_friction\".high");
    check(
        e,
        name,
        line_of(name, "high = 1e300", 1),
        "outside the plausible 0 to 10",
    );
}
