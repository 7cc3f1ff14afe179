//! What the catalogue says of a rig ([`RigKind`]): its name in study files, the quantities
//! it measures (with the one unit a study must state), the conditions a measurement may
//! fix, which part of a study describes what it simulates ([`WorldKind`], [`Worlds`]), and
//! how to build it.

use std::path::PathBuf;

use arachis_core::scenario::PullOff;

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

/// The role of a rig parameter in a diagnosis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Set by a calibration; a fit may move it.
    Base,
    /// An optional physical effect, off (0) unless switched on.
    Effect,
}

/// A parameter a rig reads, as a diagnosis needs it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigParameter {
    /// Short name on the command line (`viscoelastic`, `youngs_modulus`).
    pub name: &'static str,
    /// The key of its value (unit-suffixed, e.g. `viscoelastic_time_s`).
    pub key: &'static str,
    /// Unit, for reports.
    pub unit: &'static str,
    /// Base or effect.
    pub role: Role,
    /// Finite-difference step (absolute, in the unit): the change of each observable is far
    /// above the fixed-point resolution of the simulation, and small enough to stay in the
    /// linear range.
    pub fd_step: f64,
    /// Typical magnitude, to scale a fit's parameter vector to order one.
    pub scale: f64,
    /// Physical limits of its values.
    pub limits: Limits,
    /// One-line description.
    pub about: &'static str,
}

impl RigParameter {
    /// A base parameter named and keyed `name`, in `unit` within `limits`, described by
    /// `about`, with finite-difference step `fd_step` and typical magnitude `scale` (both
    /// in `unit`).
    pub const fn base(
        name: &'static str,
        unit: &'static str,
        limits: Limits,
        about: &'static str,
        fd_step: f64,
        scale: f64,
    ) -> Self {
        Self {
            name,
            key: name,
            unit,
            role: Role::Base,
            fd_step,
            scale,
            limits,
            about,
        }
    }
}

/// A parameter a study may give a rig: the name a study and the engine use, its report
/// label, what it is, its unit and limits, what it sets in the rig (`S`, the rig's own: a
/// property of the pod world, a setting of the pull-off rig), and how a diagnosis varies it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameter<S> {
    /// The key of its value (`pod-pod.static_friction`, `junction.strength_pa`).
    pub name: &'static str,
    /// Short label for reports (a seed's factor label, x1…).
    pub label: &'static str,
    /// What it is, in words.
    pub description: &'static str,
    /// Unit of its values (`-` for dimensionless; SI unless the name says otherwise).
    pub unit: &'static str,
    /// What it sets in the rig.
    pub sets: S,
    /// Physical limits every value must respect.
    pub limits: Limits,
    /// Finite-difference step of a diagnosis, in `unit` ([`RigParameter::fd_step`]).
    pub fd_step: f64,
    /// Typical magnitude, in `unit` ([`RigParameter::scale`]).
    pub scale: f64,
}

impl<S> Parameter<S> {
    /// This parameter as a base parameter of a diagnosis.
    pub const fn for_diagnosis(&self) -> RigParameter {
        RigParameter::base(
            self.name,
            self.unit,
            self.limits,
            self.description,
            self.fd_step,
            self.scale,
        )
    }
}

/// The base parameters of a diagnosis of every parameter of `registry`, in its order.
pub const fn diagnosis_parameters<S, const N: usize>(
    registry: &[Parameter<S>; N],
) -> [RigParameter; N] {
    // Filled below; a const fn cannot build an array from a closure.
    let mut out = [RigParameter::base("", "", Limits::Positive, "", 0.0, 0.0); N];
    let mut i = 0;
    while i < N {
        out[i] = registry[i].for_diagnosis();
        i += 1;
    }
    out
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
