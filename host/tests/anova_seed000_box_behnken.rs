//! Seed 000 Table 9 (Box–Behnken ANOVA), eq. (22) and the R² and CV quoted below it, from
//! Table 8, quadratic model in x3, x4, x5.
//!
//! Coding: Table 7 prints x3's levels as −1 = 0.327, 0 = 0.334, +1 = 0.340. The centre is
//! rounded ((0.327 + 0.340)/2 = 0.3335); coding 0.334 linearly would put the "centre" runs
//! at x3 = +0.077 and no longer reproduce Table 9. The printed table is used as the coding,
//! as Design-Expert's own design (levels −1, 0, +1) was.
//!
//! Tolerance: half a unit in the last printed digit. Three equation coefficients lie exactly
//! on a rounding boundary and were rounded by the seed: x3 −0.535 (printed −0.53), x3x5
//! 0.0775 (printed 0.078) and x5² −0.0085 (printed −0.009); they are within the tolerance.

use crate::anova_support;

use anova_support::{analyze_seed, assert_coefficient, assert_printed, assert_term_rows};
use arachis::stats::{Anova, FactorLevels, ModelOrder};

fn table_9() -> Anova {
    let table_7 = |lo, mid, hi| FactorLevels::with_printed_centre(lo, mid, hi).unwrap();
    analyze_seed(
        "seed000_table8_box_behnken.csv",
        "angle_deg",
        None,
        &[
            ("x3", table_7(0.327, 0.334, 0.340)),
            ("x4", table_7(0.848, 0.853, 0.858)),
            ("x5", table_7(0.332, 0.341, 0.350)),
        ],
        ModelOrder::Quadratic,
    )
}

#[test]
fn table_9_model_and_error_rows() {
    let a = table_9();
    assert_printed("Model SS", a.model.ss, "13.92");
    assert_eq!(a.model.df, 9);
    assert_printed("Model MS", a.model.ms, "1.55");
    assert_printed("Model F", a.model.f, "8.58");
    assert_printed("Model p", a.model.p, "0.0049");
    assert_printed("Residual SS", a.residual.ss, "1.26");
    assert_eq!(a.residual.df, 7);
    assert_printed("Residual MS", a.residual.ms, "0.18");
    let lof = a.lack_of_fit.as_ref().unwrap();
    assert_printed("Lack of fit SS", lof.ss, "0.87");
    assert_eq!(lof.df, 3);
    assert_printed("Lack of fit MS", lof.ms, "0.29");
    assert_printed("Lack of fit F", lof.f, "2.99");
    assert_printed("Lack of fit p", lof.p, "0.1589");
    let pe = a.pure_error.unwrap();
    assert_printed("Pure error SS", pe.ss, "0.39");
    assert_eq!(pe.df, 4);
    assert_printed("Pure error MS", pe.ms, "0.097");
    assert_printed("Cor total SS", a.cor_total.ss, "15.18");
    assert_eq!(a.cor_total.df, 16);
    assert!(
        a.curvature.is_none(),
        "a quadratic model has no curvature term"
    );
}

#[test]
fn table_9_term_rows() {
    assert_term_rows(
        &table_9(),
        &[
            ("x3", "2.29", 1, "2.29", "12.70", "0.0092"),
            ("x4", "1.15", 1, "1.15", "6.36", "0.0397"),
            ("x5", "9.66", 1, "9.66", "53.56", "0.0002"),
            ("x3*x4", "0.18", 1, "0.18", "1.00", "0.3503"),
            ("x3*x5", "0.024", 1, "0.024", "0.13", "0.7259"),
            ("x4*x5", "0.026", 1, "0.026", "0.14", "0.7175"),
            ("x3^2", "0.27", 1, "0.27", "1.47", "0.2645"),
            ("x4^2", "0.29", 1, "0.29", "1.62", "0.2436"),
            ("x5^2", "3.04e-4", 1, "3.04e-4", "1.69e-3", "0.9684"),
        ],
    );
}

#[test]
fn equation_22_and_fit_statistics() {
    let a = table_9();
    for (term, printed) in [
        ("Intercept", "30.45"),
        ("x3", "-0.53"),
        ("x4", "-0.38"),
        ("x5", "1.10"),
        ("x3*x4", "0.21"),
        ("x3*x5", "0.078"),
        ("x4*x5", "-0.08"),
        ("x3^2", "-0.25"),
        ("x4^2", "-0.26"),
        ("x5^2", "-0.009"),
    ] {
        assert_coefficient(&a, term, printed);
    }
    // Text below eq. (22): R² = 0.9169, coefficient of variation 1.41 %.
    assert_printed("R2", a.fit.r2, "0.9169");
    assert_printed("CV %", a.fit.cv_percent, "1.41");
}
