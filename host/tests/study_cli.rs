//! `arachis study check` on the shipped study and on a bad one, through the real binary.

use crate::cli_support;
use cli_support::arachis_at_root as arachis;

#[test]
fn shipped_study_checks_and_exports_json() {
    let out = arachis(&[
        "study",
        "check",
        "testdata/peanut-pods-saline/study.toml",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["format"], "arachis-study-1");
    assert_eq!(json["study"]["parameters"].as_object().unwrap().len(), 8);
    assert_eq!(json["derived"]["target_value"], 31.06);
}

#[test]
fn bad_study_lists_every_error_and_exits_2() {
    let out = arachis(&["study", "check", "testdata/bad-studies/range_reversed.toml"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("testdata/bad-studies/range_reversed.toml:"),
        "{err}"
    );
    assert!(err.contains("low"), "{err}");
}

/// Issue 23: `--allow-extreme` accepts implausible values (research may need them) and warns
/// once for each; without it they are refused with exit status 2.
#[test]
fn allow_extreme_turns_implausible_values_into_warnings() {
    let study = "testdata/bad-studies/implausible_values.toml";
    let refused = cli_support::arachis_at_root(&["study", "check", study]);
    assert_eq!(refused.status.code(), Some(2));
    let allowed = cli_support::arachis_at_root(&["study", "check", study, "--allow-extreme"]);
    let err = String::from_utf8_lossy(&allowed.stderr);
    assert!(allowed.status.success(), "{err}");
    assert_eq!(
        err.matches("warning: accepted with --allow-extreme")
            .count(),
        5,
        "{err}"
    );
}
