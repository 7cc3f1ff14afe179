//! `arachis export liggghts` and `arachis lab repose-pile` (issue 18 items 3 and 4): the deck
//! of a sphere study's repose rig holds the rig's own particles, time step, materials and
//! cylinder; a pod study and an EDEM pair are refused or warned about; and `lab repose-pile`
//! measures a pile exactly as the rig measured it. (Running the deck in LIGGGHTS is the
//! cross-check script's work: `scripts/cross-check-repose.sh`.)

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use arachis::rigs::pod_world::{Experiment, ModeName, ObservationDetails, RunOptions};
use arachis::study::Study;
use serde_json::Value;

use crate::cli_support;
use cli_support::arachis;

fn seed_study() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/peanut-pods-saline/study.toml")
}

/// Spheres of 4 mm in a 60 mm cylinder (quick mode: 400, in 46 mm), both pairs in
/// LIGGGHTS' conventions unless `edem`.
fn sphere_study(edem: bool) -> String {
    let text = std::fs::read_to_string(seed_study()).unwrap();
    let start = text.find("[pods]").unwrap();
    let end = text.find("# Contact pairs.").unwrap();
    let mut text = format!(
        "{}[spheres]\nmaterial = \"pod\"\nradius_mm = 4.0\n\n{}",
        &text[..start],
        &text[end..]
    )
    .replacen("pods = 150", "pods = 400", 1)
    .replacen(
        "cylinder_diameter_mm = 200.0",
        "cylinder_diameter_mm = 60.0",
        1,
    );
    if !edem {
        for pair in ["pod-pod", "pod-steel"] {
            let header = format!("[pairs.\"{pair}\"]\n");
            text = text.replacen(
                &header,
                &format!(
                    "{header}rolling_convention = \"liggghts-cdt\"\nfriction_convention = \"liggghts\"\n"
                ),
                1,
            );
        }
    }
    text
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

fn run_ok(args: &[&str]) -> (String, String) {
    let out = arachis(args);
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    );
    assert!(out.status.success(), "arachis {args:?}: {stderr}");
    (stdout, stderr)
}

/// The arguments of `arachis export liggghts STUDY --out OUT EXTRA...`.
fn export_args<'a>(study: &'a Path, out: &'a Path, extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "export",
        "liggghts",
        study.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    args
}

/// The observation details of `arachis simulate --json EXPERIMENT` on `study` (with `--seed
/// SEED` when given): the rig's own time step and geometry.
fn rig_details(study: &Path, experiment: &str, seed: Option<&str>) -> Value {
    let mut args = vec!["simulate", "--study", study.to_str().unwrap(), "--json"];
    if let Some(seed) = seed {
        args.extend(["--seed", seed]);
    }
    args.push(experiment);
    let (json, _) = run_ok(&args);
    let o: Value = serde_json::from_str(&json).unwrap();
    o["observation"]["details"].clone()
}

/// The deck's `timestep`, s.
fn deck_dt(input: &str) -> f64 {
    let line = input.lines().find(|l| l.starts_with("timestep")).unwrap();
    line.split_whitespace().nth(1).unwrap().parse().unwrap()
}

/// The rows of the `Atoms` section of a data file: id, type, diameter, density, x, y, z.
fn atoms(data: &str) -> Vec<Vec<f64>> {
    data.split("Atoms\n\n")
        .nth(1)
        .unwrap()
        .split("\n\nVelocities")
        .next()
        .unwrap()
        .lines()
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

#[test]
fn the_deck_holds_the_rigs_particles_time_step_and_cylinder() {
    let dir = tempfile::tempdir().unwrap();
    let study = write(dir.path(), "study.toml", &sphere_study(false));
    let out = dir.path().join("deck");
    let (_, stderr) = run_ok(&export_args(&study, &out, &["--seed", "3"]));
    assert!(!stderr.contains("warning"), "{stderr}");
    let input = std::fs::read_to_string(out.join("in.repose")).unwrap();
    let data = std::fs::read_to_string(out.join("particles.data")).unwrap();
    let stl = std::fs::read_to_string(out.join("cylinder.stl")).unwrap();

    // The time step is the one the rig steps with (reported by simulate).
    let details = rig_details(&study, "repose", Some("3"));
    assert_eq!(deck_dt(&input), details["dt_s"].as_f64().unwrap());

    // 400 spheres of diameter 8 mm and the pod density, inside the rig's cylinder.
    assert!(data.contains("400 atoms\n2 atom types"));
    let radius_m = details["cylinder_diameter_mm"].as_f64().unwrap() / 2e3;
    let atoms = atoms(&data);
    assert_eq!(atoms.len(), 400);
    for a in &atoms {
        assert_eq!(a[2], 0.008);
        assert_eq!(a[3], 582.36);
        assert!(
            a[4].hypot(a[5]) + 0.004 < radius_m,
            "outside the cylinder: {a:?}"
        );
        assert!(a[6] >= 0.004);
    }
    // The materials, E = 2G(1 + ν), and the pairs (pod–pod μs held at its range's centre).
    let numbers = |key: &str| -> Vec<f64> {
        let line = input.lines().find(|l| l.contains(key)).unwrap();
        line.split_whitespace()
            .filter_map(|x| x.parse().ok())
            .collect()
    };
    let close = |got: &[f64], want: &[f64]| {
        got.len() == want.len()
            && got
                .iter()
                .zip(want)
                .all(|(g, w)| (g / w - 1.0).abs() < 1e-12)
    };
    let e = numbers("youngsModulus");
    assert!(
        close(&e, &[2.0 * 3.04e6 * 1.386, 2.0 * 7.9e10 * 1.3]),
        "{e:?}"
    );
    let mu = numbers("coefficientFriction");
    assert!(close(&mu, &[2.0, 0.8575, 0.589, 0.589, 0.589]), "{mu:?}");
    let mu_r = numbers("coefficientRollingFriction");
    assert!(close(&mu_r, &[2.0, 0.335, 0.159, 0.159, 0.159]), "{mu_r:?}");
    assert!(input.contains("rolling_friction cdt limitForce on"));

    // The mesh's vertices lie on the cylinder (mm) and its normals point to the axis.
    let r_mm = radius_m * 1e3;
    let mut normals = 0;
    for l in stl.lines().map(str::trim) {
        let v: Vec<f64> = l
            .split_whitespace()
            .skip(2)
            .filter_map(|x| x.parse().ok())
            .collect();
        if l.starts_with("vertex") {
            let v: Vec<f64> = l
                .split_whitespace()
                .skip(1)
                .map(|x| x.parse().unwrap())
                .collect();
            assert!((v[0].hypot(v[1]) - r_mm).abs() < 1e-9 * r_mm);
        } else if l.starts_with("facet normal") {
            normals += 1;
            assert!(v.len() == 3 && v[2].abs() < 1e-12, "{l}");
        }
    }
    assert!(normals > 0);
}

#[test]
fn pods_are_refused_and_an_edem_pair_is_warned_about() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("deck");
    let refused = arachis(&export_args(&seed_study(), &out, &[]));
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(err.contains("no multi-sphere particles"), "{err}");
    assert!(!out.exists(), "a refused export wrote {}", out.display());
    let study = write(dir.path(), "edem.toml", &sphere_study(true));
    let (_, stderr) = run_ok(&export_args(&study, &out, &[]));
    assert!(
        stderr.contains("warning: pair pod-pod is read in conventions the deck does not have"),
        "{stderr}"
    );
    let input = std::fs::read_to_string(out.join("in.repose")).unwrap();
    assert!(input.contains("# WARNING: pair pod-pod"));
}

/// The incline deck: the rig's one sphere, DROP_GAP above the plate, its time step and its
/// tilt schedule (gravity redefined every TILT_UPDATE_S at 5°/s); an experiment without a deck
/// is refused with the list of those that have one, and writes nothing.
#[test]
fn the_incline_deck_holds_the_rigs_sphere_time_step_and_tilt_schedule() {
    let dir = tempfile::tempdir().unwrap();
    let text = sphere_study(false).replace("liggghts-cdt", "liggghts-epsd2");
    let study = write(dir.path(), "study.toml", &text);
    let out = dir.path().join("deck");
    let (stdout, stderr) = run_ok(&export_args(
        &study,
        &out,
        &["--experiment", "incline_slide"],
    ));
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(stdout.contains("liggghts -in in.incline"), "{stdout}");
    assert!(!out.join("cylinder.stl").exists());
    let input = std::fs::read_to_string(out.join("in.incline")).unwrap();
    let data = std::fs::read_to_string(out.join("particles.data")).unwrap();
    let dt = rig_details(&study, "incline_slide", None)["dt_s"]
        .as_f64()
        .unwrap();
    assert_eq!(deck_dt(&input), dt);
    // One sphere of 8 mm, pod density, at R + 0.05 mm, at rest.
    assert!(data.contains("1 atoms\n2 atom types"));
    let atom = &atoms(&data)[0];
    assert_eq!(&atom[2..6], &[0.008, 582.36, 0.0, 0.0]);
    assert!((atom[6] - 0.00405).abs() < 1e-15, "{atom:?}");
    // Gravity turns every round(0.002 s / dt) steps; the rig's onset and confirmation.
    let chunk = (0.002 / dt).round() as u64;
    assert!(
        input.contains(&format!("\nrun {chunk}\n")),
        "no run of {chunk} steps"
    );
    assert!(input.contains("fix  gravi all gravity 9.81 vector ${sx} 0.0 ${sz}"));
    assert!(input.contains("${moved} > 1e-4"));
    assert!(input.contains("${moved} > 2e-3"));
    assert!(input.contains("rolling_friction epsd2 limitForce on"));
    // No deck for the compression test: refused with the rigs that have one, nothing written.
    let none = dir.path().join("none");
    let refused = arachis(&export_args(
        &study,
        &none,
        &["--experiment", "compression"],
    ));
    assert_eq!(refused.status.code(), Some(2));
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(err.contains("repose, incline_slide"), "{err}");
    assert!(!none.exists());
}

/// Pairs in LIGGGHTS' `epsd2` rolling convention give an `epsd2` deck without warnings; a
/// study whose two pairs read rolling friction differently is written with the pod–pod
/// pair's model (LIGGGHTS sets one for all pairs) and a warning naming the other pair.
#[test]
fn epsd2_pairs_give_an_epsd2_deck_and_mixed_pairs_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let export = |name: &str, text: &str| {
        let study = write(dir.path(), name, text);
        let out = dir.path().join(name.replace(".toml", ""));
        let (_, stderr) = run_ok(&export_args(&study, &out, &[]));
        (
            std::fs::read_to_string(out.join("in.repose")).unwrap(),
            stderr,
        )
    };
    let cdt = sphere_study(false);
    let (input, stderr) = export("epsd2.toml", &cdt.replace("liggghts-cdt", "liggghts-epsd2"));
    assert!(!stderr.contains("warning"), "{stderr}");
    assert!(input.contains("rolling_friction epsd2"));
    assert!(!input.contains("rolling_friction cdt"));
    let mixed = cdt.replacen("liggghts-cdt", "liggghts-epsd2", 1);
    let (input, stderr) = export("mixed.toml", &mixed);
    assert!(
        input.contains("rolling_friction epsd2"),
        "the pod-pod pair's model"
    );
    assert!(
        stderr.contains("warning: pair pod-wall is read in conventions the deck does not have"),
        "{stderr}"
    );
    assert!(!stderr.contains("pair pod-pod"), "{stderr}");
}

/// The rig's own final pile, written as a LIGGGHTS dump, measures to the rig's angle.
#[test]
fn repose_pile_measures_a_dump_as_the_rig_measures_its_pile() {
    let dir = tempfile::tempdir().unwrap();
    let study_path = write(dir.path(), "study.toml", &sphere_study(false));
    let study = Study::load(&study_path).unwrap();
    let o = study
        .run_experiment(
            Experiment::Repose,
            &BTreeMap::new(),
            ModeName::Quick,
            5,
            &RunOptions::default(),
        )
        .unwrap();
    let ObservationDetails::Repose(details) = &o.details else {
        panic!("not a repose observation");
    };
    let mut dump = format!(
        "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{}\nITEM: ATOMS id radius x y z\n",
        details.pile.len()
    );
    for (i, s) in details.pile.iter().enumerate() {
        let [x, y, z] = s.centre_mm.map(|c| c / 1e3);
        let _ = writeln!(dump, "{} {:e} {x:e} {y:e} {z:e}", i + 1, s.radius_mm / 1e3);
    }
    let path = write(dir.path(), "final.dump", &dump);
    let (json, _) = run_ok(&["lab", "--json", "repose-pile", path.to_str().unwrap()]);
    let v: Value = serde_json::from_str(&json).unwrap();
    let angle = v["angle_deg"].as_f64().unwrap();
    assert_eq!(v["spheres"], 400);
    assert!(
        (angle - o.value).abs() < 1e-9,
        "{angle} against the rig's {}",
        o.value
    );
}
