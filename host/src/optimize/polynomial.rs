//! Polynomial response surfaces in coded units, with Design-Expert's term names.
//!
//! A term is `Intercept`, a factor's name `A` (linear), `A*B` (two-factor interaction) or
//! `A^2` (pure quadratic). Seed 000 eq. (22) is such a model in x3, x4, x5:
//! ζ = 30.45 − 0.53x3 − 0.38x4 + 1.10x5 + 0.21x3x4 + 0.078x3x5 − 0.08x4x5 − 0.25x3² − 0.26x4²
//! − 0.009x5².
//!
//! ```
//! use arachis::optimize::{Polynomial, ResponseSurface};
//! let names = vec!["A".to_string(), "B".to_string()];
//! let p = Polynomial::new(names, &[("Intercept", 1.0), ("A", 2.0), ("A*B", 0.5), ("B^2", -1.0)])
//!     .unwrap();
//! assert_eq!(p.predict(&[1.0, 2.0]), 1.0 + 2.0 + 1.0 - 4.0);
//! ```

use super::ResponseSurface;

/// One model term over factor indices (column order).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Term {
    /// The constant.
    Intercept,
    /// xᵢ.
    Linear(usize),
    /// xᵢ xⱼ, i < j.
    Interaction(usize, usize),
    /// xᵢ².
    Quadratic(usize),
}

impl Term {
    /// Parses a Design-Expert term name against the factor names; `None` if it is not a
    /// term of a (at most) quadratic model in these factors.
    pub fn parse(name: &str, factors: &[String]) -> Option<Self> {
        let name = name.trim();
        let index = |n: &str| factors.iter().position(|f| f == n.trim());
        if name == "Intercept" {
            return Some(Self::Intercept);
        }
        if let Some(i) = index(name) {
            return Some(Self::Linear(i));
        }
        if let Some(i) = name.strip_suffix("^2").and_then(index) {
            return Some(Self::Quadratic(i));
        }
        let (a, b) = name.split_once('*')?;
        match (index(a)?, index(b)?) {
            (i, j) if i == j => Some(Self::Quadratic(i)),
            (i, j) => Some(Self::Interaction(i.min(j), i.max(j))),
        }
    }

    /// The term's value at coded point `x`.
    pub fn value(self, x: &[f64]) -> f64 {
        match self {
            Self::Intercept => 1.0,
            Self::Linear(i) => x[i],
            Self::Interaction(i, j) => x[i] * x[j],
            Self::Quadratic(i) => x[i] * x[i],
        }
    }
}

/// ŷ = Σ βₜ termₜ(x) over coded factors x.
#[derive(Debug, Clone, PartialEq)]
pub struct Polynomial {
    /// Factor names in column order.
    pub factors: Vec<String>,
    /// Terms and their coefficients (in the response's unit).
    pub terms: Vec<(Term, f64)>,
}

impl Polynomial {
    /// A polynomial from `(term name, coefficient)` pairs. Returns the first name that is
    /// not a term in `factors` as the error.
    pub fn new(factors: Vec<String>, terms: &[(&str, f64)]) -> Result<Self, String> {
        let parsed = terms
            .iter()
            .map(|(name, b)| {
                Term::parse(name, &factors)
                    .map(|t| (t, *b))
                    .ok_or_else(|| (*name).to_owned())
            })
            .collect::<Result<_, _>>()?;
        Ok(Self {
            factors,
            terms: parsed,
        })
    }
}

impl ResponseSurface for Polynomial {
    fn predict(&self, coded: &[f64]) -> f64 {
        self.terms.iter().map(|(t, b)| b * t.value(coded)).sum()
    }
}
