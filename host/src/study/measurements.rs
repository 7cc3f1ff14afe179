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
//! printed) instead of `values`; exactly one of the two forms is allowed.
//! [`QUANTITIES`] and [`CONDITIONS`] are the tables of accepted quantities and condition
//! keys; later experiments and effects add rows.

use std::collections::BTreeMap;
use std::fmt;

use serde::{Deserialize, Serialize};

use crate::limits::Limits;

/// The virtual (and bench) experiments a study can measure and simulate (issue 4 §2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Experiment {
    /// Stacking (repose) angle by cylinder lifting (seed 000 §2.7, §3.6.1).
    Repose,
    /// Drop onto the 45° plate (restitution rig, seed 000 §2.6.1).
    PlateDrop,
    /// Sliding on an inclined plane (static friction, seed 000 §2.6.2).
    InclineSlide,
    /// Rolling on an incline followed by a flat (rolling friction, seed 000 §2.6.3).
    Rolling,
    /// Compression between two plates (apparent modulus, seed 000 §2.5.3).
    Compression,
}

impl Experiment {
    /// Every experiment, in declaration order.
    pub const ALL: [Experiment; 5] = [
        Self::Repose,
        Self::PlateDrop,
        Self::InclineSlide,
        Self::Rolling,
        Self::Compression,
    ];

    /// The name used in study files.
    pub fn name(self) -> &'static str {
        match self {
            Self::Repose => "repose",
            Self::PlateDrop => "plate_drop",
            Self::InclineSlide => "incline_slide",
            Self::Rolling => "rolling",
            Self::Compression => "compression",
        }
    }
}

impl fmt::Display for Experiment {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A quantity an experiment measures, with the one unit the file must state for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct QuantitySpec {
    /// The experiment.
    pub experiment: Experiment,
    /// The `quantity` key's value.
    pub name: &'static str,
    /// The `unit` key's required value.
    pub unit: &'static str,
}

/// Every accepted (experiment, quantity, unit).
pub const QUANTITIES: &[QuantitySpec] = &[
    QuantitySpec {
        experiment: Experiment::Repose,
        name: "repose_angle",
        unit: "deg",
    },
    QuantitySpec {
        experiment: Experiment::PlateDrop,
        name: "restitution",
        unit: "-",
    },
    QuantitySpec {
        experiment: Experiment::PlateDrop,
        name: "rebound_distance",
        unit: "mm",
    },
    QuantitySpec {
        experiment: Experiment::InclineSlide,
        name: "slide_angle",
        unit: "deg",
    },
    QuantitySpec {
        experiment: Experiment::InclineSlide,
        name: "static_friction",
        unit: "-",
    },
    QuantitySpec {
        experiment: Experiment::Rolling,
        name: "rolling_distance",
        unit: "mm",
    },
    QuantitySpec {
        experiment: Experiment::Rolling,
        name: "rolling_friction",
        unit: "-",
    },
    QuantitySpec {
        experiment: Experiment::Compression,
        name: "apparent_modulus",
        unit: "Pa",
    },
    QuantitySpec {
        experiment: Experiment::Compression,
        name: "peak_force",
        unit: "N",
    },
];

/// A condition key: a setting of an experiment that a measurement may fix. The key carries
/// its unit as a suffix. A measurement's condition overrides the same-named setting of the
/// plan's simulation settings when that measurement is simulated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ConditionSpec {
    /// The key, unit-suffixed.
    pub key: &'static str,
    /// Experiments it applies to; empty means every experiment.
    pub experiments: &'static [Experiment],
    /// Physical limits.
    pub limits: Limits,
}

/// Every accepted condition key.
pub const CONDITIONS: &[ConditionSpec] = &[
    ConditionSpec {
        key: "lift_speed_m_s",
        experiments: &[Experiment::Repose],
        limits: Limits::Positive,
    },
    ConditionSpec {
        key: "drop_height_mm",
        experiments: &[Experiment::PlateDrop],
        limits: Limits::Positive,
    },
    ConditionSpec {
        key: "plate_angle_deg",
        experiments: &[Experiment::PlateDrop],
        limits: Limits::Positive,
    },
    ConditionSpec {
        key: "slope_deg",
        experiments: &[Experiment::InclineSlide, Experiment::Rolling],
        limits: Limits::Positive,
    },
    ConditionSpec {
        key: "release_height_mm",
        experiments: &[Experiment::Rolling],
        limits: Limits::Positive,
    },
    ConditionSpec {
        key: "loading_speed_mm_min",
        experiments: &[Experiment::Compression],
        limits: Limits::Positive,
    },
    // Water content, wet basis (seed 000 §2.1: 36.72 %); applies to every experiment.
    ConditionSpec {
        key: "moisture_pct",
        experiments: &[],
        limits: Limits::NonNegative,
    },
];

/// One `[[measurements]]` block as written in the file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measurement {
    /// Which experiment.
    pub experiment: Experiment,
    /// What was measured (one of [`QUANTITIES`] for this experiment).
    pub quantity: String,
    /// Its unit, as [`QUANTITIES`] requires.
    pub unit: String,
    /// The conditions it was measured at (keys from [`CONDITIONS`]); empty when the study
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
        experiment: Experiment,
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

/// The accepted quantity names of `experiment`.
pub fn quantities_of(experiment: Experiment) -> Vec<&'static QuantitySpec> {
    QUANTITIES
        .iter()
        .filter(|q| q.experiment == experiment)
        .collect()
}

/// The condition keys accepted for `experiment`.
pub fn conditions_of(experiment: Experiment) -> Vec<&'static ConditionSpec> {
    CONDITIONS
        .iter()
        .filter(|c| c.experiments.is_empty() || c.experiments.contains(&experiment))
        .collect()
}
