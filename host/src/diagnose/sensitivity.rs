//! Model predictions and finite-difference sensitivities ∂ŷ/∂θ at every measured condition
//! (DESIGN §10 step 2). Base parameters use central differences; an effect at its off value
//! (0, the lower bound) uses a forward difference, the one-sided derivative that matters for
//! a parameter that can only grow. Simulations run in parallel (rayon); each is deterministic,
//! so the result does not depend on the thread count.

use anyhow::Result;
use nalgebra::DMatrix;
use rayon::prelude::*;

use super::model::Model;
use super::params::{set, value, ParamInfo, Role};
use super::residuals::Dataset;
use crate::calibration::ParameterValues;

/// Predictions at every condition of `data` with parameters `p`.
pub fn predict(data: &Dataset, model: &Model<'_>, p: &ParameterValues) -> Result<Vec<f64>> {
    data.obs
        .par_iter()
        .map(|o| model.simulate(o.experiment, &o.condition, p))
        .collect()
}

/// Columns ∂ŷ/∂θ (observable unit per parameter unit) for each parameter in `params`, given
/// the predictions `at` at `p`. Returns an N × len(params) matrix.
pub fn jacobian(
    data: &Dataset,
    model: &Model<'_>,
    p: &ParameterValues,
    at: &[f64],
    params: &[&ParamInfo],
) -> Result<DMatrix<f64>> {
    let n = data.obs.len();
    let jobs: Vec<(usize, usize)> = (0..params.len())
        .flat_map(|j| (0..n).map(move |i| (j, i)))
        .collect();
    let cols: Vec<f64> = jobs
        .par_iter()
        .map(|&(j, i)| -> Result<f64> {
            let info = params[j];
            let h = info.fd_step;
            let v = value(info, p);
            let o = &data.obs[i];
            let mut up = p.clone();
            set(info, &mut up, v + h);
            let y_up = model.simulate(o.experiment, &o.condition, &up)?;
            if v - h >= 0.0 || info.role == Role::Base {
                let mut dn = p.clone();
                set(info, &mut dn, v - h);
                let y_dn = model.simulate(o.experiment, &o.condition, &dn)?;
                Ok((y_up - y_dn) / (2.0 * h))
            } else {
                Ok((y_up - at[i]) / h)
            }
        })
        .collect::<Result<_>>()?;
    Ok(DMatrix::from_column_slice(n, params.len(), &cols))
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
}

impl Linearisation {
    /// Predictions and sensitivities at the calibration `p`: the base parameters `p` sets
    /// and the effects already on are calibrated, the effects off are candidates.
    pub fn new(data: &Dataset, model: &Model<'_>, p: &ParameterValues) -> Result<Self> {
        let predictions = predict(data, model, p)?;
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
        let calibrated_jacobian = jacobian(data, model, p, &predictions, &calibrated)?;
        let candidate_jacobian = jacobian(data, model, p, &predictions, &candidates)?;
        Ok(Linearisation {
            predictions,
            calibrated,
            calibrated_jacobian,
            candidates,
            candidate_jacobian,
        })
    }
}
