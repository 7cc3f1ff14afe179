//! Design-Expert-style text report of an [`Anova`]: the ANOVA table with significance notes,
//! the fit statistics, the coefficient table and the coded equation.

use std::fmt::Write;

use super::{Anova, TestedSource};

/// Significance level of the "significant" / "not significant" notes (Design-Expert's
/// default).
pub const SIGNIFICANCE_LEVEL: f64 = 0.05;

/// Significant digits shown, as Design-Expert shows them.
const SIGNIFICANT_DIGITS: usize = 4;

/// p-values below this print as "< 0.0001".
const SMALLEST_PRINTED_P: f64 = 1e-4;

/// `value` with [`SIGNIFICANT_DIGITS`] significant digits; scientific notation for very
/// small or large magnitudes.
pub fn format_significant(value: f64) -> String {
    if !value.is_finite() {
        return "N/A".to_owned();
    }
    if value == 0.0 {
        return "0".to_owned();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if !(-4..7).contains(&magnitude) {
        return format!("{:.*E}", SIGNIFICANT_DIGITS - 1, value);
    }
    let decimals = (SIGNIFICANT_DIGITS as i32 - 1 - magnitude).max(0) as usize;
    format!("{value:.decimals$}")
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
            format_significant(t.ss),
            t.df,
            format_significant(t.ms),
            format_significant(t.f),
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
            format_significant(ss),
            df,
            ms.map(format_significant).unwrap_or_default()
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
        ("Std. Dev.", format_significant(fit.std_dev)),
        ("Mean", format_significant(fit.mean)),
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
            format_significant(c.estimate),
            format_significant(c.se)
        );
    }
    let _ = writeln!(
        out,
        "\nFinal equation in terms of coded factors:\n{response} ="
    );
    for c in &anova.coefficients {
        let sign = if c.estimate < 0.0 { '-' } else { '+' };
        let magnitude = format_significant(c.estimate.abs());
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
        assert_eq!(format_significant(0.82161), "0.8216");
        assert_eq!(format_significant(13.4012), "13.40");
        assert_eq!(format_significant(280.41), "280.4");
        assert_eq!(format_significant(3.04e-5), "3.040E-5");
        assert_eq!(format_p(0.00002), "< 0.0001");
        assert_eq!(format_p(0.15891), "0.1589");
    }
}
