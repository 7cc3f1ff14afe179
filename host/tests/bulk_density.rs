//! The poured bulk-density rig (`rigs/bulk_density.rs`): it passes the conformance test every
//! rig passes, nearly frictionless spheres pack as densely as random close packing allows
//! beside a wall, friction and rolling resistance loosen the bed in their order, cohesion
//! loosens it further, and too few spheres to cover the measuring slab are refused.

use arachis::calibration::{Condition, ParameterValues, Rig, RunRequest};
use arachis::rigs::bulk_density::{BulkDensityRig, BULK_DENSITY, DROP_HEIGHT, KIND, PARTICLES};
use arachis::rigs::conformance;
use arachis_core::scenario::bench_bed::SPHERE_RADIUS_UM;
use arachis_core::scenario::bulk_density::{BulkDensity, CYLINDER_RADIUS_M, RANDOM_CLOSE_PACKING};
use arachis_core::scenario::materials::POD;

/// Drop height of the physics tests, mm.
const DROP_HEIGHT_MM: f64 = 300.0;
/// Nearly frictionless spheres: the limit in which a poured bed reaches random close packing.
const FRICTIONLESS: [(&str, f64); 4] = [
    ("pod-pod.static_friction", 0.01),
    ("pod-pod.rolling_friction", 0.0),
    ("pod-steel.static_friction", 0.01),
    ("pod-steel.rolling_friction", 0.0),
];
/// Smooth spheres, like glass beads.
const SMOOTH: [(&str, f64); 4] = [
    ("pod-pod.static_friction", 0.3),
    ("pod-pod.rolling_friction", 0.02),
    ("pod-steel.static_friction", 0.3),
    ("pod-steel.rolling_friction", 0.02),
];
/// SJKR cohesion energy density of the cohesion test, J/m³: strong enough to stand out of
/// one pair of runs (measured 2026-11-27 on smooth spheres at 300 mm: 5e4 J/m³ lowered the
/// density by about 9 kg/m³, 1e5 by 6–22, 2e5 by 32–38).
const COHESION_J_M3: f64 = 2.0e5;
/// Solid fraction in the half sphere diameter next to a flat wall, at least: a wall lets
/// spheres touch it along one layer only (measured radial profiles of random packings put
/// the mean of that band at 0.45–0.5; Mueller 1992, Powder Technology 72).
const WALL_BAND_FRACTION_MIN: f64 = 0.40;
/// Standard deviation of the bulk density between insertion seeds, kg/m³: measured 2.8 over
/// 13 pairs of seeds at seven settings and three drop heights (2026-11-27).
const SCATTER_KG_M3: f64 = 3.0;

fn values(base: &[(&str, f64)], extra: &[(&str, f64)]) -> ParameterValues {
    base.iter()
        .chain(extra)
        .map(|(k, v)| ((*k).to_owned(), *v))
        .collect()
}

fn bulk_density(values: &ParameterValues) -> f64 {
    let condition = Condition::from([(DROP_HEIGHT.to_owned(), DROP_HEIGHT_MM)]);
    let request = RunRequest {
        values,
        condition: &condition,
        replicate: 0,
    };
    BulkDensityRig
        .run(&request)
        .unwrap_or_else(|e| panic!("{e}"))[BULK_DENSITY]
}

#[test]
fn the_bulk_density_rig_passes_the_rig_conformance_test() {
    let values = values(&SMOOTH, &[]);
    let condition = Condition::from([
        (DROP_HEIGHT.to_owned(), 150.0),
        (
            PARTICLES.to_owned(),
            f64::from(BulkDensity::min_particles()),
        ),
    ]);
    let checked =
        conformance::check_fixed(&KIND, &values, &condition).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(checked.responses.len(), 1);
}

#[test]
fn too_few_spheres_to_cover_the_slab_are_refused() {
    let values = values(&SMOOTH, &[]);
    let condition = Condition::from([
        (DROP_HEIGHT.to_owned(), 150.0),
        (
            PARTICLES.to_owned(),
            f64::from(BulkDensity::min_particles() - 1),
        ),
    ]);
    let request = RunRequest {
        values: &values,
        condition: &condition,
        replicate: 0,
    };
    let e = BulkDensityRig.run(&request).unwrap_err();
    assert!(e.0.contains("particles"), "{e}");
}

#[test]
fn poured_beds_pack_by_their_friction_and_cohesion() {
    // The frictionless limit: random close packing (0.64) away from the wall; in the band
    // of half a diameter along the cylinder's wall, no less than WALL_BAND_FRACTION_MIN.
    let r_mm = SPHERE_RADIUS_UM as f64 / 1e3;
    let rc_mm = CYLINDER_RADIUS_M * 1e3;
    let band = 1.0 - ((rc_mm - r_mm) / rc_mm).powi(2);
    let lowest = RANDOM_CLOSE_PACKING * (1.0 - band) + WALL_BAND_FRACTION_MIN * band;
    let frictionless = bulk_density(&values(&FRICTIONLESS, &[])) / POD.density_kg_m3;
    println!("frictionless: solid fraction {frictionless:.3} (bounds {lowest:.3}–{RANDOM_CLOSE_PACKING})");
    assert!(
        (lowest..=RANDOM_CLOSE_PACKING).contains(&frictionless),
        "solid fraction {frictionless:.3} outside [{lowest:.3}, {RANDOM_CLOSE_PACKING}]"
    );

    // Friction and rolling resistance hold the bed open: smooth spheres pack looser, the
    // pods' own coefficients (μs 0.854, μr 0.346) looser still; each step by far more than
    // the scatter between insertion seeds.
    let smooth = bulk_density(&values(&SMOOTH, &[]));
    let pods = bulk_density(&ParameterValues::new());
    let sticky = bulk_density(&values(
        &SMOOTH,
        &[("pod-pod.cohesion_j_m3", COHESION_J_M3)],
    ));
    println!(
        "bulk density: frictionless {:.1}, smooth {smooth:.1}, smooth + cohesion {sticky:.1}, \
         pods {pods:.1} kg/m³",
        frictionless * POD.density_kg_m3
    );
    // Three standard deviations of a difference of two single runs.
    let apart = 3.0 * std::f64::consts::SQRT_2 * SCATTER_KG_M3;
    assert!(frictionless * POD.density_kg_m3 - smooth > apart);
    assert!(smooth - pods > apart);
    assert!(
        smooth - sticky > apart,
        "cohesion {COHESION_J_M3} J/m³ moved the density by {:.1} kg/m³",
        smooth - sticky
    );
}
