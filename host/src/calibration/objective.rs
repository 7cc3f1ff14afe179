//! What a stage's runs measure: a rig, the quantity read from its responses, the measured
//! value and the condition it was measured at. The target (what the optimum must hit) and
//! the validation (what the optimum is checked against) are each one.

use super::rig::{Condition, Rig};

/// One measured quantity of one rig.
pub struct Objective<'a> {
    /// The rig that simulates it.
    pub rig: &'a dyn Rig,
    /// The experiment's name in the study (e.g. `repose`), for reports.
    pub experiment: String,
    /// The response read from the rig (e.g. `repose_angle`).
    pub quantity: String,
    /// Its unit.
    pub unit: String,
    /// The measured mean, in `unit`.
    pub value: f64,
    /// The measurement's condition.
    pub condition: Condition,
}
