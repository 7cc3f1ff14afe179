//! The break log: one [`BondBreak`] per broken bond, written in break order into a
//! caller-provided slice. When the slice is full further breaks are still counted
//! ([`super::Bonds::breaks_total`], [`super::Bonds::breaks_not_logged`]): overflow is never
//! silent, and it never stops the simulation.

use super::breakage::BreakCriterion;
use crate::num::Scalar;

/// A bond that broke.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BondBreak<S> {
    /// Step during which the bond broke (the world's step count before that step).
    pub step: u64,
    /// Simulated time at the start of that step, ms.
    pub time_ms: S,
    /// Persistent bond id (creation order).
    pub bond_id: u32,
    /// Lower sphere id.
    pub sphere_a: u32,
    /// Higher sphere id.
    pub sphere_b: u32,
    /// Tag of the bond's set.
    pub tag: u16,
    /// Which criterion broke it.
    pub criterion: BreakCriterion,
    /// σmax at the break, MPa.
    pub sigma_max_mpa: S,
    /// τmax at the break, MPa.
    pub tau_max_mpa: S,
}

impl<S: Scalar> BondBreak<S> {
    /// Time of the break, s.
    pub fn time_s(&self) -> f64 {
        self.time_ms.to_f64() / crate::units::TIME_S_TO_MS
    }
}
