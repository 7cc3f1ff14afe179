//! Parameter values for one run: registry keys (`pod-pod.static_friction`, `pod.poisson`, …,
//! [`super::REGISTRY`]) mapped to SI values that override the study's held values,
//! the run mode, and their checks.

use std::collections::BTreeMap;
use std::fmt;
use std::str::FromStr;

use super::error::ExperimentError;
use super::parameters::{lookup_any, EFFECTS, REGISTRY};
use super::PodWorld;
use crate::nearest_name::nearest_name;

/// Registry key → value in the unit the key states (SI). Keys not given take the study's
/// held value ([`Study::held_value`]: the study's own value, else its range's centre).
/// A `BTreeMap`, so iteration (and everything derived from it) is in sorted key order.
pub type ParameterValues = BTreeMap<String, f64>;

/// The two run modes of issue 4 §5 (`[plan.modes.quick]`, `[plan.modes.full]`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ModeName {
    /// Fewer pods, coarser filling: a calibration in minutes.
    Quick,
    /// Seed scale (900 pods in the repose test, seed 000 §2.7).
    Full,
}

impl ModeName {
    /// The key under `[plan.modes]`.
    pub fn as_str(self) -> &'static str {
        match self {
            ModeName::Quick => "quick",
            ModeName::Full => "full",
        }
    }
}

impl fmt::Display for ModeName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl FromStr for ModeName {
    type Err = ExperimentError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "quick" => Ok(ModeName::Quick),
            "full" => Ok(ModeName::Full),
            other => Err(ExperimentError::UnknownMode {
                name: other.to_owned(),
            }),
        }
    }
}

/// Parses one `KEY=VALUE` override (the CLI's `--set`), checking the key against the
/// registry and the value's syntax; limits are checked by [`check_values`].
pub fn parse_assignment(text: &str) -> Result<(String, f64), ExperimentError> {
    let (key, value) = text
        .split_once('=')
        .ok_or_else(|| ExperimentError::BadValue {
            key: text.to_owned(),
            value: f64::NAN,
            reason: "expected KEY=VALUE, e.g. pod-pod.static_friction=0.854".into(),
        })?;
    let key = key.trim();
    check_key(key)?;
    let parsed = value
        .trim()
        .parse::<f64>()
        .map_err(|_| ExperimentError::BadValue {
            key: key.to_owned(),
            value: f64::NAN,
            reason: format!("'{}' is not a number", value.trim()),
        })?;
    Ok((key.to_owned(), parsed))
}

fn check_key(key: &str) -> Result<(), ExperimentError> {
    if lookup_any(key).is_some() {
        return Ok(());
    }
    let names: Vec<&str> = REGISTRY.iter().chain(&EFFECTS).map(|p| p.name).collect();
    let hint = nearest_name(key, &names)
        .map(|n| format!(", did you mean '{n}'?"))
        .unwrap_or_else(|| format!("; known parameters: {}", names.join(", ")));
    Err(ExperimentError::UnknownParameter {
        key: key.to_owned(),
        hint,
    })
}

/// Checks every key of `values` against the registry and every value against its physical
/// limits — with the study's `poisson_above_half` opt-in honoured for `pod.poisson`
/// ([`super::ParameterRange::limits`]).
pub fn check_values(world: &PodWorld<'_>, values: &ParameterValues) -> Result<(), ExperimentError> {
    for (key, &value) in values {
        check_key(key)?;
        let spec = lookup_any(key).expect("checked");
        let limits = world
            .parameters
            .get(key)
            .map_or(spec.limits, |range| range.limits(spec));
        limits
            .check(value)
            .map_err(|reason| ExperimentError::BadValue {
                key: key.clone(),
                value,
                reason,
            })?;
    }
    Ok(())
}
