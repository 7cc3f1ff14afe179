//! Issue 23: every bad input of `testdata/bad-inputs/cases.toml`, and every bad study of
//! `testdata/bad-studies/`, run through the command line: the command exits with status 2
//! before any simulation, says each expected text (the input's file, line, key or option, and
//! the fault) in a message a person can read (no panic, no debug dump, long values cut, no
//! line twice), and leaves no file behind in the folder it was given.

use crate::cli_support;
use cli_support::{arachis_at_root, REPO_ROOT};
use serde::Deserialize;

/// Longest error output accepted, bytes: one message per fault, long values cut.
const MAX_MESSAGE_BYTES: usize = 2_000;

#[derive(Deserialize)]
struct Cases {
    case: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    args: Vec<String>,
    says: Vec<String>,
}

/// Runs `args` (with `{OUT}` an empty folder) and checks the refusal; returns its message.
fn refused(args: &[String], says: &[String]) -> String {
    let out = tempfile::tempdir().unwrap();
    let args: Vec<String> = args
        .iter()
        .map(|a| a.replace("{OUT}", out.path().to_str().unwrap()))
        .collect();
    let argv: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = arachis_at_root(&argv);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(
        o.status.code(),
        Some(2),
        "arachis {args:?}: exit {:?}; {err}",
        o.status
    );
    for text in says {
        assert!(
            err.contains(text.as_str()),
            "arachis {args:?} does not say {text:?}: {err}"
        );
    }
    assert!(
        err.len() <= MAX_MESSAGE_BYTES,
        "arachis {args:?}: {} bytes of error",
        err.len()
    );
    assert!(
        !err.contains("panicked") && !err.contains(" { "),
        "arachis {args:?}: {err}"
    );
    let left: Vec<_> = std::fs::read_dir(out.path()).unwrap().collect();
    assert!(
        left.is_empty(),
        "arachis {args:?} left {} file(s) behind",
        left.len()
    );
    err
}

#[test]
fn every_bad_input_is_refused_with_a_message_that_names_it() {
    let text =
        std::fs::read_to_string(format!("{REPO_ROOT}/testdata/bad-inputs/cases.toml")).unwrap();
    let cases: Cases = toml::from_str(&text).unwrap();
    assert!(cases.case.len() >= 30, "only {} cases", cases.case.len());
    for case in &cases.case {
        refused(&case.args, &case.says);
    }
}

#[test]
fn every_bad_study_is_refused_by_study_check() {
    let dir = format!("{REPO_ROOT}/testdata/bad-studies");
    let mut checked = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if !name.ends_with(".toml") || name == "valid.toml" {
            continue;
        }
        let args = [
            "study".to_owned(),
            "check".to_owned(),
            path.display().to_string(),
        ];
        refused(&args, &[name]);
        checked += 1;
    }
    assert!(checked >= 15, "only {checked} bad studies");
}
