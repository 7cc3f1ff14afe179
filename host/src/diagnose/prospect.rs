//! Rigs not yet measured, as candidate measurements for [`super::separate::propose`] and
//! [`super::separate::identify`]: when the data cannot tell two effects apart, or cannot
//! show an effect at all, the measurement that would may be another bench test altogether
//! (a drum beside a repose pile, a fall beside a press).
//!
//! A measured experiment brings its own pure error; an unmeasured one has none, so the user
//! states the replicate SD they expect of it (`arachis diagnose --consider RIG=SD`, in the
//! unit of the rig's first quantity). The rig must be one this study can build, must have a
//! condition with a search range (where a new measurement may be proposed), and must not
//! be measured already (a measured rig is searched with its measured pure error anyway).
//!
//! ```
//! use arachis::diagnose::prospect::parse;
//! assert_eq!(parse("rebound=0.005").unwrap(), ("rebound".to_owned(), 0.005));
//! assert!(parse("rebound").is_err());
//! assert!(parse("rebound=-1").is_err());
//! ```

use anyhow::{anyhow, bail, Context, Result};

use super::residuals::Experiment;
use crate::rigs::catalogue;
use crate::rigs::kind::{RigKind, RigOptions};
use crate::study::Study;

/// `RIG=SD` of `--consider`: the rig's name and the replicate SD its measurement would have.
pub fn parse(arg: &str) -> Result<(String, f64)> {
    let (rig, sd) = arg
        .split_once('=')
        .ok_or_else(|| anyhow!("--consider {arg}: expected RIG=SD, e.g. drum=0.7"))?;
    let sd: f64 = sd
        .trim()
        .parse()
        .with_context(|| format!("--consider {arg}: the SD '{sd}' is not a number"))?;
    if !(sd.is_finite() && sd > 0.0) {
        bail!("--consider {arg}: the SD must be positive and finite");
    }
    Ok((rig.trim().to_owned(), sd))
}

/// The condition of `kind` a diagnosis may search over: its first with a search range.
fn searched(kind: &RigKind) -> Option<&'static crate::rigs::kind::ConditionKey> {
    kind.conditions.iter().find(|c| c.search.is_some())
}

/// The first of `calibrated` (parameter keys) that `kind` does not take, if any: its
/// prediction would ignore that parameter, so its sensitivities would mean nothing. A rig
/// that declares no parameters takes the study's own factors.
fn missing<'k>(kind: &RigKind, calibrated: &[&'k str]) -> Option<&'k str> {
    if kind.parameters.is_empty() {
        return None;
    }
    calibrated
        .iter()
        .copied()
        .find(|key| kind.parameters.iter().all(|p| p.key != *key))
}

/// The experiment an unmeasured rig `name` would be, with replicate SD `sd`, or why it
/// cannot be proposed. `calibrated` are the keys of the parameters the diagnosis
/// calibrates, which the rig must take.
pub fn prospect(
    study: &Study,
    measured: &[Experiment],
    calibrated: &[&str],
    (name, sd): (&str, f64),
    options: &RigOptions,
) -> Result<Experiment> {
    let kind = catalogue::find(name).ok_or_else(|| {
        let names = catalogue::names();
        let hint = crate::study::nearest_name(name, &names)
            .map_or(String::new(), |n| format!(" (did you mean '{n}'?)"));
        anyhow!(
            "--consider: no rig '{name}'{hint}; rigs: {}",
            names.join(", ")
        )
    })?;
    if measured.iter().any(|e| e.rig == name) {
        bail!(
            "--consider {name}: it is measured already; new conditions of it are searched with \
             its measured pure error"
        );
    }
    let condition = searched(kind).ok_or_else(|| {
        anyhow!("--consider {name}: the rig has no condition a diagnosis may propose")
    })?;
    if let Err(e) = study.rig(name, options) {
        bail!("--consider {name}: this study cannot simulate it: {e}");
    }
    if let Some(key) = missing(kind, calibrated) {
        bail!("--consider {name}: the rig does not take '{key}', which this diagnosis calibrates");
    }
    let quantity = kind
        .quantities
        .first()
        .ok_or_else(|| anyhow!("--consider {name}: the rig measures nothing"))?;
    Ok(Experiment {
        rig: name.to_owned(),
        quantity: quantity.name.to_owned(),
        observable_label: quantity.label.to_owned(),
        condition: (condition.key.to_owned(), condition.label.to_owned()),
        noise_sd: Some(sd),
    })
}

/// Rigs that [`prospect`] accepts and that are not in `considered`: what `--consider` could
/// add.
pub fn unmeasured(
    study: &Study,
    measured: &[Experiment],
    considered: &[Experiment],
    calibrated: &[&str],
    options: &RigOptions,
) -> Vec<&'static RigKind> {
    // The rules are `prospect`'s own; the SD plays no part in them.
    let any_sd = 1.0;
    catalogue::RIGS
        .iter()
        .copied()
        .filter(|k| considered.iter().all(|e| e.rig != k.name))
        .filter(|k| prospect(study, measured, calibrated, (k.name, any_sd), options).is_ok())
        .collect()
}

/// One line naming `rigs` (with the quantity each measures), followed by `then`; `None`
/// when there are none.
pub fn hint(rigs: &[&RigKind], then: &str) -> Option<String> {
    if rigs.is_empty() {
        return None;
    }
    let named: Vec<String> = rigs
        .iter()
        .filter_map(|k| {
            let q = k.quantities.first()?;
            Some(format!("{} ({})", k.name, q.label))
        })
        .collect();
    Some(format!(
        "rigs not yet measured that this study can simulate: {}; {then}",
        named.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_refuses_what_is_not_a_positive_sd() {
        for bad in ["drum", "drum=", "drum=x", "drum=0", "drum=inf", "drum=NaN"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        assert_eq!(parse(" drum = 0.7 ").unwrap(), ("drum".to_owned(), 0.7));
    }
}
