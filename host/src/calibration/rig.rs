//! The one interface between the plan engine and the physics: a [`Rig`] takes parameter
//! values, the condition of a measurement and a replicate number, and returns named
//! responses (a repose angle in degrees, a detachment force in N, a bed height in mm, …).
//!
//! The engine never looks inside a rig. It asks for a run's [`Rig::specification`] (a JSON
//! value holding everything that can change the result, hashed to name the run in the run
//! cache) and for its responses ([`Rig::run`]). A rig must be a pure function of the
//! request: the same values, condition and replicate give the same bits, on any thread, so
//! a stored run can be replayed instead of simulated. Replicate `r` is the same point with
//! the rig's random placement advanced by `r` (a deterministic rig ignores it).
//!
//! Every rig of the host lives in one file under `crate::rigs`; `docs/architecture.md`
//! says how to add one and `crate::rigs::conformance` is the test it must pass.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Parameter name → value, in the unit the name states (SI unless suffixed). A `BTreeMap`,
/// so everything derived from it is in sorted key order.
pub type ParameterValues = BTreeMap<String, f64>;

/// Condition key (unit-suffixed, e.g. `lift_speed_m_s`) → value: the setting of the bench
/// test a measurement was taken at.
pub type Condition = BTreeMap<String, f64>;

/// Response name (a study quantity, e.g. `repose_angle`) → value in the quantity's unit.
pub type Responses = BTreeMap<String, f64>;

/// One run asked of a rig.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunRequest<'a> {
    /// Every parameter the run sets (the varied ones and the held ones).
    pub values: &'a ParameterValues,
    /// The measurement's condition.
    pub condition: &'a Condition,
    /// 0 for the first run at these settings, 1 for the next, …: replicates differ only in
    /// the rig's random placement, so replicated centre points measure pure error.
    pub replicate: u32,
}

/// A rig's refusal or failure, in words (the engine adds the stage and run).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct RigError(pub String);

/// A virtual bench test (module notes).
pub trait Rig: Sync {
    /// A stable identifier of the rig and its code version. It is stored with every cached
    /// run, so results of another rig or build are never replayed, and printed in reports.
    fn id(&self) -> String;

    /// One sentence for reports: what this rig is.
    fn description(&self) -> String;

    /// Everything that determines the run `request`, as JSON; its canonical form is hashed
    /// to name the run ([`super::spec_hash::SpecHash`]). Refuses unknown parameters and
    /// values outside their limits, before anything is simulated.
    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError>;

    /// Simulates `request` and returns its responses. Must be deterministic in the request.
    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError>;

    /// Draws the run `request` into `dir` and returns the picture's path, when the rig can
    /// (the default cannot). Reports link it; it never changes a number.
    fn picture(&self, request: &RunRequest<'_>, dir: &Path) -> Result<Option<PathBuf>, RigError> {
        let _ = (request, dir);
        Ok(None)
    }
}

/// The response `quantity` of `responses`, or an error naming what the rig did return.
pub fn response(responses: &Responses, quantity: &str) -> Result<f64, RigError> {
    let value = responses.get(quantity).copied().ok_or_else(|| {
        let known: Vec<&str> = responses.keys().map(String::as_str).collect();
        RigError(format!(
            "the rig returned no '{quantity}' (it returned {})",
            known.join(", ")
        ))
    })?;
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RigError(format!(
            "the response {quantity} = {value} is not a finite number"
        )))
    }
}
