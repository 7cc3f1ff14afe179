//! Recalibration with an effect switched on (DESIGN §10 step 3): weighted least squares of the
//! condition means, Σ((ȳ − ŷ(θ))/SE)², by argmin's Gauss–Newton solver on nalgebra vectors,
//! with finite-difference Jacobians ([`super::sensitivity::jacobian`]); the parameters are
//! scaled to order one by their catalogue scale.
//!
//! Bounds: every parameter stays in its interval ([`super::params::interval`]: e ∈ (0, 1],
//! effects ≥ 0). argmin's Gauss–Newton has no bounds, so the fit is projected: the model is
//! evaluated at the parameters clamped into their intervals, and a parameter that the solver
//! drives past an end is held on that end while the others are fitted again (an active set,
//! the loop in [`fit`]; a held parameter is let go when the gradient points back inside).
//! The exception to "use an optimiser library" is this outer loop only; each inner fit is
//! argmin's. An estimate on an end is reported as such, with its one-sided interval
//! ([`FitResult::one_sided_interval`]).
//!
//! Bench priors (`[diagnosis.prior]`, mean ± sd of a base parameter): each free parameter with
//! one adds the residual (θ − mean)/sd, so the objective is SSE + Σ z². The tests and criteria
//! below use that objective (SSE in their formulas) and count the prior rows in N; without
//! priors nothing changes.
//!
//! Reports (see [`Comparison`]): the error before/after, the nested-model test (likelihood
//! ratio Δ = SSE₀ − SSE₁ ~ χ²₁ with the pure-error σ, and F = Δ/(SSE₁/(N − k₁)) ~ F(1, N − k₁)),
//! AIC = SSE + 2k, AICc = AIC + 2k(k+1)/(N − k − 1) and BIC = SSE + k·ln N (Gaussian
//! likelihood with σ from pure error, constants dropped), and the leave-one-condition-out
//! error (each condition predicted by a fit without it, standardised).
//! Standard errors: √diag((J̃ᵀJ̃)⁻¹) at the optimum (σ from pure error).

use anyhow::{anyhow, bail, Context, Result};
use argmin::core::{CostFunction, Executor, Jacobian, Operator, State};
use argmin::solver::gaussnewton::GaussNewton;
use nalgebra::{DMatrix, DVector};
use statrs::distribution::{ChiSquared, ContinuousCDF, FisherSnedecor, Normal};

use super::model::Model;
use super::params::{interval, set, value, ParamInfo};
use super::residuals::{BenchPrior, Dataset};
use super::score::scale_rows;
use super::sensitivity::{jacobian, predict};
use crate::calibration::ParameterValues;

/// Gauss–Newton iteration limit.
pub const MAX_ITERATIONS: u64 = 15;
/// Convergence tolerance on the change of ‖r‖ (standardised units: 1e-4 is far below the
/// sampling noise of ‖r‖, ≈ 0.7).
const COST_TOLERANCE: f64 = 1e-4;
/// A base parameter is fitted only when a change by its catalogue scale moves the
/// standardised residuals by at least this much (otherwise the data cannot determine it and
/// JᵀJ would be singular).
pub const MIN_BASE_INFLUENCE: f64 = 1.0;
/// Confidence of the one-sided interval of an estimate on an end of its interval.
pub const ONE_SIDED_CONFIDENCE: f64 = 0.95;

/// The weighted least-squares problem handed to argmin.
struct Problem<'a> {
    data: &'a Dataset,
    model: &'a Model<'a>,
    start: ParameterValues,
    free: Vec<&'static ParamInfo>,
    weights: DVector<f64>,
}

/// The bench priors of `data` on parameters of `free`, with the parameter's index in `free`:
/// each adds a residual (θ − mean)/sd after the data's.
fn priors_on<'d>(
    data: &'d Dataset,
    free: &'d [&'static ParamInfo],
) -> impl Iterator<Item = (usize, &'d BenchPrior)> + 'd {
    data.priors.iter().filter_map(move |prior| {
        let k = free.iter().position(|f| f.key == prior.param.key)?;
        Some((k, prior))
    })
}

impl<'a> Problem<'a> {
    fn new(
        data: &'a Dataset,
        model: &'a Model<'a>,
        start: &ParameterValues,
        free: &[&'static ParamInfo],
        weights: &DVector<f64>,
    ) -> Self {
        Problem {
            data,
            model,
            start: start.clone(),
            free: free.to_vec(),
            weights: weights.clone(),
        }
    }

    /// The free parameters of `p`, scaled by their catalogue scale (the solver's vector).
    fn scaled(&self, p: &ParameterValues) -> DVector<f64> {
        DVector::from_iterator(
            self.free.len(),
            self.free.iter().map(|i| value(i, p) / i.scale),
        )
    }

    fn priors(&self) -> impl Iterator<Item = (usize, &BenchPrior)> {
        priors_on(self.data, &self.free)
    }

    fn params(&self, u: &DVector<f64>) -> ParameterValues {
        let mut p = self.start.clone();
        for (k, info) in self.free.iter().enumerate() {
            let (lo, hi) = interval(info);
            set(info, &mut p, (u[k] * info.scale).clamp(lo, hi));
        }
        p
    }
}

impl Operator for Problem<'_> {
    type Param = DVector<f64>;
    type Output = DVector<f64>;
    fn apply(&self, u: &Self::Param) -> Result<Self::Output, argmin::core::Error> {
        let p = self.params(u);
        let pred = predict(self.data, self.model, &p)?;
        let data = pred
            .iter()
            .zip(&self.data.obs)
            .zip(self.weights.iter())
            .map(|((y, o), w)| (y - o.mean) * w);
        let priors = self
            .priors()
            .map(|(_, prior)| prior.z(value(prior.param, &p)));
        Ok(DVector::from_iterator(
            pred.len() + self.priors().count(),
            data.chain(priors),
        ))
    }
}

impl CostFunction for Problem<'_> {
    type Param = DVector<f64>;
    type Output = f64;
    fn cost(&self, u: &Self::Param) -> Result<f64, argmin::core::Error> {
        Ok(self.apply(u)?.norm_squared())
    }
}

impl Jacobian for Problem<'_> {
    type Param = DVector<f64>;
    type Jacobian = DMatrix<f64>;
    fn jacobian(&self, u: &Self::Param) -> Result<Self::Jacobian, argmin::core::Error> {
        let p = self.params(u);
        let at = predict(self.data, self.model, &p)?;
        let j = jacobian(self.data, self.model, &p, &at, &self.free)?;
        let mut j = scale_rows(&j, &self.weights);
        for (k, info) in self.free.iter().enumerate() {
            j.column_mut(k).scale_mut(info.scale);
        }
        // d((θ − mean)/sd)/du = scale/sd, in the parameter's column.
        for (k, prior) in self.priors().collect::<Vec<_>>() {
            let row = j.nrows();
            j = j.insert_row(row, 0.0);
            j[(row, k)] = self.free[k].scale / prior.sd;
        }
        Ok(j)
    }
}

/// A fitted model.
#[derive(Clone, Debug)]
pub struct FitResult {
    /// Fitted parameters (the others as in the start).
    pub params: ParameterValues,
    /// The free parameters.
    pub free: Vec<&'static ParamInfo>,
    /// Standard errors of the free parameters (their units).
    pub std_errors: Vec<f64>,
    /// Predictions at each condition.
    pub predictions: Vec<f64>,
    /// SSE = Σ standardised residual² over the conditions.
    pub sse: f64,
    /// Gauss–Newton iterations used.
    pub iterations: u64,
    /// Per free parameter: the end of its interval the estimate sits on, if any.
    pub on_end: Vec<Option<f64>>,
    /// Σ ((θ − mean)/sd)² over the bench priors on free parameters (0 without any).
    pub prior_sse: f64,
    /// Every bench prior's parameter and its distance (θ − mean)/sd at the fit, in SDs.
    pub prior_z: Vec<(&'static ParamInfo, f64)>,
}

impl FitResult {
    /// For free parameter `k` on an end of its interval: the one-sided interval
    /// ([`ONE_SIDED_CONFIDENCE`]) from that end inwards, end ∓ z·SE, within the interval;
    /// `None` for an estimate inside.
    pub fn one_sided_interval(&self, k: usize) -> Option<(f64, f64)> {
        let end = self.on_end[k]?;
        let info = self.free[k];
        let (lo, hi) = interval(info);
        let z = Normal::standard().inverse_cdf(ONE_SIDED_CONFIDENCE);
        let reach = z * self.std_errors[k];
        Some(if end == hi && end != lo {
            ((end - reach).max(lo), end)
        } else {
            (end, (end + reach).min(hi))
        })
    }

    /// The objective the fit minimised: SSE plus the priors' share.
    pub fn objective(&self) -> f64 {
        self.sse + self.prior_sse
    }

    /// Number of fitted parameters k.
    pub fn k(&self) -> usize {
        self.free.len()
    }
    /// AIC = SSE + 2k (SSE with the priors' share, [`FitResult::objective`]).
    pub fn aic(&self) -> f64 {
        self.objective() + 2.0 * self.k() as f64
    }
    /// AICc = AIC + 2k(k+1)/(N − k − 1) (infinite when N ≤ k + 1).
    pub fn aicc(&self, n: usize) -> f64 {
        let k = self.k() as f64;
        let d = n as f64 - k - 1.0;
        if d <= 0.0 {
            f64::INFINITY
        } else {
            self.aic() + 2.0 * k * (k + 1.0) / d
        }
    }
    /// BIC = SSE + k·ln N (SSE with the priors' share).
    pub fn bic(&self, n: usize) -> f64 {
        self.objective() + self.k() as f64 * (n as f64).ln()
    }
}

/// Base parameters that the data can determine at `p`.
pub fn determinable_base(
    data: &Dataset,
    model: &Model<'_>,
    p: &ParameterValues,
) -> Result<Vec<&'static ParamInfo>> {
    let base: Vec<&'static ParamInfo> = model
        .catalogue
        .base()
        .filter(|i| p.contains_key(i.key))
        .collect();
    let at = predict(data, model, p)?;
    let j = jacobian(data, model, p, &at, &base)?;
    let w = DVector::from_iterator(data.obs.len(), data.obs.iter().map(|o| 1.0 / o.se_mean));
    let j = scale_rows(&j, &w);
    Ok(base
        .into_iter()
        .enumerate()
        .filter(|(k, info)| {
            // A bench prior determines its parameter whatever the data say.
            j.column(*k).norm() * info.scale >= MIN_BASE_INFLUENCE
                || data.priors.iter().any(|p| p.param.key == info.key)
        })
        .map(|(_, info)| info)
        .collect())
}

/// The bench priors' share of a fit of `free` at `params`: Σ z² over the priors on free
/// parameters, and every prior's z = (θ − mean)/sd.
fn prior_terms(
    data: &Dataset,
    free: &[&'static ParamInfo],
    params: &ParameterValues,
) -> (f64, Vec<(&'static ParamInfo, f64)>) {
    let z: Vec<(&'static ParamInfo, f64)> = data
        .priors
        .iter()
        .map(|p| (p.param, p.z(value(p.param, params))))
        .collect();
    let sse = priors_on(data, free)
        .map(|(_, p)| p.z(value(p.param, params)).powi(2))
        .sum();
    (sse, z)
}

/// Residuals a fit of `free` to `data` has: one per condition and one per bench prior on a
/// free parameter.
pub fn residual_count(data: &Dataset, free: &[&'static ParamInfo]) -> usize {
    data.obs.len() + priors_on(data, free).count()
}

/// Fit the parameters `free` from `start` (which also holds the fixed ones).
pub fn fit(
    data: &Dataset,
    model: &Model<'_>,
    start: &ParameterValues,
    free: &[&'static ParamInfo],
) -> Result<FitResult> {
    if free.is_empty() {
        let predictions = predict(data, model, start)?;
        let sse = data.standardised(&predictions).iter().map(|r| r * r).sum();
        let (prior_sse, prior_z) = prior_terms(data, &[], start);
        return Ok(FitResult {
            params: start.clone(),
            free: Vec::new(),
            std_errors: Vec::new(),
            predictions,
            sse,
            iterations: 0,
            on_end: Vec::new(),
            prior_sse,
            prior_z,
        });
    }
    if free.len() >= residual_count(data, free) {
        bail!(
            "{} parameters cannot be fitted to {} conditions",
            free.len(),
            data.obs.len()
        );
    }
    let weights = DVector::from_iterator(data.obs.len(), data.obs.iter().map(|o| 1.0 / o.se_mean));
    // The active set: parameters held on an end of their interval.
    let mut held = vec![false; free.len()];
    let mut at = start.clone();
    let mut iterations = 0;
    // Each round holds or lets go at least one parameter; bounded so that it always ends.
    for _ in 0..=2 * free.len() {
        let moving: Vec<&'static ParamInfo> = free
            .iter()
            .zip(&held)
            .filter(|(_, h)| !**h)
            .map(|(i, _)| *i)
            .collect();
        let mut changed = false;
        if !moving.is_empty() {
            let (params, past_end, its) = gauss_newton(data, model, &at, &moving, &weights)?;
            iterations += its;
            at = params;
            for info in past_end {
                let k = free
                    .iter()
                    .position(|f| f.key == info.key)
                    .context("lost a parameter")?;
                held[k] = true;
                changed = true;
            }
        }
        if !changed && held.contains(&true) {
            // Let go of a held parameter whose cost falls inwards (gradient Jᵀr pointing in).
            let problem = Problem::new(data, model, &at, free, &weights);
            let u = problem.scaled(&at);
            let gradient = problem.jacobian(&u)?.transpose() * problem.apply(&u)?;
            for (k, info) in free.iter().enumerate() {
                let (lo, hi) = interval(info);
                let v = value(info, &at);
                let inwards = (v >= hi && gradient[k] > 0.0) || (v <= lo && gradient[k] < 0.0);
                if held[k] && inwards && lo < hi {
                    held[k] = false;
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let problem = Problem::new(data, model, &at, free, &weights);
    let u = problem.scaled(&at);
    let params = problem.params(&u);
    let predictions = predict(data, model, &params)?;
    let sse = data.standardised(&predictions).iter().map(|r| r * r).sum();
    let j = problem.jacobian(&u)?;
    let cov = (j.transpose() * &j).try_inverse().ok_or_else(|| {
        anyhow!("the fitted parameters are not determined by the data (singular JᵀJ)")
    })?;
    let std_errors = free
        .iter()
        .enumerate()
        .map(|(k, i)| cov[(k, k)].max(0.0).sqrt() * i.scale)
        .collect();
    let on_end = free
        .iter()
        .map(|info| {
            let (lo, hi) = interval(info);
            let v = value(info, &params);
            [lo, hi].into_iter().find(|&end| v == end)
        })
        .collect();
    let (prior_sse, prior_z) = prior_terms(data, free, &params);
    Ok(FitResult {
        params,
        free: free.to_vec(),
        std_errors,
        predictions,
        sse,
        iterations,
        on_end,
        prior_sse,
        prior_z,
    })
}

/// One argmin Gauss–Newton fit of `free` from `start`, on the parameters clamped into their
/// intervals: the fitted values (clamped), the parameters the solver drove past an end of
/// their interval, and the iterations used.
fn gauss_newton(
    data: &Dataset,
    model: &Model<'_>,
    start: &ParameterValues,
    free: &[&'static ParamInfo],
    weights: &DVector<f64>,
) -> Result<(ParameterValues, Vec<&'static ParamInfo>, u64)> {
    let problem = Problem::new(data, model, start, free, weights);
    let u0 = problem.scaled(start);
    let solver = GaussNewton::new().with_tolerance(COST_TOLERANCE)?;
    let res = Executor::new(problem, solver)
        .configure(|s| s.param(u0).max_iters(MAX_ITERATIONS))
        .run()
        .map_err(|e| anyhow!("Gauss-Newton fit failed: {e}"))?;
    let iterations = res.state().get_iter();
    let u = res
        .state()
        .get_best_param()
        .or(res.state().get_param())
        .cloned()
        .ok_or_else(|| anyhow!("Gauss-Newton returned no parameters"))?;
    let problem = res.problem.problem.as_ref().context("problem lost")?;
    let past_end = free
        .iter()
        .enumerate()
        .filter(|(k, info)| {
            let (lo, hi) = interval(info);
            let raw = u[*k] * info.scale;
            raw < lo || raw > hi
        })
        .map(|(_, info)| *info)
        .collect();
    Ok((problem.params(&u), past_end, iterations))
}

/// Base-only fit against base + effect fit.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// Number of conditions N.
    pub n: usize,
    /// SSE at the current calibration.
    pub sse_current: f64,
    /// Base parameters refitted, effect off.
    pub without: FitResult,
    /// Base parameters and the effect fitted.
    pub with: FitResult,
    /// Likelihood-ratio statistic Δ = SSE₀ − SSE₁ and its χ²₁ p-value.
    pub lr: f64,
    /// p-value of the likelihood-ratio test.
    pub lr_p: f64,
    /// F = Δ/(SSE₁/(N − k₁)) and its F(1, N − k₁) p-value (NaN when N = k₁).
    pub f: f64,
    /// p-value of the F test.
    pub f_p: f64,
    /// Leave-one-condition-out RMS standardised prediction error, without / with the effect.
    pub loco: Option<(f64, f64)>,
}

/// Fit with and without `effect`; `loco` adds the leave-one-condition-out error.
pub fn compare_with(
    data: &Dataset,
    model: &Model<'_>,
    current: &ParameterValues,
    effect: &'static ParamInfo,
    loco: bool,
) -> Result<Comparison> {
    let n = data.obs.len();
    let pred = predict(data, model, current)?;
    let sse_current = data.standardised(&pred).iter().map(|r| r * r).sum();
    let base = determinable_base(data, model, current)?;
    let without = fit(data, model, current, &base)?;
    let mut start = without.params.clone();
    // Start the effect at one finite-difference step: at exactly 0 the forward difference is
    // the right sensitivity, but Gauss–Newton needs room to move both ways.
    set(
        effect,
        &mut start,
        value(effect, current).max(effect.fd_step),
    );
    let mut free = base.clone();
    free.push(effect);
    let with = fit(data, model, &start, &free)?;
    let lr = (without.objective() - with.objective()).max(0.0);
    let lr_p = 1.0 - ChiSquared::new(1.0)?.cdf(lr);
    let dfr = residual_count(data, &with.free) as f64 - with.k() as f64;
    let (f, f_p) = if dfr > 0.0 && with.objective() > 0.0 {
        let f = lr / (with.objective() / dfr);
        (f, 1.0 - FisherSnedecor::new(1.0, dfr)?.cdf(f))
    } else {
        (f64::NAN, f64::NAN)
    };
    let loco = if loco {
        let a = loco_rms(data, model, &without.params, &without.free)?;
        let b = loco_rms(data, model, &with.params, &with.free)?;
        Some((a, b))
    } else {
        None
    };
    Ok(Comparison {
        n,
        sse_current,
        without,
        with,
        lr,
        lr_p,
        f,
        f_p,
        loco,
    })
}

/// Leave-one-condition-out: refit without each condition (from `start`) and predict it;
/// RMS of the standardised prediction errors.
pub fn loco_rms(
    data: &Dataset,
    model: &Model<'_>,
    start: &ParameterValues,
    free: &[&'static ParamInfo],
) -> Result<f64> {
    let mut ss = 0.0;
    for i in 0..data.obs.len() {
        let d = data.without(i);
        let fitted = fit(&d, model, start, free)
            .with_context(|| format!("leave-one-out fit without condition {}", i + 1))?;
        let o = &data.obs[i];
        let y = model.simulate(o.experiment, &o.condition, &fitted.params)?;
        ss += ((o.mean - y) / o.se_mean).powi(2);
    }
    Ok((ss / data.obs.len() as f64).sqrt())
}
