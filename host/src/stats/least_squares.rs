//! Ordinary least squares by Householder QR (nalgebra), with a rank check that names the
//! aliased term.
//!
//! For the model y = X b + e with X of full column rank, X = Q R gives
//! b = R⁻¹ Qᵀ y, the leverages hᵢᵢ = Σⱼ Qᵢⱼ² (diagonal of the hat matrix), and
//! (XᵀX)⁻¹ = R⁻¹ R⁻ᵀ, whose diagonal scales the coefficients' variances.
//!
//! ```
//! use nalgebra::{DMatrix, DVector};
//! // y = 1 + 2x fitted exactly through three points.
//! let x = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 1.0, 1.0, 1.0, 2.0]);
//! let y = DVector::from_vec(vec![1.0, 3.0, 5.0]);
//! let fit = arachis::stats::least_squares(&x, &y, &["Intercept", "x"]).unwrap();
//! assert!((fit.coefficients[1] - 2.0).abs() < 1e-12);
//! ```

use nalgebra::{DMatrix, DVector};

use super::StatsError;

/// A column whose component outside the span of the earlier columns is smaller than this
/// fraction of its own length is treated as a linear combination of them (aliased). Coded
/// designs have columns of order one, so 1e-8 is far above rounding (1e-15) and far below
/// any genuine design column.
const ALIAS_TOLERANCE: f64 = 1e-8;

/// An alias coefficient smaller than this is reported as "not involved" in the alias.
const ALIAS_MEMBER_TOLERANCE: f64 = 1e-6;

/// A least-squares fit.
#[derive(Debug, Clone)]
pub struct LeastSquaresFit {
    /// Estimated coefficients b, one per column of X (response units per coded unit).
    pub coefficients: DVector<f64>,
    /// Fitted values ŷ = X b (response units).
    pub fitted: DVector<f64>,
    /// Residuals e = y − ŷ (response units).
    pub residuals: DVector<f64>,
    /// Residual sum of squares Σ eᵢ² (response units squared).
    pub sse: f64,
    /// Leverages hᵢᵢ, the diagonal of X (XᵀX)⁻¹ Xᵀ (dimensionless).
    pub leverages: DVector<f64>,
    /// Diagonal of (XᵀX)⁻¹: Var(bⱼ) = σ² · this (per coded unit squared).
    pub unscaled_variances: DVector<f64>,
}

/// Fits `y` on the columns of `x` (named `names`, used in the aliasing error).
///
/// Fails with [`StatsError::Aliased`] naming the first column that is a linear combination of
/// earlier ones, and with [`StatsError::Saturated`] when there are fewer runs than columns.
pub fn least_squares<S: AsRef<str>>(
    x: &DMatrix<f64>,
    y: &DVector<f64>,
    names: &[S],
) -> Result<LeastSquaresFit, StatsError> {
    let (n, p) = x.shape();
    if y.len() != n || names.len() != p {
        return Err(StatsError::BadShape(format!(
            "model matrix is {n}×{p} but there are {} responses and {} names",
            y.len(),
            names.len()
        )));
    }
    if n < p {
        return Err(StatsError::Saturated {
            runs: n,
            parameters: p,
        });
    }
    let qr = x.clone().qr();
    let q = qr.q();
    let r = qr.r();
    check_rank(x, &r, names)?;

    let qty = q.transpose() * y;
    let coefficients = r
        .solve_upper_triangular(&qty)
        .ok_or_else(|| StatsError::BadShape("triangular solve failed".to_owned()))?;
    let fitted = x * &coefficients;
    let residuals = y - &fitted;
    let sse = residuals.norm_squared();
    let leverages = DVector::from_fn(n, |i, _| q.row(i).norm_squared());
    let r_inv = r
        .solve_upper_triangular(&DMatrix::identity(p, p))
        .ok_or_else(|| StatsError::BadShape("triangular inverse failed".to_owned()))?;
    let unscaled_variances = DVector::from_fn(p, |j, _| r_inv.row(j).norm_squared());
    Ok(LeastSquaresFit {
        coefficients,
        fitted,
        residuals,
        sse,
        leverages,
        unscaled_variances,
    })
}

/// Residual sum of squares of `y` on the columns `keep` of `x` (for Type III and model sums
/// of squares by model comparison). The columns must be linearly independent.
pub fn residual_sum_of_squares(
    x: &DMatrix<f64>,
    y: &DVector<f64>,
    keep: &[usize],
) -> Result<f64, StatsError> {
    if keep.is_empty() {
        return Ok(y.norm_squared());
    }
    let sub = x.select_columns(keep);
    let names: Vec<String> = keep.iter().map(|k| format!("column {k}")).collect();
    Ok(least_squares(&sub, y, &names)?.sse)
}

/// |Rⱼⱼ| is the length of column j's component orthogonal to columns 0..j; if it is tiny
/// relative to the column, the column is (numerically) a combination of earlier ones. The
/// combination itself solves R[..j, ..j] c = R[..j, j].
fn check_rank<S: AsRef<str>>(
    x: &DMatrix<f64>,
    r: &DMatrix<f64>,
    names: &[S],
) -> Result<(), StatsError> {
    for j in 0..x.ncols() {
        let column_norm = x.column(j).norm();
        if r[(j, j)].abs() > ALIAS_TOLERANCE * column_norm && column_norm > 0.0 {
            continue;
        }
        let aliases = if j == 0 || column_norm == 0.0 {
            Vec::new()
        } else {
            let upper = r.view((0, 0), (j, j)).upper_triangle();
            let rhs = r.view((0, j), (j, 1)).clone_owned();
            upper
                .solve_upper_triangular(&rhs)
                .map(|c| {
                    c.iter()
                        .enumerate()
                        .filter(|(_, v)| v.abs() > ALIAS_MEMBER_TOLERANCE)
                        .map(|(i, v)| format_alias(*v, names[i].as_ref()))
                        .collect()
                })
                .unwrap_or_default()
        };
        return Err(StatsError::Aliased {
            term: names[j].as_ref().to_owned(),
            aliases,
        });
    }
    Ok(())
}

/// "A" for a unit coefficient, "-B" for minus one, "0.5·C" otherwise.
fn format_alias(coefficient: f64, name: &str) -> String {
    if (coefficient - 1.0).abs() < ALIAS_MEMBER_TOLERANCE {
        name.to_owned()
    } else if (coefficient + 1.0).abs() < ALIAS_MEMBER_TOLERANCE {
        format!("-{name}")
    } else {
        format!("{coefficient:.4}·{name}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn leverages_sum_to_the_number_of_parameters() {
        let x = DMatrix::from_row_slice(4, 2, &[1.0, -1.0, 1.0, 1.0, 1.0, 0.0, 1.0, 0.5]);
        let y = DVector::from_vec(vec![1.0, 2.0, 1.7, 2.2]);
        let fit = least_squares(&x, &y, &["Intercept", "A"]).unwrap();
        assert!((fit.leverages.sum() - 2.0).abs() < 1e-12);
        // Straight-line textbook: Var(b1)/σ² = 1/Sxx with Sxx = Σ(x − x̄)².
        let mean = (-1.0 + 1.0 + 0.0 + 0.5) / 4.0;
        let sxx: f64 = [-1.0, 1.0, 0.0, 0.5]
            .iter()
            .map(|v: &f64| (v - mean).powi(2))
            .sum();
        assert!((fit.unscaled_variances[1] - 1.0 / sxx).abs() < 1e-12);
    }

    #[test]
    fn aliased_column_is_named_with_its_partners() {
        // On a 2² design a factor C set to A·B is indistinguishable from the A*B column.
        let rows = [[-1.0, -1.0], [1.0, -1.0], [-1.0, 1.0], [1.0, 1.0]];
        let x = DMatrix::from_fn(4, 4, |r, c| match c {
            0 => 1.0,
            1 => rows[r][0],
            _ => rows[r][0] * rows[r][1],
        });
        let y = DVector::from_vec(vec![1.0, 2.0, 3.0, 5.0]);
        let err = least_squares(&x, &y, &["Intercept", "A", "A*B", "C"]).unwrap_err();
        assert_eq!(
            err,
            StatsError::Aliased {
                term: "C".into(),
                aliases: vec!["A*B".into()]
            }
        );
        assert!(err.to_string().contains("'C' is aliased with 'A*B'"));
    }
}
