//! A straight line h = a + b·x fitted to contour points by ordinary least squares.
//!
//! Seed 000 §3.6.1: "The slope of the straight line at the edge of the contour obtained
//! after the fitting process is the tangent of the peanut pods' stacking angle". The bench
//! fit (Matlab `polyfit(x, h, 1)`) minimises vertical residuals, and so does this one. For
//! two parameters the normal equations have the closed form
//!
//! b = Sₓₕ / Sₓₓ,  a = h̄ − b x̄,  with Sₓₓ = Σ(xᵢ − x̄)², Sₓₕ = Σ(xᵢ − x̄)(hᵢ − h̄),
//!
//! which, computed about the means as here, is as accurate as a QR solve; it is written
//! inline rather than through nalgebra for that reason.
//!
//! ```
//! use arachis::repose::line_fit::fit_line;
//! let fit = fit_line(&[(0.0, 1.0), (1.0, 3.0), (2.0, 5.0)]).unwrap();
//! assert!((fit.slope - 2.0).abs() < 1e-12 && (fit.intercept - 1.0).abs() < 1e-12);
//! assert!((fit.r_squared - 1.0).abs() < 1e-12);
//! ```

use serde::Serialize;

/// A fitted line h = intercept + slope·x with its goodness of fit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LineFit {
    /// b (units of h per unit of x).
    pub slope: f64,
    /// a (units of h).
    pub intercept: f64,
    /// Root-mean-square vertical residual √(Σ eᵢ² / n) (units of h).
    pub rms_residual: f64,
    /// Coefficient of determination R² = 1 − Σ eᵢ² / Σ (hᵢ − h̄)² (dimensionless; 1 when
    /// every h is equal and fitted exactly).
    pub r_squared: f64,
    /// Number of points n.
    pub points: usize,
}

/// Fits h = a + b·x to `(x, h)` points; `None` with fewer than two points or when every x
/// is the same (a vertical line has no finite slope).
pub fn fit_line(points: &[(f64, f64)]) -> Option<LineFit> {
    let n = points.len();
    if n < 2 {
        return None;
    }
    let mean_x = points.iter().map(|p| p.0).sum::<f64>() / n as f64;
    let mean_h = points.iter().map(|p| p.1).sum::<f64>() / n as f64;
    let (mut sxx, mut sxh, mut shh) = (0.0, 0.0, 0.0);
    for &(x, h) in points {
        sxx += (x - mean_x).powi(2);
        sxh += (x - mean_x) * (h - mean_h);
        shh += (h - mean_h).powi(2);
    }
    if sxx <= 0.0 {
        return None;
    }
    let slope = sxh / sxx;
    let intercept = mean_h - slope * mean_x;
    let sse: f64 = points
        .iter()
        .map(|&(x, h)| (h - intercept - slope * x).powi(2))
        .sum();
    let r_squared = if shh > 0.0 { 1.0 - sse / shh } else { 1.0 };
    Some(LineFit {
        slope,
        intercept,
        rms_residual: (sse / n as f64).sqrt(),
        r_squared,
        points: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_residuals_give_known_statistics() {
        // h = 2x plus residuals +1, −1, −1, +1 at x = 0..3.
        let pts: Vec<(f64, f64)> = [(0.0, 1.0), (1.0, 1.0), (2.0, 3.0), (3.0, 7.0)].to_vec();
        let fit = fit_line(&pts).unwrap();
        // x̄ = 1.5, h̄ = 3; Sxx = 5, Sxh = (−1.5)(−2) + (−0.5)(−2) + 0.5·0 + 1.5·4 = 10.
        assert!((fit.slope - 2.0).abs() < 1e-12);
        assert!((fit.intercept - 0.0).abs() < 1e-12);
        // Residuals 1, −1, −1, 1: SSE = 4; SST = 4 + 4 + 0 + 16 = 24.
        assert!((fit.rms_residual - 1.0).abs() < 1e-12);
        assert!((fit.r_squared - (1.0 - 4.0 / 24.0)).abs() < 1e-12);
    }

    #[test]
    fn degenerate_inputs_have_no_fit() {
        assert!(fit_line(&[(1.0, 2.0)]).is_none());
        assert!(fit_line(&[(1.0, 2.0), (1.0, 5.0)]).is_none());
    }
}
