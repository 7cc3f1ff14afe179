//! The pod repose rig (`rigs::pod_bench::PodBenchRig`) on one real pile: the cheap piece
//! of the end-to-end DEM calibration (the whole quick calibration is 44 piles,
//! about 16 CPU-minutes, too slow for CI; `calibrate_committed_run` replays its committed run).
//!
//! One quick-mode repose spec at the seed's optimum (seed 000 §3.6.2), on the test pile of
//! `quick_pile_support` (150 pods × 3 spheres), one pile of about 13 CPU-s:
//! - the adapter answers what `run_pod_test` answers for the spec's values, mode and seed
//!   (bit for bit);
//! - a second adapter, with nothing in memory (as after a resumed run), draws the pile
//!   picture by simulating the spec again, and its caption prints the same angle: the
//!   re-simulation gives the same pile. The picture is the SVG the report links (a PNG
//!   once panicked there for want of a font).

use std::collections::BTreeMap;

use arachis::calibration::{Rig, RunRequest};
use arachis::rigs::pod_bench::{parameter_values, run_pod_test, PodBenchRig, PILE_PICTURE};
use arachis::rigs::pod_world::{ModeName, RunOptions};
use arachis::rigs::repose_cylinder::TEST as REPOSE;

use crate::quick_pile_support;
use quick_pile_support::test_pile_study;

#[test]
fn dem_adapter_answers_like_the_rig_and_redraws_the_same_pile() {
    let study = test_pile_study();
    let values: BTreeMap<String, f64> = [
        ("pod-pod.restitution".to_string(), 0.335),
        ("pod-pod.static_friction".to_string(), 0.854),
        ("pod-pod.rolling_friction".to_string(), 0.346),
    ]
    .into_iter()
    .collect();
    let condition = BTreeMap::new();
    let request = RunRequest {
        values: &values,
        condition: &condition,
        replicate: 0,
    };
    let dem = PodBenchRig::new(study.pod_world().unwrap(), REPOSE, ModeName::Quick);
    let spec = dem.run_spec(&request).unwrap();
    let answered = dem.run(&request).unwrap()["repose_angle"];

    // The direct rig run and the redraw by a fresh adapter (nothing in memory, as after a
    // resumed calibration) run side by side.
    let dir = tempfile::tempdir().unwrap();
    let fresh = PodBenchRig::new(study.pod_world().unwrap(), REPOSE, ModeName::Quick);
    let (direct, path) = rayon::join(
        || {
            run_pod_test(
                &study.pod_world().unwrap(),
                REPOSE,
                &condition,
                &parameter_values(&spec),
                ModeName::Quick,
                spec.simulation.random_seed,
                &RunOptions::default(),
            )
            .unwrap()
        },
        || fresh.picture(&request, dir.path()).unwrap().unwrap(),
    );
    eprintln!("adapter {answered} °, run_pod_test {} °", direct.value);
    assert_eq!(answered.to_bits(), direct.value.to_bits());
    assert_eq!(path, dir.path().join(PILE_PICTURE));
    let svg = std::fs::read_to_string(&path).unwrap();
    assert!(svg.starts_with("<svg"), "not an SVG");
    assert!(
        svg.contains(&format!("repose angle {answered:.2}°")),
        "the redrawn pile's caption does not print {answered:.2}°"
    );
}
