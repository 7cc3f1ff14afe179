//! Multi-start global search inside the coded box [−1, 1]^k.
//!
//! Starts are a deterministic Latin hypercube ([`latin_hypercube`]). From each start the
//! `argmin` crate's Nelder–Mead simplex climbs the merit function; the box is enforced by
//! searching over unbounded u with x = sin(u), which maps every u into [−1, 1] smoothly, so
//! the simplex never leaves the box. The end points are ranked by merit (ties keep start
//! order) and thinned so that no two kept solutions lie closer than a minimum distance:
//! the result is a ranked set of *distinct* solutions, as Design-Expert lists its
//! "one hundred sets of solutions" (seed 000 §3.6.2).
//!
//! ```
//! use arachis::optimize::{maximise, SearchOptions};
//! // A ridge: every point with x0 + x1 = 0.5 is optimal.
//! let merit = |x: &[f64]| -(x[0] + x[1] - 0.5).abs();
//! let found = maximise(2, &merit, &SearchOptions::default()).unwrap();
//! assert!(found.len() > 10);
//! assert!(found.iter().all(|s| s.merit > -1e-6));
//! ```

use argmin::core::{CostFunction, Error as ArgminError, Executor, State};
use argmin::solver::neldermead::NelderMead;
use rayon::prelude::*;

use super::{latin_hypercube, OptimizeError};

/// Most solutions returned (Design-Expert lists up to 100).
pub const MAX_SOLUTIONS: usize = 100;

/// Settings of the multi-start search.
#[derive(Debug, Clone, PartialEq)]
pub struct SearchOptions {
    /// Most distinct solutions to return (1 to [`MAX_SOLUTIONS`]).
    pub solutions: usize,
    /// Number of starting points.
    pub starts: usize,
    /// Seed of the Latin hypercube of starts.
    pub seed: u64,
    /// Smallest Euclidean distance, in coded units, between two returned solutions.
    pub min_distance: f64,
    /// Iteration limit of each Nelder–Mead run.
    pub max_iters: u64,
    /// Nelder–Mead stops when the standard deviation of the simplex's merits falls below this.
    pub tolerance: f64,
}

/// Starts per requested solution: several starts converge to the same point, so more
/// starts than solutions are needed to fill the list.
const STARTS_PER_SOLUTION: usize = 4;
/// Default seed of the starts (any fixed value; fixed so results are reproducible).
const DEFAULT_SEED: u64 = 20_240_531;
/// Default separation of solutions, coded units (0.5 % of the box's width of 2).
const DEFAULT_MIN_DISTANCE: f64 = 0.01;
/// Default Nelder–Mead iteration limit.
const DEFAULT_MAX_ITERS: u64 = 2_000;
/// Default Nelder–Mead tolerance on the spread of merits.
const DEFAULT_TOLERANCE: f64 = 1e-12;
/// Initial simplex edge in u (where x = sin u), about a tenth of the box.
const INITIAL_SIMPLEX_EDGE: f64 = 0.1;

impl Default for SearchOptions {
    fn default() -> Self {
        Self {
            solutions: MAX_SOLUTIONS,
            starts: STARTS_PER_SOLUTION * MAX_SOLUTIONS,
            seed: DEFAULT_SEED,
            min_distance: DEFAULT_MIN_DISTANCE,
            max_iters: DEFAULT_MAX_ITERS,
            tolerance: DEFAULT_TOLERANCE,
        }
    }
}

impl SearchOptions {
    /// Default settings for `solutions` solutions (starts scale with it).
    pub fn for_solutions(solutions: usize) -> Self {
        Self {
            solutions,
            starts: STARTS_PER_SOLUTION * solutions.max(1),
            ..Self::default()
        }
    }
}

/// One end point of the search.
#[derive(Debug, Clone, PartialEq)]
pub struct Solution {
    /// Coded factor values, each in [−1, 1].
    pub coded: Vec<f64>,
    /// Merit reached (larger is better).
    pub merit: f64,
}

/// The merit as an `argmin` cost over u, with x = sin(u).
struct BoxedCost<'a, F> {
    merit: &'a F,
}

impl<F: Fn(&[f64]) -> f64> CostFunction for BoxedCost<'_, F> {
    type Param = Vec<f64>;
    type Output = f64;

    fn cost(&self, u: &Self::Param) -> Result<Self::Output, ArgminError> {
        let x: Vec<f64> = u.iter().map(|v| v.sin()).collect();
        let m = (self.merit)(&x);
        // A NaN merit would stall the simplex; treat it as the worst point.
        Ok(if m.is_nan() { f64::INFINITY } else { -m })
    }
}

fn refine<F: Fn(&[f64]) -> f64>(
    merit: &F,
    start: &[f64],
    options: &SearchOptions,
) -> Result<Solution, OptimizeError> {
    let u0: Vec<f64> = start.iter().map(|x| x.clamp(-1.0, 1.0).asin()).collect();
    let mut simplex = vec![u0.clone()];
    for i in 0..u0.len() {
        let mut v = u0.clone();
        // Step towards the box's interior so the simplex is not folded by sin at ±π/2.
        v[i] += if u0[i] > 0.0 {
            -INITIAL_SIMPLEX_EDGE
        } else {
            INITIAL_SIMPLEX_EDGE
        };
        simplex.push(v);
    }
    let solver = NelderMead::new(simplex)
        .with_sd_tolerance(options.tolerance)
        .map_err(|e| OptimizeError::Solver(e.to_string()))?;
    let result = Executor::new(BoxedCost { merit }, solver)
        .configure(|state| state.max_iters(options.max_iters))
        .run()
        .map_err(|e| OptimizeError::Solver(e.to_string()))?;
    let state = result.state();
    let u = state
        .get_best_param()
        .ok_or_else(|| OptimizeError::Solver("no best point".into()))?;
    let coded: Vec<f64> = u.iter().map(|v| v.sin()).collect();
    let m = merit(&coded);
    Ok(Solution { coded, merit: m })
}

/// Maximises `merit` over [−1, 1]^`dims` from `options.starts` deterministic starts and
/// returns up to `options.solutions` distinct solutions, best first.
pub fn maximise<F>(
    dims: usize,
    merit: &F,
    options: &SearchOptions,
) -> Result<Vec<Solution>, OptimizeError>
where
    F: Fn(&[f64]) -> f64 + Sync,
{
    if dims == 0 {
        return Err(OptimizeError::BadSearch("no factors to vary".into()));
    }
    if !(1..=MAX_SOLUTIONS).contains(&options.solutions) {
        return Err(OptimizeError::BadSearch(format!(
            "{} solutions asked for; 1 to {MAX_SOLUTIONS} are available",
            options.solutions
        )));
    }
    if options.starts == 0 {
        return Err(OptimizeError::BadSearch("zero starting points".into()));
    }
    if !(options.min_distance.is_finite() && options.min_distance >= 0.0) {
        return Err(OptimizeError::BadSearch(format!(
            "minimum distance {} must be a non-negative number",
            options.min_distance
        )));
    }
    let starts = latin_hypercube(options.starts, dims, options.seed);
    // Each start is independent and `collect` keeps start order, so the result does not
    // depend on the number of threads.
    let mut found: Vec<Solution> = starts
        .par_iter()
        .map(|s| refine(merit, s, options))
        .collect::<Result<_, _>>()?;
    found.retain(|s| s.merit.is_finite());
    found.sort_by(|a, b| b.merit.total_cmp(&a.merit));
    let mut kept: Vec<Solution> = Vec::new();
    for s in found {
        if kept.len() == options.solutions {
            break;
        }
        let distinct = kept.iter().all(|k| {
            let d2: f64 = k
                .coded
                .iter()
                .zip(&s.coded)
                .map(|(a, b)| (a - b).powi(2))
                .sum();
            d2.sqrt() >= options.min_distance
        });
        if distinct {
            kept.push(s);
        }
    }
    Ok(kept)
}
