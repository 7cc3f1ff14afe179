//! Seed 000 Table 5 (Plackett–Burman significance analysis) from Table 4 (design and
//! stacking angles), linear model on the eight real factors x1..x8.
//!
//! Dummy columns: Table 4 prints only x1..x8 and Table 5's residual has 3 df =
//! 12 runs − 1 − 8 terms, so Design-Expert left the three dummy columns x9..x11 out of the
//! model and their sums of squares in the residual. That is what fitting x1..x8 does.
//!
//! Tolerance: half a unit in the last printed digit (see `anova_support::assert_printed`).

use crate::anova_support;

use anova_support::{analyze_seed, assert_printed, assert_term_rows};
use arachis::stats::{Anova, FactorLevels, ModelOrder};

/// Seed 000 Table 3: actual levels of x1..x8 at coded −1 and +1.
const LEVELS: [(&str, f64, f64); 8] = [
    ("x1", 0.186, 0.586),
    ("x2", 1.020, 5.060),
    ("x3", 0.314, 0.366),
    ("x4", 0.837, 0.878),
    ("x5", 0.314, 0.356),
    ("x6", 0.282, 0.396),
    ("x7", 0.578, 0.601),
    ("x8", 0.145, 0.172),
];

fn table_5() -> Anova {
    let levels: Vec<(&str, FactorLevels)> = LEVELS
        .iter()
        .map(|(n, lo, hi)| (*n, FactorLevels::new(*lo, *hi).unwrap()))
        .collect();
    analyze_seed(
        "seed000_table4_plackett_burman.csv",
        "angle_deg",
        None,
        &levels,
        ModelOrder::Linear,
    )
}

#[test]
fn table_5_model_residual_and_total() {
    let a = table_5();
    assert_printed("Model SS", a.model.ss, "280.41");
    assert_eq!(a.model.df, 8);
    assert_printed("Model MS", a.model.ms, "35.05");
    assert_printed("Model F", a.model.f, "19.79");
    assert_printed("Model p", a.model.p, "0.0161");
    assert_printed("Residual SS", a.residual.ss, "5.31");
    assert_eq!(a.residual.df, 3);
    assert_printed("Residual MS", a.residual.ms, "1.77");
    assert_printed("Cor total SS", a.cor_total.ss, "285.73");
    assert_eq!(a.cor_total.df, 11);
    // No replicates and no centre points: no pure error, lack of fit or curvature.
    assert!(a.pure_error.is_none() && a.lack_of_fit.is_none() && a.curvature.is_none());
    // Text below Table 5: R² = 0.9814.
    assert_printed("R2", a.fit.r2, "0.9814");
}

#[test]
fn table_5_factor_rows() {
    assert_term_rows(
        &table_5(),
        &[
            ("x1", "1.48", 1, "1.48", "0.83", "0.4285"),
            ("x2", "5.73", 1, "5.73", "3.23", "0.1700"),
            ("x3", "19.08", 1, "19.08", "10.77", "0.0464"),
            ("x4", "174.73", 1, "174.73", "98.66", "0.0022"),
            ("x5", "54.91", 1, "54.91", "31.01", "0.0114"),
            ("x6", "0.48", 1, "0.48", "0.27", "0.6373"),
            ("x7", "15.26", 1, "15.26", "8.61", "0.0608"),
            ("x8", "8.76", 1, "8.76", "4.94", "0.1127"),
        ],
    );
}

#[test]
fn table_5_significance_marks() {
    // "*" for p < 0.05 and "**" for p < 0.01: x4 **, x3 and x5 *, the rest unmarked.
    let a = table_5();
    let significant: Vec<&str> = a
        .terms
        .iter()
        .filter(|t| t.p < 0.05)
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(significant, ["x3", "x4", "x5"]);
    let highly: Vec<&str> = a
        .terms
        .iter()
        .filter(|t| t.p < 0.01)
        .map(|t| t.name.as_str())
        .collect();
    assert_eq!(highly, ["x4"]);
}
