//! The remaining checks of a study file, on in-memory variants of the valid fixture
//! `testdata/bad-studies/valid.toml`: measurements (replicates vs summary, duplicates,
//! several conditions, units, condition keys), pairs, plan references, STL files.

use std::path::{Path, PathBuf};

use arachis::study::{Study, StudyErrors};

fn valid_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/bad-studies/valid.toml")
}

fn with(edits: &[(&str, &str)]) -> Result<Study, StudyErrors> {
    let mut text = std::fs::read_to_string(valid_path()).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "fixture lacks {from}");
        text = text.replacen(from, to, 1);
    }
    Study::from_toml(&text, &valid_path())
}

/// The error at `key` must contain `reason`.
fn expect(result: Result<Study, StudyErrors>, key: &str, reason: &str) {
    let errors = result
        .err()
        .unwrap_or_else(|| panic!("accepted; expected {key}: {reason}"));
    let found = errors
        .errors()
        .iter()
        .any(|e| e.key.to_string() == key && e.reason.contains(reason) && e.position.is_some());
    assert!(
        found,
        "no '{reason}' at {key} (with a position); got:\n{errors}"
    );
}

const MEASUREMENT: &str = "mean = 31.06\nn = 10\n";

#[test]
fn replicates_give_mean_and_count() {
    let study = with(&[(MEASUREMENT, "values = [31.0, 31.2, 30.9, 31.1]\n")]).unwrap();
    let t = study.target().unwrap();
    assert!(t.has_replicates());
    assert_eq!(t.replicates(), Some(4));
    assert!((t.mean().unwrap() - 31.05).abs() < 1e-12);
}

/// Issue 5's shape: one experiment at several conditions, each with replicates; the target
/// picks one by its condition.
#[test]
fn several_conditions_with_replicates_load_and_the_target_picks_one() {
    let blocks = "condition = { lift_speed_m_s = 0.05 }\nvalues = [31.0, 31.2]\n\n\
                  [[measurements]]\nexperiment = \"repose\"\nquantity = \"repose_angle\"\nunit = \"deg\"\n\
                  condition = { lift_speed_m_s = 0.10 }\nvalues = [29.5, 29.9, 29.7]\n\n\
                  [[measurements]]\nexperiment = \"plate_drop\"\nquantity = \"restitution\"\nunit = \"-\"\n\
                  condition = { drop_height_mm = 300.0 }\nvalues = [0.33, 0.35]\n";
    let target =
        "quantity = \"repose_angle\"\ncondition = { lift_speed_m_s = 0.10 }\n\n[plan.validation]";
    let study = with(&[
        (MEASUREMENT, blocks),
        ("quantity = \"repose_angle\"\n\n[plan.validation]", target),
        (
            "quantity = \"repose_angle\"\nmax_relative_error_pct",
            "quantity = \"repose_angle\"\ncondition = { lift_speed_m_s = 0.05 }\nmax_relative_error_pct",
        ),
    ])
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(study.file().measurements.len(), 3);
    assert!((study.target().unwrap().mean().unwrap() - 29.7).abs() < 1e-12);
    assert!((study.validation().unwrap().mean().unwrap() - 31.1).abs() < 1e-12);
}

#[test]
fn a_target_matching_two_conditions_is_ambiguous() {
    let blocks = "condition = { lift_speed_m_s = 0.05 }\nvalues = [31.0]\n\n\
                  [[measurements]]\nexperiment = \"repose\"\nquantity = \"repose_angle\"\nunit = \"deg\"\n\
                  condition = { lift_speed_m_s = 0.10 }\nvalues = [29.5]\n";
    expect(
        with(&[(MEASUREMENT, blocks)]),
        "plan.target.condition",
        "ambiguous: 2 match",
    );
}

#[test]
fn duplicate_measurement_blocks_are_rejected() {
    let blocks = "values = [31.0]\n\n[[measurements]]\nexperiment = \"repose\"\n\
                  quantity = \"repose_angle\"\nunit = \"deg\"\nvalues = [31.2]\n";
    expect(
        with(&[(MEASUREMENT, blocks)]),
        "measurements[2]",
        "merge the replicates",
    );
}

#[test]
fn replicates_and_summary_are_exclusive_and_one_is_required() {
    expect(
        with(&[(MEASUREMENT, "values = [31.0]\nmean = 31.0\n")]),
        "measurements[1].mean",
        "not both",
    );
    expect(
        with(&[(MEASUREMENT, "")]),
        "measurements[1]",
        "missing measurement values",
    );
    expect(
        with(&[(MEASUREMENT, "mean = 31.06\n")]),
        "measurements[1].mean",
        "needs 'n'",
    );
    expect(
        with(&[(MEASUREMENT, "mean = 31.06\nn = 1\nsd = 0.2\n")]),
        "measurements[1].sd",
        "n ≥ 2",
    );
    expect(
        with(&[(MEASUREMENT, "values = [31.0, nan]\n")]),
        "measurements[1].values[2]",
        "not a finite number",
    );
}

#[test]
fn quantity_unit_and_condition_must_fit_the_experiment() {
    expect(
        with(&[("unit = \"deg\"", "unit = \"rad\"")]),
        "measurements[1].unit",
        "is in 'deg', not 'rad'",
    );
    expect(
        with(&[(
            "quantity = \"repose_angle\"\nunit",
            "quantity = \"slope\"\nunit",
        )]),
        "measurements[1].quantity",
        "repose does not measure 'slope'",
    );
    expect(
        with(&[(
            MEASUREMENT,
            "condition = { lift_sped_m_s = 0.05 }\nmean = 31.06\nn = 10\n",
        )]),
        "measurements[1].condition.lift_sped_m_s",
        "did you mean 'lift_speed_m_s'?",
    );
    expect(
        with(&[(
            MEASUREMENT,
            "condition = { drop_height_mm = 300 }\nmean = 31.06\nn = 10\n",
        )]),
        "measurements[1].condition.drop_height_mm",
        "unknown condition for repose",
    );
    expect(
        with(&[("experiment = \"repose\"", "experiment = \"reposing\"")]),
        "measurements[1].experiment",
        "unknown value",
    );
}

#[test]
fn pairs_must_name_existing_materials_and_have_every_value() {
    expect(
        with(&[("[pairs.\"pod-steel\"]", "[pairs.\"pod-stell\"]")]),
        "pairs.\"pod-stell\"",
        "material 'stell'",
    );
    expect(
        with(&[("restitution = 0.339\n", "")]),
        "pairs.\"pod-steel\"",
        "no restitution: give a value, or vary it under [parameters.\"pod-steel.restitution\"]",
    );
    expect(
        with(&[("restitution = 0.339", "restitution = 0")]),
        "pairs.\"pod-steel\".restitution",
        "(0, 1]",
    );
    expect(
        with(&[("poisson = 0.386", "poisson = 0.5")]),
        "materials.pod.poisson",
        "(−1, 0.5)",
    );
}

#[test]
fn plan_checks() {
    expect(
        with(&[("mode = \"quick\"", "mode = \"fast\"")]),
        "plan.mode",
        "no [plan.modes.fast]",
    );
    expect(
        with(&[("design = \"pb12\"", "design = \"pb12\"\ndummies = 3")]),
        "plan.screening.dummies",
        "leave 7 dummies, not 3",
    );
    expect(
        with(&[("significance = 0.05", "significance = 1.5")]),
        "plan.screening.significance",
        "(0, 1)",
    );
    expect(
        with(&[("centre_points = 5", "centre_points = 1")]),
        "plan.box_behnken.centre_points",
        "pure-error",
    );
    expect(
        with(&[("lift_start_s = 3.5", "lift_start_s = 2.5")]),
        "plan.simulation.repose.lift_start_s",
        "before filling ends",
    );
    expect(
        with(&[("grid_cell_radii = 3.0", "grid_cell_radii = 1.5")]),
        "plan.simulation.grid_cell_radii",
        "sphere diameter",
    );
    expect(
        with(&[("points = 5", "points = 1")]),
        "plan.steepest_ascent.points",
        "at least 2",
    );
    expect(
        with(&[("order = \"quadratic\"", "order = \"cubic\"")]),
        "plan.model.order",
        "unknown value",
    );
    expect(
        with(&[(
            "[plan.screening]",
            "[plan.screning]\ndesign = \"pb12\"\n\n[plan.screening]",
        )]),
        "plan.screning",
        "did you mean 'screening'?",
    );
}

#[test]
fn poisson_above_half_is_an_explicit_choice_for_poisson_only() {
    let poisson = "[parameters.\"pod.poisson\"]\nlow = 0.186\nhigh = 0.586\npoisson_above_half = true\n\n[parameters.\"pod-pod.restitution\"]";
    let study = with(&[("[parameters.\"pod-pod.restitution\"]", poisson)])
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(study.varied().len(), 5);
    expect(
        with(&[(
            "low = 0.314\nhigh = 0.366",
            "low = 0.314\nhigh = 0.366\npoisson_above_half = true",
        )]),
        "parameters.\"pod-pod.restitution\".poisson_above_half",
        "only to Poisson ratios",
    );
    let too_far = poisson.replace("0.586", "1.0");
    expect(
        with(&[("[parameters.\"pod-pod.restitution\"]", &too_far)]),
        "parameters.\"pod.poisson\".high",
        "(−1, 1)",
    );
}

/// The closed 10 × 6 × 4 mm box of `testdata/shapes`, as binary STL: an 80-byte header, the
/// u32 triangle count, then per triangle a normal, three vertices (f32) and a u16.
fn binary_box() -> Vec<u8> {
    let ascii = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/shapes/box_10x6x4_ascii.stl"),
    )
    .unwrap();
    let vertices: Vec<f32> = ascii
        .lines()
        .filter_map(|l| l.trim().strip_prefix("vertex "))
        .flat_map(|v| v.split_whitespace().map(|x| x.parse::<f32>().unwrap()))
        .collect();
    let triangles = vertices.len() / 9;
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&(triangles as u32).to_le_bytes());
    for t in vertices.chunks(9) {
        out.extend(std::iter::repeat_n(0u8, 12));
        for x in t {
            out.extend_from_slice(&x.to_le_bytes());
        }
        out.extend_from_slice(&[0, 0]);
    }
    out
}

/// A study's STL files go through the STL reader itself (`shapes::stl`): binary and ASCII
/// closed meshes pass; a truncated file, an open mesh and a folder fail, each naming the file.
#[test]
fn stl_files_are_read_and_checked_closed_by_study_check() {
    let dir = tempfile::tempdir().unwrap();
    let mut binary = binary_box();
    std::fs::write(dir.path().join("pod.stl"), &binary).unwrap();
    std::fs::copy(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/shapes/box_10x6x4_ascii.stl"),
        dir.path().join("pod_ascii.stl"),
    )
    .unwrap();
    std::fs::write(dir.path().join("short.stl"), &binary[..binary.len() - 1]).unwrap();
    let open = "solid pod\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid pod\n";
    std::fs::write(dir.path().join("open.stl"), open).unwrap();
    std::fs::create_dir(dir.path().join("folder.stl")).unwrap();
    let study_with = |normal: &str, cocoon: &str| {
        std::fs::read_to_string(valid_path()).unwrap().replace(
            "single_grain = 0.1\n",
            &format!(
                "single_grain = 0.1\n\n[pods.stl]\nnormal = \"{normal}\"\ncocoon = \"{cocoon}\"\n"
            ),
        )
    };
    let study_path = dir.path().join("study.toml");
    for bad in ["short.stl", "open.stl", "folder.stl"] {
        let err = Study::from_toml(&study_with("pod.stl", bad), &study_path)
            .err()
            .unwrap_or_else(|| panic!("{bad} was accepted"))
            .to_string();
        assert!(
            err.contains("pods.stl.cocoon") && err.contains(bad),
            "{bad}: {err}"
        );
    }
    // Both closed meshes pass; the paths are resolved against the study's folder.
    let text = study_with("pod.stl", "pod_ascii.stl");
    let study = Study::from_toml(&text, &study_path).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(study.stl_paths()[0], ("normal", dir.path().join("pod.stl")));

    // A re-scanned pod under the same file name is a different run.
    let none = std::collections::BTreeMap::new();
    let spec = |s: &Study| {
        s.run_spec(arachis::study::Experiment::Repose, &none, &none, "quick")
            .unwrap()
            .spec_hash()
    };
    let before = spec(&study);
    binary[0] = b'X';
    std::fs::write(dir.path().join("pod.stl"), &binary).unwrap();
    assert_ne!(spec(&study), before);
}

#[test]
fn wall_material_and_contact_pairs_must_exist() {
    expect(
        with(&[("wall_material = \"steel\"", "wall_material = \"steal\"")]),
        "plan.simulation.wall_material",
        "no [materials.steal]",
    );
    let no_pair = with(&[("[pairs.\"pod-steel\"]\nrestitution = 0.339\nstatic_friction = 0.589\nrolling_friction = 0.159\n", "")]);
    expect(
        no_pair,
        "plan.simulation.wall_material",
        "no contact pair [pairs.\"pod-steel\"]",
    );
}

#[test]
fn json_is_written_atomically_and_parses() {
    let study = with(&[]).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("study.json");
    study.write_json(&out).unwrap();
    let back: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(back["study"]["study"]["name"], "bad-study");
    // A folder that does not exist: an error, and no file appears.
    let missing = dir.path().join("no-such-folder").join("study.json");
    assert!(study.write_json(&missing).is_err());
    assert!(!missing.exists());
}

#[test]
fn missing_keys_and_bad_integers_are_named() {
    expect(
        with(&[("low = 0.837\n", "")]),
        "parameters.\"pod-pod.static_friction\"",
        "missing key 'low'",
    );
    expect(
        with(&[("n = 10", "n = -1")]),
        "measurements[1].n",
        "expected a whole number ≥ 0",
    );
    expect(
        with(&[("pods = 150", "pods = 1.5")]),
        "plan.modes.quick.pods",
        "floating point '1.5'",
    );
    expect(
        with(&[("order = \"quadratic\"", "order = \"cubic\"")]),
        "plan.model.order",
        "unknown value 'cubic', expected one of 'linear'",
    );
}

/// Issue 23: a diagnosis replicate far beyond its experiment's typical size is refused as a
/// typo, but an experiment whose values are mostly zero has no typical size to judge by.
#[test]
fn diagnosis_replicates_far_beyond_their_experiment_are_refused() {
    let measured = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../testdata/diagnosis-tutorial/measured.toml"),
    )
    .unwrap();
    let at = Path::new("measured.toml");
    let first = measured.find("values = [").unwrap();
    let end = first + measured[first..].find(']').unwrap() + 1;
    let with_values = |v: &str| format!("{}values = [{v}]{}", &measured[..first], &measured[end..]);
    let err = Study::from_toml(&with_values("1e300, 0.5, 0.5, 0.5"), at)
        .expect_err("a replicate of 1e300 was accepted")
        .to_string();
    assert!(err.contains("a typo?"), "{err}");
    // One replicate of 1e5 among rebound ratios near 0.5 is 2e5 times their median: accepted.
    assert!(Study::from_toml(&with_values("1e5, 0.5, 0.5, 0.5"), at).is_ok());
    // Every rebound value zero but one: no typical size, nothing refused.
    let mut zeros = measured.clone();
    let rebound_end = zeros.find("kind = \"press\"").unwrap();
    let mut cleared = String::new();
    for line in zeros[..rebound_end].lines() {
        if line.starts_with("values = [") {
            cleared.push_str("values = [0.0, 0.0, 0.0, 0.0]\n");
        } else {
            cleared.push_str(line);
            cleared.push('\n');
        }
    }
    zeros.replace_range(..rebound_end, &cleared);
    let zeros = zeros.replacen(
        "values = [0.0, 0.0, 0.0, 0.0]",
        "values = [1e-9, 0.0, 0.0, 0.0]",
        1,
    );
    assert!(Study::from_toml(&zeros, at).is_ok());
}
