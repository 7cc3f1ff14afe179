//! Issue 4 must-show: the repose angle rises with pod–pod static friction and with pod–pod
//! rolling friction, on the real DEM rig (cylinder lifting, `experiments::repose`).
//!
//! Cost: the test pile of `quick_pile_support` (150 pods in the quick mode's cylinder scaling,
//! 3 spheres per pod), about 11–15 CPU-s a pile
//! in release; 3 levels × 2 placement seeds = 6 piles, run 2 at a time.
//!
//! Design: a shared base at the seed's calibrated pair (μs = 0.854, μr = 0.346; e = 0.335,
//! seed 000 §3.6.2) and one low level per factor (μs = 0.3, μr = 0.01), far below the
//! seed's ranges, because the pile-to-pile scatter of so small a pile is large: the base
//! gave 39.3° with placement seed 1 and 51.7° with seed 2 when this test was written.
//! Every level is run with the same two placement seeds, so the comparison is paired (the
//! same packing before the lift); the test asks for a rise at each seed, not only in the
//! mean. Measured when written (seed 1, seed 2): μs 0.3 → 0.854: 34.5° → 39.3°,
//! 44.8° → 51.7°; μr 0.01 → 0.346: 24.7° → 39.3°, 22.5° → 51.7°.
//!
//! The threshold is a rise of more than [`MIN_RISE_DEG`] at every seed: the rig reports the
//! mean over 12 views × 2 flanks, so a tie or a sub-degree wobble does not count as a rise.

use std::sync::Arc;

use arachis::rigs::pod_world::*;
use arachis::study::Experiment as ExperimentKind;
use rayon::prelude::*;

mod quick_pile_support;
use quick_pile_support::test_pile_study;

/// Placement seeds (paired across levels).
const SEEDS: [u64; 2] = [1, 2];
/// Seed 000 §3.6.2: calibrated pod–pod restitution, static and rolling friction.
const E_POD_POD: f64 = 0.335;
const MU_S_HIGH: f64 = 0.854;
const MU_R_HIGH: f64 = 0.346;
/// The low levels: well below the seed's ranges (0.837–0.878 and 0.314–0.356).
const MU_S_LOW: f64 = 0.3;
const MU_R_LOW: f64 = 0.01;
/// A rise must exceed this at every seed, degrees.
const MIN_RISE_DEG: f64 = 1.0;

#[test]
fn repose_angle_rises_with_pod_pod_static_and_rolling_friction() {
    let study = test_pile_study();
    let options = RunOptions {
        vtk_dir: None,
        templates: Some(Arc::new(TemplateCache::new())),
    };
    // (μs, μr): base, low μs, low μr.
    let levels = [
        (MU_S_HIGH, MU_R_HIGH),
        (MU_S_LOW, MU_R_HIGH),
        (MU_S_HIGH, MU_R_LOW),
    ];
    let runs: Vec<(usize, u64)> = (0..levels.len())
        .flat_map(|l| SEEDS.map(|s| (l, s)))
        .collect();
    let angles: Vec<f64> = runs
        .par_iter()
        .map(|&(l, seed)| {
            let (mu_s, mu_r) = levels[l];
            let values: ParameterValues = [
                ("pod-pod.restitution".to_string(), E_POD_POD),
                ("pod-pod.static_friction".to_string(), mu_s),
                ("pod-pod.rolling_friction".to_string(), mu_r),
            ]
            .into_iter()
            .collect();
            study
                .run_experiment(
                    ExperimentKind::Repose,
                    &values,
                    ModeName::Quick,
                    seed,
                    &options,
                )
                .unwrap()
                .value
        })
        .collect();
    let k = SEEDS.len();
    let at = |l: usize| &angles[l * k..(l + 1) * k];
    let (base, low_s, low_r) = (at(0), at(1), at(2));
    let mean = |a: &[f64]| a.iter().sum::<f64>() / a.len() as f64;
    eprintln!(
        "seeds {SEEDS:?}: base (μs {MU_S_HIGH}, μr {MU_R_HIGH}) {base:.2?}°; \
         μs {MU_S_LOW} {low_s:.2?}°; μr {MU_R_LOW} {low_r:.2?}°"
    );
    eprintln!(
        "means: μs {MU_S_LOW} → {MU_S_HIGH}: {:.2}° → {:.2}°; μr {MU_R_LOW} → {MU_R_HIGH}: {:.2}° → {:.2}°",
        mean(low_s),
        mean(base),
        mean(low_r),
        mean(base)
    );
    for i in 0..k {
        assert!(
            base[i] - low_s[i] > MIN_RISE_DEG,
            "static friction, seed {}: {:.2}° → {:.2}°",
            SEEDS[i],
            low_s[i],
            base[i]
        );
        assert!(
            base[i] - low_r[i] > MIN_RISE_DEG,
            "rolling friction, seed {}: {:.2}° → {:.2}°",
            SEEDS[i],
            low_r[i],
            base[i]
        );
    }
}
