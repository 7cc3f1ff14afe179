//! The registry of calibratable parameters, and the ranges a study varies them over.
//!
//! [`REGISTRY`] is the one table of every parameter a study may vary. A parameter is named
//! `<owner>.<property>`, where the owner is a material (`pod`) or a contact pair
//! (`pod-pod`, `pod-steel`) and the property is the key of that material or pair in the
//! study file, so `pod-pod.static_friction` varies `[pairs."pod-pod"] static_friction`.
//! Each entry carries the label seed 000 Table 3 gives it (x1…x8), which reports use as a
//! short name. Later physical effects (cohesion, drag, …, issue 5) and the plant's bonds
//! (issue 6) add rows here; nothing else needs to change.
//!
//! In the file a range is `[parameters."pod-pod.static_friction"] low = 0.837, high = 0.878`
//! (seed 000 Table 3, x4), in the units the name states (SI; `_pa` is pascals).
//!
//! ```
//! use arachis::study::parameters::lookup;
//! let x4 = lookup("pod-pod.static_friction").unwrap();
//! assert_eq!(x4.label, "x4");
//! assert!(x4.limits.check(-0.1).is_err());
//! ```

use serde::{Deserialize, Serialize};

use crate::limits::Limits;
use crate::rigs::parameter::Parameter;

/// What a parameter sets: a property of a material or of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Owner {
    /// A `[materials.<name>]` table.
    Material(&'static str),
    /// A `[pairs."<a>-<b>"]` table.
    Pair(&'static str),
}

/// What a pod-world parameter sets: `property` of the material or pair `owner`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Property {
    /// The material or pair it belongs to.
    pub owner: Owner,
    /// The key of the property in the owner's table.
    pub property: &'static str,
}

/// One calibratable parameter of the pod world.
pub type ParameterSpec = Parameter<Property>;

/// Every calibratable parameter, in seed 000 Table 3 order (x1…x8). A diagnosis varies
/// each by a hundredth of a coefficient (0.1 MPa for the shear modulus), far above the
/// fixed-point resolution and inside the screened ranges.
pub const REGISTRY: [ParameterSpec; 8] = [
    ParameterSpec {
        name: "pod.poisson",
        label: "x1",
        description: "Poisson's ratio of peanut pods",
        unit: "-",
        sets: Property {
            owner: Owner::Material("pod"),
            property: "poisson",
        },
        limits: Limits::Poisson,
        fd_step: 0.01,
        scale: 0.4,
    },
    ParameterSpec {
        name: "pod.shear_modulus_pa",
        label: "x2",
        description: "shear modulus of peanut pods",
        unit: "Pa",
        sets: Property {
            owner: Owner::Material("pod"),
            property: "shear_modulus_pa",
        },
        limits: Limits::Positive,
        fd_step: 1.0e5,
        scale: 3.0e6,
    },
    ParameterSpec {
        name: "pod-pod.restitution",
        label: "x3",
        description: "pod–pod coefficient of restitution",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "restitution",
        },
        limits: Limits::Restitution,
        fd_step: 0.01,
        scale: 0.3,
    },
    ParameterSpec {
        name: "pod-pod.static_friction",
        label: "x4",
        description: "pod–pod coefficient of static friction",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "static_friction",
        },
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.85,
    },
    ParameterSpec {
        name: "pod-pod.rolling_friction",
        label: "x5",
        description: "pod–pod coefficient of rolling friction",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "rolling_friction",
        },
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.3,
    },
    ParameterSpec {
        name: "pod-steel.restitution",
        label: "x6",
        description: "pod–65Mn steel coefficient of restitution",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-steel"),
            property: "restitution",
        },
        limits: Limits::Restitution,
        fd_step: 0.01,
        scale: 0.3,
    },
    ParameterSpec {
        name: "pod-steel.static_friction",
        label: "x7",
        description: "pod–65Mn steel coefficient of static friction",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-steel"),
            property: "static_friction",
        },
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.6,
    },
    ParameterSpec {
        name: "pod-steel.rolling_friction",
        label: "x8",
        description: "pod–65Mn steel coefficient of rolling friction",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-steel"),
            property: "rolling_friction",
        },
        limits: Limits::Friction,
        fd_step: 0.01,
        scale: 0.16,
    },
];

/// The optional physical effects of the pod world (issue 22), each a key of a pair's table,
/// off at 0: never a factor of a calibration plan, offered by a diagnosis as candidates for
/// what the model lacks. Their finite-difference steps are large enough to move a quick
/// pile by more than its fixed-point noise; common random numbers take care of the
/// placement scatter (`diagnose::model`).
pub const EFFECTS: [ParameterSpec; 3] = [
    ParameterSpec {
        name: "pod-pod.cohesion_j_m3",
        label: "cohesion",
        description: "pod–pod SJKR cohesion, attraction k × contact area (LIGGGHTS sjkr)",
        unit: "J/m^3",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "cohesion_j_m3",
        },
        limits: Limits::NonNegative,
        fd_step: 2.0e3,
        scale: 1.0e4,
    },
    ParameterSpec {
        name: "pod-pod.epsd_rolling_friction",
        label: "epsd_rolling",
        description: "pod–pod EPSD rolling resistance on top of the rolling friction, torque \
                      limit μr·R*·Fn (Ai et al. 2011 type C)",
        unit: "-",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "epsd_rolling_friction",
        },
        limits: Limits::NonNegative,
        fd_step: 0.02,
        scale: 0.1,
    },
    ParameterSpec {
        name: "pod-pod.viscoelastic_time_s",
        label: "viscoelastic",
        description: "pod–pod viscoelastic damping, restitution falling with impact speed \
                      (Brilliantov et al. 1996)",
        unit: "s",
        sets: Property {
            owner: Owner::Pair("pod-pod"),
            property: "viscoelastic_time_s",
        },
        limits: Limits::NonNegative,
        fd_step: 2.0e-6,
        scale: 1.0e-5,
    },
];

/// The registry entry named `name` (a calibratable parameter, seed 000 Table 3).
pub fn lookup(name: &str) -> Option<&'static ParameterSpec> {
    REGISTRY.iter().find(|p| p.name == name)
}

/// The registry entry or optional effect named `name`: anything a run's values may set.
pub fn lookup_any(name: &str) -> Option<&'static ParameterSpec> {
    lookup(name).or_else(|| EFFECTS.iter().find(|p| p.name == name))
}

/// The optional effect setting `property` of pair `pair`, if one is registered.
pub fn effect_for(pair: &str, property: &str) -> Option<&'static ParameterSpec> {
    EFFECTS.iter().find(|p| {
        p.sets.property == property && matches!(p.sets.owner, Owner::Pair(o) if o == pair)
    })
}

/// The registry entry setting `property` of `owner` (a material or pair name).
pub fn for_property(owner: &str, property: &str) -> Option<&'static ParameterSpec> {
    REGISTRY.iter().find(|p| {
        p.sets.property == property
            && match p.sets.owner {
                Owner::Material(m) | Owner::Pair(m) => m == owner,
            }
    })
}

/// Every registered name, in registry order.
pub fn names() -> Vec<&'static str> {
    REGISTRY.iter().map(|p| p.name).collect()
}

/// How far a study varies one parameter: `[parameters."<name>"]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParameterRange {
    /// Low level (coded −1), in the parameter's unit.
    pub low: f64,
    /// High level (coded +1), in the parameter's unit.
    pub high: f64,
    /// Report label; defaults to the registry's (seed 000 Table 3's x-label).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// Accept a Poisson-ratio range reaching [0.5, 1) (beyond the isotropic-elastic limit,
    /// within the contact model's; see [`Limits::PoissonContactModel`]). Only for Poisson
    /// ratios.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub poisson_above_half: bool,
    /// Where the range comes from (free text, e.g. "seed 000 §3.2.2").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

impl ParameterRange {
    /// The limits this range is checked against: the parameter's, widened for a Poisson
    /// ratio when `poisson_above_half` is set.
    pub fn limits(&self, spec: &ParameterSpec) -> Limits {
        if spec.limits == Limits::Poisson && self.poisson_above_half {
            Limits::PoissonContactModel
        } else {
            spec.limits
        }
    }

    /// Centre level (coded 0): (low + high)/2.
    pub fn centre(&self) -> f64 {
        0.5 * (self.low + self.high)
    }
}
