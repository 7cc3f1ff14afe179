//! Synthetic measurements with a hidden effect, for testing the loop and for teaching:
//! the true observable at each condition is simulated with the study's calibration plus the
//! hidden effect, and each replicate adds independent N(0, σ²) noise from a ChaCha8 stream
//! seeded with `seed` (rand_chacha + rand_distr), so the output is a deterministic function of
//! (study, hidden effect, noise, seed).

use anyhow::{bail, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::experiment::ExperimentKind;
use super::params::{ModelParams, ParamInfo};
use super::study::Diagnosis;

/// Noise SD per experiment kind (observable units).
#[derive(Clone, Debug, Default)]
pub struct NoiseSpec {
    /// SD for every kind without its own entry.
    pub all: Option<f64>,
    /// Per-kind SDs.
    pub per_kind: Vec<(ExperimentKind, f64)>,
}

impl NoiseSpec {
    /// SD for `kind`, falling back to the experiment's `noise_sd`.
    pub fn sd(&self, kind: ExperimentKind, study_sd: Option<f64>) -> Result<f64> {
        let sd = self
            .per_kind
            .iter()
            .find(|(k, _)| *k == kind)
            .map(|(_, s)| *s)
            .or(self.all)
            .or(study_sd);
        match sd {
            Some(s) if s.is_finite() && s > 0.0 => Ok(s),
            Some(s) => bail!("noise SD for {} must be > 0, got {s}", kind.name()),
            None => bail!(
                "no noise SD for {}: give --noise {}=SIGMA or noise_sd in the study",
                kind.name(),
                kind.name()
            ),
        }
    }
}

/// True observables (no noise) at every point of every experiment, with `hidden` effects.
pub fn truths(d: &Diagnosis, hidden: &[(&ParamInfo, f64)]) -> Result<(ModelParams, Vec<Vec<f64>>)> {
    let mut p = d.calibration;
    for (info, v) in hidden {
        info.set(&mut p, *v);
    }
    p.validate()?;
    let mut out = Vec::new();
    for e in &d.experiment {
        let ys: Result<Vec<f64>> = e
            .point
            .iter()
            .map(|pt| e.kind.simulate(pt.condition, &p))
            .collect();
        out.push(ys?);
    }
    Ok((p, out))
}

/// The study with noisy replicates around `truth` (replicate count: the point's
/// `replicates`, else its number of values, else `default_replicates`).
pub fn add_noise(
    d: &Diagnosis,
    truth: &[Vec<f64>],
    noise: &NoiseSpec,
    seed: u64,
    default_replicates: usize,
) -> Result<Diagnosis> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = d.clone();
    for (ei, e) in out.experiment.iter_mut().enumerate() {
        let sd = noise.sd(e.kind, e.noise_sd)?;
        let normal = Normal::new(0.0, sd)?;
        for (pi, pt) in e.point.iter_mut().enumerate() {
            let n = pt.replicates.unwrap_or(if pt.values.is_empty() {
                default_replicates
            } else {
                pt.values.len()
            });
            pt.values = (0..n)
                .map(|_| truth[ei][pi] + normal.sample(&mut rng))
                .collect();
            pt.replicates = None;
        }
    }
    Ok(out)
}
