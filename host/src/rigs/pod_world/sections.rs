//! The study sections that describe a pod world: `[materials.<name>]` ([`Material`]),
//! `[pods]` ([`Pods`]: the particle material, size, shape mix, optional scanned STLs) or
//! `[spheres]` ([`Spheres`]: sphere particles of one radius or a size distribution) and
//! `[pairs."<a>-<b>"]` ([`Pair`]: contact properties of two materials). Every key is
//! unit-suffixed and in SI (or mm for pod geometry, as the seeds print it); every table
//! denies unknown keys, so a misspelt key is an error rather than an ignored setting.

use std::fmt::Display;
use std::str::FromStr;

use arachis_core::contact::{Conventions, FrictionConvention, RollingConvention};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `[materials.<name>]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Density, kg/m³.
    pub density_kg_m3: f64,
    /// Poisson ratio ν, dimensionless.
    pub poisson: f64,
    /// Shear modulus G, Pa.
    pub shear_modulus_pa: f64,
    /// Where the numbers are printed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

impl Material {
    /// Young's modulus E = 2G(1 + ν), Pa (seed 000 eq. (12) solved for E).
    pub fn youngs_modulus_pa(&self) -> f64 {
        2.0 * self.shear_modulus_pa * (1.0 + self.poisson)
    }
}

/// `[pairs."<a>-<b>"]`. A property may be left out when `[parameters]` varies it; it then
/// takes the range's centre wherever a fixed value is needed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pair {
    /// Coefficient of restitution e, dimensionless.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
    /// Coefficient of static friction μs, dimensionless.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_friction: Option<f64>,
    /// Coefficient of rolling friction μr, dimensionless (CDT form; its meaning depends on
    /// `rolling_convention`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rolling_friction: Option<f64>,
    /// How μr is read: `edem` (the default; T_i = −μr·Fn·L_i·ω̂_i, seed 000 eq. (7)),
    /// `liggghts-cdt` (LIGGGHTS' `rolling_friction cdt`: relative spin, R*, elastic force) or
    /// `liggghts-epsd2` (LIGGGHTS' `rolling_friction epsd2`: a spring torque k_t·R*² on the
    /// relative spin, capped at μr·Fn·R*).
    /// `docs/conventions.md` compares them and says when a μr converts.
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "by_name",
        serialize_with = "name_of"
    )]
    pub rolling_convention: Option<RollingConvention>,
    /// How the Coulomb limit applies: `edem` (the default; spring plus damping capped at
    /// μs·Fn) or `liggghts` (LIGGGHTS' `tangential history`: the spring alone tested).
    #[serde(
        default,
        skip_serializing_if = "Option::is_none",
        deserialize_with = "by_name",
        serialize_with = "name_of"
    )]
    pub friction_convention: Option<FrictionConvention>,
    /// Optional effect: SJKR cohesion energy density k, J/m³ (0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cohesion_j_m3: Option<f64>,
    /// Optional effect: EPSD rolling resistance μr on top of `rolling_friction` (Ai et al.
    /// 2011 type C, no dashpot; 0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epsd_rolling_friction: Option<f64>,
    /// Optional effect: viscoelastic relaxation time A, s (0 or absent: off).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscoelastic_time_s: Option<f64>,
    /// Where the numbers are printed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

/// A convention read by its name, with the accepted names in the error.
fn by_name<'de, D, T>(d: D) -> Result<Option<T>, D::Error>
where
    D: Deserializer<'de>,
    T: FromStr,
    T::Err: Display,
{
    let name = String::deserialize(d)?;
    name.parse()
        .map(Some)
        .map_err(|e| serde::de::Error::custom(format!("'{name}': {e}")))
}

/// A convention written by its name.
fn name_of<S: Serializer, T: Display>(value: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
    match value {
        Some(v) => s.collect_str(v),
        None => s.serialize_none(),
    }
}

/// The contact properties of a pair, in file order.
pub const PAIR_PROPERTIES: [&str; 3] = ["restitution", "static_friction", "rolling_friction"];

/// The optional effects of a pair (off when absent), in file order.
pub const PAIR_EFFECTS: [&str; 3] = [
    "cohesion_j_m3",
    "epsd_rolling_friction",
    "viscoelastic_time_s",
];

impl Pair {
    /// The pair's conventions (EDEM's where the study names none).
    pub fn conventions(&self) -> Conventions {
        Conventions {
            rolling: self.rolling_convention.unwrap_or_default(),
            friction: self.friction_convention.unwrap_or_default(),
        }
    }

    /// The value of property `name` (one of [`PAIR_PROPERTIES`] or [`PAIR_EFFECTS`]).
    pub fn property(&self, name: &str) -> Option<f64> {
        match name {
            "restitution" => self.restitution,
            "static_friction" => self.static_friction,
            "rolling_friction" => self.rolling_friction,
            "cohesion_j_m3" => self.cohesion_j_m3,
            "epsd_rolling_friction" => self.epsd_rolling_friction,
            "viscoelastic_time_s" => self.viscoelastic_time_s,
            _ => None,
        }
    }
}

/// `[pods]`: the particles of the study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pods {
    /// The `[materials]` entry the pods are made of.
    pub material: String,
    /// Pod length L, mm.
    pub length_mm: f64,
    /// Pod width W, mm.
    pub width_mm: f64,
    /// Pod thickness H, mm.
    pub thickness_mm: f64,
    /// Fractions of each harvest-time shape (seed 000 §2.2.1); they sum to 1.
    pub shape_mix: ShapeMix,
    /// Scanned shapes, by shape, relative to the study file. A shape without one is
    /// generated from L × W × H.
    #[serde(default, skip_serializing_if = "StlPaths::is_empty")]
    pub stl: StlPaths,
}

/// `[spheres]`: sphere particles instead of pods (grain, seeds, glass beads, or a
/// cross-check against a code without clumps). Either one radius (`radius_mm`) or a discrete
/// size distribution (`[[spheres.sizes]]`, each a radius and its fraction by number); every
/// pod rig (repose by cylinder lifting, incline, compression, ...) runs on them.
///
/// ```toml
/// [spheres]
/// material = "pod"
/// radius_mm = 4.0
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spheres {
    /// The `[materials]` entry the spheres are made of.
    pub material: String,
    /// Radius of every sphere, mm (when the spheres are of one size).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Size classes by number (when the spheres are of several sizes); fractions sum to 1.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sizes: Vec<SizeClass>,
    /// Where the numbers come from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
}

/// One size class of `[[spheres.sizes]]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SizeClass {
    /// Sphere radius, mm.
    pub radius_mm: f64,
    /// Fraction of the spheres (by number) of this radius, in [0, 1].
    pub fraction: f64,
}

impl Spheres {
    /// The size classes: the one radius with fraction 1, or `sizes` in file order.
    pub fn classes(&self) -> Vec<SizeClass> {
        match self.radius_mm {
            Some(radius_mm) => vec![SizeClass {
                radius_mm,
                fraction: 1.0,
            }],
            None => self.sizes.clone(),
        }
    }
}

/// The particles of a pod world: pods or spheres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Particles<'a> {
    /// `[pods]`.
    Pods(&'a Pods),
    /// `[spheres]`.
    Spheres(&'a Spheres),
}

impl Particles<'_> {
    /// The `[materials]` entry the particles are made of.
    pub fn material(&self) -> &str {
        match self {
            Particles::Pods(p) => &p.material,
            Particles::Spheres(s) => &s.material,
        }
    }

    /// The study section that describes them.
    pub fn section(&self) -> &'static str {
        match self {
            Particles::Pods(_) => "pods",
            Particles::Spheres(_) => "spheres",
        }
    }
}

/// `[pods.shape_mix]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeMix {
    /// Normal pods (two kernels with a waist).
    pub normal: f64,
    /// Cocoon pods.
    pub cocoon: f64,
    /// Single-grain ellipsoidal pods.
    pub single_grain: f64,
}

impl ShapeMix {
    /// (shape key, fraction), in file order.
    pub fn entries(&self) -> [(&'static str, f64); 3] {
        [
            ("normal", self.normal),
            ("cocoon", self.cocoon),
            ("single_grain", self.single_grain),
        ]
    }
}

/// `[pods.stl]`: optional scanned STL file per shape.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StlPaths {
    /// Normal pod scan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<String>,
    /// Cocoon pod scan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cocoon: Option<String>,
    /// Single-grain pod scan.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub single_grain: Option<String>,
}

impl StlPaths {
    /// True when no shape has a scan.
    pub fn is_empty(&self) -> bool {
        self.entries().is_empty()
    }

    /// (shape key, path as written) for every shape that has a scan.
    pub fn entries(&self) -> Vec<(&'static str, &str)> {
        [
            ("normal", &self.normal),
            ("cocoon", &self.cocoon),
            ("single_grain", &self.single_grain),
        ]
        .into_iter()
        .filter_map(|(k, p)| p.as_deref().map(|p| (k, p)))
        .collect()
    }
}
