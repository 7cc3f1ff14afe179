//! Issue 23: every count limit (`src/count_limits.rs`) refuses before anything is allocated
//! or simulated. Each over-limit command runs under `ulimit -v 4000000` (4 GB of address
//! space; the faults this replaces grew to 24 GB) and `ulimit -t 2` (two CPU seconds; one ran
//! past a minute), so a refusal that allocated or computed first would be killed by the
//! kernel instead of exiting with status 2. The message must name the input and its limit.

use std::path::Path;
use std::process::{Command, Output};

/// `arachis ARGS` under the address-space and CPU-time limits.
fn limited(args: &[&str]) -> Output {
    Command::new("bash")
        .arg("-c")
        .arg(r#"ulimit -v 4000000 -t 2 && exec "$@""#)
        .arg("bash")
        .arg(env!("CARGO_BIN_EXE_arachis"))
        .args(args)
        .output()
        .expect("bash runs")
}

fn bad_study(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/bad-studies")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

#[test]
fn every_count_beyond_its_limit_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let study = bad_study("counts_too_large.toml");
    let valid = bad_study("valid.toml");
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec![
                "doe",
                "design",
                "--type",
                "steepest",
                "--factors",
                "A,B",
                "--coefficients",
                "1,1",
                "--step",
                "1",
                "--points",
                "1000000000",
            ],
            vec!["--points", "1000000000", "10000"],
        ),
        (
            vec![
                "doe",
                "design",
                "--type",
                "bbd",
                "--factors",
                "A,B,C",
                "--center",
                "100000000",
            ],
            vec!["--center", "100000000", "1000"],
        ),
        (
            vec!["pulloff", "--stalk-spheres", "100000000"],
            vec!["--stalk-spheres", "at most 64"],
        ),
        (
            vec!["plant-calibrate", "--out", out, "--jobs", "100000"],
            vec!["--jobs", "100000", "1024"],
        ),
        (
            vec!["calibrate", &valid, "--out", out, "--jobs", "100000"],
            vec!["--jobs", "100000", "1024"],
        ),
        (
            vec!["harvest", "--plants", "100000000"],
            vec!["--plants", "100000000", "10000"],
        ),
        (
            vec!["harvest", "--replicates", "100000000"],
            vec!["--replicates", "100000000", "1000"],
        ),
        (
            vec!["study", "check", &study],
            vec!["plan.steepest_ascent.points", "at most 10000"],
        ),
        (
            vec!["calibrate", &study, "--out", out],
            vec!["plan.box_behnken.centre_points", "at most 1000"],
        ),
    ];
    for (args, needles) in cases {
        let o = limited(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(
            o.status.code(),
            Some(2),
            "arachis {args:?} (killed by a limit if no code): {stderr}"
        );
        for n in needles {
            assert!(stderr.contains(n), "arachis {args:?}: no '{n}' in {stderr}");
        }
        assert!(!Path::new(out).exists(), "arachis {args:?} wrote {out}");
    }
}
