//! The seeds' printed design tables, read from `testdata/seed-tables/`, against the designs this
//! crate generates.
//!
//! Tolerance: half a unit in the last printed digit of each cell (the seeds print actual levels
//! rounded to 2–3 decimals), plus 1e-12 for binary rounding where the seed rounds an exact half
//! (seed 000 Table 7 prints the x3 centre 0.3335 as 0.334).
//!
//! Each table is checked twice: as a multiset of rows (independent of run order) and cell by
//! cell in the printed run order, using the stored permutations of
//! `arachis::doe::seed_run_orders`.

use std::path::PathBuf;

use arachis::doe::{
    box_behnken, central_composite, plackett_burman, seed_run_orders, steepest_ascent, Alpha,
    Design, Factor, PlackettBurmanRuns,
};
use arachis::io::CsvTable;

fn seed_table(name: &str) -> CsvTable {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/seed-tables")
        .join(name);
    CsvTable::read(&path).unwrap()
}

/// Half a unit in the last digit of a printed number.
fn half_unit(text: &str) -> f64 {
    let decimals = text.split_once('.').map_or(0, |(_, d)| d.len());
    0.5 * 10f64.powi(-(decimals as i32)) + 1e-12
}

/// The printed cells of `columns`, as (value, tolerance) per run, in printed order.
fn printed(table: &CsvTable, columns: &[&str]) -> Vec<Vec<(f64, f64)>> {
    let idx: Vec<usize> = columns
        .iter()
        .map(|c| table.column_index(c).unwrap())
        .collect();
    table
        .rows
        .iter()
        .map(|row| {
            idx.iter()
                .map(|&i| (table.f64_cell(row, i).unwrap(), half_unit(&row.cells[i])))
                .collect()
        })
        .collect()
}

/// Checks the printed run numbers are 1, 2, … in file order.
fn assert_runs_in_order(table: &CsvTable) {
    let runs = table.f64_column("run").unwrap();
    let expected: Vec<f64> = (1..=runs.len()).map(|r| r as f64).collect();
    assert_eq!(runs, expected);
}

/// Generated actual levels in run order equal the printed ones cell by cell.
fn assert_matches_in_printed_order(design: &Design, table: &CsvTable, columns: &[&str]) {
    assert_runs_in_order(table);
    let cells = printed(table, columns);
    let generated = design.actual_in_run_order();
    assert_eq!(generated.len(), cells.len(), "number of runs");
    for (run, (gen, want)) in generated.iter().zip(&cells).enumerate() {
        for (j, (g, (p, tol))) in gen.iter().zip(want).enumerate() {
            assert!(
                (g - p).abs() <= *tol,
                "run {}: column {}: generated {g}, printed {p} (tolerance {tol})",
                run + 1,
                columns[j]
            );
        }
    }
}

/// Generated and printed rows are equal as multisets: every printed row is matched to its
/// own generated row (in any order) within the printed-digit tolerance. Levels differ by far
/// more than the tolerance, so a greedy match is exact.
fn assert_same_rows(design: &Design, table: &CsvTable, columns: &[&str]) {
    let generated: Vec<Vec<f64>> = (0..design.runs()).map(|s| design.actual_row(s)).collect();
    let cells = printed(table, columns);
    assert_eq!(generated.len(), cells.len(), "number of runs");
    let mut used = vec![false; generated.len()];
    for (run, want) in cells.iter().enumerate() {
        let hit = (0..generated.len()).find(|&s| {
            !used[s]
                && generated[s]
                    .iter()
                    .zip(want)
                    .all(|(g, (p, tol))| (g - p).abs() <= *tol)
        });
        match hit {
            Some(s) => used[s] = true,
            None => panic!(
                "printed run {} {:?} is not a row of the design",
                run + 1,
                want
            ),
        }
    }
}

fn factor(name: &str, unit: &str, low: f64, high: f64) -> Factor {
    Factor::new(name, unit, low, high).unwrap()
}

/// Seed 000 Table 3: the Plackett–Burman levels.
fn seed000_table3() -> Vec<Factor> {
    vec![
        factor("x1", "-", 0.186, 0.586),
        factor("x2", "MPa", 1.020, 5.060),
        factor("x3", "-", 0.314, 0.366),
        factor("x4", "-", 0.837, 0.878),
        factor("x5", "-", 0.314, 0.356),
        factor("x6", "-", 0.282, 0.396),
        factor("x7", "-", 0.578, 0.601),
        factor("x8", "-", 0.145, 0.172),
    ]
}

const SEED000_PB_COLUMNS: [&str; 8] = ["x1", "x2", "x3", "x4", "x5", "x6", "x7", "x8"];

#[test]
fn seed000_table4_is_the_12_run_plackett_burman_design() {
    let table = seed_table("seed000_table4_plackett_burman.csv");
    let design = plackett_burman(PlackettBurmanRuns::Twelve, &seed000_table3(), 0)
        .unwrap()
        .with_dummy_names(&["x9", "x10", "x11"])
        .unwrap();
    assert_eq!(design.runs(), 12);
    assert_same_rows(&design, &table, &SEED000_PB_COLUMNS);
    let design = design
        .with_run_order(&seed_run_orders::SEED000_TABLE4_PLACKETT_BURMAN)
        .unwrap();
    assert_matches_in_printed_order(&design, &table, &SEED000_PB_COLUMNS);
}

/// Seed 000 Table 7: the Box–Behnken levels (−1 and +1; the centre follows).
fn seed000_table7() -> Vec<Factor> {
    vec![
        factor("x3", "-", 0.327, 0.340),
        factor("x4", "-", 0.848, 0.858),
        factor("x5", "-", 0.332, 0.350),
    ]
}

#[test]
fn seed000_table7_centre_levels_are_the_midpoints() {
    // Table 7 prints centres 0.334, 0.853, 0.341; midpoints 0.3335, 0.853, 0.341.
    let printed_centres = [0.334, 0.853, 0.341];
    for (f, p) in seed000_table7().iter().zip(printed_centres) {
        assert!(
            (f.centre() - p).abs() <= 0.0005 + 1e-12,
            "{}: {}",
            f.name,
            f.centre()
        );
    }
}

#[test]
fn seed000_table8_is_the_3_factor_box_behnken_design_with_5_centre_points() {
    let table = seed_table("seed000_table8_box_behnken.csv");
    let design = box_behnken(&seed000_table7(), 5).unwrap();
    assert_eq!(design.runs(), 17);
    assert_same_rows(&design, &table, &["x3", "x4", "x5"]);
    let design = design
        .with_run_order(&seed_run_orders::SEED000_TABLE8_BOX_BEHNKEN)
        .unwrap();
    assert_matches_in_printed_order(&design, &table, &["x3", "x4", "x5"]);
}

/// Seed 001 Table 5: the Plackett–Burman levels (X7 in 1e5 N/m³, X8 in 1e5 Pa, X9 in mm).
fn seed001_table5() -> Vec<Factor> {
    vec![
        factor("X1", "-", 0.61, 0.82),
        factor("X2", "-", 0.45, 0.76),
        factor("X3", "-", 0.16, 0.33),
        factor("X4", "-", 0.42, 0.68),
        factor("X5", "-", 0.32, 0.54),
        factor("X6", "-", 0.18, 0.39),
        factor("X7", "1e5 N/m^3", 3.00, 7.00),
        factor("X8", "1e5 Pa", 6.00, 14.00),
        factor("X9", "mm", 1.00, 1.20),
    ]
}

const SEED001_PB_COLUMNS: [&str; 9] = ["X1", "X2", "X3", "X4", "X5", "X6", "X7", "X8", "X9"];

#[test]
fn seed001_table6_is_the_12_run_plackett_burman_design_with_3_centre_points() {
    let table = seed_table("seed001_table6_plackett_burman.csv");
    let design = plackett_burman(PlackettBurmanRuns::Twelve, &seed001_table5(), 3).unwrap();
    assert_eq!(design.runs(), 15);
    assert_eq!(design.dummy_columns.len(), 2);
    assert_same_rows(&design, &table, &SEED001_PB_COLUMNS);
    let design = design
        .with_run_order(&seed_run_orders::SEED001_TABLE6_PLACKETT_BURMAN)
        .unwrap();
    assert_matches_in_printed_order(&design, &table, &SEED001_PB_COLUMNS);
}

/// Seed 001 Table 9 gives the axial levels (coded ±1.414): X7 4.00…6.00, X8 8.00…12.00.
fn seed001_table9_from_axial_levels() -> Vec<Factor> {
    vec![
        Factor::from_axial_levels("X7", "1e5 N/m^3", 4.00, 6.00, 1.414).unwrap(),
        Factor::from_axial_levels("X8", "1e5 Pa", 8.00, 12.00, 1.414).unwrap(),
    ]
}

#[test]
fn seed001_table9_unit_levels_follow_from_the_axial_levels() {
    // Table 9 prints coded ±1 as 4.293/5.707 (X7) and 8.586/11.414 (X8), 3 decimals.
    let f = seed001_table9_from_axial_levels();
    let printed = [(4.293, 5.707), (8.586, 11.414)];
    for (f, (lo, hi)) in f.iter().zip(printed) {
        assert!((f.low - lo).abs() <= 0.0005, "{}: low {}", f.name, f.low);
        assert!((f.high - hi).abs() <= 0.0005, "{}: high {}", f.name, f.high);
    }
}

#[test]
fn seed001_table10_is_the_2_factor_central_composite_design_alpha_1414() {
    let table = seed_table("seed001_table10_ccd.csv");
    let design =
        central_composite(&seed001_table9_from_axial_levels(), Alpha::Value(1.414), 5).unwrap();
    assert_eq!(design.runs(), 13);
    assert_same_rows(&design, &table, &["X7", "X8"]);
    let design = design
        .with_run_order(&seed_run_orders::SEED001_TABLE10_CENTRAL_COMPOSITE)
        .unwrap();
    assert_matches_in_printed_order(&design, &table, &["X7", "X8"]);
}

#[test]
fn seed001_table10_also_follows_from_the_printed_unit_levels() {
    // Entering Table 9's printed ±1 levels instead puts the axial points at
    // 5.00 ± 1.414 × 0.707 = 4.0003 / 5.9997, which still prints as 4.00 / 6.00.
    let factors = vec![
        factor("X7", "1e5 N/m^3", 4.293, 5.707),
        factor("X8", "1e5 Pa", 8.586, 11.414),
    ];
    let design = central_composite(&factors, Alpha::Value(1.414), 5)
        .unwrap()
        .with_run_order(&seed_run_orders::SEED001_TABLE10_CENTRAL_COMPOSITE)
        .unwrap();
    let table = seed_table("seed001_table10_ccd.csv");
    assert_matches_in_printed_order(&design, &table, &["X7", "X8"]);
}

#[test]
fn seed001_table8_is_a_straight_path_from_the_low_corner() {
    // Seed 001 Table 8: X7 and X8 rise by a quarter of the Table 5 range per step
    // (coded step 0.5 along direction (1, 1) from (−1, −1)).
    let table = seed_table("seed001_table8_steepest_ascent.csv");
    let factors = vec![
        factor("X7", "1e5 N/m^3", 3.00, 7.00),
        factor("X8", "1e5 Pa", 6.00, 14.00),
    ];
    let design = steepest_ascent(&factors, &[1.0, 1.0], &[-1.0, -1.0], 0.5, 5).unwrap();
    assert_matches_in_printed_order(&design, &table, &["X7", "X8"]);
}

#[test]
fn seed000_table6_is_not_a_straight_path() {
    // Seed 000 Table 6 runs from the Table 3 low levels (run 1) to the high levels (run 5).
    // A straight path in equal steps reproduces x3 (step 0.013) but not x5, which rises
    // 0.018, 0.018, 0.003, 0.003: run 3 prints 0.350 where the straight path has 0.335.
    // The printed path is therefore hand-set; this test documents that with numbers and
    // would fail if a transcription error made the path straight.
    let table = seed_table("seed000_table6_steepest_ascent.csv");
    let factors = vec![
        factor("x3", "-", 0.314, 0.366),
        factor("x4", "-", 0.837, 0.878),
        factor("x5", "-", 0.314, 0.356),
    ];
    let design = steepest_ascent(&factors, &[1.0, 1.0, 1.0], &[-1.0; 3], 0.5, 5).unwrap();
    let generated = design.actual_in_run_order();
    let cells = printed(&table, &["x3", "x4", "x5"]);
    for (g, p) in generated.iter().zip(&cells) {
        assert!(
            (g[0] - p[0].0).abs() <= p[0].1,
            "x3: {} vs {}",
            g[0],
            p[0].0
        );
    }
    let x5_gap = (generated[2][2] - cells[2][2].0).abs();
    assert!(
        (x5_gap - 0.015).abs() < 1e-9,
        "x5 at run 3 differs by {x5_gap}"
    );
    // x4 is off by more than rounding too: 0.84725 on the line, 0.848 printed at run 2.
    let x4_gap = (generated[1][1] - cells[1][1].0).abs();
    assert!(x4_gap > cells[1][1].1, "x4 at run 2 differs by {x4_gap}");
}
