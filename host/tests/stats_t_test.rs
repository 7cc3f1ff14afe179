//! The pooled two-sample t-test and relative error: seed 001 Table 12 and a textbook case.

use arachis::stats::{pooled_t_test, relative_error_percent};

/// Seed 001 Table 12: harvest loss rate, %, simulation (y1) and field trials (y2).
const SIMULATION: [f64; 4] = [3.75, 4.02, 4.27, 3.18];
const FIELD: [f64; 4] = [4.01, 3.83, 4.04, 3.42];

#[test]
fn seed_001_table_12_simulation_agrees_with_field() {
    let test = pooled_t_test(&SIMULATION, &FIELD).unwrap();
    assert_eq!(test.df, 6);
    // The seed reports no significant difference (p > 0.05).
    assert!(test.p > 0.05, "p = {}", test.p);
    // Means 3.805 and 3.825 differ by 0.02 against a pooled s.d. of about 0.39.
    assert!((test.mean_1 - 3.805).abs() < 1e-12 && (test.mean_2 - 3.825).abs() < 1e-12);
}

#[test]
fn seed_001_table_12_relative_errors() {
    // Printed "absolute value of relative error" row: 6.93 4.73 5.39 7.55 (%). They are
    // relative to the simulated value y1: |3.75 − 4.01|/3.75 = 6.93 %, whereas relative to
    // the field value it would be 6.48 %.
    let printed = [6.93, 4.73, 5.39, 7.55];
    for ((sim, field), want) in SIMULATION.iter().zip(FIELD).zip(printed) {
        let got = relative_error_percent(field, *sim);
        assert!(
            (got - want).abs() <= 0.005,
            "{sim} vs {field}: {got} ≠ {want}"
        );
    }
}

#[test]
fn seed_000_eq_21_relative_error() {
    // Seed 000 Table 6 run 1: ζ' = 23.89° against the bench angle 31.06° gives ψ = 23.08 %.
    assert!((relative_error_percent(23.89, 31.06) - 23.08).abs() <= 0.005);
}

#[test]
fn textbook_portland_cement_mortar() {
    // Montgomery, Design and Analysis of Experiments, Table 2.1: tension bond strength
    // (kgf/cm²) of modified and unmodified mortar. Printed: t0 = −2.19 (software output),
    // 18 df, P = 0.042.
    let modified = [
        16.85, 16.40, 17.21, 16.35, 16.52, 17.04, 16.96, 17.15, 16.59, 16.57,
    ];
    let unmodified = [
        16.62, 16.75, 17.37, 17.12, 16.98, 16.87, 17.34, 17.02, 17.08, 17.27,
    ];
    let test = pooled_t_test(&modified, &unmodified).unwrap();
    assert_eq!(test.df, 18);
    assert!((test.t + 2.19).abs() <= 0.005, "t = {}", test.t);
    assert!((test.p - 0.042).abs() <= 0.0005, "p = {}", test.p);
}

#[test]
fn degenerate_samples_are_errors() {
    assert!(pooled_t_test(&[1.0], &[1.0, 2.0]).is_err());
    assert!(pooled_t_test(&[1.0, 1.0], &[2.0, 2.0]).is_err());
}

#[test]
fn seed_000_tables_6_and_8_relative_error_columns() {
    // Every printed ψ in seed 000 Tables 6 and 8 is eq. (21) against the bench angle 31.06°
    // (seed 000 §3.6.1), to half a unit in its last printed digit (0.005 %).
    const BENCH_ANGLE_DEG: f64 = 31.06;
    for file in [
        "seed000_table6_steepest_ascent.csv",
        "seed000_table8_box_behnken.csv",
    ] {
        let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("../testdata/seed-tables")
            .join(file);
        let table = arachis::io::CsvTable::read(&path).unwrap();
        let angles = table.f64_column("angle_deg").unwrap();
        let printed = table.f64_column("rel_error_pct").unwrap();
        for (angle, psi) in angles.iter().zip(printed) {
            let got = relative_error_percent(*angle, BENCH_ANGLE_DEG);
            assert!(
                (got - psi).abs() <= 0.005,
                "{file}: ζ = {angle}: ψ {got} ≠ printed {psi}"
            );
        }
    }
}
