//! Optimisation on fitted response surfaces (issue 3): Derringer–Suich desirability and a
//! multi-start search over the coded design box that returns a ranked set of distinct
//! solutions, as Design-Expert's numerical optimisation does.
//!
//! Any model plugs in through [`ResponseSurface`] (closures implement it); fit files from
//! `arachis doe analyze --json` are read by [`FitFile`] into a [`Polynomial`].
//!
//! ```
//! use arachis::optimize::{optimise_desirability, Goal, GoalKind, Polynomial, SearchOptions};
//! // Seed 000 eq. (22), stacking angle in degrees over coded x3, x4, x5.
//! let names = ["x3", "x4", "x5"].map(String::from).to_vec();
//! let eq22 = Polynomial::new(names, &[
//!     ("Intercept", 30.45), ("x3", -0.53), ("x4", -0.38), ("x5", 1.10),
//!     ("x3*x4", 0.21), ("x3*x5", 0.078), ("x4*x5", -0.08),
//!     ("x3^2", -0.25), ("x4^2", -0.26), ("x5^2", -0.009),
//! ]).unwrap();
//! let goal = Goal::new(GoalKind::Target(31.06), 28.0, 32.2).unwrap();
//! let found = optimise_desirability(&[(&eq22, goal)], 3, &SearchOptions::for_solutions(5)).unwrap();
//! assert!((found[0].predictions[0] - 31.06).abs() < 0.01);
//! ```

pub mod desirability;
pub mod error;
pub mod fit_file;
pub mod latin_hypercube;
pub mod multistart;
pub mod numerical;
pub mod polynomial;
pub mod surface;

pub use desirability::{overall_desirability, Goal, GoalKind};
pub use error::OptimizeError;
pub use fit_file::{FitFactor, FitFile};
pub use latin_hypercube::latin_hypercube;
pub use multistart::{maximise, SearchOptions, Solution, MAX_SOLUTIONS};
pub use numerical::{
    goal_with_default_limits, optimise_desirability, surface_range, DesirableSolution,
};
pub use polynomial::{Polynomial, Term};
pub use surface::ResponseSurface;
