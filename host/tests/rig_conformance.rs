//! Every rig of the catalogue passes the rig conformance test (`rigs::conformance`, the
//! test `docs/architecture.md` asks of a new rig), each on one request it can run: the pod
//! rigs on the shipped study (the bulk density and the drum at their default conditions, the repose rig on the cheap test pile, about 25 CPU-s for its
//! two piles), the pull-off rig on seed 001's study, the single-sphere rigs on the diagnosis
//! tutorial's calibration, the harvest rig on a short drum. The two pod rigs that are
//! measurable but not simulated yet refuse to run, with a reason.

use std::path::Path;

use arachis::calibration::{Condition, ParameterValues, RunRequest};
use arachis::rigs::catalogue;
use arachis::rigs::conformance::check;
use arachis::rigs::kind::RigOptions;
use arachis::rigs::pod_world::ModeName;
use arachis::study::Study;

use crate::quick_pile_support;
use quick_pile_support::test_pile_study;

fn root(path: &str) -> String {
    format!("{}/../{path}", env!("CARGO_MANIFEST_DIR"))
}

fn load(path: &str) -> Study {
    Study::load(Path::new(&root(path))).unwrap()
}

fn quick() -> RigOptions {
    RigOptions {
        mode: Some(ModeName::Quick),
        ..RigOptions::default()
    }
}

/// Checks rig `name` of `study` at its held values and `condition`.
fn conforms(study: &Study, name: &str, condition: &Condition) {
    let kind = catalogue::find(name).unwrap();
    let rig = study.rig(name, &quick()).unwrap();
    let values = study.current_values();
    let request = RunRequest {
        values: &values,
        condition,
        replicate: 0,
    };
    let checked = check(kind, rig.as_ref(), &request).unwrap_or_else(|e| panic!("{e}"));
    println!("{name}: {:?}", checked.responses);
}

#[test]
fn the_pod_rigs_conform() {
    let study = load("testdata/peanut-pods-saline/study.toml");
    let condition = study.condition_of("repose");
    for name in ["incline_slide", "compression"] {
        conforms(&study, name, &condition);
    }
    conforms(&test_pile_study(), "repose", &condition);
    let poured = study.condition_of("pod_bulk_density");
    conforms(&study, "pod_bulk_density", &poured);
    conforms(&study, "pod_drum", &study.condition_of("pod_drum"));
}

#[test]
fn the_pull_off_rig_conforms() {
    conforms(
        &load("testdata/peanut-plant/study.toml"),
        "pull_off",
        &Condition::new(),
    );
}

#[test]
fn the_single_sphere_rigs_conform() {
    let study = load("testdata/diagnosis-tutorial/measured.toml");
    for (name, key, value) in [
        ("rebound", "drop_height_m", 0.1),
        ("press", "load_n", 0.01),
        ("fall", "fall_height_m", 0.5),
        ("unload", "peak_load_n", 0.01),
    ] {
        conforms(&study, name, &Condition::from([(key.to_owned(), value)]));
    }
}

#[test]
fn the_harvest_rig_conforms_on_a_short_drum() {
    let kind = catalogue::find("harvest").unwrap();
    let study = load("testdata/diagnosis-tutorial/measured.toml");
    let rig = study.rig("harvest", &RigOptions::default()).unwrap();
    // A 20 mm drum and a 2 m/s conveyor keep each pass short (as tests/harvest.rs does).
    let values = ParameterValues::from([
        ("machine.drum_length_m".to_owned(), 0.02),
        ("machine.forward_speed_m_s".to_owned(), 2.0),
    ]);
    let request = RunRequest {
        values: &values,
        condition: &Condition::new(),
        replicate: 0,
    };
    let checked = check(kind, rig.as_ref(), &request).unwrap_or_else(|e| panic!("{e}"));
    let loss = checked.responses["loss_rate"];
    assert!((0.0..=100.0).contains(&loss), "{loss} %");
}

#[test]
fn rigs_not_built_yet_refuse_to_run_and_say_so() {
    let study = load("testdata/peanut-pods-saline/study.toml");
    for name in ["plate_drop", "rolling"] {
        let rig = study.rig(name, &quick()).unwrap();
        let values = study.current_values();
        let condition = Condition::new();
        let request = RunRequest {
            values: &values,
            condition: &condition,
            replicate: 0,
        };
        let err = rig.run(&request).unwrap_err().0;
        assert!(err.contains("not built"), "{name}: {err}");
    }
}
