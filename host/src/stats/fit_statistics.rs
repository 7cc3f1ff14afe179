//! Design-Expert's fit statistics: R², adjusted R², predicted R², adequate precision, CV %.
//!
//! Definitions (Stat-Ease's ANOVA help pages; DESIGN §9):
//! - R² = SS_model / (SS_model + SS_res);
//! - adjusted R² = 1 − MS_res / [(SS_model + SS_res) / (df_model + df_res)];
//! - PRESS = Σ (eᵢ / (1 − hᵢᵢ))²; predicted R² = 1 − PRESS / (SS_model + SS_res);
//! - adequate precision = (max ŷ − min ŷ) / √(p σ̂² / n), p model parameters, n runs;
//! - CV % = 100 √MS_res / ȳ.
//!
//! Stat-Ease's denominators are SS_model + SS_res = SS_total − SS_curvature, not
//! SS_total as DESIGN §9 writes for predicted R²: the two agree without a curvature term,
//! and only the Stat-Ease form reproduces seed 001's R² = 0.9875 (55.67 / (55.67 + 0.7053);
//! 55.67 / 63.37 would give 0.8785).

use serde::Serialize;

/// A leverage this close to 1 makes a deletion residual e/(1 − h) meaningless: the run
/// alone determines a parameter, and predicted R² is not defined (Design-Expert: "N/A").
const UNIT_LEVERAGE_TOLERANCE: f64 = 1e-10;

/// Everything the statistics need, in response units.
#[derive(Debug, Clone, Copy)]
pub struct FitInputs<'a> {
    /// Model sum of squares.
    pub ss_model: f64,
    /// Model degrees of freedom.
    pub df_model: usize,
    /// Residual sum of squares.
    pub ss_residual: f64,
    /// Residual degrees of freedom.
    pub df_residual: usize,
    /// Residuals eᵢ of the fit.
    pub residuals: &'a [f64],
    /// Leverages hᵢᵢ of the fit.
    pub leverages: &'a [f64],
    /// Model predictions ŷᵢ at the runs.
    pub predictions: &'a [f64],
    /// Number of model parameters p, intercept included.
    pub parameters: usize,
    /// Observed responses.
    pub y: &'a [f64],
}

/// The fit statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FitStatistics {
    /// Coefficient of determination (dimensionless).
    pub r2: f64,
    /// Adjusted R² (dimensionless).
    pub adj_r2: f64,
    /// Predicted R² (dimensionless); `None` when a run has leverage 1.
    pub pred_r2: Option<f64>,
    /// PRESS (response units squared); `None` when a run has leverage 1.
    pub press: Option<f64>,
    /// Adequate precision, a signal-to-noise ratio (dimensionless; > 4 is adequate).
    pub adeq_precision: f64,
    /// Coefficient of variation, % of the mean response.
    pub cv_percent: f64,
    /// Standard deviation √MS_res (response units).
    pub std_dev: f64,
    /// Mean response ȳ (response units).
    pub mean: f64,
}

/// Computes the fit statistics.
pub fn fit_statistics(inputs: &FitInputs<'_>) -> FitStatistics {
    let n = inputs.y.len() as f64;
    let explained_total = inputs.ss_model + inputs.ss_residual;
    let ms_residual = inputs.ss_residual / inputs.df_residual as f64;
    let total_df = (inputs.df_model + inputs.df_residual) as f64;
    let r2 = inputs.ss_model / explained_total;
    let adj_r2 = 1.0 - ms_residual / (explained_total / total_df);
    let press = press(inputs.residuals, inputs.leverages);
    let pred_r2 = press.map(|p| 1.0 - p / explained_total);
    let (min, max) = inputs
        .predictions
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    let mean_prediction_variance = inputs.parameters as f64 * ms_residual / n;
    let adeq_precision = (max - min) / mean_prediction_variance.sqrt();
    let mean = inputs.y.iter().sum::<f64>() / n;
    let std_dev = ms_residual.sqrt();
    FitStatistics {
        r2,
        adj_r2,
        pred_r2,
        press,
        adeq_precision,
        cv_percent: 100.0 * std_dev / mean,
        std_dev,
        mean,
    }
}

/// PRESS = Σ (eᵢ / (1 − hᵢᵢ))² (Stat-Ease, "ANOVA: PRESS"); `None` if any hᵢᵢ ≈ 1.
pub fn press(residuals: &[f64], leverages: &[f64]) -> Option<f64> {
    residuals
        .iter()
        .zip(leverages)
        .map(|(e, h)| {
            let free = 1.0 - h;
            (free > UNIT_LEVERAGE_TOLERANCE).then(|| (e / free).powi(2))
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn press_equals_brute_force_leave_one_out() {
        // Straight line through 5 points; deletion residuals by refitting without each point.
        let x = [0.0, 1.0, 2.0, 3.0, 4.0];
        let y = [1.0, 2.9, 5.2, 6.8, 9.3];
        let line = |xs: &[f64], ys: &[f64]| {
            let n = xs.len() as f64;
            let mx = xs.iter().sum::<f64>() / n;
            let my = ys.iter().sum::<f64>() / n;
            let sxy: f64 = xs.iter().zip(ys).map(|(a, b)| (a - mx) * (b - my)).sum();
            let sxx: f64 = xs.iter().map(|a| (a - mx).powi(2)).sum();
            let b1 = sxy / sxx;
            (my - b1 * mx, b1, mx, sxx)
        };
        let (b0, b1, mx, sxx) = line(&x, &y);
        let residuals: Vec<f64> = x.iter().zip(&y).map(|(a, b)| b - b0 - b1 * a).collect();
        let leverages: Vec<f64> = x.iter().map(|a| 0.2 + (a - mx).powi(2) / sxx).collect();
        let mut brute = 0.0;
        for i in 0..5 {
            let xs: Vec<f64> = (0..5).filter(|&j| j != i).map(|j| x[j]).collect();
            let ys: Vec<f64> = (0..5).filter(|&j| j != i).map(|j| y[j]).collect();
            let (c0, c1, _, _) = line(&xs, &ys);
            brute += (y[i] - c0 - c1 * x[i]).powi(2);
        }
        let fast = press(&residuals, &leverages).unwrap();
        assert!((fast - brute).abs() < 1e-12 * brute);
    }

    #[test]
    fn unit_leverage_leaves_press_undefined() {
        assert_eq!(press(&[0.1, 0.0], &[0.5, 1.0]), None);
    }
}
