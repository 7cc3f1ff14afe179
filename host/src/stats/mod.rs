//! Regression, ANOVA and hypothesis tests with Design-Expert's conventions (issue 3 item 3,
//! DESIGN §9).
//!
//! A [`CodedDesign`] (factors in coded units and one response) is fitted by least squares
//! ([`least_squares`], QR) with a [`ModelOrder`]'s terms ([`model_terms`]); [`analyze`]
//! builds the ANOVA table with Type III sums of squares, the curvature term, lack of fit and
//! pure error, and the fit statistics. [`pooled_t_test`] compares two samples.

mod anova;
mod coded_design;
pub mod curvature;
pub mod design_table;
mod error;
mod fit_statistics;
pub mod lack_of_fit;
mod least_squares;
mod model_terms;
pub mod p_values;
pub mod report;
mod t_test;

pub use anova::{analyze, Anova, Coefficient, ErrorSource, TermRow, TestedSource};
pub use coded_design::{CodedDesign, FactorLevels};
pub use design_table::{read_design_table, DesignTable};
pub use error::StatsError;
pub use fit_statistics::{fit_statistics, press, FitInputs, FitStatistics};
pub use least_squares::{least_squares, residual_sum_of_squares, LeastSquaresFit};
pub use model_terms::{model_matrix, model_terms, ModelOrder, Term, TermKind};
pub use t_test::{pooled_t_test, relative_error_percent, PooledTTest};
