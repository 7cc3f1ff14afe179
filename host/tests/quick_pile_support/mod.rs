//! The cheap DEM pile the repose tests run: the shipped study's quick mode set to
//! [`TEST_PODS`] pods of [`TEST_SPHERES_PER_POD`] spheres (the shipped quick mode fills each
//! pod with 6), about 11–15 CPU-s a pile in release.

use std::path::Path;

use arachis::study::Study;

/// The shipped study.
pub const STUDY: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../testdata/peanut-pods-saline/study.toml"
);
/// Pods in the test pile (in the same cylinder scaling as the quick mode's).
pub const TEST_PODS: u32 = 150;
/// Spheres per pod of the test pile.
pub const TEST_SPHERES_PER_POD: u32 = 3;

/// The shipped study with its quick mode replaced by the test pile.
pub fn test_pile_study() -> Study {
    let text = std::fs::read_to_string(STUDY).unwrap();
    let mut in_quick = false;
    let mut replaced = 0;
    let lines: Vec<String> = text
        .lines()
        .map(|line| {
            if line.starts_with('[') {
                in_quick = line.trim() == "[plan.modes.quick]";
            }
            if in_quick && line.starts_with("spheres_per_pod") {
                replaced += 1;
                format!("spheres_per_pod = {TEST_SPHERES_PER_POD}")
            } else if in_quick && line.starts_with("pods") {
                replaced += 1;
                format!("pods = {TEST_PODS}")
            } else {
                line.to_owned()
            }
        })
        .collect();
    assert_eq!(
        replaced, 2,
        "the study's quick mode lacks pods or spheres_per_pod"
    );
    Study::from_toml(&lines.join("\n"), Path::new(STUDY)).unwrap()
}
