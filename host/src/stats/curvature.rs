//! Design-Expert's curvature term for two-level factorial and Plackett–Burman designs with
//! centre points (DESIGN §9; seed 001 Table 7).
//!
//! A first-order or 2FI model cannot follow a bend in the response, but centre points can
//! see one: if the mean at the centre differs from the mean of the factorial points, the
//! surface is curved. Design-Expert splits this 1-df comparison out of the residual before
//! testing the model terms. Here it is a column in the fit that is 1 at centre points and 0
//! elsewhere; its Type III sum of squares equals the textbook contrast
//! SS_curv = n_F n_C (ȳ_F − ȳ_C)² / (n_F + n_C), and the intercept becomes the factorial
//! mean ȳ_F (seed 001's coded equation opens with it: 8.13).

use super::ModelOrder;

/// Coded values within this distance of 0 or ±1 are taken as exactly that level; coded
/// values computed from rounded actual levels miss them by about 1e-12.
pub const LEVEL_TOLERANCE: f64 = 1e-6;

/// The centre-point indicator (1 at centre points, 0 at factorial points) when the design
/// and model call for a curvature term: the model has no quadratic terms, there is at least
/// one centre point and one factorial point, and every other run has each factor at ±1.
pub fn centre_point_indicator(coded: &[Vec<f64>], order: ModelOrder) -> Option<Vec<f64>> {
    if order == ModelOrder::Quadratic {
        return None;
    }
    let is_centre = |run: &Vec<f64>| run.iter().all(|v| v.abs() < LEVEL_TOLERANCE);
    let is_corner = |run: &Vec<f64>| run.iter().all(|v| (v.abs() - 1.0).abs() < LEVEL_TOLERANCE);
    let centres = coded.iter().filter(|r| is_centre(r)).count();
    let corners = coded.iter().filter(|r| is_corner(r)).count();
    if centres == 0 || corners == 0 || centres + corners != coded.len() {
        return None;
    }
    Some(
        coded
            .iter()
            .map(|r| if is_centre(r) { 1.0 } else { 0.0 })
            .collect(),
    )
}

/// SS_curv = n_F n_C (ȳ_F − ȳ_C)² / (n_F + n_C) (Montgomery, *Design and Analysis of
/// Experiments*, §6.8), with `indicator` as from [`centre_point_indicator`].
pub fn curvature_sum_of_squares(y: &[f64], indicator: &[f64]) -> f64 {
    let (mut sum_c, mut n_c, mut sum_f, mut n_f) = (0.0, 0.0, 0.0, 0.0);
    for (v, c) in y.iter().zip(indicator) {
        if *c > 0.5 {
            sum_c += v;
            n_c += 1.0;
        } else {
            sum_f += v;
            n_f += 1.0;
        }
    }
    let difference = sum_f / n_f - sum_c / n_c;
    n_f * n_c * difference * difference / (n_f + n_c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_two_level_designs_with_centres_qualify() {
        let factorial = vec![vec![-1.0, 1.0], vec![1.0, -1.0], vec![0.0, 0.0]];
        assert_eq!(
            centre_point_indicator(&factorial, ModelOrder::Linear),
            Some(vec![0.0, 0.0, 1.0])
        );
        assert_eq!(
            centre_point_indicator(&factorial, ModelOrder::Quadratic),
            None
        );
        let axial = vec![vec![-1.0, 1.0], vec![1.414, 0.0], vec![0.0, 0.0]];
        assert_eq!(centre_point_indicator(&axial, ModelOrder::Linear), None);
        let no_centre = vec![vec![-1.0, 1.0], vec![1.0, -1.0]];
        assert_eq!(centre_point_indicator(&no_centre, ModelOrder::Linear), None);
    }
}
