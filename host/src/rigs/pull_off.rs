//! The pull-off rig: the core's virtual tensile test ([`PullOff`], seed 001 §2.3) — a
//! bonded pod pulled off its clamped stalk — with the nine factors of seed 001's screening
//! (Table 5, x1…x9) settable. Responses: the detachment force and, as an independent check,
//! σc·πRb², the force at which the bond criterion breaks the junction in pure tension.
//!
//! Q32.32 fixed point and no random placement, so the same values give the same bits on
//! any machine and thread count, and a replicate is the same run. [`PullOffArenas`] owns
//! the storage the core borrows (the core never allocates); `arachis pulloff` uses it too.
//!
//! Two readings are needed because the rig is not the seed's EDEM set-up:
//! - Steel pairs (x1–x6): the rig has no steel grips — the clamp and the gripper are
//!   kinematic bodies — so the pod stalk–steel pair sets the rig's stalk–stalk contact and
//!   the pod–steel pair its stalk–pod and pod–pod contact, the nearest unbonded pairs.
//! - Strength (x8): seed 001 Table 4 gives σc = τc and the rig keeps them equal, so x8 sets
//!   both critical stresses of the junction. In the axial pull of a texture analyser the
//!   junction is in pure tension and σc decides the break; with τc alone x8 could not act.
//!
//! x7 is taken literally (3e5–7e5 N/m³): in an axial pull it sets only the junction's
//! shear and twist stiffness, which the stalk barely loads.

use arachis_core::bond::BondSetSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::pull_off::{PullOff, PullOffResult};
use arachis_core::scenario::ScenarioError;
use serde_json::json;

use super::kind::{Quantity, RigKind, WorldKind};
use super::parameter::{self, diagnosis_parameters, RigParameter};
use crate::arena::{OwnedBonds, OwnedStorage};
use crate::calibration::{ParameterValues, Responses, Rig, RigError, RunRequest};
use crate::limits::Limits;

/// The rig's name in study files.
pub const NAME: &str = "pull_off";
/// The response calibrated to: the largest pull force before the junction broke, N.
pub const DETACHMENT_FORCE: &str = "detachment_force";
/// The independent check: σc·πRb² of the run's junction, N.
pub const PREDICTED_AXIAL_FORCE: &str = "predicted_axial_force";

/// This rig in the catalogue.
pub const KIND: RigKind = RigKind {
    name: NAME,
    about: "a bonded pod pulled off its clamped stalk (tensile test, seed 001 §2.3)",
    world: WorldKind::PullOff,
    random: false,
    quantities: &[
        Quantity {
            name: DETACHMENT_FORCE,
            unit: "N",
            label: "detachment force, N",
        },
        Quantity {
            name: PREDICTED_AXIAL_FORCE,
            unit: "N",
            label: "σc·πRb² of the junction, N",
        },
    ],
    conditions: &[],
    parameters: &DIAGNOSIS_PARAMETERS,
    build: |worlds, _| {
        let base = worlds.pull_off.ok_or_else(|| {
            RigError("the pull-off rig needs the study's [rig] and its topology".into())
        })?;
        Ok(Box::new(PullOffRig { base }))
    },
};

/// Step budget of one pull: 50 ms of pulling at dt 5e-7 s, 5 mm at 0.1 m/s, about 20 times
/// the junction's stretch at break in the seed's ranges.
pub const MAX_STEPS: u64 = 100_000;
/// Fastest gripper speed the rig accepts, m/s: the pull must stay quasi-static. Measured on
/// the shipped plant (2026-11-26): the detachment force is 3.553 N at 0.1 m/s, 3.396 N at 10
/// m/s (−4 % of the static 3.554 N) and 3.017 N at 30 m/s (−15 %); at 1 000 m/s the gripper
/// outran the junction and the rig reported no detachment and 0 N.
pub const MAX_PULL_SPEED_M_S: f64 = 10.0;

/// Which property of the rig a factor sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Setting {
    /// Stalk–stalk sliding friction μs.
    StalkFriction,
    /// Stalk–stalk rolling friction μr.
    StalkRollingFriction,
    /// Stalk–stalk restitution e.
    StalkRestitution,
    /// Stalk–pod and pod–pod sliding friction μs.
    PodFriction,
    /// Stalk–pod and pod–pod rolling friction μr.
    PodRollingFriction,
    /// Stalk–pod and pod–pod restitution e.
    PodRestitution,
    /// Junction tangential stiffness per unit area kt, N/m³.
    JunctionTangentialStiffness,
    /// Junction critical stresses σc = τc, Pa.
    JunctionStrength,
    /// Junction bond radius Rb, m.
    JunctionBondRadius,
}

/// One settable parameter of the rig.
pub type Parameter = parameter::Parameter<Setting>;

/// Seed 001 Table 5's factors, in its order. A diagnosis varies the coefficients by a
/// hundredth, the junction's stiffness and strength by 1e4 (N/m³, Pa) and its radius by
/// 1 µm, each far above the fixed-point resolution and far inside Table 5's ranges.
pub const PARAMETERS: [Parameter; 9] = [
    Parameter {
        name: "stalk.static_friction",
        label: "x1",
        description: "static friction, pod stalk–steel",
        unit: "-",
        sets: Setting::StalkFriction,
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.7,
    },
    Parameter {
        name: "stalk.rolling_friction",
        label: "x2",
        description: "rolling friction, pod stalk–steel",
        unit: "-",
        sets: Setting::StalkRollingFriction,
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.6,
    },
    Parameter {
        name: "stalk.restitution",
        label: "x3",
        description: "restitution, pod stalk–steel",
        unit: "-",
        sets: Setting::StalkRestitution,
        limits: Limits::Restitution,
        fd_step: 0.01,
        scale: 0.25,
    },
    Parameter {
        name: "pod.static_friction",
        label: "x4",
        description: "static friction, pod–steel",
        unit: "-",
        sets: Setting::PodFriction,
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.55,
    },
    Parameter {
        name: "pod.rolling_friction",
        label: "x5",
        description: "rolling friction, pod–steel",
        unit: "-",
        sets: Setting::PodRollingFriction,
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.43,
    },
    Parameter {
        name: "pod.restitution",
        label: "x6",
        description: "restitution, pod–steel",
        unit: "-",
        sets: Setting::PodRestitution,
        limits: Limits::Restitution,
        fd_step: 0.01,
        scale: 0.28,
    },
    Parameter {
        name: "junction.tangential_stiffness_n_m3",
        label: "x7",
        description: "tangential stiffness per unit area, pod–pod stalk",
        unit: "N/m^3",
        sets: Setting::JunctionTangentialStiffness,
        limits: Limits::Positive,
        fd_step: 1.0e4,
        scale: 5.0e5,
    },
    Parameter {
        name: "junction.strength_pa",
        label: "x8",
        description: "critical stress (σc = τc), pod–pod stalk",
        unit: "Pa",
        sets: Setting::JunctionStrength,
        limits: Limits::Positive,
        fd_step: 1.0e4,
        scale: 1.0e6,
    },
    Parameter {
        name: "junction.bond_radius_m",
        label: "x9",
        description: "bond radius, pod–pod stalk",
        unit: "m",
        sets: Setting::JunctionBondRadius,
        limits: Limits::Positive,
        fd_step: 1.0e-6,
        scale: 1.1e-3,
    },
];

/// The parameters for a diagnosis.
pub const DIAGNOSIS_PARAMETERS: [RigParameter; 9] = diagnosis_parameters(&PARAMETERS);

/// Seed 001's significant screening factors (Table 7: p < 0.05), most significant first.
pub const SEED_SIGNIFICANT: [&str; 4] = ["x8", "x7", "x2", "x4"];
/// Seed 001's factors carried to the response surface (Table 7: p ≤ 0.01).
pub const SEED_CARRIED: [&str; 2] = ["x7", "x8"];

/// The parameter labelled `label` (x1…x9).
pub fn by_label(label: &str) -> Option<&'static Parameter> {
    PARAMETERS.iter().find(|p| p.label == label)
}

/// The parameter named `name`.
pub fn by_name(name: &str) -> Option<&'static Parameter> {
    PARAMETERS.iter().find(|p| p.name == name)
}

impl Parameter {
    /// The value this parameter has in `rig`.
    pub fn get(&self, rig: &PullOff) -> f64 {
        match self.sets {
            Setting::StalkFriction => rig.stalk_contact.friction,
            Setting::StalkRollingFriction => rig.stalk_contact.rolling_friction,
            Setting::StalkRestitution => rig.stalk_contact.restitution,
            Setting::PodFriction => rig.pod_contact.friction,
            Setting::PodRollingFriction => rig.pod_contact.rolling_friction,
            Setting::PodRestitution => rig.pod_contact.restitution,
            Setting::JunctionTangentialStiffness => rig.junction.tangential_stiffness_n_m3,
            Setting::JunctionStrength => rig.junction.normal_strength_pa,
            Setting::JunctionBondRadius => rig.junction.radius_m,
        }
    }

    /// Sets `value` (in [`Self::unit`]) in `rig`.
    pub fn apply(&self, rig: &mut PullOff, value: f64) {
        match self.sets {
            Setting::StalkFriction => rig.stalk_contact.friction = value,
            Setting::StalkRollingFriction => rig.stalk_contact.rolling_friction = value,
            Setting::StalkRestitution => rig.stalk_contact.restitution = value,
            Setting::PodFriction => rig.pod_contact.friction = value,
            Setting::PodRollingFriction => rig.pod_contact.rolling_friction = value,
            Setting::PodRestitution => rig.pod_contact.restitution = value,
            Setting::JunctionTangentialStiffness => {
                rig.junction.tangential_stiffness_n_m3 = value;
            }
            Setting::JunctionStrength => {
                rig.junction.normal_strength_pa = value;
                rig.junction.tangential_strength_pa = value;
            }
            Setting::JunctionBondRadius => rig.junction.radius_m = value,
        }
    }
}

/// Owned arenas of one pull-off world.
pub struct PullOffArenas<S: Scalar> {
    storage: OwnedStorage<S>,
    bonds: OwnedBonds<S>,
}

impl<S: Scalar> PullOffArenas<S> {
    /// Arenas sized for `rig`.
    pub fn new(rig: &PullOff) -> Self {
        Self {
            storage: OwnedStorage::new(rig.storage_lengths()),
            bonds: OwnedBonds::new(rig.bond_capacity()),
        }
    }

    /// The world of `rig` over these arenas.
    pub fn world(&mut self, rig: &PullOff) -> Result<World<'_, S>, ScenarioError> {
        rig.build(self.storage.storage(), self.bonds.storage())
    }
}

/// The pull-off rig over a base set-up (module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PullOffRig {
    /// The rig before the run's values are applied: the geometry, the bond sets and the
    /// pull's conditions.
    pub base: PullOff,
}

impl PullOffRig {
    /// The rig with `values` applied (names of [`PARAMETERS`]; others keep the base's).
    pub fn rig(&self, values: &ParameterValues) -> Result<PullOff, RigError> {
        let mut rig = self.base;
        for (name, &value) in values {
            let p = by_name(name).ok_or_else(|| {
                let known: Vec<&str> = PARAMETERS.iter().map(|p| p.name).collect();
                RigError(format!(
                    "the pull-off rig has no parameter '{name}' (it has {})",
                    known.join(", ")
                ))
            })?;
            p.limits.check(value).map_err(|reason| {
                RigError(format!(
                    "{} ({}) = {value}: {reason}",
                    p.label, p.description
                ))
            })?;
            p.apply(&mut rig, value);
        }
        Ok(rig)
    }

    /// Pulls once with `values`. Fails if the junction does not break within
    /// [`MAX_STEPS`] or a stalk bond breaks first (then the junction's force was never
    /// measured).
    pub fn pull(&self, values: &ParameterValues) -> Result<Responses, RigError> {
        let rig = self.rig(values)?;
        let mut arenas = PullOffArenas::<Fx>::new(&rig);
        let mut world = arenas.world(&rig).map_err(|e| RigError(e.to_string()))?;
        let r: PullOffResult = rig
            .run(&mut world, MAX_STEPS, |_, _| {})
            .map_err(|e| RigError(e.to_string()))?;
        if r.stalk_broke_first {
            return Err(RigError("a stalk bond broke before the junction".into()));
        }
        if r.break_step.is_none() {
            return Err(RigError(format!(
                "the junction held for {MAX_STEPS} steps (peak {} N)",
                r.detachment_force_n
            )));
        }
        Ok(Responses::from([
            (DETACHMENT_FORCE.to_owned(), r.detachment_force_n),
            (
                PREDICTED_AXIAL_FORCE.to_owned(),
                rig.predicted_axial_detachment_n(),
            ),
        ]))
    }
}

/// A bond set as JSON.
fn bond_set(b: &BondSetSpec) -> serde_json::Value {
    json!({
        "normal_stiffness_n_m3": b.normal_stiffness_n_m3,
        "tangential_stiffness_n_m3": b.tangential_stiffness_n_m3,
        "normal_strength_pa": b.normal_strength_pa,
        "tangential_strength_pa": b.tangential_strength_pa,
        "radius_m": b.radius_m,
    })
}

/// A contact pair as JSON.
fn pair(p: &PairSpec) -> serde_json::Value {
    json!({
        "restitution": p.restitution,
        "friction": p.friction,
        "rolling_friction": p.rolling_friction,
    })
}

impl Rig for PullOffRig {
    fn id(&self) -> String {
        format!("arachis-pull-off-{}", env!("CARGO_PKG_VERSION"))
    }

    fn description(&self) -> String {
        "Arachis virtual tensile test (fixed-point core; a bonded pod pulled off its clamped \
         stalk, seed 001 §2.3)"
            .to_owned()
    }

    fn specification(&self, request: &RunRequest<'_>) -> Result<serde_json::Value, RigError> {
        if let Some(key) = request.condition.keys().next() {
            return Err(RigError(format!(
                "the pull-off rig takes no condition '{key}' (its pull is set by the study's \
                 [rig])"
            )));
        }
        // Deterministic: replicates are the same run, so the replicate is not part of it.
        let rig = self.rig(request.values)?;
        Ok(json!({
            "rig": NAME,
            "stalk_spheres": rig.stalk_spheres,
            "pull_speed_m_s": rig.pull_speed_m_s,
            "pull_angle_deg": rig.pull_angle_deg,
            "bond_time_s": rig.bond_time_s,
            "junction": bond_set(&rig.junction),
            "stalk": bond_set(&rig.stalk),
            "stalk_contact": pair(&rig.stalk_contact),
            "pod_contact": pair(&rig.pod_contact),
        }))
    }

    fn run(&self, request: &RunRequest<'_>) -> Result<Responses, RigError> {
        self.pull(request.values)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_parameter_sets_only_its_property() {
        let base = PullOff::default();
        let mut rig = base;
        by_label("x8").unwrap().apply(&mut rig, 1.0e6);
        assert_eq!(rig.junction.normal_strength_pa, 1.0e6);
        assert_eq!(rig.junction.tangential_strength_pa, 1.0e6);
        assert_eq!(rig.stalk, base.stalk);
        let mut rig = base;
        by_label("x4").unwrap().apply(&mut rig, 0.5);
        assert_eq!(rig.pod_contact.friction, 0.5);
        assert_eq!(rig.stalk_contact, base.stalk_contact);
        assert_eq!(by_label("x4").unwrap().get(&rig), 0.5);
    }

    #[test]
    fn unphysical_or_unknown_values_are_refused_before_pulling() {
        let rig = PullOffRig {
            base: PullOff::default(),
        };
        let bad = ParameterValues::from([("stalk.restitution".to_owned(), 1.5)]);
        assert!(rig.pull(&bad).unwrap_err().0.contains("x3"));
        let unknown = ParameterValues::from([("stalk.colour".to_owned(), 1.0)]);
        assert!(rig.rig(&unknown).unwrap_err().0.contains("no parameter"));
    }
}
