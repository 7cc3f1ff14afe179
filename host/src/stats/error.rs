//! Why a regression or test could not be computed: every variant names the term, factor or
//! count at fault, so the command line can print it as is.

use thiserror::Error;

/// A regression, ANOVA or hypothesis test that cannot be computed from the data given.
#[derive(Debug, Error, PartialEq)]
pub enum StatsError {
    /// A model term is a linear combination of earlier terms on this design.
    #[error(
        "term '{term}' is aliased with {} on this design and cannot be estimated; \
         drop it or choose a smaller model",
        describe_aliases(aliases)
    )]
    Aliased {
        /// The term that cannot be estimated.
        term: String,
        /// Earlier terms it is a combination of (may be empty if only the intercept).
        aliases: Vec<String>,
    },
    /// The model has as many parameters as there are runs: nothing is left to test against.
    #[error(
        "the model has {parameters} parameters for {runs} runs, leaving no residual degrees \
         of freedom (saturated model); use a smaller model or more runs"
    )]
    Saturated {
        /// Number of runs (rows).
        runs: usize,
        /// Number of estimated parameters, intercept and curvature included.
        parameters: usize,
    },
    /// A factor takes one value in every run.
    #[error("factor '{factor}' has a single level ({value}) in all {runs} runs; a factor needs at least two levels")]
    OneLevel {
        /// Factor name.
        factor: String,
        /// The only value it takes (coded units).
        value: f64,
        /// Number of runs.
        runs: usize,
    },
    /// The inputs disagree in length or are too short.
    #[error("{0}")]
    BadShape(String),
    /// The response does not vary (every run the same to 1 part in 10¹²): there is nothing
    /// to model, and any fit would report rounding noise as effects.
    #[error("no variation to model: the response is {value} in every run")]
    NoVariation {
        /// The response's value.
        value: f64,
    },
    /// The residual variance is zero, so F statistics are undefined.
    #[error(
        "the model fits every run exactly (residual sum of squares is zero); F-tests are undefined"
    )]
    PerfectFit,
}

fn describe_aliases(aliases: &[String]) -> String {
    if aliases.is_empty() {
        "the terms before it".to_owned()
    } else {
        aliases
            .iter()
            .map(|a| format!("'{a}'"))
            .collect::<Vec<_>>()
            .join(" + ")
    }
}
