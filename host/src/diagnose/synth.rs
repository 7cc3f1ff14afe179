//! Synthetic measurements with a hidden effect, for testing the loop and for teaching:
//! the true observable at each condition is simulated with the study's calibration plus the
//! hidden effect, and each replicate adds independent N(0, σ²) noise from a ChaCha8 stream
//! seeded with `seed` (rand_chacha + rand_distr), so the output is a deterministic function of
//! (study, hidden effect, noise, seed).

use std::path::Path;

use anyhow::{anyhow, bail, Context, Result};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

use super::model::Model;
use super::params::{set, ParamInfo};
use crate::calibration::ParameterValues;
use crate::study::measurements::Series;

/// Noise SD per rig (observable units).
#[derive(Clone, Debug, Default)]
pub struct NoiseSpec {
    /// SD for every rig without its own entry.
    pub all: Option<f64>,
    /// Per-rig SDs.
    pub per_rig: Vec<(String, f64)>,
}

/// Largest noise SD, as a multiple of the largest |true value| of the series it is added to:
/// beyond it the measurements carry no trace of the model (`--noise 1e300` once wrote values
/// of 1e300 into a study).
pub const MAX_NOISE_RATIO: f64 = 10.0;

impl NoiseSpec {
    /// SD for `rig`, falling back to the experiment's `noise_sd`.
    pub fn sd(&self, rig: &str, study_sd: Option<f64>) -> Result<f64> {
        let sd = self
            .per_rig
            .iter()
            .find(|(k, _)| k == rig)
            .map(|(_, s)| *s)
            .or(self.all)
            .or(study_sd);
        match sd {
            Some(s) if s.is_finite() && s > 0.0 => Ok(s),
            Some(s) => bail!("noise SD for {rig} must be > 0, got {s}"),
            None => {
                bail!("no noise SD for {rig}: give --noise {rig}=SIGMA or noise_sd in the study")
            }
        }
    }
}

/// True observables (no noise) at every point of every series, with `current` values and
/// the `hidden` effects on; returns the values used and the truths.
pub fn truths(
    model: &Model<'_>,
    series: &[Series],
    current: &ParameterValues,
    hidden: &[(&ParamInfo, f64)],
) -> Result<(ParameterValues, Vec<Vec<f64>>)> {
    let mut p = current.clone();
    for (info, v) in hidden {
        set(info, &mut p, *v);
    }
    let mut out = Vec::new();
    for (ei, s) in series.iter().enumerate() {
        let ys: Result<Vec<f64>> = s
            .points
            .iter()
            .map(|pt| model.simulate(ei, &pt.condition, &p))
            .collect();
        out.push(ys?);
    }
    Ok((p, out))
}

/// One row of a truth file: a rig, a condition value and the true observable there.
#[derive(Debug, serde::Deserialize)]
struct TruthRow {
    experiment: String,
    condition: f64,
    truth: f64,
}

/// Relative tolerance when matching a truth file's condition to a study's.
const CONDITION_MATCH: f64 = 1e-9;

/// True observables at every point of `series` read from a CSV file (columns `experiment`,
/// `condition`, `truth`; `#` lines are comments), e.g. made by another engine
/// (`scripts/liggghts-diagnosis-truth.py`). Every point needs its row: an error names the first
/// that has none.
pub fn truths_from_csv(path: &Path, series: &[Series]) -> Result<Vec<Vec<f64>>> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_path(path)
        .with_context(|| format!("cannot read the truth file {}", path.display()))?;
    let mut rows = Vec::new();
    for (i, row) in reader.deserialize::<TruthRow>().enumerate() {
        let row = row.with_context(|| format!("{}: row {}", path.display(), i + 1))?;
        if !(row.condition.is_finite() && row.truth.is_finite()) {
            bail!(
                "{}: row {}: condition and truth must be finite numbers",
                path.display(),
                i + 1
            );
        }
        rows.push(row);
    }
    series
        .iter()
        .map(|s| {
            s.points
                .iter()
                .map(|pt| {
                    let x = pt.condition.values().next().copied().unwrap_or(f64::NAN);
                    rows.iter()
                        .find(|r| {
                            r.experiment == s.experiment
                                && (r.condition - x).abs() <= CONDITION_MATCH * x.abs().max(1.0)
                        })
                        .map(|r| r.truth)
                        .ok_or_else(|| {
                            anyhow!(
                                "{}: no truth for {} at condition {x}",
                                path.display(),
                                s.experiment
                            )
                        })
                })
                .collect()
        })
        .collect()
}

/// Noisy replicates around `truth` for every point of `series` (replicate count: the
/// point's `replicates`, else its number of values, else `default_replicates`).
pub fn add_noise(
    series: &[Series],
    truth: &[Vec<f64>],
    noise: &NoiseSpec,
    seed: u64,
    default_replicates: usize,
) -> Result<Vec<Vec<Vec<f64>>>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut out = Vec::new();
    for (ei, s) in series.iter().enumerate() {
        let sd = noise.sd(&s.experiment, s.noise_sd)?;
        let largest = truth[ei].iter().fold(0.0f64, |m, y| m.max(y.abs()));
        if largest > 0.0 && sd > MAX_NOISE_RATIO * largest {
            bail!(
                "noise SD {sd:e} for {} is more than {MAX_NOISE_RATIO} times its largest true \
                 value ({largest:e}): the synthetic measurements would be noise alone",
                s.experiment
            );
        }
        let normal = Normal::new(0.0, sd)?;
        let mut points = Vec::new();
        for (pi, pt) in s.points.iter().enumerate() {
            let n = pt.replicates.unwrap_or(if pt.values.is_empty() {
                default_replicates
            } else {
                pt.values.len()
            });
            points.push(
                (0..n)
                    .map(|_| truth[ei][pi] + normal.sample(&mut rng))
                    .collect(),
            );
        }
        out.push(points);
    }
    Ok(out)
}
