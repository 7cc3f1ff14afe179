//! Measurements reduced to condition means with their uncertainty, standardised residuals and
//! the lack-of-fit test per experiment (DESIGN §10 step 1).
//!
//! Pure error per experiment: s² = Σ(y − ȳ_c)² / Σ(n_c − 1), pooled over its conditions.
//! Standardised residual at condition c: r_c = (ȳ_c − ŷ_c)/(s/√n_c). If the model is right,
//! Σ r_c² / k over the k conditions of an experiment follows F(k, df_pe) (the ŷ are taken as
//! given, not fitted to these data), which is the lack-of-fit test reported; χ²_k would ignore
//! that s is estimated and claim misfit too often with few replicates.

use anyhow::Result;
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

use super::experiment::ExperimentKind;
use super::study::Diagnosis;

/// One condition of one experiment, reduced.
#[derive(Clone, Debug)]
pub struct Obs {
    /// Experiment index in the study.
    pub experiment: usize,
    /// Experiment kind.
    pub kind: ExperimentKind,
    /// Condition.
    pub condition: f64,
    /// Replicates.
    pub values: Vec<f64>,
    /// Mean of the replicates.
    pub mean: f64,
    /// Standard error of the mean, s/√n, with s the experiment's pure-error SD.
    pub se_mean: f64,
}

/// Pure error of one experiment.
#[derive(Clone, Copy, Debug)]
pub struct PureError {
    /// Pooled replicate SD, observable unit.
    pub sd: f64,
    /// Degrees of freedom Σ(n_c − 1).
    pub df: usize,
}

/// The reduced data set, conditions of all experiments stacked in study order.
#[derive(Clone, Debug)]
pub struct Dataset {
    /// The conditions.
    pub obs: Vec<Obs>,
    /// Pure error per experiment.
    pub pure_error: Vec<PureError>,
}

/// Smallest pure-error SD accepted, relative to the mean magnitude: replicates that agree to
/// every digit would make the standardised residuals infinite.
const MIN_RELATIVE_SD: f64 = 1e-12;

impl Dataset {
    /// Reduce a checked study with measurements.
    pub fn new(d: &Diagnosis) -> Result<Self> {
        let mut obs = Vec::new();
        let mut pure_error = Vec::new();
        for (ei, e) in d.experiment.iter().enumerate() {
            let mut ss = 0.0;
            let mut df = 0usize;
            let mut scale = 0.0f64;
            for p in &e.point {
                let n = p.values.len() as f64;
                let m = p.values.iter().sum::<f64>() / n;
                ss += p.values.iter().map(|v| (v - m).powi(2)).sum::<f64>();
                df += p.values.len() - 1;
                scale = scale.max(m.abs());
            }
            let sd = (ss / df as f64)
                .sqrt()
                .max(MIN_RELATIVE_SD * scale.max(1.0));
            pure_error.push(PureError { sd, df });
            for p in &e.point {
                let n = p.values.len() as f64;
                obs.push(Obs {
                    experiment: ei,
                    kind: e.kind,
                    condition: p.condition,
                    values: p.values.clone(),
                    mean: p.values.iter().sum::<f64>() / n,
                    se_mean: sd / n.sqrt(),
                });
            }
        }
        Ok(Dataset { obs, pure_error })
    }

    /// Standardised residuals (ȳ − ŷ)/(s/√n) for predictions `pred` (one per condition).
    pub fn standardised(&self, pred: &[f64]) -> Vec<f64> {
        self.obs
            .iter()
            .zip(pred)
            .map(|(o, p)| (o.mean - p) / o.se_mean)
            .collect()
    }

    /// A copy without condition `skip` (for leave-one-condition-out); the pure error stays
    /// that of the full data.
    pub fn without(&self, skip: usize) -> Dataset {
        let mut d = self.clone();
        d.obs.remove(skip);
        d
    }

    /// Number of experiments.
    pub fn experiments(&self) -> usize {
        self.pure_error.len()
    }
}

/// Lack of fit of one experiment.
#[derive(Clone, Debug)]
pub struct LackOfFit {
    /// Experiment index.
    pub experiment: usize,
    /// Σ r² over its conditions.
    pub chi2: f64,
    /// Number of conditions k.
    pub conditions: usize,
    /// Pure-error degrees of freedom.
    pub df_pe: usize,
    /// p-value of F = (Σ r²/k) ~ F(k, df_pe).
    pub p_value: f64,
    /// Replicate-level RMS of y − ŷ, observable unit.
    pub rms: f64,
    /// Pure-error SD, observable unit.
    pub sd: f64,
}

/// Lack-of-fit test per experiment for predictions `pred`.
pub fn lack_of_fit(data: &Dataset, pred: &[f64]) -> Result<Vec<LackOfFit>> {
    let r = data.standardised(pred);
    let mut out = Vec::new();
    for (ei, pe) in data.pure_error.iter().enumerate() {
        let idx: Vec<usize> = (0..data.obs.len())
            .filter(|&i| data.obs[i].experiment == ei)
            .collect();
        let k = idx.len();
        let chi2: f64 = idx.iter().map(|&i| r[i] * r[i]).sum();
        let (mut ss, mut n) = (0.0, 0usize);
        for &i in &idx {
            for v in &data.obs[i].values {
                ss += (v - pred[i]).powi(2);
                n += 1;
            }
        }
        let p_value = if k == 0 {
            1.0
        } else {
            let f = FisherSnedecor::new(k as f64, pe.df as f64)?;
            1.0 - f.cdf(chi2 / k as f64)
        };
        out.push(LackOfFit {
            experiment: ei,
            chi2,
            conditions: k,
            df_pe: pe.df,
            p_value,
            rms: (ss / n.max(1) as f64).sqrt(),
            sd: pe.sd,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::params::ModelParams;
    use crate::diagnose::study::{Experiment, Point};

    #[test]
    fn pure_error_is_pooled_and_residuals_standardised() {
        // Points (1, 3) and (2, 4, 6): SS = 2 + 8 = 10 on 1 + 2 df, s = √(10/3).
        let d = Diagnosis {
            name: String::new(),
            calibration: ModelParams {
                restitution: 0.5,
                youngs_modulus_pa: 8.43e6,
                viscoelastic_time_s: 0.0,
                cohesion_j_m3: 0.0,
                drag_coefficient: 0.0,
                plastic_fraction: 0.0,
            },
            experiment: vec![Experiment {
                kind: ExperimentKind::Fall,
                noise_sd: None,
                point: vec![
                    Point {
                        condition: 0.5,
                        values: vec![1.0, 3.0],
                        replicates: None,
                    },
                    Point {
                        condition: 1.0,
                        values: vec![2.0, 4.0, 6.0],
                        replicates: None,
                    },
                ],
            }],
        };
        let data = Dataset::new(&d).unwrap();
        let s = (10.0f64 / 3.0).sqrt();
        assert!((data.pure_error[0].sd - s).abs() < 1e-12);
        assert_eq!(data.pure_error[0].df, 3);
        let r = data.standardised(&[0.0, 4.0]);
        assert!((r[0] - 2.0 / (s / 2f64.sqrt())).abs() < 1e-12);
        assert_eq!(r[1], 0.0);
        // F = (r₀² + 0)/2 on (2, 3) df.
        let lof = lack_of_fit(&data, &[0.0, 4.0]).unwrap();
        assert!((lof[0].chi2 - r[0] * r[0]).abs() < 1e-12);
        let f = FisherSnedecor::new(2.0, 3.0).unwrap();
        assert!((lof[0].p_value - (1.0 - f.cdf(r[0] * r[0] / 2.0))).abs() < 1e-12);
    }
}
