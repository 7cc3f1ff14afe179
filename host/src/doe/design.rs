//! A design matrix: runs × factors in coded units, with the factors that map them to actual
//! units, the kind of each point, and the order in which the runs are carried out.
//!
//! Rows are kept in *standard order* (the order the construction produces them, as
//! Design-Expert's "Std" column). The *run order* is a permutation of them: by default the
//! standard order; [`Design::with_run_order`] sets another one, for example a seed's printed
//! (randomised) order from [`super::seed_run_orders`].

use super::{DesignError, Factor};

/// What a run is, for analyses that split curvature or pure error from centre points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PointType {
    /// A corner of the two-level cube (factorial and Plackett–Burman runs).
    Factorial,
    /// An axial (star) point of a central composite design.
    Axial,
    /// A Box–Behnken edge mid-point (two or three factors at ±1, the rest at 0).
    Edge,
    /// A centre point (all factors at coded 0).
    Centre,
    /// A point on a steepest-ascent path.
    Path,
}

impl PointType {
    /// Short lower-case label used in CSV output.
    pub fn label(self) -> &'static str {
        match self {
            Self::Factorial => "factorial",
            Self::Axial => "axial",
            Self::Edge => "edge",
            Self::Centre => "centre",
            Self::Path => "path",
        }
    }
}

/// A design of experiments.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// What kind of design this is, in words (e.g. "Box-Behnken").
    pub kind: String,
    /// The real factors, in column order; they give the actual units.
    pub factors: Vec<Factor>,
    /// Names of dummy columns that follow the real factors (Plackett–Burman designs only);
    /// they have coded values but no actual levels.
    pub dummy_columns: Vec<String>,
    /// Coded values in standard order: one row per run, `factors.len() + dummy_columns.len()`
    /// columns.
    pub coded: Vec<Vec<f64>>,
    /// Kind of each run, in standard order.
    pub point_types: Vec<PointType>,
    /// `run_order[r]` is the 0-based standard-order index of the run carried out `r`-th.
    pub run_order: Vec<usize>,
}

impl Design {
    /// A design in standard order (run order = standard order).
    pub(crate) fn new(
        kind: &str,
        factors: Vec<Factor>,
        dummy_columns: Vec<String>,
        coded: Vec<Vec<f64>>,
        point_types: Vec<PointType>,
    ) -> Self {
        debug_assert_eq!(coded.len(), point_types.len());
        let run_order = (0..coded.len()).collect();
        Self {
            kind: kind.to_owned(),
            factors,
            dummy_columns,
            coded,
            point_types,
            run_order,
        }
    }

    /// Number of runs.
    pub fn runs(&self) -> usize {
        self.coded.len()
    }

    /// Names of all coded columns: the factors, then the dummy columns.
    pub fn column_names(&self) -> Vec<String> {
        self.factors
            .iter()
            .map(|f| f.name.clone())
            .chain(self.dummy_columns.iter().cloned())
            .collect()
    }

    /// Actual levels (each in its factor's unit) of standard-order run `std`, real factors only.
    pub fn actual_row(&self, std: usize) -> Vec<f64> {
        self.factors
            .iter()
            .zip(&self.coded[std])
            .map(|(f, &x)| f.to_actual(x))
            .collect()
    }

    /// Coded rows in run order.
    pub fn coded_in_run_order(&self) -> Vec<Vec<f64>> {
        self.run_order
            .iter()
            .map(|&s| self.coded[s].clone())
            .collect()
    }

    /// Actual rows (real factors only) in run order.
    pub fn actual_in_run_order(&self) -> Vec<Vec<f64>> {
        self.run_order.iter().map(|&s| self.actual_row(s)).collect()
    }

    /// The same design carried out in another order. `std_order_by_run[r]` is the **1-based**
    /// standard-order number of the `r`-th run (Design-Expert's "Std" column read down its
    /// "Run" column). Rejects anything that is not a permutation of `1..=runs`.
    pub fn with_run_order(mut self, std_order_by_run: &[usize]) -> Result<Self, DesignError> {
        let n = self.runs();
        if std_order_by_run.len() != n {
            return Err(DesignError::BadRunOrder(format!(
                "{} entries for a design of {n} runs",
                std_order_by_run.len()
            )));
        }
        let mut seen = vec![false; n];
        for &s in std_order_by_run {
            if s == 0 || s > n || seen[s - 1] {
                return Err(DesignError::BadRunOrder(format!(
                    "{s} is out of 1..={n} or repeated"
                )));
            }
            seen[s - 1] = true;
        }
        self.run_order = std_order_by_run.iter().map(|s| s - 1).collect();
        Ok(self)
    }

    /// Renames the dummy columns (e.g. `x9`, `x10`, `x11` as in seed 000 Table 3).
    pub fn with_dummy_names(mut self, names: &[&str]) -> Result<Self, DesignError> {
        if names.len() != self.dummy_columns.len() {
            return Err(DesignError::BadFactorSpec {
                spec: names.join(","),
                reason: format!(
                    "{} dummy names given, the design has {} dummy columns",
                    names.len(),
                    self.dummy_columns.len()
                ),
            });
        }
        self.dummy_columns = names.iter().map(|s| (*s).to_owned()).collect();
        Ok(self)
    }
}

/// `n` centre points (all coded 0) over `columns` columns.
pub(crate) fn centre_rows(n: usize, columns: usize) -> (Vec<Vec<f64>>, Vec<PointType>) {
    (vec![vec![0.0; columns]; n], vec![PointType::Centre; n])
}

/// The 2^`k` corners of the cube in standard (Yates) order: the first column alternates
/// fastest (−, +, −, +, …), the second in pairs, and so on.
pub(crate) fn yates_corners(k: usize) -> Vec<Vec<f64>> {
    (0..1usize << k)
        .map(|i| {
            (0..k)
                .map(|j| if (i >> j) & 1 == 1 { 1.0 } else { -1.0 })
                .collect()
        })
        .collect()
}
