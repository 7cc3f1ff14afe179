//! Issue 22 item 1: the dynamic angle of repose of whole pods in a rotating drum
//! (`rigs::pod_drum`), on seed 000's shipped study in its quick mode.
//!
//! - Theory: a settled bed of the study's pods turned slowly by a small angle is lifted as a
//!   rigid block, so the reading (the direction of the bed's centre of mass seen from the
//!   axis) turns with the drum.
//! - The same seed gives the same bits; pods with a tenth of the study's pod–pod friction
//!   (the pod–steel pair as the study has it, so the bed cannot slip on the shell) flow at a
//!   lower angle than the study's pods, by more than three standard deviations of the seeds'
//!   scatter.
//! - The layout keeps every pod inside the drum and a cell apart from its neighbours.

use std::collections::BTreeMap;
use std::path::Path;

use arachis::rigs::pod_drum::{run, spin, DrumLayout, MAX_SETTLE_S, ROTATION_SPEED};
use arachis::rigs::pod_world::frames::FrameRecorder;
use arachis::rigs::pod_world::setup::{
    add_materials, run_steps, set_rayleigh_timestep, settle, steps_for, Arena, RunInputs,
};
use arachis::rigs::pod_world::{
    Experiment, ModeName, ObservationDetails, ParameterValues, RunOptions, TemplateCache,
};
use arachis::rigs::repose_cylinder::{at_rest_energy_j, CELL_GAP_MM, CHECK_INTERVAL_S, MIN_FILL_S};
use arachis::study::Study;
use arachis_core::scenario::drum::bed_angle_deg;

use crate::cli_support::REPO_ROOT;

const STUDY: &str = "testdata/peanut-pods-saline/study.toml";

/// The tests' drum speed, rpm: twice the default, so a run turns its 6 rad in half the time.
const SPEED_RPM: f64 = 20.0;

fn inputs(values: &[(&str, f64)]) -> RunInputs {
    let study = Study::load(&Path::new(REPO_ROOT).join(STUDY)).unwrap();
    let values: ParameterValues = values.iter().map(|(k, v)| ((*k).to_owned(), *v)).collect();
    RunInputs::resolve(
        &study.pod_world().unwrap(),
        Experiment::PodDrum,
        &BTreeMap::from([(ROTATION_SPEED.to_owned(), SPEED_RPM)]),
        &values,
        ModeName::Quick,
        &TemplateCache::new(),
    )
    .unwrap()
}

#[test]
fn the_layout_keeps_pods_inside_the_drum_and_apart() {
    let i = inputs(&[]);
    let layout = DrumLayout::new(&i, 1);
    assert_eq!(layout.particles.len(), i.mode.pods as usize);
    let bound = |class: usize| i.template(class).bounding_radius_mm;
    let largest = i
        .templates
        .iter()
        .map(|t| t.bounding_radius_mm)
        .fold(0.0, f64::max);
    for (k, a) in layout.particles.iter().enumerate() {
        let [x, y, z] = a.position_mm;
        assert!(x.hypot(z) + bound(a.class) < layout.radius_mm);
        assert!(y.abs() + bound(a.class) < 0.5 * layout.length_mm);
        for b in &layout.particles[k + 1..] {
            let d: f64 = (0..3)
                .map(|c| (a.position_mm[c] - b.position_mm[c]).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                d >= 2.0 * largest + CELL_GAP_MM - 1e-9,
                "{a:?} {b:?}: {d} mm"
            );
        }
    }
}

#[test]
fn a_slow_small_turn_lifts_the_bed_as_a_block() {
    let i = inputs(&[]);
    let layout = DrumLayout::new(&i, 1);
    let mut arena = Arena::new(&i, layout.particles.len(), layout.sphere_total);
    let mut w = arena.world(Experiment::PodDrum).unwrap();
    let mats = add_materials(&mut w, &i, Experiment::PodDrum).unwrap();
    layout.build(&mut w, &i, mats).unwrap();
    set_rayleigh_timestep(&mut w, &i, Experiment::PodDrum).unwrap();
    let mut frames = FrameRecorder::new(None);
    let at_rest_j = at_rest_energy_j(&i, layout.particles.len());
    let chunk = steps_for(&w, CHECK_INTERVAL_S);
    let (from_s, until_s) = (MIN_FILL_S, MAX_SETTLE_S);
    settle(
        &mut w,
        chunk,
        from_s,
        until_s,
        at_rest_j,
        &mut frames,
        Experiment::PodDrum,
    )
    .unwrap();
    // 2 rpm for a turn of 0.25 rad (14.3°): far below the pods' angle of stability.
    let omega = 2.0 * std::f64::consts::TAU / 60.0;
    let turn = 0.25;
    let before = bed_angle_deg(&w, omega);
    spin(&mut w, omega).unwrap();
    let steps = steps_for(&w, turn / omega);
    run_steps(&mut w, steps, Experiment::PodDrum).unwrap();
    let after = bed_angle_deg(&w, omega);
    eprintln!(
        "bed angle {before:.2}° → {after:.2}° for a turn of {:.2}°",
        turn.to_degrees()
    );
    // A block turns with the drum; the pods settle into the shell's new position by a few
    // tenths of a degree (10 % of the turn).
    assert!(
        ((after - before) - turn.to_degrees()).abs() < 0.1 * turn.to_degrees(),
        "the bed turned {:.2}° for a turn of {:.2}°",
        after - before,
        turn.to_degrees()
    );
}

#[test]
fn a_seed_gives_its_bits_and_smooth_pods_flow_flatter() {
    let smooth = [
        ("pod-pod.static_friction", 0.085),
        ("pod-pod.rolling_friction", 0.03),
    ];
    let angles = |i: &RunInputs| -> Vec<(f64, String)> {
        (1..=2)
            .map(|seed| {
                let o = run(i, seed, &RunOptions::default()).unwrap();
                let ObservationDetails::PodDrum(d) = &o.details else {
                    panic!("not a drum run")
                };
                assert_eq!(d.speed_rpm, SPEED_RPM);
                (o.value, o.digest)
            })
            .collect()
    };
    let rough_inputs = inputs(&[]);
    let rough = angles(&rough_inputs);
    let again = run(&rough_inputs, 1, &RunOptions::default()).unwrap();
    assert_eq!(again.digest, rough[0].1);
    assert_eq!(again.value.to_bits(), rough[0].0.to_bits());
    assert_ne!(rough[0].1, rough[1].1);
    let smooth: Vec<f64> = angles(&inputs(&smooth)).into_iter().map(|a| a.0).collect();
    let rough: Vec<f64> = rough.into_iter().map(|a| a.0).collect();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let var = |v: &[f64]| {
        let m = mean(v);
        v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64
    };
    let pooled = ((var(&rough) + var(&smooth)) / 2.0).sqrt();
    eprintln!("rough {rough:?}, smooth {smooth:?}, pooled SD {pooled:.2}°");
    assert!(
        mean(&rough) - mean(&smooth) > 3.0 * pooled,
        "rough {:.2}° vs smooth {:.2}°, SD {pooled:.2}°",
        mean(&rough),
        mean(&smooth)
    );
}
