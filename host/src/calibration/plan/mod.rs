//! The five stages of a calibration plan, one module each, and [`run_plan`], which runs them
//! in order: [`screening`] → [`steepest_ascent`] → [`response_surface`] (a
//! [`box_behnken`] or [`central_composite`] design) → [`optimum`] → [`validation`].

pub mod box_behnken;
pub mod central_composite;
pub mod optimum;
pub mod response_surface;
pub mod screening;
pub mod steepest_ascent;
pub mod validation;

use super::executor::Executor;
use super::{CalibrateError, Problem};

/// Every stage's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Stages {
    /// Stage 1.
    pub screening: screening::Screening,
    /// Stage 2.
    pub path: steepest_ascent::SteepestAscent,
    /// Stage 3.
    pub surface: response_surface::ResponseSurface,
    /// Stage 4.
    pub optimum: optimum::Optimum,
    /// Stage 5.
    pub validation: validation::Validation,
}

/// Runs the plan of `problem` on `executor`. Returns every stage even when validation
/// misses its limit ([`validation::Validation::passed`] tells).
pub fn run_plan(problem: &Problem<'_>, executor: &Executor) -> Result<Stages, CalibrateError> {
    let plan = &problem.plan;
    let all = &problem.factors;
    let target = &problem.target;
    let screening = screening::run(
        executor,
        target,
        all,
        &plan.screening,
        response_surface::factor_range(plan.surface.design),
    )?;
    let path = steepest_ascent::run(executor, target, all, &screening, &plan.path)?;
    let surface = response_surface::run(
        executor,
        target,
        all,
        &path,
        plan.path.step_coded,
        &plan.surface,
    )?;
    let optimum = optimum::run(executor, target, &surface)?;
    let validation = validation::run(
        executor,
        &problem.validation,
        all,
        &optimum,
        &plan.validation,
    )?;
    Ok(Stages {
        screening,
        path,
        surface,
        optimum,
        validation,
    })
}
