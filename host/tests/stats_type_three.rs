//! Type III sums of squares by formula, b_j² / [(XᵀX)⁻¹]_jj, agree with their definition:
//! the rise in residual SS when the term alone is dropped from the model. Checked on random
//! non-orthogonal designs, where sequential (Type I) and partial sums of squares differ.

use arachis::stats::{
    analyze, model_matrix, model_terms, residual_sum_of_squares, CodedDesign, ModelOrder,
};
use nalgebra::DVector;
use proptest::prelude::*;

proptest! {
    #[test]
    fn type_three_is_the_drop_one_refit(
        runs in prop::collection::vec(prop::collection::vec(-1.5f64..1.5, 3), 16..24),
        noise in prop::collection::vec(-1.0f64..1.0, 24),
    ) {
        let names: Vec<String> = ["A", "B", "C"].iter().map(|s| s.to_string()).collect();
        let y: Vec<f64> = runs
            .iter()
            .zip(&noise)
            .map(|(x, e)| 5.0 + 2.0 * x[0] - x[1] + 0.5 * x[0] * x[2] + x[1] * x[1] + e)
            .collect();
        let design = CodedDesign::new(names.clone(), runs.clone(), y.clone()).unwrap();
        let anova = analyze(&design, ModelOrder::Quadratic).unwrap();
        let terms = model_terms(&names, ModelOrder::Quadratic);
        let x = model_matrix(&terms, &runs);
        let yv = DVector::from_vec(y);
        let all: Vec<usize> = (0..terms.len()).collect();
        let full = residual_sum_of_squares(&x, &yv, &all).unwrap();
        for (j, row) in anova.terms.iter().enumerate() {
            let keep: Vec<usize> = all.iter().copied().filter(|&c| c != j + 1).collect();
            let dropped = residual_sum_of_squares(&x, &yv, &keep).unwrap();
            prop_assert!((row.ss - (dropped - full)).abs() <= 1e-8 * (1.0 + dropped));
        }
        // Without curvature, model + residual = corrected total.
        prop_assert!((anova.model.ss + anova.residual.ss - anova.cor_total.ss).abs()
            <= 1e-9 * anova.cor_total.ss);
    }
}
