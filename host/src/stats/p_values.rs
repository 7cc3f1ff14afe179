//! Upper-tail probabilities of the F and Student t distributions, from statrs (no
//! hand-rolled special functions).

use statrs::distribution::{ContinuousCDF, FisherSnedecor, StudentsT};

/// P(F(df₁, df₂) > f): the p-value of an F statistic. NaN when a df is not positive;
/// 0 for an infinite F.
pub fn f_upper_tail(f: f64, df_numerator: f64, df_denominator: f64) -> f64 {
    if f.is_infinite() && f > 0.0 {
        return 0.0;
    }
    FisherSnedecor::new(df_numerator, df_denominator)
        .map(|d| d.sf(f))
        .unwrap_or(f64::NAN)
}

/// P(|T(df)| > |t|): the two-sided p-value of a t statistic. NaN when df is not positive.
pub fn t_two_sided(t: f64, df: f64) -> f64 {
    StudentsT::new(0.0, 1.0, df)
        .map(|d| 2.0 * d.sf(t.abs()))
        .unwrap_or(f64::NAN)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_quantiles() {
        // Printed tables: F(0.05; 1, 10) = 4.96, t(0.025; 10) = 2.228.
        assert!((f_upper_tail(4.96, 1.0, 10.0) - 0.05).abs() < 5e-4);
        assert!((t_two_sided(2.228, 10.0) - 0.05).abs() < 5e-4);
    }
}
