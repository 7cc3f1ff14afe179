//! Regression ANOVA with Design-Expert's conventions: Type III (partial) sums of squares,
//! F = MS_term / MS_residual, a curvature term for two-level designs with centre points,
//! and the residual split into lack of fit and pure error (DESIGN §9).
//!
//! Each model term has one degree of freedom, so its Type III sum of squares is
//! SS_j = b_j² / [(XᵀX)⁻¹]_jj, the rise in residual SS when the term alone is dropped.
//! The model SS is the rise when every model term is dropped (intercept and curvature kept).
//!
//! ```
//! use arachis::stats::{analyze, CodedDesign, ModelOrder};
//! // A 2² factorial with three centre points; y = 10 + 2A − B plus noise.
//! let runs = vec![
//!     vec![-1.0, -1.0], vec![1.0, -1.0], vec![-1.0, 1.0], vec![1.0, 1.0],
//!     vec![0.0, 0.0], vec![0.0, 0.0], vec![0.0, 0.0],
//! ];
//! let y = vec![9.1, 13.0, 7.0, 10.9, 10.2, 9.9, 10.1];
//! let design = CodedDesign::new(vec!["A".into(), "B".into()], runs, y).unwrap();
//! let anova = analyze(&design, ModelOrder::Linear).unwrap();
//! assert_eq!(anova.terms[0].name, "A");
//! assert!(anova.curvature.is_some());
//! assert_eq!(anova.residual.df, 3);
//! ```

use nalgebra::DVector;
use serde::Serialize;

use super::curvature::centre_point_indicator;
use super::fit_statistics::{fit_statistics, FitInputs, FitStatistics};
use super::lack_of_fit::pure_error;
use super::least_squares::{least_squares, residual_sum_of_squares};
use super::model_terms::{model_matrix, model_terms, ModelOrder};
use super::p_values::f_upper_tail;
use super::{CodedDesign, StatsError};

/// Name of the curvature column in aliasing messages.
const CURVATURE_NAME: &str = "Curvature";

/// A source tested against the residual (or, for lack of fit, against pure error).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TestedSource {
    /// Sum of squares (response units squared).
    pub ss: f64,
    /// Degrees of freedom.
    pub df: usize,
    /// Mean square SS/df.
    pub ms: f64,
    /// F-value.
    pub f: f64,
    /// p-value P(F > f).
    pub p: f64,
}

/// One model term's row of the ANOVA table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TermRow {
    /// Term name (`A`, `A*B`, `A^2`).
    pub name: String,
    /// Type III sum of squares (response units squared).
    pub ss: f64,
    /// Degrees of freedom (1).
    pub df: usize,
    /// Mean square.
    pub ms: f64,
    /// F = MS / MS_residual.
    pub f: f64,
    /// p-value.
    pub p: f64,
}

/// An error source: residual or pure error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorSource {
    /// Sum of squares (response units squared).
    pub ss: f64,
    /// Degrees of freedom.
    pub df: usize,
    /// Mean square.
    pub ms: f64,
}

/// One coefficient of the coded equation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Coefficient {
    /// Term name (`Intercept`, `A`, `A*B`, `A^2`).
    pub term: String,
    /// Estimate (response units per coded unit of the term).
    pub estimate: f64,
    /// Standard error √(MS_res [(XᵀX)⁻¹]_jj).
    pub se: f64,
}

/// A complete analysis of one response.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Anova {
    /// The model fitted.
    #[serde(skip)]
    pub order: ModelOrder,
    /// Factor names in column order (the coded equation's variables).
    #[serde(skip)]
    pub factor_names: Vec<String>,
    /// Model term rows, intercept excluded, in Design-Expert's order.
    pub terms: Vec<TermRow>,
    /// The model as a whole.
    pub model: TestedSource,
    /// Curvature (two-level designs with centre points and no quadratic terms), else `None`.
    pub curvature: Option<TestedSource>,
    /// Residual (curvature removed).
    pub residual: ErrorSource,
    /// Lack of fit, when there are replicates and df left for it.
    pub lack_of_fit: Option<TestedSource>,
    /// Pure error, when there are replicates.
    pub pure_error: Option<ErrorSource>,
    /// Corrected total SS Σ(y − ȳ)² and its df n − 1.
    pub cor_total: ErrorSource,
    /// Fit statistics.
    #[serde(flatten)]
    pub fit: FitStatistics,
    /// Coded equation, intercept first (curvature is not part of the equation).
    pub coefficients: Vec<Coefficient>,
}

/// Relative spread below which a response counts as constant: rounding of values typed with
/// up to twelve significant digits.
pub const CONSTANT_RESPONSE_SPREAD: f64 = 1e-12;

/// `Err(NoVariation)` when every response equals the first to [`CONSTANT_RESPONSE_SPREAD`]
/// of its size (a constant response once gave R² −4.9 and "Lack of Fit significant").
fn check_variation(response: &[f64]) -> Result<(), StatsError> {
    let Some(&first) = response.first() else {
        return Ok(());
    };
    let (lo, hi) = response
        .iter()
        .fold((first, first), |(lo, hi), &v| (lo.min(v), hi.max(v)));
    let size = lo.abs().max(hi.abs());
    if hi - lo <= CONSTANT_RESPONSE_SPREAD * size {
        return Err(StatsError::NoVariation { value: first });
    }
    Ok(())
}

/// Fits `order` to `design` and builds the ANOVA table.
///
/// Errors: a response without variation, an aliased term (named), a saturated model (no
/// residual df), or an exact fit.
pub fn analyze(design: &CodedDesign, order: ModelOrder) -> Result<Anova, StatsError> {
    check_variation(&design.response)?;
    let terms = model_terms(&design.factor_names, order);
    let n = design.runs.len();
    let p_model = terms.len();
    let mut x = model_matrix(&terms, &design.runs);
    let mut names: Vec<String> = terms.iter().map(|t| t.name.clone()).collect();
    let indicator = centre_point_indicator(&design.runs, order);
    if let Some(c) = &indicator {
        x = x.insert_column(p_model, 0.0);
        x.column_mut(p_model).copy_from_slice(c);
        names.push(CURVATURE_NAME.to_owned());
    }
    let p_full = x.ncols();
    let y = DVector::from_column_slice(&design.response);
    let fit = least_squares(&x, &y, &names)?;
    if n <= p_full {
        return Err(StatsError::Saturated {
            runs: n,
            parameters: p_full,
        });
    }

    let df_residual = n - p_full;
    let ss_residual = fit.sse;
    let ms_residual = ss_residual / df_residual as f64;
    let mean = design.response.iter().sum::<f64>() / n as f64;
    let ss_total: f64 = design.response.iter().map(|v| (v - mean).powi(2)).sum();
    if ss_residual <= f64::EPSILON * ss_total {
        return Err(StatsError::PerfectFit);
    }
    let tested = |ss: f64, df: usize| {
        let ms = ss / df as f64;
        let f = ms / ms_residual;
        TestedSource {
            ss,
            df,
            ms,
            f,
            p: f_upper_tail(f, df as f64, df_residual as f64),
        }
    };
    let type3 = |j: usize| fit.coefficients[j].powi(2) / fit.unscaled_variances[j];

    let term_rows = (1..p_model)
        .map(|j| {
            let t = tested(type3(j), 1);
            TermRow {
                name: names[j].clone(),
                ss: t.ss,
                df: 1,
                ms: t.ms,
                f: t.f,
                p: t.p,
            }
        })
        .collect();
    let curvature = indicator.as_ref().map(|_| tested(type3(p_model), 1));

    // Model SS: residual SS of intercept (+ curvature) alone, minus the full residual SS.
    let mut reduced = vec![0];
    if indicator.is_some() {
        reduced.push(p_model);
    }
    let ss_model = residual_sum_of_squares(&x, &y, &reduced)? - ss_residual;
    let df_model = p_model - 1;
    let model = tested(ss_model, df_model);

    let pure = pure_error(&design.runs, &design.response);
    let pure_error_row = pure.map(|pe| ErrorSource {
        ss: pe.ss,
        df: pe.df,
        ms: pe.ss / pe.df as f64,
    });
    let lack_of_fit = pure_error_row.and_then(|pe| {
        let df = df_residual.checked_sub(pe.df).filter(|df| *df > 0)?;
        let ss = (ss_residual - pe.ss).max(0.0);
        let ms = ss / df as f64;
        let f = ms / pe.ms;
        Some(TestedSource {
            ss,
            df,
            ms,
            f,
            p: f_upper_tail(f, df as f64, pe.df as f64),
        })
    });

    let model_columns = x.columns(0, p_model);
    let model_coefficients = fit.coefficients.rows(0, p_model);
    let predictions: DVector<f64> = model_columns * model_coefficients;
    let fit_stats = fit_statistics(&FitInputs {
        ss_model,
        df_model,
        ss_residual,
        df_residual,
        residuals: fit.residuals.as_slice(),
        leverages: fit.leverages.as_slice(),
        predictions: predictions.as_slice(),
        parameters: p_model,
        y: &design.response,
    });
    let coefficients = (0..p_model)
        .map(|j| Coefficient {
            term: names[j].clone(),
            estimate: fit.coefficients[j],
            se: (ms_residual * fit.unscaled_variances[j]).sqrt(),
        })
        .collect();

    Ok(Anova {
        order,
        factor_names: design.factor_names.clone(),
        terms: term_rows,
        model,
        curvature,
        residual: ErrorSource {
            ss: ss_residual,
            df: df_residual,
            ms: ms_residual,
        },
        lack_of_fit,
        pure_error: pure_error_row,
        cor_total: ErrorSource {
            ss: ss_total,
            df: n - 1,
            ms: ss_total / (n - 1) as f64,
        },
        fit: fit_stats,
        coefficients,
    })
}

impl Anova {
    /// Predicted response (response units) at coded settings `x` (one value per factor, in
    /// column order) from the coded equation.
    pub fn predict(&self, x: &[f64]) -> f64 {
        let terms = model_terms(&self.factor_names, self.order);
        terms
            .iter()
            .zip(&self.coefficients)
            .map(|(t, c)| c.estimate * t.value(x))
            .sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_squared(y: Vec<f64>) -> CodedDesign {
        let runs = vec![
            vec![-1.0, -1.0],
            vec![1.0, -1.0],
            vec![-1.0, 1.0],
            vec![1.0, 1.0],
            vec![-1.0, -1.0],
        ];
        CodedDesign::new(vec!["A".into(), "B".into()], runs, y).unwrap()
    }

    #[test]
    fn exact_fit_is_an_error_not_infinite_f() {
        let design = two_squared(vec![1.0, 3.0, 2.0, 4.0, 1.0]); // y = 2.5 + A + 0.5B
        assert_eq!(
            analyze(&design, ModelOrder::Linear),
            Err(StatsError::PerfectFit)
        );
    }

    /// Issue 23: a constant response is refused in words, not analysed into rounding noise
    /// (R² −4.9, "Lack of Fit significant"); a response that varies by a little more than
    /// the threshold is analysed.
    #[test]
    fn a_constant_response_has_no_variation_to_model() {
        let design = two_squared(vec![5.0; 5]);
        assert_eq!(
            analyze(&design, ModelOrder::Linear),
            Err(StatsError::NoVariation { value: 5.0 })
        );
        assert!(StatsError::NoVariation { value: 5.0 }
            .to_string()
            .contains("no variation to model"));
        let design = two_squared(vec![5.0, 5.0 + 1e-9, 5.0, 5.0, 5.0 - 2e-9]);
        assert!(!matches!(
            analyze(&design, ModelOrder::Linear),
            Err(StatsError::NoVariation { .. })
        ));
    }

    #[test]
    fn prediction_reproduces_fitted_values() {
        let design = two_squared(vec![1.1, 3.0, 2.2, 4.1, 0.9]);
        let anova = analyze(&design, ModelOrder::TwoFactorInteraction).unwrap();
        let terms = model_terms(&design.factor_names, ModelOrder::TwoFactorInteraction);
        let x = model_matrix(&terms, &design.runs);
        let names: Vec<&str> = terms.iter().map(|t| t.name.as_str()).collect();
        let y = DVector::from_column_slice(&design.response);
        let fit = least_squares(&x, &y, &names).unwrap();
        for (run, fitted) in design.runs.iter().zip(fit.fitted.iter()) {
            assert!((anova.predict(run) - fitted).abs() < 1e-12);
        }
        // The replicated corner is fitted by its mean, (1.1 + 0.9)/2, under the 2FI model.
        assert!((anova.predict(&[-1.0, -1.0]) - 1.0).abs() < 1e-12);
    }
}
