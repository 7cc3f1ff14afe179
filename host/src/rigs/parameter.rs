//! A rig's parameters: the registry entry a study names and a rig applies ([`Parameter`],
//! generic over what it sets in its rig), and the view a diagnosis takes of it
//! ([`RigParameter`]: its unit, role, limits and finite-difference step).

use crate::limits::Limits;

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

    /// This parameter as a candidate effect of a diagnosis (off at 0).
    pub const fn for_diagnosis_as_effect(&self) -> RigParameter {
        RigParameter {
            role: Role::Effect,
            ..self.for_diagnosis()
        }
    }
}

/// The parameters of a diagnosis: every parameter of `registry` as a base parameter, then
/// every one of `effects` as a candidate effect, in their order (`T` = N + M).
pub const fn diagnosis_parameters_with_effects<
    S,
    const N: usize,
    const M: usize,
    const T: usize,
>(
    registry: &[Parameter<S>; N],
    effects: &[Parameter<S>; M],
) -> [RigParameter; T] {
    assert!(T == N + M, "T must be N + M");
    let mut out = [RigParameter::base("", "", Limits::Positive, "", 0.0, 0.0); T];
    let mut i = 0;
    while i < N {
        out[i] = registry[i].for_diagnosis();
        i += 1;
    }
    while i < T {
        out[i] = effects[i - N].for_diagnosis_as_effect();
        i += 1;
    }
    out
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
