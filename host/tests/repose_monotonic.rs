//! Issue 4 must-show: the repose angle rises with pod–pod static friction and with pod–pod
//! rolling friction, on the real DEM rig (cylinder lifting, `rigs::repose_cylinder`).
//!
//! Cost: the test pile of `quick_pile_support` (150 pods in the quick mode's cylinder scaling,
//! 3 spheres per pod), about 4 CPU-s a pile in release; 16 placement seeds at the base and at
//! low μs, [`ROLLING_SEEDS`] of them at low μr: 40 piles, run 2 at a time.
//!
//! Design: a shared base at the seed's calibrated pair (μs = 0.854, μr = 0.346; e = 0.335,
//! seed 000 §3.6.2) and one low level per factor (μs = 0.3, μr = 0.01), far below the
//! seed's ranges. Every level is run with the same eight placement seeds, so the comparison
//! is paired (the same packing before the lift). The claim is tested as a one-sided paired
//! t-test of the rise over the seeds at α = [`ALPHA`], with a mean rise of more than
//! [`MIN_RISE_DEG`].
//!
//! Why eight seeds and a test: the pile-to-pile scatter of so small a pile is about 5°, so a
//! rise at a single seed is partly chance. The first version asked for a rise of more than
//! 1° at each of two seeds; when the core's results changed (issue 16, digests re-blessed),
//! seed 2 rose by only 0.76° (42.39° → 43.15°) while seed 1 rose by 3.93°. Measured then over
//! seeds 1–8: μs 0.3 → 0.854 rises at every seed, by 0.76–14.85° (mean 7.7°, t = 4.2, one-sided
//! p ≈ 0.002); μr 0.01 → 0.346 by 15–29° (mean 20.5°).
//!
//! Why sixteen: when the cylinder got solid rims (2026-11-26) the eight seeds gave for μs a
//! mean rise of 5.72° with one seed falling by 8.32° (p = 0.043, above α); the power of eight
//! pairs was too low for a 5–7° pile scatter, not the rise too small. Over seeds 1–16: μs
//! 0.3 → 0.854 rises by 8.57° on average (p = 1.2e-4), μr 0.01 → 0.346 by 20.04°
//! (p = 1.2e-10); α and the minimum rise are unchanged.
//!
//! Why eight for rolling friction: its rise is about 20° against a 5–7° scatter, so half the
//! pairs still give p far below α (measured over seeds 1–8: see the test's output), and the
//! eight piles it saves are a sixth of the test's cost (CI's 20 minutes, README).

use std::sync::Arc;

use arachis::rigs::pod_world::*;
use arachis::study::Experiment as ExperimentKind;
use rayon::prelude::*;

use crate::quick_pile_support;
use quick_pile_support::test_pile_study;

/// Placement seeds (paired across levels).
const SEEDS: [u64; 16] = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16];
/// How many of [`SEEDS`] (the first) the low rolling-friction level is run with.
const ROLLING_SEEDS: usize = 8;
/// One-sided significance level of the paired t-test.
const ALPHA: f64 = 0.01;
/// Seed 000 §3.6.2: calibrated pod–pod restitution, static and rolling friction.
const E_POD_POD: f64 = 0.335;
const MU_S_HIGH: f64 = 0.854;
const MU_R_HIGH: f64 = 0.346;
/// The low levels: well below the seed's ranges (0.837–0.878 and 0.314–0.356).
const MU_S_LOW: f64 = 0.3;
const MU_R_LOW: f64 = 0.01;
/// The mean rise must exceed this, degrees: the rig reports the mean over 12 views × 2
/// flanks, so a sub-degree wobble does not count as a rise.
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
    let seeds_of = |l: usize| {
        if l == 2 {
            &SEEDS[..ROLLING_SEEDS]
        } else {
            &SEEDS[..]
        }
    };
    let runs: Vec<(usize, u64)> = (0..levels.len())
        .flat_map(|l| seeds_of(l).iter().map(move |&s| (l, s)))
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
    let (base, low_s, low_r) = (&angles[..k], &angles[k..2 * k], &angles[2 * k..]);
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
        mean(&base[..ROLLING_SEEDS])
    );
    // Paired by seed: the low μr level's seeds are the first of the base's.
    let rises = |low: &[f64]| -> Vec<f64> { base.iter().zip(low).map(|(b, l)| b - l).collect() };
    for (name, low) in [("static friction", low_s), ("rolling friction", low_r)] {
        let d = rises(low);
        let seeds = &SEEDS[..d.len()];
        let (m, p) = paired_t_test(&d);
        eprintln!(
            "{name}: rises {d:.2?}° over seeds {seeds:?}, mean {m:.2}°, one-sided p = {p:.2e}"
        );
        assert!(
            m > MIN_RISE_DEG,
            "{name}: mean rise {m:.2}° over seeds {seeds:?}"
        );
        assert!(
            p < ALPHA,
            "{name}: one-sided p = {p:.3} over seeds {seeds:?} (rises {d:.2?}°)"
        );
    }
}

/// Mean of the paired differences and the one-sided p-value of a t-test that it is > 0.
fn paired_t_test(d: &[f64]) -> (f64, f64) {
    use statrs::distribution::{ContinuousCDF, StudentsT};
    let n = d.len() as f64;
    let m = d.iter().sum::<f64>() / n;
    let sd = (d.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    let t = m / (sd / n.sqrt());
    let dist = StudentsT::new(0.0, 1.0, n - 1.0).expect("n > 1");
    (m, 1.0 - dist.cdf(t))
}
