//! Model terms of a response-surface polynomial in coded factors, named the way the rest of
//! Arachis reads them: `Intercept`, `A` (the factor's column name), `A*B` (factors in column
//! order) and `A^2`.
//!
//! Terms come in Design-Expert's order: intercept, main effects, two-factor interactions,
//! then pure quadratics.
//!
//! ```
//! use arachis::stats::{model_terms, ModelOrder};
//! let names: Vec<String> = model_terms(&["A", "B"], ModelOrder::Quadratic)
//!     .iter()
//!     .map(|t| t.name.clone())
//!     .collect();
//! assert_eq!(names, ["Intercept", "A", "B", "A*B", "A^2", "B^2"]);
//! ```

use nalgebra::DMatrix;

/// Which polynomial to fit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelOrder {
    /// Intercept and main effects.
    Linear,
    /// Linear plus all two-factor interactions (2FI).
    TwoFactorInteraction,
    /// 2FI plus pure quadratic terms.
    Quadratic,
}

impl ModelOrder {
    /// The name Design-Expert uses for the model ("Linear", "2FI", "Quadratic").
    pub fn label(self) -> &'static str {
        match self {
            Self::Linear => "Linear",
            Self::TwoFactorInteraction => "2FI",
            Self::Quadratic => "Quadratic",
        }
    }
}

/// What a term multiplies: indices are factor positions (column order).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TermKind {
    /// The constant 1.
    Intercept,
    /// Coded factor `i`.
    Linear(usize),
    /// Product of coded factors `i < j`.
    Interaction(usize, usize),
    /// Square of coded factor `i`.
    Square(usize),
}

/// One named model term.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Term {
    /// Name by the naming contract (`Intercept`, `A`, `A*B`, `A^2`).
    pub name: String,
    /// What it multiplies.
    pub kind: TermKind,
}

impl Term {
    /// The term's value at one run, from the coded factor values `x`.
    pub fn value(&self, x: &[f64]) -> f64 {
        match self.kind {
            TermKind::Intercept => 1.0,
            TermKind::Linear(i) => x[i],
            TermKind::Interaction(i, j) => x[i] * x[j],
            TermKind::Square(i) => x[i] * x[i],
        }
    }
}

/// The terms of `order` for factors named `factors` (in column order).
pub fn model_terms<S: AsRef<str>>(factors: &[S], order: ModelOrder) -> Vec<Term> {
    let name = |i: usize| factors[i].as_ref();
    let k = factors.len();
    let mut terms = vec![Term {
        name: "Intercept".to_owned(),
        kind: TermKind::Intercept,
    }];
    terms.extend((0..k).map(|i| Term {
        name: name(i).to_owned(),
        kind: TermKind::Linear(i),
    }));
    if order != ModelOrder::Linear {
        for i in 0..k {
            for j in i + 1..k {
                terms.push(Term {
                    name: format!("{}*{}", name(i), name(j)),
                    kind: TermKind::Interaction(i, j),
                });
            }
        }
    }
    if order == ModelOrder::Quadratic {
        terms.extend((0..k).map(|i| Term {
            name: format!("{}^2", name(i)),
            kind: TermKind::Square(i),
        }));
    }
    terms
}

/// The model matrix: one row per run (`coded[run][factor]`), one column per term.
pub fn model_matrix(terms: &[Term], coded: &[Vec<f64>]) -> DMatrix<f64> {
    DMatrix::from_fn(coded.len(), terms.len(), |r, c| terms[c].value(&coded[r]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_factor_interactions_keep_column_order() {
        let names: Vec<String> = model_terms(&["x3", "x4", "x5"], ModelOrder::TwoFactorInteraction)
            .into_iter()
            .map(|t| t.name)
            .collect();
        assert_eq!(
            names,
            ["Intercept", "x3", "x4", "x5", "x3*x4", "x3*x5", "x4*x5"]
        );
    }

    #[test]
    fn matrix_evaluates_each_term() {
        let terms = model_terms(&["A", "B"], ModelOrder::Quadratic);
        let m = model_matrix(&terms, &[vec![2.0, -3.0]]);
        assert_eq!(
            m.row(0).iter().copied().collect::<Vec<_>>(),
            [1.0, 2.0, -3.0, -6.0, 4.0, 9.0]
        );
    }
}
