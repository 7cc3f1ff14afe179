//! Measurements reduced to condition means with their uncertainty, standardised residuals and
//! the lack-of-fit test per experiment (DESIGN §10 step 1).
//!
//! Pure error per experiment: s² = Σ(y − ȳ_c)² / Σ(n_c − 1), pooled over its conditions.
//! Standardised residual at condition c: r_c = (ȳ_c − ŷ_c)/(s/√n_c). If the model is right,
//! Σ r_c² / k over the k conditions of an experiment follows F(k, df_pe) (the ŷ are taken as
//! given, not fitted to these data), which is the lack-of-fit test reported; χ²_k would ignore
//! that s is estimated and claim misfit too often with few replicates.

use anyhow::{bail, Result};
use statrs::distribution::{ContinuousCDF, FisherSnedecor};

use super::params::{Catalogue, ParamInfo};
use crate::calibration::Condition;
use crate::rigs::single_sphere::PARAMETERS;
use crate::study::Study;

/// One condition of one experiment, reduced.
#[derive(Clone, Debug)]
pub struct Obs {
    /// Experiment index in the study.
    pub experiment: usize,
    /// The condition.
    pub condition: Condition,
    /// The condition's value on the experiment's axis (its first key).
    pub x: f64,
    /// Replicates (empty for a printed summary).
    pub values: Vec<f64>,
    /// Number of replicates.
    pub n: usize,
    /// Σ (v − mean)² over the replicates, from a printed SD as (n − 1)·SD².
    pub ss_within: f64,
    /// Mean of the replicates.
    pub mean: f64,
    /// Standard error of the mean, s/√n, with s the experiment's pure-error SD.
    pub se_mean: f64,
}

/// One experiment: a rig's quantity measured at several conditions.
#[derive(Clone, Debug, PartialEq)]
pub struct Experiment {
    /// The rig.
    pub rig: String,
    /// The quantity.
    pub quantity: String,
    /// The quantity, with its unit, for tables and plots.
    pub observable_label: String,
    /// The condition axis: its key and its label with the unit.
    pub condition: (String, String),
    /// The study's noise SD for synthesising it, if any.
    pub noise_sd: Option<f64>,
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
    /// The experiments.
    pub experiments: Vec<Experiment>,
    /// The conditions.
    pub obs: Vec<Obs>,
    /// Pure error per experiment.
    pub pure_error: Vec<PureError>,
    /// Bench measurements of base parameters (`[diagnosis.prior]`).
    pub priors: Vec<BenchPrior>,
}

/// A base parameter measured on the bench: a fit adds ((θ − mean)/sd)² to its objective.
#[derive(Clone, Copy, Debug)]
pub struct BenchPrior {
    /// The parameter.
    pub param: &'static ParamInfo,
    /// Bench mean and SD, in the parameter's unit.
    pub mean: f64,
    /// Bench SD.
    pub sd: f64,
}

impl BenchPrior {
    /// How far `value` lies from the bench mean, in bench SDs.
    pub fn z(&self, value: f64) -> f64 {
        (value - self.mean) / self.sd
    }
}

/// Smallest pure-error SD accepted, relative to the mean magnitude: replicates that agree to
/// every digit would make the standardised residuals infinite.
const MIN_RELATIVE_SD: f64 = 1e-12;

/// The experiments of `study`: its series, with their rigs' labels.
pub fn experiments(study: &Study) -> Vec<Experiment> {
    study
        .series()
        .into_iter()
        .map(|s| {
            let kind = crate::rigs::catalogue::find(&s.experiment);
            let label = kind
                .and_then(|k| k.quantity(&s.quantity))
                .map_or(format!("{}, {}", s.quantity, s.unit), |q| {
                    q.label.to_owned()
                });
            let key = s
                .points
                .first()
                .and_then(|p| p.condition.keys().next().cloned())
                .unwrap_or_default();
            let axis = kind
                .and_then(|k| k.condition(&key))
                .map_or(key.clone(), |c| c.label.to_owned());
            Experiment {
                rig: s.experiment,
                quantity: s.quantity,
                observable_label: label,
                condition: (key, axis),
                noise_sd: s.noise_sd,
            }
        })
        .collect()
}

impl Dataset {
    /// Reduces the measurements of `study`. Every point needs replicate values or a printed
    /// mean ± SD over n, and each experiment ≥ 1 degree of freedom of pure error (some point
    /// with ≥ 2 replicates).
    pub fn new(study: &Study) -> Result<Self> {
        let experiments = experiments(study);
        let mut obs = Vec::new();
        let mut pure_error = Vec::new();
        for (ei, (e, s)) in experiments.iter().zip(study.series()).enumerate() {
            let what = format!("experiment {} ({})", ei + 1, e.rig);
            let mut ss = 0.0;
            let mut df = 0usize;
            let mut scale = 0.0f64;
            let mut reduced = Vec::new();
            for (pi, p) in s.points.iter().enumerate() {
                let (n, m, within) = match (&p.summary, p.values.is_empty()) {
                    (_, false) => {
                        let n = p.values.len();
                        let m = p.values.iter().sum::<f64>() / n as f64;
                        (n, m, p.values.iter().map(|v| (v - m).powi(2)).sum::<f64>())
                    }
                    (Some(sum), true) => {
                        let n = sum.n as usize;
                        (n, sum.mean, sum.sd * sum.sd * n.saturating_sub(1) as f64)
                    }
                    (None, true) => bail!(
                        "in {}: {what} point {}: no values (the diagnosis needs the replicates \
                         as measured, or their mean, sd and n)",
                        study.path().display(),
                        pi + 1
                    ),
                };
                if n == 0 {
                    bail!(
                        "in {}: {what} point {}: n = 0 replicates",
                        study.path().display(),
                        pi + 1
                    );
                }
                reduced.push((n, m, within));
                ss += within;
                df += n - 1;
                scale = scale.max(m.abs());
            }
            if df == 0 {
                bail!(
                    "in {}: {what}: no replicates, so the measurement uncertainty (pure error) \
                     is unknown; measure some condition at least twice",
                    study.path().display()
                );
            }
            let sd = (ss / df as f64)
                .sqrt()
                .max(MIN_RELATIVE_SD * scale.max(1.0));
            pure_error.push(PureError { sd, df });
            for (p, &(n, mean, ss_within)) in s.points.iter().zip(&reduced) {
                obs.push(Obs {
                    experiment: ei,
                    x: p.condition.get(&e.condition.0).copied().unwrap_or(f64::NAN),
                    condition: p.condition.clone(),
                    values: p.values.clone(),
                    n,
                    ss_within,
                    mean,
                    se_mean: sd / (n as f64).sqrt(),
                });
            }
        }
        // `[diagnosis.prior]` names single-sphere parameters; a calibration study's `[priors]`
        // those of its measured rigs (both checked when the study was loaded).
        let catalogue = Catalogue::of_rigs(experiments.iter().map(|e| e.rig.as_str()));
        let single_sphere = study
            .file()
            .diagnosis
            .iter()
            .flat_map(|d| &d.prior)
            .map(|(name, p)| (PARAMETERS.iter().find(|i| i.name == name), p));
        let of_rigs = study
            .file()
            .priors
            .iter()
            .map(|(name, p)| (catalogue.0.iter().copied().find(|i| i.name == name), p));
        let priors = single_sphere
            .chain(of_rigs)
            .filter_map(|(param, p)| {
                Some(BenchPrior {
                    param: param?,
                    mean: p.mean,
                    sd: p.sd,
                })
            })
            .collect();
        Ok(Dataset {
            experiments,
            obs,
            pure_error,
            priors,
        })
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
            let o = &data.obs[i];
            if o.values.is_empty() {
                // A printed summary: Σ(v − ŷ)² = Σ(v − ȳ)² + n(ȳ − ŷ)².
                ss += o.ss_within + o.n as f64 * (o.mean - pred[i]).powi(2);
            } else {
                for v in &o.values {
                    ss += (v - pred[i]).powi(2);
                }
            }
            n += o.n;
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

    #[test]
    fn pure_error_is_pooled_and_residuals_standardised() {
        // Points (1, 3) and (2, 4, 6): SS = 2 + 8 = 10 on 1 + 2 df, s = √(10/3).
        let text = "[diagnosis]\n[diagnosis.calibration]\nrestitution = 0.5\n\
                    youngs_modulus_pa = 8.43e6\n[[diagnosis.experiment]]\nkind = \"fall\"\n\
                    [[diagnosis.experiment.point]]\ncondition = 0.5\nvalues = [1.0, 3.0]\n\
                    [[diagnosis.experiment.point]]\ncondition = 1.0\nvalues = [2.0, 4.0, 6.0]\n";
        let study = Study::from_toml(text, std::path::Path::new("t.toml")).unwrap();
        let data = Dataset::new(&study).unwrap();
        let s = (10.0f64 / 3.0).sqrt();
        assert!((data.pure_error[0].sd - s).abs() < 1e-12);
        assert_eq!(data.pure_error[0].df, 3);
        assert_eq!(data.experiments[0].condition.1, "fall height, m");
        let r = data.standardised(&[0.0, 4.0]);
        assert!((r[0] - 2.0 / (s / 2f64.sqrt())).abs() < 1e-12);
        assert_eq!(r[1], 0.0);
        // F = (r₀² + 0)/2 on (2, 3) df.
        let lof = lack_of_fit(&data, &[0.0, 4.0]).unwrap();
        assert!((lof[0].chi2 - r[0] * r[0]).abs() < 1e-12);
        let f = FisherSnedecor::new(2.0, 3.0).unwrap();
        assert!((lof[0].p_value - (1.0 - f.cdf(r[0] * r[0] / 2.0))).abs() < 1e-12);
    }

    /// The replicates of the test above, as measured and as a paper prints them (mean ± SD
    /// over n): the same pure error, residuals and lack of fit.
    #[test]
    fn printed_summaries_reduce_like_their_replicates() {
        let study = |a: &str, b: &str| {
            let text = format!(
                "[study]\nname = \"t\"\ndescription = \"t\"\ncitation = \"t\"\n\
                 [[measurements]]\nexperiment = \"fall\"\nquantity = \"fall_time\"\n\
                 unit = \"ms\"\ncondition = {{ fall_height_m = 0.5 }}\n{a}\n\
                 [[measurements]]\nexperiment = \"fall\"\nquantity = \"fall_time\"\n\
                 unit = \"ms\"\ncondition = {{ fall_height_m = 1.0 }}\n{b}\n"
            );
            Study::from_toml(&text, std::path::Path::new("t.toml")).unwrap()
        };
        let values =
            Dataset::new(&study("values = [1.0, 3.0]", "values = [2.0, 4.0, 6.0]")).unwrap();
        let printed = Dataset::new(&study(
            "mean = 2.0\nsd = 1.4142135623730951\nn = 2",
            "mean = 4.0\nsd = 2.0\nn = 3",
        ))
        .unwrap();
        assert!((printed.pure_error[0].sd - values.pure_error[0].sd).abs() < 1e-12);
        assert_eq!(printed.pure_error[0].df, values.pure_error[0].df);
        let pred = [0.5, 4.5];
        let (a, b) = (values.standardised(&pred), printed.standardised(&pred));
        assert!(a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-12));
        let (a, b) = (
            lack_of_fit(&values, &pred).unwrap(),
            lack_of_fit(&printed, &pred).unwrap(),
        );
        assert!(
            (a[0].rms - b[0].rms).abs() < 1e-12,
            "{} vs {}",
            a[0].rms,
            b[0].rms
        );
        // A mean without its SD cannot say how much replicates scatter.
        let err = Dataset::new(&study("mean = 2.0\nn = 2", "values = [2.0, 4.0, 6.0]"))
            .unwrap_err()
            .to_string();
        assert!(err.contains("no values"), "{err}");
    }

    /// A calibration study's `[priors]` name base parameters of the rigs it measures.
    #[test]
    fn a_calibration_study_states_bench_priors_of_its_rigs() {
        let study = |priors: &str| {
            let text = format!(
                "[study]\nname = \"t\"\ndescription = \"t\"\ncitation = \"t\"\n\
                 [[measurements]]\nexperiment = \"fall\"\nquantity = \"fall_time\"\n\
                 unit = \"ms\"\ncondition = {{ fall_height_m = 0.5 }}\nvalues = [1.0, 3.0]\n\
                 [priors]\n{priors}\n"
            );
            Study::from_toml(&text, std::path::Path::new("t.toml"))
        };
        let data =
            Dataset::new(&study("restitution = { mean = 0.5, sd = 0.02 }").unwrap()).unwrap();
        assert_eq!(data.priors.len(), 1);
        assert_eq!(data.priors[0].param.name, "restitution");
        assert_eq!((data.priors[0].mean, data.priors[0].sd), (0.5, 0.02));
        for (bad, says) in [
            ("restitution = { mean = 0.5, sd = 0.0 }", "sd = 0 must be"),
            (
                "cohesion = { mean = 1.0, sd = 0.1 }",
                "unknown base parameter 'cohesion'",
            ),
            (
                "\"pod-pod.rolling_friction\" = { mean = 0.3, sd = 0.01 }",
                "unknown base parameter",
            ),
        ] {
            let err = study(bad).unwrap_err().to_string();
            assert!(err.contains("priors") && err.contains(says), "{bad}: {err}");
        }
    }
}
