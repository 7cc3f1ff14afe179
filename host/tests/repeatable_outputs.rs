//! Issue 23: every command that writes files writes the same bytes when run twice with the
//! same input: no timing, thread count, path or random state leaks into a file a user or a
//! test compares. Each command below runs twice into two fresh folders, and every file of the
//! first run must equal its namesake of the second, byte for byte. (The calibrations, which
//! take minutes, have their own replay tests: `calibrate_committed_run.rs` and
//! `plant_calibrate_cli.rs` against committed bytes; `harvest.rs` runs its report twice. The
//! other commands write no file: `lab` without `--svg`, `doe analyze`/`optimize`, `study`,
//! `diagnose`, `plant` print to standard output.)

use crate::cli_support;
use cli_support::{arachis_at_root, REPO_ROOT};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Every file below `dir`, by its path relative to `dir`.
fn files(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let rel = path.strip_prefix(dir).unwrap().to_path_buf();
                out.insert(rel, std::fs::read(&path).unwrap());
            }
        }
    }
    out
}

/// Runs `args` (with `{OUT}` replaced by a fresh folder) twice; returns the two folders'
/// files after checking each run succeeded and wrote something.
fn twice(args: &[&str]) -> [BTreeMap<PathBuf, Vec<u8>>; 2] {
    let runs = [0, 1].map(|_| {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().to_str().unwrap().to_owned();
        let args: Vec<String> = args.iter().map(|a| a.replace("{OUT}", &out)).collect();
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = arachis_at_root(&args);
        assert!(
            o.status.success(),
            "arachis {args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let found = files(dir.path());
        assert!(!found.is_empty(), "arachis {args:?} wrote nothing");
        found
    });
    runs
}

#[test]
fn every_file_writing_command_writes_the_same_bytes_twice() {
    let measured = "testdata/diagnosis-tutorial/measured.toml";
    let template = "testdata/diagnosis-tutorial/template.toml";
    // A study of spheres for the LIGGGHTS export: the shipped one with its pods replaced.
    let keep = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(format!(
        "{REPO_ROOT}/testdata/peanut-pods-saline/study.toml"
    ))
    .unwrap();
    let (start, end) = (
        text.find("[pods]").unwrap(),
        text.find("# Contact pairs.").unwrap(),
    );
    let spheres = keep.path().join("spheres.toml");
    std::fs::write(
        &spheres,
        format!(
            "{}[spheres]\nmaterial = \"pod\"\nradius_mm = 4.0\n\n{}",
            &text[..start],
            &text[end..]
        ),
    )
    .unwrap();
    let spheres = spheres.to_str().unwrap();
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "doe",
            "design",
            "--type",
            "bbd",
            "--factors",
            "A:0:1,B:0:1,C:0:1",
            "--out",
            "{OUT}/design.csv",
        ],
        vec![
            "synth",
            template,
            "--hidden",
            "drag=0.3",
            "--seed",
            "3",
            "--out",
            "{OUT}/m.toml",
        ],
        vec![
            "fit",
            measured,
            "--with",
            "viscoelastic",
            "--no-loco",
            "--out",
            "{OUT}/fit.toml",
            "--plots",
            "{OUT}/fit-plots",
        ],
        vec![
            "lab",
            "repose",
            "testdata/repose/synthetic_pile_31.06deg.png",
            "--svg",
            "{OUT}/contour.svg",
        ],
        vec![
            "simulate",
            "--study",
            "testdata/peanut-pods-saline/study.toml",
            "incline_slide",
            "--vtk",
            "{OUT}/incline-vtk",
        ],
        vec!["compare", measured, "--plots", "{OUT}/plots"],
        vec![
            "pulloff",
            "--max-steps",
            "4000",
            "--curve",
            "{OUT}/pull.csv",
            "--vtk",
            "{OUT}/vtk",
            "--frame-every",
            "1000",
        ],
        vec![
            "pour",
            "--particles",
            "200",
            "--steps",
            "400",
            "--dt",
            "2e-5",
            "--vtk",
            "{OUT}/bed",
            "--frames",
            "3",
        ],
        vec!["export", "liggghts", spheres, "--out", "{OUT}/deck"],
        vec![
            "export",
            "liggghts",
            spheres,
            "--experiment",
            "incline_slide",
            "--out",
            "{OUT}/incline",
        ],
    ];
    for args in cases {
        let [a, b] = twice(&args);
        assert_eq!(
            a.keys().collect::<Vec<_>>(),
            b.keys().collect::<Vec<_>>(),
            "arachis {args:?}: other files"
        );
        for (name, bytes) in &a {
            assert!(
                *bytes == b[name],
                "arachis {args:?}: {} differs between two runs",
                name.display()
            );
        }
    }
}
