//! Shared helpers for the seed ANOVA tests: read a seed table, analyse it, and compare a
//! computed number with the digits a seed prints.

use std::path::PathBuf;

use arachis::io::CsvTable;
use arachis::stats::{analyze, read_design_table, Anova, FactorLevels, ModelOrder};

/// Path of a transcribed seed table.
pub fn seed_table_path(file: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../testdata/seed-tables")
        .join(file)
}

/// Analyses `response` of seed table `file` with the given factor levels.
pub fn analyze_seed(
    file: &str,
    response: &str,
    factors: Option<&[&str]>,
    levels: &[(&str, FactorLevels)],
    order: ModelOrder,
) -> Anova {
    let table = CsvTable::read(&seed_table_path(file)).unwrap();
    let factors: Option<Vec<String>> = factors.map(|f| f.iter().map(|s| s.to_string()).collect());
    let levels: Vec<(String, FactorLevels)> = levels
        .iter()
        .map(|(n, l)| (n.to_string(), l.clone()))
        .collect();
    let design = read_design_table(&table, response, factors.as_deref(), &levels).unwrap();
    analyze(&design.design, order).unwrap()
}

/// Half a unit in the last digit of a printed number such as "13.92", "0.0161" or "3.04e-4".
pub fn half_unit(printed: &str) -> f64 {
    let (mantissa, exponent) = match printed.split_once(['e', 'E']) {
        Some((m, e)) => (m, e.parse::<i32>().unwrap()),
        None => (printed, 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    0.5 * 10f64.powi(exponent - decimals)
}

/// Asserts that `value` rounds to the `printed` digits: |value − printed| ≤ half a unit in
/// the last printed digit (plus 1e-12 relative, so that a value exactly on the rounding
/// boundary, which the seed rounded half-up, is accepted). "<0.0001" means value < 1e-4.
pub fn assert_printed(label: &str, value: f64, printed: &str) {
    if let Some(bound) = printed.strip_prefix('<') {
        let bound: f64 = bound.parse().unwrap();
        assert!(value < bound, "{label}: {value} is not < {bound}");
        return;
    }
    let target: f64 = printed.parse().unwrap();
    let tolerance = half_unit(printed) * (1.0 + 1e-9) + 1e-12 * target.abs();
    assert!(
        (value - target).abs() <= tolerance,
        "{label}: computed {value} does not round to the printed {printed} (±{tolerance})"
    );
}

/// The printed rows of a seed ANOVA table: (source, SS, df, MS, F, p); "" = not printed.
pub type PrintedRow<'a> = (&'a str, &'a str, usize, &'a str, &'a str, &'a str);

/// Checks each printed term row (`source` is the term name) against `anova`.
pub fn assert_term_rows(anova: &Anova, rows: &[PrintedRow<'_>]) {
    for &(name, ss, df, ms, f, p) in rows {
        let row = anova
            .terms
            .iter()
            .find(|t| t.name == name)
            .unwrap_or_else(|| panic!("no term {name}"));
        assert_eq!(row.df, df, "{name} df");
        for (what, value, printed) in [
            ("SS", row.ss, ss),
            ("MS", row.ms, ms),
            ("F", row.f, f),
            ("p", row.p, p),
        ] {
            if !printed.is_empty() {
                assert_printed(&format!("{name} {what}"), value, printed);
            }
        }
    }
}

/// Asserts the coded-equation coefficient of `term` against its printed digits.
pub fn assert_coefficient(anova: &Anova, term: &str, printed: &str) {
    let c = anova
        .coefficients
        .iter()
        .find(|c| c.term == term)
        .unwrap_or_else(|| panic!("no coefficient {term}"));
    assert_printed(&format!("coefficient {term}"), c.estimate, printed);
}
