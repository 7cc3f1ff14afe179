//! The bench-bed rig (`rigs/bench_bed.rs`, DESIGN §8): it passes the conformance test every
//! rig passes, its settled bed obeys what granular packing allows (never denser than random
//! close packing, looser with more friction), and a study measures it like any other rig.

use std::path::Path;

use arachis::calibration::{Condition, ParameterValues, Responses, Rig, RunRequest};
use arachis::rigs::bench_bed::{
    BenchBedRig, BED_HEIGHT, COM_HEIGHT, KIND, KINETIC_ENERGY, PARTICLES, SETTLE_TIME,
};
use arachis::rigs::conformance;
use arachis::rigs::kind::RigOptions;
use arachis::study::Study;
use arachis_core::scenario::bench_bed::{
    CYLINDER_RADIUS_M, SETTLED_KINETIC_ENERGY_J, SPHERE_RADIUS_UM,
};

/// Spheres of the packing test: a bed about five diameters deep, so the floor and the top
/// layer do not dominate its packing.
const PACKING_PARTICLES: f64 = 600.0;
/// Settling time of the packing test, s: the 600 spheres fall at most 0.4 m (0.3 s).
const PACKING_SETTLE_S: f64 = 0.6;
/// Random close packing of equal spheres, the densest random packing (Scott & Kilgour
/// 1969; Torquato et al. 2000).
const RANDOM_CLOSE_PACKING: f64 = 0.64;
/// Pod–pod and pod–steel coefficients of a nearly frictionless pod (DESIGN §8 has 0.854
/// and 0.589 static, 0.346 and 0.159 rolling).
const SLIPPERY: [(&str, f64); 4] = [
    ("pod-pod.static_friction", 0.1),
    ("pod-pod.rolling_friction", 0.0),
    ("pod-steel.static_friction", 0.1),
    ("pod-steel.rolling_friction", 0.0),
];

fn condition(particles: f64, settle_time_s: f64) -> Condition {
    Condition::from([
        (PARTICLES.to_owned(), particles),
        (SETTLE_TIME.to_owned(), settle_time_s),
    ])
}

fn values(pairs: &[(&str, f64)]) -> ParameterValues {
    pairs.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect()
}

fn run(values: &ParameterValues, condition: &Condition) -> Responses {
    let request = RunRequest {
        values,
        condition,
        replicate: 0,
    };
    BenchBedRig.run(&request).unwrap_or_else(|e| panic!("{e}"))
}

/// The solid fraction of a settled bed of `particles` spheres from its centre-of-mass
/// height: the centres of a bed filled evenly to height H average H/2, so the bed fills
/// π R² · 2·com_height of the cylinder.
fn packing_fraction(particles: f64, com_height_mm: f64) -> f64 {
    let r_mm = SPHERE_RADIUS_UM as f64 / 1e3;
    let cylinder_mm = CYLINDER_RADIUS_M * 1e3;
    let solid = particles * 4.0 / 3.0 * std::f64::consts::PI * r_mm.powi(3);
    solid / (std::f64::consts::PI * cylinder_mm * cylinder_mm * 2.0 * com_height_mm)
}

#[test]
fn the_bench_bed_passes_the_rig_conformance_test() {
    // A short run of a small bed: conformance asks about the interface, not the physics.
    let values = values(&[("pod-pod.static_friction", 0.7)]);
    let checked = conformance::check_fixed(&KIND, &values, &condition(200.0, 0.05))
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(checked.responses.len(), 3);
}

#[test]
fn a_settled_bed_is_no_denser_than_random_close_packing_and_friction_loosens_it() {
    let condition = condition(PACKING_PARTICLES, PACKING_SETTLE_S);
    let design = run(&values(&[]), &condition);
    let slippery = run(&values(&SLIPPERY), &condition);
    for (name, bed) in [("DESIGN §8", &design), ("slippery", &slippery)] {
        assert!(
            bed[KINETIC_ENERGY] < SETTLED_KINETIC_ENERGY_J,
            "{name}: not settled, {bed:?}"
        );
        let phi = packing_fraction(PACKING_PARTICLES, bed[COM_HEIGHT]);
        assert!(phi < RANDOM_CLOSE_PACKING, "{name}: φ = {phi}, {bed:?}");
        // The 95th percentile of the tops lies above the mean of the centres.
        assert!(bed[BED_HEIGHT] > bed[COM_HEIGHT], "{name}: {bed:?}");
    }
    let (phi_design, phi_slippery) = (
        packing_fraction(PACKING_PARTICLES, design[COM_HEIGHT]),
        packing_fraction(PACKING_PARTICLES, slippery[COM_HEIGHT]),
    );
    assert!(
        phi_slippery > phi_design,
        "friction did not loosen the bed: φ {phi_slippery} slippery vs {phi_design}"
    );
    assert!(slippery[BED_HEIGHT] < design[BED_HEIGHT]);
}

#[test]
fn a_bad_condition_or_parameter_is_refused_before_anything_is_simulated() {
    let refused = |values: &ParameterValues, condition: &Condition, why: &str| {
        let request = RunRequest {
            values,
            condition,
            replicate: 0,
        };
        let err = BenchBedRig.specification(&request).unwrap_err().0;
        assert!(err.contains(why), "{err}");
    };
    let none = values(&[]);
    refused(&none, &condition(10.5, 0.1), "whole number");
    refused(&none, &condition(1e7, 0.1), "at most");
    refused(&none, &condition(10.0, 1e-6), "shorter than one step");
    refused(
        &none,
        &Condition::from([("lift_speed_m_s".to_owned(), 0.01)]),
        "not 'lift_speed_m_s'",
    );
    refused(
        &values(&[("pod-pod.restitution", 1.5)]),
        &condition(10.0, 0.1),
        "pod-pod.restitution",
    );
}

/// A study of the bed: its height measured at 300 spheres, pod–pod friction to calibrate.
const STUDY: &str = r#"
[study]
name = "bench-bed"
description = "pod-pod friction from the height of a poured bed"
citation = "a test study"

[[measurements]]
experiment = "bench_bed"
quantity = "bed_height"
unit = "mm"
condition = { particles = 300, settle_time_s = 0.5 }
values = [25.0, 25.5]

[parameters."pod-pod.static_friction"]
low = 0.3
high = 0.9
"#;

#[test]
fn a_study_measures_the_bench_bed_and_names_its_parameters() {
    let path = Path::new("bench-bed/study.toml");
    let study = Study::from_toml(STUDY, path).unwrap_or_else(|e| panic!("{e}"));
    let factors = study.factors();
    assert_eq!(factors.len(), 1);
    assert_eq!(factors[0].name, "pod-pod.static_friction");
    let rig = study
        .rig("bench_bed", &RigOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let measured = &study.measurements()[0];
    let request = RunRequest {
        values: &values(&[("pod-pod.static_friction", 0.6)]),
        condition: &measured.condition,
        replicate: 0,
    };
    let spec = rig
        .specification(&request)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec["particles"], 300);
    assert_eq!(spec["pod_pod"][1], 0.6);

    let in_cm = STUDY.replace("unit = \"mm\"", "unit = \"cm\"");
    let err = Study::from_toml(&in_cm, path).unwrap_err().to_string();
    assert!(err.contains("mm"), "{err}");
    let other_rig = STUDY.replace("pod-pod.static_friction", "pod.shear_modulus_pa");
    let err = Study::from_toml(&other_rig, path).unwrap_err().to_string();
    assert!(err.contains("no measured rig has it"), "{err}");
}
