//! Model predictions and finite-difference sensitivities ∂ŷ/∂θ at every measured condition
//! (DESIGN §10 step 2). Central differences where both steps stay inside the parameter's
//! interval ([`super::params::interval`]); within a step of an end, the one-sided difference
//! away from it: forward for an effect at its off value 0 (the derivative that matters for a
//! parameter that can only grow), backward for a restitution of 1. No simulation is asked
//! for at an inadmissible value. Simulations run in parallel or through the model's
//! executor ([`Model::simulate_all`]); each is deterministic, so the result does not depend
//! on the thread count or on where it ran.

use anyhow::{bail, Result};
use nalgebra::{DMatrix, DVector};

use super::model::{replicate_mean, Model};
use super::params::{interval, set, value, ParamInfo, Role};
use super::residuals::Dataset;
use crate::calibration::ParameterValues;

/// Predictions at every condition of `data` with parameters `p`.
pub fn predict(data: &Dataset, model: &Model<'_>, p: &ParameterValues) -> Result<Vec<f64>> {
    Ok(predict_replicates(data, model, p)?
        .iter()
        .map(|v| replicate_mean(v))
        .collect())
}

/// Every replicate of the prediction at every condition of `data` with parameters `p`
/// ([`Model::simulate_replicates`]); [`predict`] is their means.
pub fn predict_replicates(
    data: &Dataset,
    model: &Model<'_>,
    p: &ParameterValues,
) -> Result<Vec<Vec<f64>>> {
    let runs: Vec<_> = data
        .obs
        .iter()
        .map(|o| (o.experiment, &o.condition, p.clone()))
        .collect();
    model.simulate_replicates(&runs)
}

/// Columns ∂ŷ/∂θ (observable unit per parameter unit) for each parameter in `params`, given
/// the predictions `at` at `p`. Returns an N × len(params) matrix. Every simulation of the
/// matrix is asked for in one batch.
pub fn jacobian(
    data: &Dataset,
    model: &Model<'_>,
    p: &ParameterValues,
    at: &[f64],
    params: &[&ParamInfo],
) -> Result<DMatrix<f64>> {
    let steps = Steps::simulate(data, model, p, params)?;
    let means: Vec<f64> = steps.y.iter().map(|v| replicate_mean(v)).collect();
    Ok(DMatrix::from_fn(data.obs.len(), params.len(), |i, j| {
        steps.derivative(j, i, |k| means[k], at[i])
    }))
}

/// [`jacobian`] at the predictions' replicates `at` (each condition's placements, as
/// [`Model::simulate_replicates`] gives them), with the columns' standard errors from the
/// placements' scatter: each placement's own finite difference (paired: the same placement
/// at every parameter set), their SD over √(placements); 0 for a condition simulated once.
/// The derivatives are those [`jacobian`] gives at the replicates' means, bit for bit.
pub fn jacobian_and_scatter(
    data: &Dataset,
    model: &Model<'_>,
    p: &ParameterValues,
    at: &[Vec<f64>],
    params: &[&ParamInfo],
) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let steps = Steps::simulate(data, model, p, params)?;
    let means: Vec<f64> = steps.y.iter().map(|v| replicate_mean(v)).collect();
    let (n, cols) = (data.obs.len(), params.len());
    let value = DMatrix::from_fn(n, cols, |i, j| {
        steps.derivative(j, i, |k| means[k], replicate_mean(&at[i]))
    });
    let scatter = DMatrix::from_fn(n, cols, |i, j| {
        let paired: Vec<f64> = (0..at[i].len())
            .map(|r| steps.derivative(j, i, |k| steps.y[k][r], at[i][r]))
            .collect();
        standard_error(&paired)
    });
    Ok((value, scatter))
}

/// The stepped runs of a Jacobian: each parameter's step and difference, and every replicate
/// of every run, parameter j's shift s at condition i at index `offsets[j] + s·N + i`.
struct Steps {
    columns: Vec<(f64, Difference)>,
    offsets: Vec<usize>,
    n: usize,
    y: Vec<Vec<f64>>,
}

impl Steps {
    /// Every stepped run of `params` at `p`, simulated in one batch.
    fn simulate(
        data: &Dataset,
        model: &Model<'_>,
        p: &ParameterValues,
        params: &[&ParamInfo],
    ) -> Result<Self> {
        let columns: Vec<(f64, Difference)> = params
            .iter()
            .map(|info| Ok((info.fd_step, Difference::at(info, value(info, p))?)))
            .collect::<Result<_>>()?;
        let mut runs = Vec::new();
        let mut offsets = Vec::with_capacity(params.len());
        for (info, &(_, difference)) in params.iter().zip(&columns) {
            offsets.push(runs.len());
            for shifted in difference.stepped(info, p) {
                runs.extend(
                    data.obs
                        .iter()
                        .map(|o| (o.experiment, &o.condition, shifted.clone())),
                );
            }
        }
        Ok(Steps {
            columns,
            offsets,
            n: data.obs.len(),
            y: model.simulate_replicates(&runs)?,
        })
    }

    /// ∂ŷ/∂θ of column `j` at condition `i`, from each stepped run's value `y(k)` and the
    /// unstepped prediction `at`.
    fn derivative(&self, j: usize, i: usize, y: impl Fn(usize) -> f64, at: f64) -> f64 {
        let (h, difference) = self.columns[j];
        let m = difference.shifts().len();
        let k = self.offsets[j] + i;
        let ys = [y(k), y(k + (m - 1) * self.n)];
        difference.derivative(h, &ys[..m], at)
    }
}

/// Standard error of the mean of `x`: SD/√n, 0 for fewer than two values.
pub(super) fn standard_error(x: &[f64]) -> f64 {
    if x.len() < 2 {
        return 0.0;
    }
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (var / n).sqrt()
}

/// Which finite difference a sensitivity takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Difference {
    /// (ŷ(θ + h) − ŷ(θ − h))/2h.
    Central,
    /// (ŷ(θ + h) − ŷ(θ))/h.
    Forward,
    /// (ŷ(θ) − ŷ(θ − h))/h.
    Backward,
}

impl Difference {
    /// The difference for `info` at value `v`: central when θ ± h both lie in its interval,
    /// else the one-sided difference that stays inside. An error when neither step does (an
    /// interval narrower than the step), naming the parameter.
    pub fn at(info: &ParamInfo, v: f64) -> Result<Self> {
        let (lo, hi) = interval(info);
        let h = info.fd_step;
        let (up, down) = (v + h <= hi, v - h >= lo);
        Ok(match (up, down) {
            (true, true) => Self::Central,
            (true, false) => Self::Forward,
            (false, true) => Self::Backward,
            (false, false) => bail!(
                "{} = {v} {}: a finite-difference step of {h} leaves its interval [{lo}, {hi}] \
                 on both sides",
                info.name,
                info.unit
            ),
        })
    }

    /// The steps it simulates, θ + sign·h for each sign (θ itself is the prediction).
    pub fn shifts(self) -> &'static [f64] {
        match self {
            Self::Central => &[1.0, -1.0],
            Self::Forward => &[1.0],
            Self::Backward => &[-1.0],
        }
    }

    /// `p` with `info` moved by each step of [`Difference::shifts`], in that order.
    pub fn stepped(self, info: &ParamInfo, p: &ParameterValues) -> Vec<ParameterValues> {
        let v = value(info, p);
        self.shifts()
            .iter()
            .map(|sign| {
                let mut q = p.clone();
                set(info, &mut q, v + sign * info.fd_step);
                q
            })
            .collect()
    }

    /// ∂ŷ/∂θ from the predictions at the steps (`ys`, in [`Difference::shifts`] order) and
    /// at θ (`at`), for step `h`.
    pub fn derivative(self, h: f64, ys: &[f64], at: f64) -> f64 {
        match self {
            Self::Central => (ys[0] - ys[1]) / (2.0 * h),
            Self::Forward => (ys[0] - at) / h,
            Self::Backward => (at - ys[0]) / h,
        }
    }
}

/// Everything the score test needs, computed once per study and calibration.
#[derive(Clone, Debug)]
pub struct Linearisation {
    /// Predictions at the current calibration.
    pub predictions: Vec<f64>,
    /// Calibrated parameters (base parameters and effects already on).
    pub calibrated: Vec<&'static ParamInfo>,
    /// ∂ŷ/∂θ of the calibrated parameters, N × p.
    pub calibrated_jacobian: DMatrix<f64>,
    /// Candidate effects (those off in the calibration).
    pub candidates: Vec<&'static ParamInfo>,
    /// ∂ŷ/∂θ of the candidates at their off value, N × m.
    pub candidate_jacobian: DMatrix<f64>,
    /// The bench priors on calibrated parameters, as extra rows of the score test.
    pub prior_rows: Vec<PriorRow>,
    /// Standard errors of [`Linearisation::calibrated_jacobian`] from the placements'
    /// scatter ([`jacobian_and_scatter`]); zeros where a condition was simulated once.
    pub calibrated_scatter: DMatrix<f64>,
    /// Standard errors of [`Linearisation::candidate_jacobian`], likewise.
    pub candidate_scatter: DMatrix<f64>,
}

/// A bench prior as one more standardised observation of a calibrated parameter: residual
/// (mean − θ)/sd, sensitivity 1/sd in the parameter's column, 0 for every effect.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PriorRow {
    /// The parameter's column in [`Linearisation::calibrated`].
    pub column: usize,
    /// 1/sd, per parameter unit.
    pub inverse_sd: f64,
    /// (mean − θ)/sd at the calibration.
    pub residual: f64,
}

impl Linearisation {
    /// J̃: the calibrated parameters' sensitivities with each condition's row scaled by its
    /// weight `w`, then a row per bench prior (1/sd in its parameter's column).
    pub fn weighted_calibrated(&self, w: &[f64]) -> DMatrix<f64> {
        let n = w.len();
        let mut jt = DMatrix::from_fn(n, self.calibrated.len(), |i, j| {
            self.calibrated_jacobian[(i, j)] * w[i]
        })
        .resize_vertically(n + self.prior_rows.len(), 0.0);
        for (i, p) in self.prior_rows.iter().enumerate() {
            jt[(n + i, p.column)] = p.inverse_sd;
        }
        jt
    }

    /// s̃: candidate `k`'s sensitivity with each condition scaled by its weight `w`, and 0 in
    /// the rows of the bench priors (an effect does not move a bench value).
    pub fn weighted_candidate(&self, k: usize, w: &[f64]) -> DVector<f64> {
        let n = w.len();
        DVector::from_fn(n + self.prior_rows.len(), |i, _| {
            if i < n {
                self.candidate_jacobian[(i, k)] * w[i]
            } else {
                0.0
            }
        })
    }

    /// Predictions and sensitivities at the calibration `p`: the base parameters `p` sets
    /// and the effects already on are calibrated, the effects off are candidates.
    pub fn new(data: &Dataset, model: &Model<'_>, p: &ParameterValues) -> Result<Self> {
        let at = predict_replicates(data, model, p)?;
        let predictions: Vec<f64> = at.iter().map(|v| replicate_mean(v)).collect();
        let calibrated: Vec<&'static ParamInfo> = model
            .catalogue
            .0
            .iter()
            .copied()
            .filter(|i| match i.role {
                Role::Base => p.contains_key(i.key),
                Role::Effect => value(i, p) > 0.0,
            })
            .collect();
        let candidates: Vec<&'static ParamInfo> = model
            .catalogue
            .effects()
            .filter(|i| value(i, p) == 0.0)
            .collect();
        let (calibrated_jacobian, calibrated_scatter) =
            jacobian_and_scatter(data, model, p, &at, &calibrated)?;
        let (candidate_jacobian, candidate_scatter) =
            jacobian_and_scatter(data, model, p, &at, &candidates)?;
        let prior_rows = data
            .priors
            .iter()
            .filter_map(|prior| {
                let column = calibrated.iter().position(|c| c.key == prior.param.key)?;
                Some(PriorRow {
                    column,
                    inverse_sd: 1.0 / prior.sd,
                    residual: -prior.z(value(prior.param, p)),
                })
            })
            .collect();
        Ok(Linearisation {
            predictions,
            calibrated,
            calibrated_jacobian,
            candidates,
            candidate_jacobian,
            prior_rows,
            calibrated_scatter,
            candidate_scatter,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rigs::single_sphere::PARAMETERS;

    fn param(name: &str) -> &'static ParamInfo {
        PARAMETERS.iter().find(|p| p.name == name).unwrap()
    }

    #[test]
    fn the_difference_stays_inside_the_interval() {
        let e = param("restitution");
        assert_eq!(Difference::at(e, 0.5).unwrap(), Difference::Central);
        // e = 1 is admissible, 1 + h is not; e near its open lower end 0 steps upwards.
        assert_eq!(Difference::at(e, 1.0).unwrap(), Difference::Backward);
        assert_eq!(Difference::at(e, 0.015).unwrap(), Difference::Forward);
        let cohesion = param("cohesion");
        assert_eq!(Difference::at(cohesion, 0.0).unwrap(), Difference::Forward);
        assert_eq!(Difference::at(cohesion, 1e4).unwrap(), Difference::Central);
        // A plastic fraction in [0, 1] with a step wider than the interval has no difference.
        let mut wide = *param("hysteretic");
        wide.fd_step = 2.0;
        let err = Difference::at(&wide, 0.5).unwrap_err().to_string();
        assert!(
            err.contains("hysteretic") && err.contains("both sides"),
            "{err}"
        );
    }

    #[test]
    fn each_difference_is_exact_on_a_line() {
        let (h, slope, at) = (0.01, 3.0, 2.0);
        let y = |s: f64| at + slope * s * h;
        for d in [
            Difference::Central,
            Difference::Forward,
            Difference::Backward,
        ] {
            let ys: Vec<f64> = d.shifts().iter().map(|&s| y(s)).collect();
            assert!((d.derivative(h, &ys, at) - slope).abs() < 1e-9, "{d:?}");
        }
    }
}
