//! Why a design could not be made.
//!
//! Every variant says which input is wrong and what would be accepted, so the command line can
//! print it as it is.

use thiserror::Error;

/// A design request that cannot be honoured.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum DesignError {
    /// A factor's levels are not usable (`low >= high`, not finite, or an empty name).
    #[error("factor '{name}': {reason}")]
    BadFactor {
        /// The factor's name as given.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// A factor specification on the command line could not be parsed.
    #[error("factor specification '{spec}': {reason}")]
    BadFactorSpec {
        /// The text as given.
        spec: String,
        /// What is wrong.
        reason: String,
    },
    /// The design does not exist for this number of factors.
    #[error("{design}: {k} factors given, but it needs {allowed}")]
    FactorCount {
        /// The design.
        design: &'static str,
        /// Factors given.
        k: usize,
        /// The accepted range, in words.
        allowed: String,
    },
    /// Two factors share a name, so their columns could not be told apart.
    #[error("two factors are both named '{0}'")]
    DuplicateName(String),
    /// A fractional-factorial generator such as `D=ABC` is malformed or inconsistent.
    #[error("generator '{generator}': {reason}")]
    BadGenerator {
        /// The generator as given.
        generator: String,
        /// What is wrong.
        reason: String,
    },
    /// An axial distance that is not a positive finite number.
    #[error("alpha {0}: the axial distance must be a positive finite number")]
    BadAlpha(f64),
    /// A steepest-ascent request that cannot define a path.
    #[error("steepest ascent: {0}")]
    BadPath(String),
    /// A run order that is not a permutation of the design's runs.
    #[error("run order: {0}")]
    BadRunOrder(String),
}
