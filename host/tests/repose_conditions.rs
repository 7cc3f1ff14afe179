//! Issue 22 item 1: the repose rig's conditions. A measurement may give the lifting speed and
//! the cylinder's diameter (at full scale); each replaces the study's value in the run, a
//! quick mode scales the diameter as it scales the study's own, a run without them is
//! specified exactly as before, and a cylinder narrower than a pod is refused, not run.

use std::collections::BTreeMap;
use std::path::Path;

use arachis::rigs::pod_world::setup::RunInputs;
use arachis::rigs::pod_world::{Experiment, ModeName, ParameterValues, TemplateCache};
use arachis::rigs::repose_cylinder::{Layout, CYLINDER_DIAMETER, KIND, LIFT_SPEED};
use arachis::study::Study;

use crate::cli_support;
use cli_support::REPO_ROOT;

const STUDY: &str = "testdata/peanut-pods-saline/study.toml";
/// The study's cylinder diameter (seed 000 §2.7 assumption in the study file), mm.
const STUDY_DIAMETER_MM: f64 = 200.0;

fn inputs(condition: &[(&str, f64)]) -> Result<RunInputs, String> {
    let study = Study::load(&Path::new(REPO_ROOT).join(STUDY)).unwrap();
    let condition: BTreeMap<String, f64> = condition
        .iter()
        .map(|(k, v)| ((*k).to_owned(), *v))
        .collect();
    RunInputs::resolve(
        &study.pod_world().unwrap(),
        Experiment::Repose,
        &condition,
        &ParameterValues::new(),
        ModeName::Quick,
        &TemplateCache::new(),
    )
    .map_err(|e| e.to_string())
}

#[test]
fn the_catalogue_offers_both_conditions_within_ranges() {
    let lift = KIND.condition(LIFT_SPEED).unwrap();
    let diameter = KIND.condition(CYLINDER_DIAMETER).unwrap();
    // Seed 000's own values are accepted, a lift of 2 m/s and a 5 m cylinder are not.
    assert!(lift.check(0.05).is_ok() && diameter.check(200.0).is_ok());
    assert!(lift.check(2.0).is_err() && diameter.check(5000.0).is_err());
}

#[test]
fn a_measured_diameter_replaces_the_studys_and_is_scaled_like_it() {
    let base = inputs(&[(LIFT_SPEED, 0.05)]).unwrap();
    let wide = inputs(&[(LIFT_SPEED, 0.05), (CYLINDER_DIAMETER, 150.0)]).unwrap();
    assert_eq!(
        base.simulation.repose.cylinder_diameter_mm,
        STUDY_DIAMETER_MM
    );
    assert_eq!(wide.simulation.repose.cylinder_diameter_mm, 150.0);
    // The quick mode's 150 pods in a cylinder scaled by (150 / 900)^(1/3), both alike.
    let scale = (f64::from(base.mode.pods) / f64::from(base.full_pods.unwrap())).cbrt();
    let d = |i: &RunInputs| Layout::new(i, 1).unwrap().diameter_mm;
    assert!((d(&base) - STUDY_DIAMETER_MM * scale).abs() < 1e-9);
    assert!((d(&wide) - 150.0 * scale).abs() < 1e-9);
    // Another run: its own specification and cache entry.
    assert_ne!(base.spec.spec_hash(), wide.spec.spec_hash());
}

#[test]
fn a_measured_lift_speed_replaces_the_studys() {
    let slow = inputs(&[(LIFT_SPEED, 0.01)]).unwrap();
    assert_eq!(slow.simulation.repose.lift_speed_m_s, 0.01);
    assert_ne!(
        slow.spec.spec_hash(),
        inputs(&[(LIFT_SPEED, 0.05)]).unwrap().spec.spec_hash()
    );
}

#[test]
fn a_cylinder_narrower_than_a_pod_is_refused() {
    let narrow = inputs(&[(CYLINDER_DIAMETER, 20.0)]).unwrap();
    let e = Layout::new(&narrow, 1).unwrap_err().to_string();
    assert!(e.contains("narrower than one pod"), "{e}");
}
