//! Issue 22 item 5: seed 000's own numbers as a diagnosis (`testdata/diagnosis-seed000/`,
//! docs/diagnosis-tutorial.md "Seed 000's pile"): the bench ranges of §3.2 as priors on the
//! six pair coefficients, the stacking angle 31.06° (SD assumed 1°) as the measurement, quick
//! piles of 150 pods predicted by the mean of four placements. The diagnosis simulated 64
//! piles (about 5 minutes on 2 cores, 2026-11-27); they are committed in
//! `testdata/diagnosis-seed000/runs/`, so this test replays them and fails if any would have
//! to be simulated again.
//!
//! What the diagnosis finds is what the test pins: the pile at the bench values is far too
//! steep, no effect can be tested with one angle at one condition, and every finite
//! difference is lost in the scatter of the placements, which the tool says.

use crate::cli_support;
use cli_support::replay;

const STUDY: &str = "testdata/diagnosis-seed000/study.toml";
const RUNS: &str = "testdata/diagnosis-seed000/runs";

#[test]
fn seed_000s_pile_is_too_steep_and_its_differences_are_lost_in_the_scatter() {
    let compared = replay("compare", STUDY, RUNS, &["--replicates", "4"]);
    // 31.06° measured, ± 1/√10 (the assumed SD over the seed's 10 repeats); the mean of four
    // quick piles at the bench values lies 45 standard errors above it.
    let row = compared
        .lines()
        .find(|l| l.trim_start().starts_with("0.050000"))
        .unwrap_or_else(|| panic!("no condition row in\n{compared}"));
    let cols: Vec<f64> = row
        .split_whitespace()
        .filter_map(|c| c.parse().ok())
        .collect();
    let (measured, se, simulated, residual) = (cols[2], cols[3], cols[4], cols[5]);
    assert_eq!(measured, 31.06);
    assert!((se - 1.0 / 10f64.sqrt()).abs() < 1e-3, "{row}");
    assert!(simulated > 40.0, "{row}");
    assert!(
        (residual - (measured - simulated) / se).abs() < 0.01,
        "{row}"
    );

    let text = replay("diagnose", STUDY, RUNS, &["--replicates", "4"]);
    assert!(
        text.contains("verdict: no candidate effect is identifiable with these data"),
        "{text}"
    );
    // One stacking angle cannot say more: the tool names the bench tests of the study's own
    // pods it could simulate next (issue 22), the pod drum and the poured bulk density.
    let rigs = text
        .lines()
        .find(|l| l.starts_with("rigs not yet measured that this study can simulate:"))
        .unwrap_or_else(|| panic!("no rigs named in\n{text}"));
    for rig in [
        "pod_drum (dynamic angle of repose, deg)",
        "pod_bulk_density (bulk density, kg/m³)",
    ] {
        assert!(rigs.contains(rig), "{rig} not in: {rigs}");
    }
    assert!(
        !rigs.contains("repose ("),
        "the measured rig is not named: {rigs}"
    );
    // Six base parameters and three effects at one condition: nine differences, each within
    // Student's 95 % quantile for four placements (3.18 SE).
    assert!(
        text.contains("paired over 4 placements; 9 of 9 within the scatter"),
        "{text}"
    );
    assert!(
        text.contains(
            "warning: every candidate's finite differences lie within the placements' scatter"
        ),
        "{text}"
    );
    // The calibration sits on the bench values: no prior is in conflict.
    for name in ["pod-pod.rolling_friction", "pod-pod.static_friction"] {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(name) && l.contains("bench"))
            .unwrap_or_else(|| panic!("no prior line for {name} in\n{text}"));
        assert!(
            line.ends_with("-0.0 SD") || line.ends_with("+0.0 SD"),
            "{line}"
        );
    }
}
