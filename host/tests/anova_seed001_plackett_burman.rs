//! Seed 001 Table 7 (Plackett–Burman ANOVA with centre points), its coded equation and R²,
//! from Table 6, linear model in X1..X9.
//!
//! Curvature: Table 6 has 12 factorial runs and 3 centre runs (6, 9, 13). Table 7 prints no
//! curvature row, but its residual (0.7053 on 4 df = 15 − 1 − 9 − 1) and its total leave
//! exactly one df and 63.37 − 55.67 − 0.7053 = 6.99 unaccounted for: Design-Expert split the
//! 1-df curvature term out before the residual. Lack of fit (2 df: the two unprinted dummy
//! columns) and pure error (2 df: three centre replicates) split that residual.
//!
//! Tolerance: half a unit in the last printed digit. The intercept 8.125 (the factorial
//! mean, 97.50/12) lies exactly on the rounding boundary of the printed 8.13.

use crate::anova_support;

use anova_support::{
    analyze_seed, assert_coefficient, assert_printed, assert_term_rows, half_unit, seed_table_path,
};
use arachis::io::CsvTable;
use arachis::stats::curvature::{centre_point_indicator, curvature_sum_of_squares};
use arachis::stats::{read_design_table, Anova, FactorLevels, ModelOrder};

/// Seed 001 Table 5: actual levels at coded −1 and +1.
const LEVELS: [(&str, f64, f64); 9] = [
    ("X1", 0.61, 0.82),
    ("X2", 0.45, 0.76),
    ("X3", 0.16, 0.33),
    ("X4", 0.42, 0.68),
    ("X5", 0.32, 0.54),
    ("X6", 0.18, 0.39),
    ("X7", 3.00, 7.00),
    ("X8", 6.00, 14.00),
    ("X9", 1.00, 1.20),
];

const FILE: &str = "seed001_table6_plackett_burman.csv";

fn levels() -> Vec<(&'static str, FactorLevels)> {
    LEVELS
        .iter()
        .map(|(n, lo, hi)| (*n, FactorLevels::new(*lo, *hi).unwrap()))
        .collect()
}

fn table_7() -> Anova {
    analyze_seed(FILE, "force_n", None, &levels(), ModelOrder::Linear)
}

#[test]
fn table_7_model_and_error_rows() {
    let a = table_7();
    assert_printed("Model SS", a.model.ss, "55.67");
    assert_eq!(a.model.df, 9);
    assert_printed("Model MS", a.model.ms, "6.19");
    assert_printed("Model F", a.model.f, "35.08");
    assert_printed("Model p", a.model.p, "0.0019");
    assert_printed("Residual SS", a.residual.ss, "0.7053");
    assert_eq!(a.residual.df, 4);
    assert_printed("Residual MS", a.residual.ms, "0.1763");
    let lof = a.lack_of_fit.as_ref().unwrap();
    assert_printed("Lack of fit SS", lof.ss, "0.3331");
    assert_eq!(lof.df, 2);
    assert_printed("Lack of fit MS", lof.ms, "0.1665");
    assert_printed("Lack of fit F", lof.f, "0.8947");
    assert_printed("Lack of fit p", lof.p, "0.5278");
    let pe = a.pure_error.unwrap();
    assert_printed("Pure error SS", pe.ss, "0.3723");
    assert_eq!(pe.df, 2);
    assert_printed("Pure error MS", pe.ms, "0.1861");
    assert_printed("Cor total SS", a.cor_total.ss, "63.37");
    assert_eq!(a.cor_total.df, 14);
    // Text below the equation: R² = 0.9875 (= SS_model / (SS_model + SS_residual)).
    assert_printed("R2", a.fit.r2, "0.9875");
}

#[test]
fn curvature_is_split_out_before_the_residual() {
    let a = table_7();
    let c = a
        .curvature
        .as_ref()
        .expect("centre points give a curvature term");
    assert_eq!(c.df, 1);
    // Not printed: implied by Cor total − Model − Residual, each rounded as printed.
    let implied = 63.37 - 55.67 - 0.7053;
    let rounding = half_unit("63.37") + half_unit("55.67") + half_unit("0.7053");
    assert!(
        (c.ss - implied).abs() <= rounding,
        "curvature SS {} vs implied {implied} ± {rounding}",
        c.ss
    );
    // And it is the textbook factorial-vs-centre contrast.
    let table = CsvTable::read(&seed_table_path(FILE)).unwrap();
    let levels: Vec<(String, FactorLevels)> = levels()
        .into_iter()
        .map(|(n, l)| (n.to_owned(), l))
        .collect();
    let design = read_design_table(&table, "force_n", None, &levels)
        .unwrap()
        .design;
    let indicator = centre_point_indicator(&design.runs, ModelOrder::Linear).unwrap();
    assert_eq!(indicator.iter().sum::<f64>(), 3.0);
    let contrast = curvature_sum_of_squares(&design.response, &indicator);
    assert!((c.ss - contrast).abs() < 1e-9 * contrast);
}

#[test]
fn table_7_factor_rows() {
    assert_term_rows(
        &table_7(),
        &[
            ("X1", "0.8216", 1, "0.8216", "4.66", "0.0970"),
            ("X2", "1.86", 1, "1.86", "10.53", "0.0315"),
            ("X3", "0.5376", 1, "0.5376", "3.05", "0.1557"),
            ("X4", "3.06", 1, "3.06", "17.36", "0.0141"),
            ("X5", "0.1083", 1, "0.1083", "0.6142", "0.4770"),
            ("X6", "0.7008", 1, "0.7008", "3.97", "0.1170"),
            ("X7", "13.40", 1, "13.40", "75.98", "0.0010"),
            ("X8", "34.00", 1, "34.00", "192.84", "0.0002"),
            ("X9", "1.18", 1, "1.18", "6.68", "0.0610"),
        ],
    );
}

#[test]
fn coded_equation() {
    // Seed 001: F = 8.13 − 0.2617x1 + 0.3933x2 + 0.2117x3 − 0.505x4 + 0.095x5 + 0.2417x6
    //               + 1.06x7 − 1.68x8 + 0.3133x9. The extracted text drops each "−" and
    //               leaves a bare gap where it stood ("8.13 0.2617 x 1 + 0.3933 x 2"),
    //               while every "+" survives.
    let a = table_7();
    for (term, printed) in [
        ("Intercept", "8.13"),
        ("X1", "-0.2617"),
        ("X2", "0.3933"),
        ("X3", "0.2117"),
        ("X4", "-0.505"),
        ("X5", "0.095"),
        ("X6", "0.2417"),
        ("X7", "1.06"),
        ("X8", "-1.68"),
        ("X9", "0.3133"),
    ] {
        assert_coefficient(&a, term, printed);
    }
}
