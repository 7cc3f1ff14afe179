//! Model predictions and finite-difference sensitivities ∂ŷ/∂θ at every measured condition
//! (DESIGN §10 step 2). Base parameters use central differences; an effect at its off value
//! (0, the lower bound) uses a forward difference, the one-sided derivative that matters for
//! a parameter that can only grow. Simulations run in parallel or through the model's
//! executor ([`Model::simulate_all`]); each is deterministic, so the result does not depend
//! on the thread count or on where it ran.

use anyhow::Result;
use nalgebra::DMatrix;

use super::model::Model;
use super::params::{set, value, ParamInfo, Role};
use super::residuals::Dataset;
use crate::calibration::ParameterValues;

/// Predictions at every condition of `data` with parameters `p`.
pub fn predict(data: &Dataset, model: &Model<'_>, p: &ParameterValues) -> Result<Vec<f64>> {
    let runs: Vec<_> = data
        .obs
        .iter()
        .map(|o| (o.experiment, &o.condition, p.clone()))
        .collect();
    model.simulate_all(&runs)
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
    let n = data.obs.len();
    // Per column: the step, and whether the difference is central (else forward from `at`).
    let columns: Vec<(f64, bool)> = params
        .iter()
        .map(|info| {
            let (h, v) = (info.fd_step, value(info, p));
            (h, v - h >= 0.0 || info.role == Role::Base)
        })
        .collect();
    let mut runs = Vec::new();
    for (info, &(h, central)) in params.iter().zip(&columns) {
        let v = value(info, p);
        let shifts: &[f64] = if central { &[1.0, -1.0] } else { &[1.0] };
        for &sign in shifts {
            let mut shifted = p.clone();
            set(info, &mut shifted, v + sign * h);
            runs.extend(
                data.obs
                    .iter()
                    .map(|o| (o.experiment, &o.condition, shifted.clone())),
            );
        }
    }
    let y = model.simulate_all(&runs)?;
    let mut cols = Vec::with_capacity(n * params.len());
    let mut k = 0;
    for &(h, central) in &columns {
        let up = &y[k..k + n];
        k += n;
        if central {
            let dn = &y[k..k + n];
            k += n;
            cols.extend(up.iter().zip(dn).map(|(u, d)| (u - d) / (2.0 * h)));
        } else {
            cols.extend(up.iter().zip(at).map(|(u, a)| (u - a) / h));
        }
    }
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
