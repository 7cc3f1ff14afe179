//! The shipped study `testdata/peanut-pods-saline/study.toml` loads, holds the numbers seed
//! 000 prints, agrees with the seed's other tables, and survives round trips through TOML
//! and JSON.
//!
//! Tolerances: a number typed from the seed must equal it exactly (it is the same decimal);
//! a number derived from printed numbers must agree within half a unit in the last printed
//! digit, widened by the rounding of its inputs where stated.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use arachis::io::CsvTable;
use arachis::study::parameters::lookup;
use arachis::study::{Experiment, Study, StudyFile};

fn repo(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path)
}

fn shipped() -> Study {
    Study::load(&repo("testdata/peanut-pods-saline/study.toml")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn materials_and_pairs_are_the_printed_numbers() {
    let study = shipped();
    let s = study.file();
    let pod = &s.materials["pod"];
    // Seed 000 §3.1.1–§3.1.3.
    assert_eq!(
        (pod.density_kg_m3, pod.poisson, pod.shear_modulus_pa),
        (582.36, 0.386, 3.04e6)
    );
    // §3.1.3 derives G = 3.04 MPa from E = 8.43 MPa by eq. (12): E = 2G(1 + ν) must give
    // 8.43 within half a unit of G's last digit (0.005 MPa) times 2(1 + ν) = 2.772, plus
    // half a unit of E's (0.005): 0.0189 MPa. (2 × 3.04 × 1.386 = 8.427.)
    let e_mpa = pod.youngs_modulus_pa() / 1e6;
    assert!((e_mpa - 8.43).abs() <= 0.005 * 2.772 + 0.005, "E = {e_mpa}");
    // Seed 000 Table 1 (65Mn steel).
    let steel = &s.materials["steel"];
    assert_eq!(
        (steel.density_kg_m3, steel.poisson, steel.shear_modulus_pa),
        (7865.0, 0.3, 7.9e10)
    );
    // Seed 001 Table 1 pod size.
    assert_eq!(
        {
            let pods = s.pods.as_ref().unwrap();
            (pods.length_mm, pods.width_mm, pods.thickness_mm)
        },
        (34.27, 18.29, 15.76)
    );
    // Seed 000 §3.4: the held pod–steel values.
    let ps = &s.pairs["pod-steel"];
    assert_eq!(
        (ps.restitution, ps.static_friction, ps.rolling_friction),
        (Some(0.339), Some(0.589), Some(0.159))
    );
    // Pod–pod is calibrated, so it carries no fixed values.
    let pp = &s.pairs["pod-pod"];
    assert_eq!(
        (pp.restitution, pp.static_friction, pp.rolling_friction),
        (None, None, None)
    );
}

#[test]
fn target_is_the_bench_angle_as_a_printed_summary() {
    let study = shipped();
    let t = study.target().unwrap();
    assert_eq!(t.experiment, Experiment::Repose.name());
    assert_eq!(t.mean(), Some(31.06)); // seed 000 §3.6.1
    assert_eq!(t.replicates(), Some(10)); // "repeated 10 times"
    assert!(!t.has_replicates(), "the seed prints only the mean");
    assert_eq!(t.sd, None, "the seed prints no SD");
    assert_eq!(t.condition["lift_speed_m_s"], 0.05);
    assert_eq!(study.validation(), Some(t));
}

/// Seed 000 Table 6 and Table 8 print ψ = |ζ′ − ζ|/ζ × 100 % (eq. (21)) against the bench
/// angle; the study's target must reproduce every printed ψ. Tolerance: half a unit of ψ's
/// last digit (0.005 %) plus the effect of ζ′'s rounding, 0.005°/31.06° × 100 % = 0.016 %.
#[test]
fn target_reproduces_the_printed_relative_errors() {
    let target = shipped().target().unwrap().mean().unwrap();
    let tolerance = 0.005 + 0.005 / target * 100.0;
    let mut checked = 0;
    for table in [
        "seed000_table6_steepest_ascent.csv",
        "seed000_table8_box_behnken.csv",
    ] {
        let csv = CsvTable::read(&repo("testdata/seed-tables").join(table)).unwrap();
        let angles = csv.f64_column("angle_deg").unwrap();
        let psi = csv.f64_column("rel_error_pct").unwrap();
        for (a, p) in angles.iter().zip(&psi) {
            let mine = (a - target).abs() / target * 100.0;
            assert!(
                (mine - p).abs() <= tolerance,
                "{table}: ζ′ {a}: ψ {mine} vs printed {p}"
            );
            checked += 1;
        }
    }
    assert_eq!(checked, 5 + 17);
}

/// The ranges are Table 3's; Table 4 (a different printed table) must use exactly these two
/// levels in every factor column. x2 is printed in MPa, the study holds Pa.
#[test]
fn ranges_are_table_3_and_the_levels_of_table_4() {
    let study = shipped();
    let varied = study.varied();
    let labels: Vec<&str> = varied.iter().map(|v| v.label.as_str()).collect();
    assert_eq!(labels, ["x1", "x2", "x3", "x4", "x5", "x6", "x7", "x8"]);
    let table3 = [
        (0.186, 0.586),
        (1.020e6, 5.060e6),
        (0.314, 0.366),
        (0.837, 0.878),
        (0.314, 0.356),
        (0.282, 0.396),
        (0.578, 0.601),
        (0.145, 0.172),
    ];
    let csv = CsvTable::read(&repo(
        "testdata/seed-tables/seed000_table4_plackett_burman.csv",
    ))
    .unwrap();
    for (v, (low, high)) in varied.iter().zip(table3) {
        assert_eq!((v.range.low, v.range.high), (low, high), "{}", v.spec.name);
        let scale = if v.spec.name == "pod.shear_modulus_pa" {
            1e6
        } else {
            1.0
        };
        let mut levels: Vec<f64> = csv
            .f64_column(&v.label)
            .unwrap()
            .iter()
            .map(|x| x * scale)
            .collect();
        levels.sort_by(f64::total_cmp);
        levels.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * scale);
        assert_eq!(levels.len(), 2, "{}", v.label);
        assert!(
            (levels[0] - low).abs() <= 1e-9 * scale && (levels[1] - high).abs() <= 1e-9 * scale
        );
    }
}

/// Seed 000 §3.4 holds x1, x2, x6, x7, x8 at 0.386, 3.04 MPa, 0.339, 0.589, 0.159. The study
/// gives them as base values; each is its range's centre within half a unit in the printed
/// last digit (x7: centre 0.5895 printed 0.589; x8: 0.1585 printed 0.159).
#[test]
fn held_values_are_the_printed_ones_and_the_range_centres() {
    let study = shipped();
    let printed = [
        ("pod.poisson", 0.386, 0.0005),
        ("pod.shear_modulus_pa", 3.04e6, 0.005e6),
        ("pod-steel.restitution", 0.339, 0.0005),
        ("pod-steel.static_friction", 0.589, 0.0005),
        ("pod-steel.rolling_friction", 0.159, 0.0005),
    ];
    for (name, value, half_unit) in printed {
        let spec = lookup(name).unwrap();
        assert_eq!(study.held_value(spec), Some(value), "{name}");
        let centre = study.file().parameters[name].centre();
        assert!(
            (centre - value).abs() <= half_unit * (1.0 + 1e-9),
            "{name}: centre {centre}"
        );
    }
    // Pod–pod has no base value: held at its range centre.
    let x4 = lookup("pod-pod.static_friction").unwrap();
    assert_eq!(study.held_value(x4), Some(0.5 * (0.837 + 0.878)));
}

/// The plan's design settings reproduce the seed's tables: 8 factors + 3 dummies in 12 runs
/// (§3.3), the path starting at Table 6 row 1 with x3 steps of 0.013, and Table 8's number
/// of centre runs.
#[test]
fn plan_matches_the_printed_designs() {
    let study = shipped();
    let plan = study.file().plan.as_ref().unwrap();
    assert_eq!(plan.screening.design_runs(), 12);
    assert_eq!(plan.screening.columns() - study.varied().len() as u32, 3);
    let path = CsvTable::read(&repo(
        "testdata/seed-tables/seed000_table6_steepest_ascent.csv",
    ))
    .unwrap();
    assert_eq!(
        path.f64_column("x3").unwrap().len() as u32,
        plan.steepest_ascent.points
    );
    for label in ["x3", "x4", "x5"] {
        let range = study
            .varied()
            .into_iter()
            .find(|v| v.label == label)
            .unwrap()
            .range
            .clone();
        let first = path.f64_column(label).unwrap()[0];
        let origin = range.centre()
            + plan.steepest_ascent.origin_coded.unwrap() * (range.high - range.low) / 2.0;
        assert!(
            (first - origin).abs() < 1e-12,
            "{label}: {first} vs {origin}"
        );
    }
    // x3 moves 0.5 coded = 0.013 per point; printed to 3 decimals, so within 0.0005 + 0.0005.
    let x3 = path.f64_column("x3").unwrap();
    let step = plan.steepest_ascent.step_coded * (0.366 - 0.314) / 2.0;
    for w in x3.windows(2) {
        assert!((w[1] - w[0] - step).abs() <= 0.001, "{w:?}");
    }
    let bb = CsvTable::read(&repo("testdata/seed-tables/seed000_table8_box_behnken.csv")).unwrap();
    let (a, b, c) = (
        bb.f64_column("x3").unwrap(),
        bb.f64_column("x4").unwrap(),
        bb.f64_column("x5").unwrap(),
    );
    let centres = (0..a.len())
        .filter(|&i| (a[i], b[i], c[i]) == (0.334, 0.853, 0.341))
        .count();
    assert_eq!(
        centres as u32,
        plan.box_behnken.as_ref().unwrap().centre_points
    );
    assert_eq!(plan.modes["full"].pods, 900); // §2.7
    let simulation = plan.simulation.as_ref().unwrap();
    assert_eq!(simulation.dt_rayleigh_fraction, 0.2); // §2.7
    assert_eq!(simulation.repose.lift_speed_m_s, 0.05); // §2.7
}

#[test]
fn toml_round_trip_gives_the_same_study() {
    let study = shipped();
    let text = study.to_toml();
    let again = Study::from_toml(&text, study.path()).unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(again.file(), study.file());
}

#[test]
fn json_export_round_trips_and_carries_the_derived_numbers() {
    let study = shipped();
    let json: serde_json::Value = serde_json::from_str(&study.to_json()).unwrap();
    assert_eq!(json["format"], "arachis-study-1");
    assert_eq!(json["derived"]["target_value"], 31.06);
    assert_eq!(json["derived"]["target_replicates"], 10);
    assert_eq!(json["derived"]["target_replicates_printed"], false);
    assert_eq!(json["derived"]["screening_dummies"], 3);
    assert_eq!(json["derived"]["varied"][3]["label"], "x4");
    let file: StudyFile = serde_json::from_value(json["study"].clone()).unwrap();
    assert_eq!(&file, study.file());
}

#[test]
fn summary_names_what_a_user_checks() {
    let text = shipped().summary();
    for needle in [
        "peanut-pods-saline",
        "pod: ρ 582.36 kg/m³, ν 0.386, G 3.04 MPa",
        "repose repose_angle: 31.06 deg (n = 10, printed mean)",
        "x4   pod-pod.static_friction      0.837 … 0.878",
        "8 factors + 3 dummies",
        "mode quick (default): 150 pods",
    ] {
        assert!(text.contains(needle), "summary lacks '{needle}':\n{text}");
    }
}

#[test]
fn spec_hash_is_stable_and_tells_runs_apart() {
    let study = shipped();
    let condition = study.target().unwrap().condition.clone();
    let optimum: BTreeMap<String, f64> = [
        ("pod-pod.restitution", 0.335),
        ("pod-pod.static_friction", 0.854),
        ("pod-pod.rolling_friction", 0.346),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_owned(), v))
    .collect();
    let spec = study
        .run_spec(Experiment::Repose, &condition, &optimum, "full")
        .unwrap();
    // Held parameters take the study's values; varied ones the given values.
    assert_eq!(spec.pairs["pod-pod"].static_friction, 0.854);
    assert_eq!(spec.pairs["pod-steel"].static_friction, 0.589);
    assert_eq!(spec.materials["pod"].poisson, 0.386);
    assert_eq!(spec.mode.pods, 900);
    // Canonical JSON: sorted keys, no whitespace.
    let json = spec.canonical_json();
    assert!(
        json.starts_with(
            r#"{"condition":{"lift_speed_m_s":0.05,"moisture_pct":36.72},"experiment":"repose","#
        ),
        "{json}"
    );
    assert!(!json.contains(' '), "{json}");
    assert_keys_sorted(&serde_json::from_str(&json).unwrap());
    // Same spec → same hash; any change → another hash.
    let again = study
        .run_spec(Experiment::Repose, &condition, &optimum, "full")
        .unwrap();
    assert_eq!(spec.spec_hash(), again.spec_hash());
    let mut nudged = optimum.clone();
    nudged.insert("pod-pod.static_friction".into(), 0.855);
    let other = study
        .run_spec(Experiment::Repose, &condition, &nudged, "full")
        .unwrap();
    assert_ne!(spec.spec_hash(), other.spec_hash());
    let quick = study
        .run_spec(Experiment::Repose, &condition, &optimum, "quick")
        .unwrap();
    assert_ne!(spec.spec_hash(), quick.spec_hash());
    // Unknown names and modes are errors, not silently ignored.
    let mut typo = optimum.clone();
    typo.insert("pod-pod.static_fricton".into(), 0.85);
    assert!(study
        .run_spec(Experiment::Repose, &condition, &typo, "full")
        .is_err());
    assert!(study
        .run_spec(Experiment::Repose, &condition, &optimum, "huge")
        .is_err());
}

/// Every object's keys, at every depth, are in bytewise order.
fn assert_keys_sorted(value: &serde_json::Value) {
    match value {
        serde_json::Value::Object(map) => {
            let keys: Vec<&String> = map.keys().collect();
            let mut sorted = keys.clone();
            sorted.sort();
            assert_eq!(keys, sorted);
            map.values().for_each(assert_keys_sorted);
        }
        serde_json::Value::Array(items) => items.iter().for_each(assert_keys_sorted),
        _ => {}
    }
}

/// Published FNV-1a 64 test vectors (Fowler–Noll–Vo reference test suite).
#[test]
fn fnv1a_matches_published_vectors() {
    use arachis::calibration::spec_hash::fnv1a_64;
    assert_eq!(fnv1a_64(b""), 0xcbf29ce484222325);
    assert_eq!(fnv1a_64(b"a"), 0xaf63dc4c8601ec8c);
    assert_eq!(fnv1a_64(b"foobar"), 0x85944171f73967e8);
}

/// The digest is fixed across machines and builds: FNV-1a over canonical JSON has no
/// platform-dependent input. The value was computed once from the test fixture
/// `testdata/bad-studies/valid.toml` (not the shipped study, which others tune); if the
/// fixture or the spec layout changes on purpose, update it, and bump SPEC_FORMAT_VERSION
/// when the meaning of a field changed so old cache entries retire.
#[test]
fn spec_hash_golden_value() {
    let study = Study::load(&repo("testdata/bad-studies/valid.toml")).unwrap();
    let condition = BTreeMap::new();
    let spec = study
        .run_spec(Experiment::Repose, &condition, &BTreeMap::new(), "quick")
        .unwrap();
    let text = spec.canonical_json();
    assert_eq!(
        arachis::calibration::spec_hash::fnv1a_64(text.as_bytes()),
        spec.spec_hash().0
    );
    assert_eq!(spec.spec_hash().to_string(), GOLDEN, "{text}");
}

/// Cross-checked with an independent Python FNV-1a over the same canonical text (whose
/// key order and separators match `json.dumps(sort_keys=True, separators=(",", ":"))`).
const GOLDEN: &str = "e06a5c36655f144c";
