//! What the catalogue says of a rig ([`RigKind`]): its name in study files, the quantities
//! it measures (with the one unit a study must state), the conditions a measurement may
//! fix, which part of a study describes what it simulates ([`WorldKind`], [`Worlds`]), and
//! how to build it.

use std::path::PathBuf;

use arachis_core::scenario::PullOff;

use super::parameter::RigParameter;
use super::pod_world::{ModeName, PodWorld};
use crate::calibration::{Rig, RigError};
use crate::limits::Limits;

/// A quantity a rig measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantity {
    /// The name, as a study's `quantity` key and the rig's response name.
    pub name: &'static str,
    /// The one unit a study must state for it.
    pub unit: &'static str,
    /// What it is, with its unit, for tables and plots.
    pub label: &'static str,
}

/// A condition a measurement may fix: a setting of the bench test, its key unit-suffixed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConditionKey {
    /// The key (e.g. `lift_speed_m_s`).
    pub key: &'static str,
    /// What it is, with its unit, for plots and messages.
    pub label: &'static str,
    /// Physical limits of its values.
    pub limits: Limits,
    /// The values the rig can simulate (inclusive), when narrower than the limits.
    pub range: Option<(f64, f64)>,
    /// Where a diagnosis may propose a new measurement (inclusive), when it may.
    pub search: Option<(f64, f64)>,
}

impl ConditionKey {
    /// A condition `key` described by `label`, any value within `limits`.
    pub const fn new(key: &'static str, label: &'static str, limits: Limits) -> Self {
        Self {
            key,
            label,
            limits,
            range: None,
            search: None,
        }
    }

    /// This condition restricted to `range` (inclusive), a diagnosis proposing new
    /// measurements within `search`.
    pub const fn within(self, range: (f64, f64), search: (f64, f64)) -> Self {
        Self {
            range: Some(range),
            search: Some(search),
            ..self
        }
    }

    /// Why `value` cannot be a value of this condition, if it cannot.
    pub fn check(&self, value: f64) -> Result<(), String> {
        self.limits.check(value)?;
        match self.range {
            Some((lo, hi)) if !(lo..=hi).contains(&value) => {
                Err(format!("{value} is outside [{lo}, {hi}] ({})", self.label))
            }
            _ => Ok(()),
        }
    }
}

/// What a rig simulates, as a study describes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WorldKind {
    /// Pods of a shape mix in steel rigs: `[materials]`, `[pods]`, `[pairs]`,
    /// `[parameters]`, `[plan.modes]` and `[plan.simulation]`.
    Pods,
    /// The pull-off tensile test: `[rig]` and its plant topology.
    PullOff,
    /// Nothing beyond the rig's own fixed set-up and the parameter values.
    Fixed,
}

/// The parts of a study that rigs are built from.
#[derive(Debug, Clone, Copy, Default)]
pub struct Worlds<'a> {
    /// The pod world, when the study has one.
    pub pods: Option<PodWorld<'a>>,
    /// The pull-off rig's set-up, when the study has one.
    pub pull_off: Option<PullOff>,
    /// The study file's folder (files a rig reads are relative to it).
    pub dir: Option<&'a std::path::Path>,
}

/// How to build a rig: options of the command, never of the physics.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RigOptions {
    /// The run mode of a pod rig (`quick`, `full`).
    pub mode: Option<ModeName>,
    /// Where a rig may write VTK frames of every run (none by default).
    pub vtk_dir: Option<PathBuf>,
}

/// Builds a rig over a study's worlds.
pub type BuildRig = for<'a> fn(&Worlds<'a>, &RigOptions) -> Result<Box<dyn Rig + 'a>, RigError>;

/// One rig of the catalogue.
#[derive(Clone, Copy)]
pub struct RigKind {
    /// Its name in study files (`[[measurements]] experiment`, `[[diagnosis.experiment]]
    /// kind`).
    pub name: &'static str,
    /// What it is, in a few words.
    pub about: &'static str,
    /// What part of a study describes what it simulates.
    pub world: WorldKind,
    /// Whether replicates differ (a random placement advanced per replicate); a rig
    /// without gives the same bits for every replicate, so one run says all.
    pub random: bool,
    /// What it measures.
    pub quantities: &'static [Quantity],
    /// The conditions a measurement of it may fix.
    pub conditions: &'static [ConditionKey],
    /// Its parameters with finite-difference steps, for a diagnosis (empty: the study's
    /// factors are its parameters).
    pub parameters: &'static [RigParameter],
    /// How to build it.
    pub build: BuildRig,
}

impl std::fmt::Debug for RigKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RigKind").field("name", &self.name).finish()
    }
}

impl RigKind {
    /// The quantity named `name`.
    pub fn quantity(&self, name: &str) -> Option<&'static Quantity> {
        self.quantities.iter().find(|q| q.name == name)
    }

    /// The condition keyed `key`.
    pub fn condition(&self, key: &str) -> Option<&'static ConditionKey> {
        self.conditions.iter().find(|c| c.key == key)
    }
}
