//! The nine factors of seed 001's Plackett–Burman screening (Table 5, x1…x9) and how each
//! one sets the pull-off rig ([`arachis_core::scenario::PullOff`]).
//!
//! Ranges are the seed's, in SI units (Table 5 prints x7 in 10⁵ N/m³, x8 in 10⁵ Pa and x9
//! in mm). Two readings are needed because the rig is not the seed's EDEM set-up:
//! - Steel pairs (x1–x6): the rig has no steel grips — the clamp and the gripper are
//!   kinematic bodies — so the pod stalk–steel pair sets the rig's stalk–stalk contact and
//!   the pod–steel pair its stalk–pod and pod–pod contact, the nearest unbonded pairs.
//! - Strength (x8): seed 001 Table 4 gives σc = τc and the rig keeps them equal, so x8 sets
//!   both critical stresses of the junction. In the axial pull of a texture analyser
//!   (seed 001 §2.3) the junction is in pure tension and σc decides the break; with τc
//!   alone x8 could not act.
//!
//! x7 is taken literally (3e5–7e5 N/m³): in an axial pull it sets only the junction's
//! shear and twist stiffness, which the stalk barely loads.

use arachis_core::scenario::PullOff;
use serde::Serialize;

use crate::doe::{DesignError, Factor};

/// Which property of the rig a factor sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
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

/// One screening factor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlantFactor {
    /// Seed 001 Table 5 label (x1…x9).
    pub label: &'static str,
    /// What it is, in words.
    pub description: &'static str,
    /// Unit of `low` and `high` (SI).
    pub unit: &'static str,
    /// Level at coded −1.
    pub low: f64,
    /// Level at coded +1.
    pub high: f64,
    /// What it sets in the rig.
    pub setting: Setting,
}

/// Seed 001 Table 5, SI units.
pub const TABLE5: [PlantFactor; 9] = [
    PlantFactor {
        label: "x1",
        description: "static friction, pod stalk–steel",
        unit: "-",
        low: 0.61,
        high: 0.82,
        setting: Setting::StalkFriction,
    },
    PlantFactor {
        label: "x2",
        description: "rolling friction, pod stalk–steel",
        unit: "-",
        low: 0.45,
        high: 0.76,
        setting: Setting::StalkRollingFriction,
    },
    PlantFactor {
        label: "x3",
        description: "restitution, pod stalk–steel",
        unit: "-",
        low: 0.16,
        high: 0.33,
        setting: Setting::StalkRestitution,
    },
    PlantFactor {
        label: "x4",
        description: "static friction, pod–steel",
        unit: "-",
        low: 0.42,
        high: 0.68,
        setting: Setting::PodFriction,
    },
    PlantFactor {
        label: "x5",
        description: "rolling friction, pod–steel",
        unit: "-",
        low: 0.32,
        high: 0.54,
        setting: Setting::PodRollingFriction,
    },
    PlantFactor {
        label: "x6",
        description: "restitution, pod–steel",
        unit: "-",
        low: 0.18,
        high: 0.39,
        setting: Setting::PodRestitution,
    },
    PlantFactor {
        label: "x7",
        description: "tangential stiffness per unit area, pod–pod stalk",
        unit: "N/m^3",
        low: 3.0e5,
        high: 7.0e5,
        setting: Setting::JunctionTangentialStiffness,
    },
    PlantFactor {
        label: "x8",
        description: "critical stress (σc = τc), pod–pod stalk",
        unit: "Pa",
        low: 6.0e5,
        high: 14.0e5,
        setting: Setting::JunctionStrength,
    },
    PlantFactor {
        label: "x9",
        description: "bond radius, pod–pod stalk",
        unit: "m",
        low: 1.0e-3,
        high: 1.2e-3,
        setting: Setting::JunctionBondRadius,
    },
];

/// Seed 001's significant screening factors (Table 7: p < 0.05), most significant first.
pub const SEED_SIGNIFICANT: [&str; 4] = ["x8", "x7", "x2", "x4"];
/// Seed 001's factors carried to the response surface (Table 7: p ≤ 0.01).
pub const SEED_CARRIED: [&str; 2] = ["x7", "x8"];

impl PlantFactor {
    /// The `doe` factor (named by its label).
    pub fn factor(&self) -> Result<Factor, DesignError> {
        Factor::new(self.label, self.unit, self.low, self.high)
    }

    /// The range centre (the held value of an uncarried factor).
    pub fn centre(&self) -> f64 {
        0.5 * (self.low + self.high)
    }

    /// Why `value` cannot be set, if it cannot: friction ≥ 0, restitution in (0, 1],
    /// stiffness, strength and radius > 0.
    pub fn check(&self, value: f64) -> Result<(), String> {
        let ok = value.is_finite()
            && match self.setting {
                Setting::StalkFriction
                | Setting::StalkRollingFriction
                | Setting::PodFriction
                | Setting::PodRollingFriction => value >= 0.0,
                Setting::StalkRestitution | Setting::PodRestitution => value > 0.0 && value <= 1.0,
                Setting::JunctionTangentialStiffness
                | Setting::JunctionStrength
                | Setting::JunctionBondRadius => value > 0.0,
            };
        if ok {
            Ok(())
        } else {
            Err(format!(
                "{} ({}) = {value} {} is outside its physical limits",
                self.label, self.description, self.unit
            ))
        }
    }

    /// Sets `value` (in [`Self::unit`]) in `rig`.
    pub fn apply(&self, rig: &mut PullOff, value: f64) {
        match self.setting {
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

/// The factor labelled `label`.
pub fn by_label(label: &str) -> Option<&'static PlantFactor> {
    TABLE5.iter().find(|f| f.label == label)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn apply_sets_only_its_property() {
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
    }

    #[test]
    fn limits_refuse_unphysical_values() {
        assert!(by_label("x3").unwrap().check(1.2).is_err());
        assert!(by_label("x9").unwrap().check(0.0).is_err());
        assert!(by_label("x1").unwrap().check(0.0).is_ok());
    }
}
