//! Issue 22 item 1: whole pods running out of a flat-bottomed silo (`rigs::pod_hopper`).
//!
//! - Theory: the rig run on sphere particles (the shipped study with `[spheres]` of radius
//!   4 mm in place of its pods, and smooth coefficients, like glass beads) discharges at a
//!   rate inside Beverloo's law's published spread, and passes the conformance test every
//!   rig passes (same request, same bits).
//! - Pods: at the quick calibration's optimum, the study's pods arch over an orifice of two
//!   pod lengths at once, and run through one of about six pod lengths (200 mm) without
//!   arching before the window closes.
//! - An orifice that does not fit the silo is refused by `simulate` (exit 2, the key named,
//!   nothing written).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use arachis::calibration::{Condition, ParameterValues, RunRequest};
use arachis::rigs::catalogue;
use arachis::rigs::conformance::check;
use arachis::rigs::kind::RigOptions;
use arachis::rigs::pod_hopper::{
    run, DISCHARGED_FRACTION, FLOW_WINDOW, MASS_FLOW_RATE, ORIFICE_DIAMETER,
};
use arachis::rigs::pod_world::observation::HopperDetails;
use arachis::rigs::pod_world::setup::RunInputs;
use arachis::rigs::pod_world::{
    Experiment, ModeName, ObservationDetails, RunOptions, TemplateCache,
};
use arachis::study::Study;
use arachis_core::units::STANDARD_GRAVITY_M_S2;

use crate::cli_support::{assert_simulate_refuses_measurement, REPO_ROOT};

const STUDY: &str = "testdata/peanut-pods-saline/study.toml";

/// The sphere particles' radius, mm (the bench bed's pod spheres).
const SPHERE_RADIUS_MM: f64 = 4.0;
/// Coefficients of smooth spheres, like glass beads: Beverloo's law is a law of
/// free-flowing material (as in the sphere hopper's test, `tests/hopper.rs`).
const SMOOTH: [(&str, f64); 4] = [
    ("pod-pod.static_friction", 0.3),
    ("pod-pod.rolling_friction", 0.02),
    ("pod-steel.static_friction", 0.3),
    ("pod-steel.rolling_friction", 0.02),
];
/// Orifice of the sphere test, mm: five sphere diameters, half the silo's diameter (the
/// silo is ten particle radii across, 80 mm).
const SPHERE_ORIFICE_MM: f64 = 40.0;
/// Beverloo's discharge coefficient C and empty-annulus coefficient k for spheres, the
/// spread of published fits (Nedderman 1992, *Statics and kinematics of granular
/// materials*, §10.3: C 0.55–0.65, k 1.3–2.9).
const BEVERLOO_C: (f64, f64) = (0.55, 0.65);
const BEVERLOO_K: (f64, f64) = (1.3, 2.9);
/// Solid fraction of a poured fill of spheres: random loose to random close packing.
const PACKING: (f64, f64) = (0.58, 0.64);
/// The quick calibration's optimum (`docs/calibration-quick-dem/calibration.json`), rounded.
const CALIBRATED: [(&str, f64); 3] = [
    ("pod-pod.rolling_friction", 0.0656),
    ("pod-steel.restitution", 0.132),
    ("pod-steel.static_friction", 0.685),
];
/// A narrow orifice, mm: two pod lengths (34.27 mm, seed 001 Table 1).
const NARROW_MM: f64 = 70.0;
/// A wide orifice, mm: about six pod lengths.
const WIDE_MM: f64 = 200.0;

fn study_path() -> PathBuf {
    Path::new(REPO_ROOT).join(STUDY)
}

/// The shipped study with `[spheres]` of radius [`SPHERE_RADIUS_MM`] in place of `[pods]`.
fn sphere_study() -> Study {
    let text = std::fs::read_to_string(study_path()).unwrap();
    let (start, end) = (
        text.find("[pods]").unwrap(),
        text.find("# Contact pairs.").unwrap(),
    );
    let text = format!(
        "{}[spheres]\nmaterial = \"pod\"\nradius_mm = {SPHERE_RADIUS_MM}\n\n{}",
        &text[..start],
        &text[end..]
    );
    Study::from_toml(&text, &study_path()).unwrap()
}

fn values(pairs: &[(&str, f64)]) -> ParameterValues {
    pairs.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect()
}

/// Beverloo's rate W = C·ρ_b·√g·(D − k·d)^(5/2), g/s.
fn beverloo_g_s(c: f64, packing: f64, k: f64, density_kg_m3: f64) -> f64 {
    let d_m = 2.0 * SPHERE_RADIUS_MM * 1e-3;
    let opening_m = SPHERE_ORIFICE_MM * 1e-3 - k * d_m;
    c * packing * density_kg_m3 * STANDARD_GRAVITY_M_S2.sqrt() * opening_m.powf(2.5) * 1e3
}

#[test]
fn spheres_conform_and_discharge_as_beverloo_says() {
    let study = sphere_study();
    let kind = catalogue::find("pod_hopper").unwrap();
    let options = RigOptions {
        mode: Some(ModeName::Quick),
        ..RigOptions::default()
    };
    let rig = study.rig("pod_hopper", &options).unwrap();
    let mut values = study.current_values();
    values.extend(self::values(&SMOOTH));
    let condition = Condition::from([(ORIFICE_DIAMETER.to_owned(), SPHERE_ORIFICE_MM)]);
    let request = RunRequest {
        values: &values,
        condition: &condition,
        replicate: 0,
    };
    // Conformance runs the request twice and compares the bits.
    let checked = check(kind, rig.as_ref(), &request).unwrap_or_else(|e| panic!("{e}"));
    let rate = checked.responses[MASS_FLOW_RATE];
    let density = inputs(&study, SPHERE_ORIFICE_MM, &values).pod.density_kg_m3;
    let low = beverloo_g_s(BEVERLOO_C.0, PACKING.0, BEVERLOO_K.1, density);
    let high = beverloo_g_s(BEVERLOO_C.1, PACKING.1, BEVERLOO_K.0, density);
    eprintln!(
        "spheres through {SPHERE_ORIFICE_MM} mm: {rate:.1} g/s; Beverloo {low:.1}–{high:.1} g/s"
    );
    assert!(
        (low..=high).contains(&rate),
        "{rate} g/s outside [{low}, {high}]"
    );
    // The flow ran through the whole window without arching.
    assert!(checked.responses[DISCHARGED_FRACTION] >= FLOW_WINDOW.1);
}

fn inputs(study: &Study, orifice_mm: f64, values: &ParameterValues) -> RunInputs {
    RunInputs::resolve(
        &study.pod_world().unwrap(),
        Experiment::PodHopper,
        &BTreeMap::from([(ORIFICE_DIAMETER.to_owned(), orifice_mm)]),
        values,
        ModeName::Quick,
        &TemplateCache::new(),
    )
    .unwrap()
}

fn pod_run(orifice_mm: f64) -> (f64, HopperDetails) {
    let study = Study::load(&study_path()).unwrap();
    let inputs = inputs(&study, orifice_mm, &values(&CALIBRATED));
    let o = run(&inputs, 1, &RunOptions::default()).unwrap();
    let ObservationDetails::PodHopper(d) = o.details else {
        panic!("not a hopper run")
    };
    eprintln!(
        "pods through {orifice_mm} mm: {:.0} g/s, {:.1} % out, jammed {}, window {:?} s",
        o.value,
        100.0 * d.discharged_fraction,
        d.jammed,
        d.window_s
    );
    (o.value, d)
}

#[test]
fn pods_arch_over_a_narrow_orifice_and_run_through_a_wide_one() {
    let (_, narrow) = pod_run(NARROW_MM);
    assert!(narrow.jammed);
    assert!(narrow.discharged_fraction < FLOW_WINDOW.0, "{narrow:?}");
    let (rate, wide) = pod_run(WIDE_MM);
    assert!(!wide.jammed, "{wide:?}");
    assert!(wide.discharged_fraction >= FLOW_WINDOW.1);
    // The whole window's mass over its time, as the rig defines the rate.
    let window_g = (FLOW_WINDOW.1 - FLOW_WINDOW.0) * wide.fill_mass_kg * 1e3;
    let expected = window_g / (wide.window_s[1] - wide.window_s[0]);
    assert!(
        (rate - expected).abs() < 1e-9 * expected,
        "{rate} vs {expected}"
    );
}

#[test]
fn an_orifice_that_does_not_fit_the_silo_is_refused_and_nothing_is_written() {
    assert_simulate_refuses_measurement(
        "pod_hopper",
        "experiment = \"pod_hopper\"\nquantity = \"mass_flow_rate\"\nunit = \"g/s\"\n\
         condition = { orifice_diameter_mm = 300.0 }\nmean = 3000.0\nn = 3",
        "orifice_diameter_mm = 300",
    );
}
