//! Bench measurements: which experiment, under which conditions, and the replicates.
//!
//! A `[[measurements]]` block holds one quantity of one experiment at one set of
//! conditions. Several blocks for the same experiment at different conditions (drop
//! heights, slopes, lift speeds, moisture; issue 5) are how a study spans conditions:
//!
//! ```toml
//! [[measurements]]
//! experiment = "repose"
//! quantity = "repose_angle"
//! unit = "deg"
//! condition = { lift_speed_m_s = 0.05, moisture_pct = 36.72 }
//! values = [31.2, 30.8, 31.1]      # replicates, as measured
//! ```
//!
//! When a paper prints only a summary, the block gives `mean` and `n` (and `sd` when
//! printed) instead of `values`; exactly one of the two forms is allowed. The experiment is
//! a rig's name, and its quantities and condition keys are those the rig declares
//! (`crate::rigs::catalogue`).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// One `[[measurements]]` block as written in the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measurement {
    /// Which experiment: a rig's name.
    pub experiment: String,
    /// What was measured (a quantity of the experiment's rig).
    pub quantity: String,
    /// Its unit, as the rig states it.
    pub unit: String,
    /// The conditions it was measured at (the rig's condition keys); empty when the study
    /// has a single condition.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub condition: BTreeMap<String, f64>,
    /// Replicates as measured, in the quantity's unit. Excludes `mean`/`sd`/`n`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub values: Option<Vec<f64>>,
    /// Mean of the replicates when only a summary is printed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mean: Option<f64>,
    /// Sample standard deviation, when printed (needs `mean`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sd: Option<f64>,
    /// Number of replicates behind `mean` (needs `mean`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub n: Option<u32>,
    /// Where the numbers are printed (free text).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

impl Measurement {
    /// The mean of the replicates (arithmetic mean of `values`, or the printed `mean`).
    pub fn mean(&self) -> Option<f64> {
        match (&self.values, self.mean) {
            (Some(v), _) if !v.is_empty() => Some(v.iter().sum::<f64>() / v.len() as f64),
            (_, m) => m,
        }
    }

    /// The number of replicates.
    pub fn replicates(&self) -> Option<u32> {
        match &self.values {
            Some(v) => u32::try_from(v.len()).ok(),
            None => self.n,
        }
    }

    /// True when the block holds the replicates themselves, not a printed summary.
    pub fn has_replicates(&self) -> bool {
        self.values.is_some()
    }

    /// True when the block measures `experiment`'s `quantity` at a condition that includes
    /// every key of `condition` with the same value.
    pub fn matches(
        &self,
        experiment: &str,
        quantity: &str,
        condition: &BTreeMap<String, f64>,
    ) -> bool {
        self.experiment == experiment
            && self.quantity == quantity
            && condition
                .iter()
                .all(|(k, v)| self.condition.get(k) == Some(v))
    }
}

/// Every measurement of `file`: its `[[measurements]]`, a pull-off study's `[measurement]`
/// (a printed force, no replicates), and each point of `[diagnosis]` (its replicates at the
/// rig's one condition; none in a template).
pub fn study_measurements(file: &super::StudyFile) -> Vec<Measurement> {
    let mut out = measurement_blocks(file);
    out.extend(
        study_series(file)
            .into_iter()
            .take(diagnosis_blocks(file))
            .flat_map(|s| {
                s.points.into_iter().map(move |p| Measurement {
                    experiment: s.experiment.clone(),
                    quantity: s.quantity.clone(),
                    unit: s.unit.clone(),
                    condition: p.condition,
                    values: (!p.values.is_empty()).then_some(p.values),
                    mean: None,
                    sd: None,
                    n: None,
                    source: None,
                })
            }),
    );
    out
}

/// The `[[diagnosis.experiment]]` blocks of `file`.
fn diagnosis_blocks(file: &super::StudyFile) -> usize {
    file.diagnosis.as_ref().map_or(0, |d| d.experiment.len())
}

/// `file`'s `[[measurements]]` and a pull-off study's `[measurement]`.
fn measurement_blocks(file: &super::StudyFile) -> Vec<Measurement> {
    let mut out = file.measurements.clone();
    if let Some(m) = &file.measurement {
        out.push(Measurement {
            experiment: crate::rigs::pull_off::NAME.to_owned(),
            quantity: m.quantity.clone(),
            unit: PULL_OFF_FORCE_UNIT.to_owned(),
            condition: BTreeMap::new(),
            values: None,
            mean: Some(m.value_n),
            sd: None,
            n: None,
            source: Some(m.source.clone()),
        });
    }
    out
}

/// The unit of a pull-off study's measured force.
const PULL_OFF_FORCE_UNIT: &str = "N";

/// One measured point of a [`Series`]: a condition and its replicates.
#[derive(Debug, Clone, PartialEq)]
pub struct SeriesPoint {
    /// The condition.
    pub condition: BTreeMap<String, f64>,
    /// The replicates (none for a printed mean, or a template's point).
    pub values: Vec<f64>,
    /// How many replicates a template asks for.
    pub replicates: Option<usize>,
    /// The printed summary of replicates not given one by one: mean ± SD over n (a block
    /// with `mean`, `sd` and `n` and no `values`).
    pub summary: Option<Summary>,
}

/// Replicates as a paper prints them: mean ± sample SD over n, in the quantity's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation of one replicate.
    pub sd: f64,
    /// Number of replicates.
    pub n: u32,
}

/// One quantity of one rig measured at several conditions: what the diagnosis loop tests
/// for lack of fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The rig.
    pub experiment: String,
    /// The quantity.
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The measurement noise SD to synthesise with, when the study gives one.
    pub noise_sd: Option<f64>,
    /// The points, in file order.
    pub points: Vec<SeriesPoint>,
}

/// The series of `file`: each `[[diagnosis.experiment]]` block, then its `[[measurements]]`
/// grouped by experiment and quantity (in order of first appearance), then a pull-off
/// study's `[measurement]`.
pub fn study_series(file: &super::StudyFile) -> Vec<Series> {
    let mut out: Vec<Series> = Vec::new();
    for e in file.diagnosis.iter().flat_map(|d| &d.experiment) {
        let Some(rig) = crate::rigs::catalogue::find(&e.kind) else {
            continue;
        };
        let (Some(q), Some(c)) = (rig.quantities.first(), rig.conditions.first()) else {
            continue;
        };
        out.push(Series {
            experiment: e.kind.clone(),
            quantity: q.name.to_owned(),
            unit: q.unit.to_owned(),
            noise_sd: e.noise_sd,
            points: e
                .point
                .iter()
                .map(|p| SeriesPoint {
                    condition: BTreeMap::from([(c.key.to_owned(), p.condition)]),
                    values: p.values.clone(),
                    replicates: p.replicates,
                    summary: None,
                })
                .collect(),
        });
    }
    let first = out.len();
    for m in measurement_blocks(file) {
        let summary = match (&m.values, m.mean, m.sd, m.n) {
            (None, Some(mean), Some(sd), Some(n)) => Some(Summary { mean, sd, n }),
            _ => None,
        };
        let point = SeriesPoint {
            values: m.values.clone().unwrap_or_default(),
            condition: m.condition.clone(),
            replicates: None,
            summary,
        };
        match out[first..]
            .iter_mut()
            .find(|s| s.experiment == m.experiment && s.quantity == m.quantity)
        {
            Some(s) => s.points.push(point),
            None => out.push(Series {
                experiment: m.experiment,
                quantity: m.quantity,
                unit: m.unit,
                noise_sd: None,
                points: vec![point],
            }),
        }
    }
    out
}
