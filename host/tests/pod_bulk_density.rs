//! Issue 22 item 1: the poured bulk density of whole pods (`rigs::pod_bulk_density`), on
//! seed 000's shipped study in its quick mode.
//!
//! - The slab's mass agrees with an independent count: each pod's mass spread evenly over
//!   the union of its spheres, sampled on a 0.4 mm grid.
//! - The same seed gives the same bits; another seed packs another bed.
//! - Pods with little friction pack denser than the study's pods, by more than three
//!   standard deviations of the seeds' scatter.
//! - The drop height comes from the condition, else the default; a drop height outside the
//!   accepted range is refused by `simulate` (exit 2, nothing written).

use std::collections::BTreeMap;
use std::f64::consts::PI;
use std::path::Path;

use arachis::rigs::pod_bulk_density::{run, DEFAULT_DROP_HEIGHT_MM, DROP_HEIGHT};
use arachis::rigs::pod_world::observation::{BedPod, BulkDensityDetails};
use arachis::rigs::pod_world::setup::RunInputs;
use arachis::rigs::pod_world::{
    Experiment, ModeName, Observation, ObservationDetails, ParameterValues, RunOptions,
    TemplateCache,
};
use arachis::rigs::repose_cylinder::at_rest_energy_j;
use arachis::study::Study;

use crate::cli_support::{assert_simulate_refuses_measurement, REPO_ROOT};

const STUDY: &str = "testdata/peanut-pods-saline/study.toml";

fn inputs(condition: &[(&str, f64)], values: &[(&str, f64)]) -> RunInputs {
    let study = Study::load(&Path::new(REPO_ROOT).join(STUDY)).unwrap();
    let condition: BTreeMap<String, f64> = condition
        .iter()
        .map(|(k, v)| ((*k).to_owned(), *v))
        .collect();
    let values: ParameterValues = values.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect();
    RunInputs::resolve(
        &study.pod_world().unwrap(),
        Experiment::PodBulkDensity,
        &condition,
        &values,
        ModeName::Quick,
        &TemplateCache::new(),
    )
    .unwrap()
}

fn details(o: &Observation) -> &BulkDensityDetails {
    match &o.details {
        ObservationDetails::PodBulkDensity(d) => d,
        other => panic!("not a bulk-density run: {other:?}"),
    }
}

/// Grid pitch of the independent count, mm (the quick mode's smallest sphere has a radius
/// of about 5 mm, so a sphere holds about 8 000 grid points).
const GRID_MM: f64 = 0.4;

/// Share of `pod`'s union of spheres (its volume, each point counted once) between the
/// heights `slab`, sampled on a grid of pitch [`GRID_MM`].
fn union_share(pod: &BedPod, slab: [f64; 2]) -> f64 {
    let lo = |k: usize| {
        pod.spheres
            .iter()
            .map(|s| s.centre_mm[k] - s.radius_mm)
            .fold(f64::INFINITY, f64::min)
    };
    let hi = |k: usize| {
        pod.spheres
            .iter()
            .map(|s| s.centre_mm[k] + s.radius_mm)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let points = |k: usize| ((hi(k) - lo(k)) / GRID_MM).ceil() as usize;
    let (mut inside, mut total) = (0u64, 0u64);
    for i in 0..points(0) {
        for j in 0..points(1) {
            for l in 0..points(2) {
                let p = [
                    lo(0) + (i as f64 + 0.5) * GRID_MM,
                    lo(1) + (j as f64 + 0.5) * GRID_MM,
                    lo(2) + (l as f64 + 0.5) * GRID_MM,
                ];
                let solid = pod.spheres.iter().any(|s| {
                    let d2: f64 = (0..3).map(|k| (p[k] - s.centre_mm[k]).powi(2)).sum();
                    d2 < s.radius_mm * s.radius_mm
                });
                if solid {
                    total += 1;
                    inside += u64::from(p[2] >= slab[0] && p[2] < slab[1]);
                }
            }
        }
    }
    inside as f64 / total as f64
}

#[test]
fn the_slab_mass_matches_an_independent_grid_count() {
    let i = inputs(&[], &[]);
    let o = run(&i, 1, &RunOptions::default()).unwrap();
    let d = details(&o);
    let grid_kg: f64 = d
        .bed
        .iter()
        .map(|pod| pod.mass_kg * union_share(pod, d.slab_mm))
        .sum();
    let rel = (d.slab_mass_kg - grid_kg).abs() / grid_kg;
    eprintln!(
        "slab {:?} mm: rig {:.5} kg, grid {grid_kg:.5} kg ({:.3} %); {:.1} kg/m³",
        d.slab_mm,
        d.slab_mass_kg,
        100.0 * rel,
        o.value
    );
    // The two weightings differ only for the pods cut by a plane of the slab (a sphere's
    // share against the union's), and those errors take either sign: 1 % of the mass.
    assert!(rel < 0.01, "rig and grid differ by {:.3} %", 100.0 * rel);
    // Density = mass over the slab's volume inside the cylinder (SI).
    let r_m = d.cylinder_diameter_mm / 2.0 / 1000.0;
    let slab_m = (d.slab_mm[1] - d.slab_mm[0]) / 1000.0;
    assert!((o.value - d.slab_mass_kg / (PI * r_m * r_m * slab_m)).abs() < 1e-9 * o.value);
    // The slab lies inside the bed: a pod length above the floor and below the level.
    assert!(d.slab_mm[0] > 0.0 && d.slab_mm[1] < d.level_mm && d.slab_mm[1] > d.slab_mm[0]);
    // Every pod of the mix is in the bed, and the bed is at rest.
    assert_eq!(d.bed.len(), d.pods as usize);
    assert!(d.final_kinetic_energy_j < at_rest_energy_j(&i, d.pods as usize));
}

#[test]
fn a_seed_gives_its_bits_and_another_seed_another_bed() {
    let i = inputs(&[], &[]);
    let a = run(&i, 7, &RunOptions::default()).unwrap();
    let b = run(&i, 7, &RunOptions::default()).unwrap();
    let c = run(&i, 8, &RunOptions::default()).unwrap();
    assert_eq!(a.digest, b.digest);
    assert_eq!(a.value.to_bits(), b.value.to_bits());
    assert_ne!(a.digest, c.digest);
    assert_ne!(a.value, c.value);
}

#[test]
fn smooth_pods_pack_denser_than_the_studys() {
    // The study's pods (μs 0.837–0.878, μr 0.314–0.356 against each other, held at the
    // centres) and pods with a tenth of that friction, on the same seeds.
    let smooth = [
        ("pod-pod.static_friction", 0.085),
        ("pod-pod.rolling_friction", 0.03),
        ("pod-steel.static_friction", 0.06),
        ("pod-steel.rolling_friction", 0.015),
    ];
    let seeds = 1..=4;
    let densities = |i: &RunInputs| -> Vec<f64> {
        seeds
            .clone()
            .map(|s| run(i, s, &RunOptions::default()).unwrap().value)
            .collect()
    };
    let rough = densities(&inputs(&[], &[]));
    let smooth = densities(&inputs(&[], &smooth));
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let sd = |v: &[f64]| {
        let m = mean(v);
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
    };
    let pooled = ((sd(&rough).powi(2) + sd(&smooth).powi(2)) / 2.0).sqrt();
    eprintln!("rough {rough:?}, smooth {smooth:?}, pooled SD {pooled:.2} kg/m³");
    assert!(
        mean(&smooth) - mean(&rough) > 3.0 * pooled,
        "smooth {:.1} vs rough {:.1} kg/m³, SD {pooled:.2}",
        mean(&smooth),
        mean(&rough)
    );
}

#[test]
fn the_drop_height_comes_from_the_condition_else_the_default() {
    let default = inputs(&[], &[]);
    let high = inputs(&[(DROP_HEIGHT, 300.0)], &[]);
    assert_ne!(default.spec.spec_hash(), high.spec.spec_hash());
    let at = |i: &RunInputs| details(&run(i, 1, &RunOptions::default()).unwrap()).drop_height_mm;
    assert_eq!(at(&default), DEFAULT_DROP_HEIGHT_MM);
    assert_eq!(at(&high), 300.0);
}

#[test]
fn a_drop_height_outside_its_range_is_refused_and_nothing_is_written() {
    assert_simulate_refuses_measurement(
        "pod_bulk_density",
        "experiment = \"pod_bulk_density\"\nquantity = \"bulk_density\"\nunit = \
         \"kg/m^3\"\ncondition = { drop_height_mm = 5.0 }\nmean = 300.0\nn = 3",
        "drop_height_mm",
    );
}
