//! The test every rig must pass: [`check`], called from the rig's own test with one request
//! it can run. It asks what the engine and the diagnosis rely on, and nothing about the
//! physics (the rig's test checks that against theory or the seeds):
//! - the catalogue entry is complete: a name, quantities with units and labels, distinct
//!   condition keys, diagnosis parameters with positive steps and scales;
//! - the rig names itself (`id`, `description`);
//! - a run's specification is a JSON object, the same for the same request, and it
//!   changes with the replicate exactly when the rig's replicates differ
//!   ([`RigKind::random`]);
//! - a run returns only quantities the rig declares, finite, and the same bits when run
//!   again;
//! - an unknown parameter is refused before anything is simulated.

use super::kind::{RigKind, RigOptions, WorldKind};
use crate::calibration::spec_hash::SpecHash;
use crate::calibration::{Condition, ParameterValues, Responses, Rig, RunRequest};

/// A parameter no rig has.
pub const UNKNOWN_PARAMETER: &str = "conformance.no_such_parameter";

/// What [`check`] saw, for the rig's test to look at further.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The responses of the request.
    pub responses: Responses,
    /// Its specification's hash.
    pub spec_hash: SpecHash,
}

/// [`check`] of a rig that needs no study ([`WorldKind::Fixed`]): built from `kind` with
/// default options, on replicate 0 of `values` at `condition`.
pub fn check_fixed(
    kind: &RigKind,
    values: &ParameterValues,
    condition: &Condition,
) -> Result<Checked, String> {
    if kind.world != WorldKind::Fixed {
        return Err(format!("{}: the rig is built from a study", kind.name));
    }
    let rig = (kind.build)(&Default::default(), &RigOptions::default())
        .map_err(|e| format!("{}: building the rig failed: {e}", kind.name))?;
    let request = RunRequest {
        values,
        condition,
        replicate: 0,
    };
    check(kind, rig.as_ref(), &request)
}

/// Checks `rig`, built from catalogue entry `kind`, on `request` (module notes); the first
/// failure in words.
pub fn check(kind: &RigKind, rig: &dyn Rig, request: &RunRequest<'_>) -> Result<Checked, String> {
    catalogue_entry(kind)?;
    if rig.id().trim().is_empty() || rig.description().trim().is_empty() {
        return Err(format!(
            "{}: the rig needs an id and a description",
            kind.name
        ));
    }
    let spec = rig
        .specification(request)
        .map_err(|e| format!("{}: the specification failed: {e}", kind.name))?;
    if !spec.is_object() {
        return Err(format!("{}: a specification is a JSON object", kind.name));
    }
    let again = rig.specification(request).map_err(|e| e.0)?;
    if SpecHash::of(&spec) != SpecHash::of(&again) {
        return Err(format!(
            "{}: the same request gave two specifications",
            kind.name
        ));
    }
    let next = RunRequest {
        replicate: request.replicate + 1,
        ..*request
    };
    let replicate_differs =
        SpecHash::of(&rig.specification(&next).map_err(|e| e.0)?) != SpecHash::of(&spec);
    if replicate_differs != kind.random {
        return Err(format!(
            "{}: the catalogue says replicates {} but the specification {} with the replicate",
            kind.name,
            if kind.random {
                "differ"
            } else {
                "are the same run"
            },
            if replicate_differs {
                "changes"
            } else {
                "does not change"
            }
        ));
    }
    let responses = rig
        .run(request)
        .map_err(|e| format!("{}: the run failed: {e}", kind.name))?;
    if responses.is_empty() {
        return Err(format!(
            "{}: a run returns at least one response",
            kind.name
        ));
    }
    for (name, value) in &responses {
        if kind.quantity(name).is_none() {
            return Err(format!(
                "{}: returned '{name}', which it does not declare",
                kind.name
            ));
        }
        if !value.is_finite() {
            return Err(format!("{}: {name} = {value} is not finite", kind.name));
        }
    }
    let rerun = rig.run(request).map_err(|e| e.0)?;
    let bits = |r: &Responses| r.values().map(|v| v.to_bits()).collect::<Vec<_>>();
    if bits(&rerun) != bits(&responses) {
        return Err(format!(
            "{}: the same request gave {responses:?}, then {rerun:?}",
            kind.name
        ));
    }
    let mut unknown: ParameterValues = request.values.clone();
    unknown.insert(UNKNOWN_PARAMETER.to_owned(), 1.0);
    let refused = RunRequest {
        values: &unknown,
        ..*request
    };
    if rig.specification(&refused).is_ok() {
        return Err(format!(
            "{}: an unknown parameter was accepted; a rig refuses what it cannot set",
            kind.name
        ));
    }
    Ok(Checked {
        responses,
        spec_hash: SpecHash::of(&spec),
    })
}

/// The catalogue entry's own checks.
fn catalogue_entry(kind: &RigKind) -> Result<(), String> {
    let fail = |why: &str| Err(format!("{}: {why}", kind.name));
    if kind.name.is_empty() || kind.about.is_empty() {
        return fail("a rig needs a name and a few words on what it is");
    }
    if kind.quantities.is_empty()
        || kind
            .quantities
            .iter()
            .any(|q| q.name.is_empty() || q.unit.is_empty() || q.label.is_empty())
    {
        return fail("every quantity needs a name, a unit and a label");
    }
    for (i, c) in kind.conditions.iter().enumerate() {
        if kind.conditions[..i].iter().any(|d| d.key == c.key) {
            return fail("condition keys must be distinct");
        }
    }
    if kind
        .parameters
        .iter()
        .any(|p| !(p.fd_step > 0.0 && p.scale > 0.0))
    {
        return fail("a diagnosis parameter needs a positive step and scale");
    }
    Ok(())
}
