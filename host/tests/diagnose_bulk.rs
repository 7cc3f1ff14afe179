//! Diagnosis on bulk rigs (issue 22 item 1): the hopper and the drum, measured with a hidden
//! pod–pod SJKR cohesion of 3e4 J/m³ (`testdata/diagnosis-bulk/measured.toml`, written by
//!
//! ```sh
//! arachis synth testdata/diagnosis-bulk/template.toml --hidden pod-pod.cohesion_j_m3=3e4 \
//!     --noise hopper=4 --noise drum=0.7 --seed 1 --out measured.toml
//! ```
//!
//! ). The diagnosis simulated 320 runs (33 minutes on 2 shared cores); they are committed in
//! `testdata/diagnosis-bulk/runs/`, so this test replays them in milliseconds and fails if any
//! would have to be simulated again.

use crate::cli_support;
use cli_support::replay;

const MEASURED: &str = "testdata/diagnosis-bulk/measured.toml";
const RUNS: &str = "testdata/diagnosis-bulk/runs";

#[test]
fn hidden_cohesion_in_hopper_and_drum_data_is_ranked_first() {
    let text = replay("diagnose", MEASURED, RUNS, &["--replicates", "2"]);
    // Both rigs miss something; cohesion comes first and is claimed.
    assert!(text.contains("hopper   sum r^2"), "{text}");
    assert!(text.contains("drum     sum r^2"), "{text}");
    let first = text
        .lines()
        .find(|l| l.trim_start().starts_with("1 "))
        .unwrap_or_else(|| panic!("no ranking in\n{text}"));
    assert!(
        first.contains("pod-pod.cohesion_j_m3") && first.contains("MISSING"),
        "{text}"
    );
    assert!(
        text.contains("verdict: the model lacks an effect; best candidate 'pod-pod.cohesion_j_m3'"),
        "{text}"
    );
    // Each finite difference is shown against the two placements' scatter: cohesion's stands
    // out of it at one condition at least, so its rank is evidence.
    assert!(
        text.contains(
            "finite differences against the placements' scatter (paired over 2 placements;"
        ),
        "{text}"
    );
    assert!(!text.contains("warning: every"), "{text}");
    // The proposal's own differences are paired over two placements as well, and at the
    // proposed orifice both effects' lie within that scatter (Student's 12.7 SE for two
    // placements): the tool says the proposal may rest on noise.
    let proposal = text
        .lines()
        .skip_while(|l| !l.starts_with("to tell"))
        .nth(1)
        .unwrap_or_else(|| panic!("no proposal in\n{text}"));
    assert!(
        proposal.contains("pod-pod.cohesion_j_m3 and pod-pod.epsd_rolling_friction lie within")
            && proposal.contains("may rest on noise"),
        "{proposal}"
    );
}
