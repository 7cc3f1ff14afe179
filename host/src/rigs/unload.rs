//! The unload rig: a pod sphere loaded on a steel floor, then unloaded to half the load.
//! Condition: the peak load, N; observable: the resting overlap after unloading, µm. It starts,
//! like the press, at rest at the Hertz overlap of the peak load (the contact's peak overlap
//! α_max), then settles under half that load: elastically it rests at 2^{-2/3} of the peak
//! overlap, with a plastic fraction λ on the unloading curve of
//! [`arachis_core::contact::HystereticNormal`] at λ·α_max + (1 − λ)·2^{-2/3}·α_max — the
//! load–unload loop of a compression test (seed 001), the one cheap rig that sees
//! hysteresis apart from restitution.

use super::kind::{ConditionKey, Quantity, RigKind};
use super::press::settle;
use super::single_sphere::*;
use crate::calibration::RigError;
use crate::limits::Limits;

/// The final load as a fraction of the peak.
pub const UNLOAD_FRACTION: f64 = 0.5;

/// This rig's test.
pub const TEST: SingleSphereTest = SingleSphereTest {
    name: "unload",
    about: "load then unload to half; resting overlap against peak load",
    quantity: Quantity {
        name: "unloaded_overlap",
        unit: "um",
        label: "overlap after unloading to half, um",
    },
    condition: ConditionKey::new("peak_load_n", "peak load, N", Limits::Positive)
        .within((5.0e-4, 0.5), (1.0e-3, 0.2)),
    parameters: PARAMETERS_WITHOUT_ROLLING,
    simulate,
};

/// This rig in the catalogue.
pub const KIND: RigKind = TEST.kind(|_, _| Ok(Box::new(SingleSphereRig { test: &TEST })));

/// The resting overlap (µm) after loading to `load_n` (N) and unloading to half.
fn simulate(load_n: f64, p: &ModelParams) -> Result<f64, RigError> {
    settle(load_n, p, UNLOAD_FRACTION)
}
