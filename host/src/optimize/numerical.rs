//! Numerical optimisation of one or more response surfaces by overall desirability, as
//! Design-Expert's "Optimization → Numerical" does: maximise D = (Π dᵢ^rᵢ)^(1/Σrᵢ) over the
//! coded design box and list distinct solutions with D > 0, best first.
//!
//! Where D = 0 (some response outside its limits) the search climbs instead towards the
//! limits, by minus the summed shortfall, so starts in a dead zone still find their way.
//!
//! ```
//! use arachis::optimize::{optimise_desirability, Goal, GoalKind, SearchOptions};
//! let y = |x: &[f64]| 30.0 + x[0] + 0.5 * x[1];
//! let goal = Goal::new(GoalKind::Target(30.7), 28.5, 31.5).unwrap();
//! let found = optimise_desirability(&[(&y, goal)], 2, &SearchOptions::for_solutions(10)).unwrap();
//! assert_eq!(found.len(), 10);
//! assert!((found[0].predictions[0] - 30.7).abs() < 1e-6);
//! ```

use super::{
    maximise, overall_desirability, Goal, GoalKind, OptimizeError, ResponseSurface, SearchOptions,
};

/// A point of the design box with its overall desirability and predicted responses.
#[derive(Debug, Clone, PartialEq)]
pub struct DesirableSolution {
    /// Coded factor values, each in [−1, 1].
    pub coded: Vec<f64>,
    /// Overall desirability D ∈ (0, 1].
    pub desirability: f64,
    /// Predicted responses, in the order of the goals, each in its response's unit.
    pub predictions: Vec<f64>,
}

/// Maximises the overall desirability of `responses` (surface and goal each) over
/// [−1, 1]^`dims`; returns up to `options.solutions` distinct solutions with D > 0.
pub fn optimise_desirability(
    responses: &[(&dyn ResponseSurface, Goal)],
    dims: usize,
    options: &SearchOptions,
) -> Result<Vec<DesirableSolution>, OptimizeError> {
    if responses.is_empty() {
        return Err(OptimizeError::BadSearch("no goals given".into()));
    }
    let goals: Vec<Goal> = responses.iter().map(|(_, g)| *g).collect();
    let predict = |x: &[f64]| -> Vec<f64> { responses.iter().map(|(s, _)| s.predict(x)).collect() };
    let merit = |x: &[f64]| {
        let ys = predict(x);
        let d = overall_desirability(&goals, &ys);
        if d > 0.0 {
            d
        } else {
            -goals
                .iter()
                .zip(&ys)
                .map(|(g, &y)| g.shortfall(y))
                .sum::<f64>()
        }
    };
    Ok(maximise(dims, &merit, options)?
        .into_iter()
        .filter(|s| s.merit > 0.0)
        .map(|s| {
            let predictions = predict(&s.coded);
            DesirableSolution {
                desirability: overall_desirability(&goals, &predictions),
                coded: s.coded,
                predictions,
            }
        })
        .collect())
}

/// Starts used to find a surface's extremes.
const RANGE_STARTS: usize = 64;

/// The smallest and largest prediction of `surface` over [−1, 1]^`dims` (each found by the
/// multi-start search): Design-Expert's default goal limits are the observed response range,
/// which a fit file does not carry, so the predicted range over the box stands in for it.
pub fn surface_range(
    surface: &dyn ResponseSurface,
    dims: usize,
) -> Result<(f64, f64), OptimizeError> {
    let options = SearchOptions {
        solutions: 1,
        starts: RANGE_STARTS,
        ..SearchOptions::default()
    };
    let best = |sign: f64| -> Result<f64, OptimizeError> {
        let merit = |x: &[f64]| sign * surface.predict(x);
        let found = maximise(dims, &merit, &options)?;
        found
            .first()
            .map(|s| surface.predict(&s.coded))
            .ok_or_else(|| OptimizeError::Solver("the surface is nowhere finite".into()))
    };
    Ok((best(-1.0)?, best(1.0)?))
}

/// A goal from its kind with limits defaulting to `range` (the surface's predicted range);
/// a target must lie inside the limits.
pub fn goal_with_default_limits(
    kind: GoalKind,
    limits: Option<(f64, f64)>,
    range: (f64, f64),
) -> Result<Goal, OptimizeError> {
    let (low, high) = limits.unwrap_or(range);
    Goal::new(kind, low, high)
}
