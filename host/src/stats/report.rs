//! Design-Expert-style text report of an [`Anova`]: the ANOVA table with significance notes,
//! the fit statistics, the coefficient table and the coded equation.

use std::fmt::Write;

use super::{Anova, TestedSource};

/// Significance level of the "significant" / "not significant" notes (Design-Expert's
/// default).
pub const SIGNIFICANCE_LEVEL: f64 = 0.05;

/// Values of at least this magnitude print with [`LARGE_DECIMALS`] decimals.
const LARGE_THRESHOLD: f64 = 1.0;
/// Decimals for values of magnitude ≥ 1 ("55.67", "192.84" in seed 001 Table 7).
const LARGE_DECIMALS: usize = 2;
/// Values of at least this magnitude (and below 1) print with [`SMALL_DECIMALS`] decimals.
const SMALL_THRESHOLD: f64 = 1e-3;
/// Decimals for values in [0.001, 1) ("0.8216", "0.0018" in seed 001 Tables 7 and 11).
const SMALL_DECIMALS: usize = 4;
/// Mantissa decimals in scientific notation below 0.001 ("3.04E-004" in seed 000 Table 9).
const SCIENTIFIC_DECIMALS: usize = 2;

/// p-values below this print as "< 0.0001".
const SMALLEST_PRINTED_P: f64 = 1e-4;

/// `value` the way Design-Expert's ANOVA prints it (and the seeds copy it): two decimals
/// from 1 up, four decimals below 1, scientific notation below 0.001.
pub fn format_number(value: f64) -> String {
    if !value.is_finite() {
        return "N/A".to_owned();
    }
    let magnitude = value.abs();
    if magnitude >= LARGE_THRESHOLD {
        format!("{value:.LARGE_DECIMALS$}")
    } else if magnitude >= SMALL_THRESHOLD || magnitude == 0.0 {
        format!("{value:.SMALL_DECIMALS$}")
    } else {
        format!("{value:.SCIENTIFIC_DECIMALS$E}")
    }
}

/// A p-value as Design-Expert prints it: four decimals, or "< 0.0001".
pub fn format_p(p: f64) -> String {
    if !p.is_finite() {
        "N/A".to_owned()
    } else if p < SMALLEST_PRINTED_P {
        "< 0.0001".to_owned()
    } else {
        format!("{p:.4}")
    }
}

fn note(p: f64) -> &'static str {
    if p < SIGNIFICANCE_LEVEL {
        "significant"
    } else {
        "not significant"
    }
}

/// The full text report for `response`.
pub fn text_report(anova: &Anova, response: &str) -> String {
    let mut out = String::new();
    let _ = writeln!(
        out,
        "ANOVA for {} model, response {response} (Type III partial sums of squares)\n",
        anova.order.label()
    );
    let _ = writeln!(
        out,
        "{:<14} {:>14} {:>4} {:>12} {:>10} {:>9}",
        "Source", "Sum of Squares", "df", "Mean Square", "F-value", "p-value"
    );
    let tested = |out: &mut String, name: &str, t: &TestedSource, show: bool| {
        let _ = writeln!(
            out,
            "{:<14} {:>14} {:>4} {:>12} {:>10} {:>9}  {}",
            name,
            format_number(t.ss),
            t.df,
            format_number(t.ms),
            format_number(t.f),
            format_p(t.p),
            if show { note(t.p) } else { "" }
        );
    };
    tested(&mut out, "Model", &anova.model, true);
    for t in &anova.terms {
        let row = TestedSource {
            ss: t.ss,
            df: t.df,
            ms: t.ms,
            f: t.f,
            p: t.p,
        };
        tested(&mut out, &t.name, &row, false);
    }
    if let Some(c) = &anova.curvature {
        tested(&mut out, "Curvature", c, true);
    }
    let error_row = |out: &mut String, name: &str, ss: f64, df: usize, ms: Option<f64>| {
        let _ = writeln!(
            out,
            "{:<14} {:>14} {:>4} {:>12}",
            name,
            format_number(ss),
            df,
            ms.map(format_number).unwrap_or_default()
        );
    };
    let r = &anova.residual;
    error_row(&mut out, "Residual", r.ss, r.df, Some(r.ms));
    if let Some(l) = &anova.lack_of_fit {
        tested(&mut out, "Lack of Fit", l, true);
    }
    if let Some(pe) = &anova.pure_error {
        error_row(&mut out, "Pure Error", pe.ss, pe.df, Some(pe.ms));
    }
    let total = &anova.cor_total;
    error_row(&mut out, "Cor Total", total.ss, total.df, None);

    let fit = &anova.fit;
    let _ = writeln!(out, "\nFit statistics");
    let rows = [
        ("Std. Dev.", format_number(fit.std_dev)),
        ("Mean", format_number(fit.mean)),
        ("C.V. %", format!("{:.2}", fit.cv_percent)),
        ("R²", format!("{:.4}", fit.r2)),
        ("Adjusted R²", format!("{:.4}", fit.adj_r2)),
        (
            "Predicted R²",
            fit.pred_r2
                .map_or("N/A (a run has leverage 1)".to_owned(), |v| {
                    format!("{v:.4}")
                }),
        ),
        ("Adeq Precision", format!("{:.4}", fit.adeq_precision)),
    ];
    for (label, value) in rows {
        let _ = writeln!(out, "  {label:<15} {value}");
    }

    let _ = writeln!(out, "\nCoefficients in terms of coded factors");
    let _ = writeln!(
        out,
        "{:<14} {:>12} {:>12}",
        "Term", "Estimate", "Std. Error"
    );
    for c in &anova.coefficients {
        let _ = writeln!(
            out,
            "{:<14} {:>12} {:>12}",
            c.term,
            format_number(c.estimate),
            format_number(c.se)
        );
    }
    let _ = writeln!(
        out,
        "\nFinal equation in terms of coded factors:\n{response} ="
    );
    for c in &anova.coefficients {
        let sign = if c.estimate < 0.0 { '-' } else { '+' };
        let magnitude = format_number(c.estimate.abs());
        if c.term == "Intercept" {
            let _ = writeln!(out, "  {sign}{magnitude}");
        } else {
            let _ = writeln!(out, "  {sign}{magnitude} * {}", c.term);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_print_like_design_expert() {
        assert_eq!(format_number(0.82161), "0.8216");
        assert_eq!(format_number(13.4012), "13.40");
        assert_eq!(format_number(192.8411), "192.84");
        assert_eq!(format_number(0.001752), "0.0018");
        assert_eq!(format_number(-0.2617), "-0.2617");
        assert_eq!(format_number(3.042e-4), "3.04E-4");
        assert_eq!(format_p(0.00002), "< 0.0001");
        assert_eq!(format_p(0.15891), "0.1589");
    }
}
