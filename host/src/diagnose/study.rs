//! The diagnosis study file (TOML): the current calibration and, per experiment, the
//! measurements at several conditions with replicates. A `[diagnosis]` section, so it can sit
//! next to other study sections later.
//!
//! ```toml
//! [diagnosis]
//! name = "pods, lab 2026-11"
//! [diagnosis.calibration]          # base parameters; effects default to 0 (off)
//! restitution = 0.5
//! youngs_modulus_pa = 8.43e6
//! [[diagnosis.experiment]]
//! kind = "rebound"                 # rebound | press | fall | unload (see `experiment`)
//! noise_sd = 0.01                  # optional: used only by `arachis synth`
//! [[diagnosis.experiment.point]]
//! condition = 0.05                 # drop height, m
//! values = [0.551, 0.562, 0.548]   # replicates; or `replicates = 5` in a synth template
//! ```

use std::path::Path;

use anyhow::{bail, ensure, Context, Result};
use serde::{Deserialize, Serialize};

use super::experiment::ExperimentKind;
use super::params::ModelParams;

/// The whole file.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DiagnosisFile {
    /// The diagnosis section.
    pub diagnosis: Diagnosis,
}

/// A diagnosis study.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Diagnosis {
    /// Free-text name.
    #[serde(default)]
    pub name: String,
    /// The current calibration (base parameters and any effects already on).
    pub calibration: ModelParams,
    /// The experiments.
    #[serde(default)]
    pub experiment: Vec<Experiment>,
}

/// One experiment: a kind and its measured points.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiment {
    /// What is measured.
    pub kind: ExperimentKind,
    /// Measurement noise SD in the observable's unit; only `arachis synth` uses it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise_sd: Option<f64>,
    /// Measurements at each condition.
    pub point: Vec<Point>,
}

/// Replicate measurements at one condition.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Point {
    /// The condition (unit per experiment kind).
    pub condition: f64,
    /// Replicate measurements (unit per experiment kind).
    #[serde(default)]
    pub values: Vec<f64>,
    /// Number of replicates to synthesise (templates only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub replicates: Option<usize>,
}

/// Largest replicate count a template may ask for.
pub const MAX_REPLICATES: usize = 1000;

impl Diagnosis {
    /// Read and check a study file with measurements.
    pub fn load(path: &Path) -> Result<Self> {
        let d = Self::load_unchecked(path)?;
        d.check(true)
            .with_context(|| format!("in {}", path.display()))?;
        Ok(d)
    }

    /// Read a study file that may be a template (points with `replicates` and no values).
    pub fn load_template(path: &Path) -> Result<Self> {
        let d = Self::load_unchecked(path)?;
        d.check(false)
            .with_context(|| format!("in {}", path.display()))?;
        Ok(d)
    }

    fn load_unchecked(path: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(path)
            .with_context(|| format!("cannot read study {}", path.display()))?;
        let f: DiagnosisFile = toml::from_str(&text)
            .with_context(|| format!("{} is not a valid diagnosis study", path.display()))?;
        Ok(f.diagnosis)
    }

    /// Check the study; with `need_values` every point needs ≥ 1 value and each experiment
    /// ≥ 1 degree of freedom of pure error (some point with ≥ 2 replicates).
    pub fn check(&self, need_values: bool) -> Result<()> {
        self.calibration.validate().context("calibration")?;
        ensure!(
            !self.experiment.is_empty(),
            "the study has no [[diagnosis.experiment]]"
        );
        for (ei, e) in self.experiment.iter().enumerate() {
            let what = format!("experiment {} ({})", ei + 1, e.kind.name());
            ensure!(!e.point.is_empty(), "{what} has no points");
            if let Some(s) = e.noise_sd {
                ensure!(
                    s.is_finite() && s >= 0.0,
                    "{what}: noise_sd {s} must be >= 0"
                );
            }
            let (lo, hi) = e.kind.condition_range();
            let mut df = 0usize;
            for (pi, p) in e.point.iter().enumerate() {
                let c = p.condition;
                ensure!(
                    c.is_finite() && c >= lo && c <= hi,
                    "{what} point {}: condition {c} outside [{lo}, {hi}] ({})",
                    pi + 1,
                    e.kind.condition_label()
                );
                if e.point[..pi].iter().any(|q| q.condition == c) {
                    bail!("{what}: condition {c} appears twice; put all replicates in one point");
                }
                if let Some(v) = p.values.iter().find(|v| !v.is_finite()) {
                    bail!("{what} point {}: value {v} is not a finite number", pi + 1);
                }
                if let Some(r) = p.replicates {
                    ensure!(
                        (1..=MAX_REPLICATES).contains(&r),
                        "{what} point {}: replicates {r} must be in 1..={MAX_REPLICATES}",
                        pi + 1
                    );
                }
                if need_values {
                    ensure!(!p.values.is_empty(), "{what} point {}: no values", pi + 1);
                }
                df += p.values.len().saturating_sub(1);
            }
            if need_values {
                ensure!(
                    df >= 1,
                    "{what}: no replicates, so the measurement uncertainty (pure error) is \
                     unknown; measure some condition at least twice"
                );
            }
        }
        Ok(())
    }

    /// The study as TOML text.
    pub fn to_toml(&self) -> Result<String> {
        Ok(toml::to_string(&DiagnosisFile {
            diagnosis: self.clone(),
        })?)
    }
}
