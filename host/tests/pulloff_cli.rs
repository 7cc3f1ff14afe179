//! `arachis pulloff` end to end: the default virtual tensile test through the real binary
//! (about 4 200 steps of 11 spheres: about a second in a debug build), its JSON line, its
//! curve and VTK files, and its refusal of bad input (exit 2).

use serde_json::Value;

use crate::cli_support;
use cli_support::arachis;

/// Relative tolerance of the detachment force against σc·A of the junction (axial pull, pure
/// tension; the core's digest test measures −3.7e-4).
const FORCE_TOL: f64 = 0.01;

#[test]
fn default_pull_detaches_at_the_criterion_force_and_writes_files() {
    let dir = tempfile::tempdir().unwrap();
    let curve = dir.path().join("curve.csv");
    let vtk = dir.path().join("vtk");
    let out = arachis(&[
        "pulloff",
        "--curve",
        curve.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
        "--frame-every",
        "1000",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: Value = serde_json::from_slice(&out.stdout).expect("one JSON line");
    assert_eq!(v["detached"], true);
    assert_eq!(v["stalk_broke_first"], false);
    let f = v["detachment_force_n"].as_f64().unwrap();
    let predicted = v["predicted_axial_detachment_n"].as_f64().unwrap();
    assert!(
        ((f - predicted) / predicted).abs() < FORCE_TOL,
        "{f} vs {predicted}"
    );
    assert_eq!(v["digest"].as_str().unwrap().len(), 16);
    // One curve row per step, displacement growing at 0.1 m/s × 5e-7 s per step.
    let text = std::fs::read_to_string(&curve).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert_eq!(rows[0], "displacement_m,force_n");
    assert_eq!(rows.len() as u64 - 1, v["steps"].as_u64().unwrap());
    let last_d: f64 = rows[rows.len() - 1]
        .split(',')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let expect_d = v["steps"].as_f64().unwrap() * 0.1 * 5e-7;
    assert!((last_d - expect_d).abs() < 1e-9);
    assert!(vtk.join("particles.pvd").exists());
    assert!(vtk.join("frame_000000.vtk").exists());
}

#[test]
fn bad_arguments_are_clear_errors() {
    for (args, message) in [
        (
            vec!["pulloff", "--speed", "0"],
            "--speed must be a positive",
        ),
        // Issue 23: at 1 000 m/s the rig reported no detachment and 0 N.
        (
            vec!["pulloff", "--speed", "1000"],
            "beyond the rig's 10 m/s",
        ),
        (
            vec!["pulloff", "--bond-radius", "-1e-3"],
            "--bond-radius must be > 0",
        ),
        (vec!["pulloff", "--tau-c", "nan"], "--tau-c must be > 0"),
        (
            vec!["pulloff", "--stalk-spheres", "1"],
            "--stalk-spheres must be at least 2",
        ),
    ] {
        let out = arachis(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(message), "{args:?}: {err}");
    }
}
