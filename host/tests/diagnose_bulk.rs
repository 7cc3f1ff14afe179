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

mod cli_support;
use cli_support::{arachis_at_root as arachis, file_stamps};

const MEASURED: &str = "testdata/diagnosis-bulk/measured.toml";
const RUNS: &str = "testdata/diagnosis-bulk/runs";

#[test]
fn hidden_cohesion_in_hopper_and_drum_data_is_ranked_first() {
    let dir = tempfile::tempdir().unwrap();
    let runs = dir.path().join("runs");
    std::fs::create_dir(&runs).unwrap();
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for e in std::fs::read_dir(root.join(RUNS)).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), runs.join(e.file_name())).unwrap();
    }
    let before = file_stamps(&runs);
    let out = arachis(&[
        "diagnose",
        MEASURED,
        "--runs",
        runs.to_str().unwrap(),
        "--replicates",
        "2",
    ]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        file_stamps(&runs),
        before,
        "a run was simulated instead of replayed: the committed cache no longer matches"
    );
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
}
