//! The hopper rig (`rigs/hopper.rs`): it passes the conformance test every rig passes, its
//! discharge of nearly frictionless spheres follows Beverloo's law within the law's own
//! published spread, and cohesion chokes a small orifice far more than a large one, the
//! signature that makes the orifice diameter a diagnostic condition.

use arachis::calibration::{Condition, ParameterValues, Rig, RunRequest};
use arachis::rigs::conformance;
use arachis::rigs::hopper::{HopperRig, KIND, MASS_FLOW_RATE, ORIFICE_DIAMETER, PARTICLES};
use arachis_core::scenario::bench_bed::SPHERE_RADIUS_UM;
use arachis_core::scenario::materials::POD;
use arachis_core::units::STANDARD_GRAVITY_M_S2;

/// Coefficients of smooth spheres, like glass beads (the pods' own, μs 0.854 and μr 0.346,
/// jam orifices of up to seven diameters): Beverloo's law is a law of free-flowing material.
const SMOOTH: [(&str, f64); 4] = [
    ("pod-pod.static_friction", 0.3),
    ("pod-pod.rolling_friction", 0.02),
    ("pod-steel.static_friction", 0.3),
    ("pod-steel.rolling_friction", 0.02),
];
/// Orifice diameters of the test, mm: five to seven sphere diameters.
const SMALL_MM: f64 = 40.0;
const MIDDLE_MM: f64 = 48.0;
const LARGE_MM: f64 = 56.0;
/// Beverloo's discharge coefficient C and empty-annulus coefficient k for spheres, the
/// spread of published fits (Nedderman 1992, *Statics and kinematics of granular
/// materials*, §10.3: C 0.55–0.65, k 1.3–2.9).
const BEVERLOO_C: (f64, f64) = (0.55, 0.65);
const BEVERLOO_K: (f64, f64) = (1.3, 2.9);
/// Solid fraction of the poured fill, random loose to random close packing of spheres.
const PACKING: (f64, f64) = (0.58, 0.64);
/// SJKR cohesion energy density of the cohesion test, J/m³: a contact's attraction at a
/// sphere's own weight (Bond number about one is near 1.4e4).
const COHESION_J_M3: f64 = 5.0e4;

fn values(extra: &[(&str, f64)]) -> ParameterValues {
    SMOOTH
        .iter()
        .chain(extra)
        .map(|(k, v)| ((*k).to_owned(), *v))
        .collect()
}

fn flow(values: &ParameterValues, diameter_mm: f64) -> f64 {
    let condition = Condition::from([(ORIFICE_DIAMETER.to_owned(), diameter_mm)]);
    let request = RunRequest {
        values,
        condition: &condition,
        replicate: 0,
    };
    HopperRig.run(&request).unwrap_or_else(|e| panic!("{e}"))[MASS_FLOW_RATE]
}

/// Beverloo's rate W = C·ρ_b·√g·(D − k·d)^(5/2), g/s, for an orifice of `diameter_mm`.
fn beverloo_g_s(c: f64, packing: f64, k: f64, diameter_mm: f64) -> f64 {
    let d_particle_m = 2.0 * SPHERE_RADIUS_UM as f64 * 1e-6;
    let bulk_density = packing * POD.density_kg_m3;
    let kg_s = c
        * bulk_density
        * STANDARD_GRAVITY_M_S2.sqrt()
        * (diameter_mm * 1e-3 - k * d_particle_m).powf(2.5);
    kg_s * 1e3
}

#[test]
fn the_hopper_passes_the_rig_conformance_test() {
    // A small silo: conformance asks about the interface, not the physics.
    let values = values(&[]);
    let condition = Condition::from([
        (ORIFICE_DIAMETER.to_owned(), MIDDLE_MM),
        (PARTICLES.to_owned(), 100.0),
    ]);
    let checked =
        conformance::check_fixed(&KIND, &values, &condition).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(checked.responses.len(), 1);
}

#[test]
fn smooth_spheres_discharge_as_beverloo_says_and_cohesion_chokes_small_orifices() {
    let smooth = values(&[]);
    let [small, middle, large] = [SMALL_MM, MIDDLE_MM, LARGE_MM].map(|d| flow(&smooth, d));
    println!("smooth spheres: {small:.1}, {middle:.1}, {large:.1} g/s at {SMALL_MM}, {MIDDLE_MM}, {LARGE_MM} mm");

    // The rate at the middle orifice lies within Beverloo's law over its published spread
    // of C, k and the fill's packing (slowest: small C, loose, large k).
    let slowest = beverloo_g_s(BEVERLOO_C.0, PACKING.0, BEVERLOO_K.1, MIDDLE_MM);
    let fastest = beverloo_g_s(BEVERLOO_C.1, PACKING.1, BEVERLOO_K.0, MIDDLE_MM);
    assert!(
        (slowest..=fastest).contains(&middle),
        "{middle:.1} g/s outside Beverloo's [{slowest:.1}, {fastest:.1}]"
    );
    // How the rate grows with the orifice: ((D₂ − kd)/(D₁ − kd))^(5/2) over the spread of
    // k (C and the packing cancel).
    let ratio = |k: f64| beverloo_g_s(1.0, 1.0, k, LARGE_MM) / beverloo_g_s(1.0, 1.0, k, SMALL_MM);
    let (lo, hi) = (ratio(BEVERLOO_K.0), ratio(BEVERLOO_K.1));
    assert!(small < middle && middle < large);
    assert!(
        (lo..=hi).contains(&(large / small)),
        "rate ratio {:.2} outside Beverloo's [{lo:.2}, {hi:.2}]",
        large / small
    );

    // Cohesion holds the spheres together over the small orifice (an arch) while the large
    // one still runs: the relative loss at the small orifice is the larger by far.
    let sticky = values(&[("pod-pod.cohesion_j_m3", COHESION_J_M3)]);
    let (small_c, large_c) = (flow(&sticky, SMALL_MM), flow(&sticky, LARGE_MM));
    println!("cohesion {COHESION_J_M3} J/m³: {small_c:.1} and {large_c:.1} g/s");
    let (loss_small, loss_large) = (1.0 - small_c / small, 1.0 - large_c / large);
    assert!(
        loss_small > 0.5 && loss_large < 1.0 / 3.0,
        "cohesion cost {loss_small:.2} of the small orifice's rate, {loss_large:.2} of the large"
    );
}
