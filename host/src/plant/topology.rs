//! The topology file (TOML), read with `serde` + `toml` and checked by [`Topology::check`].
//!
//! ```toml
//! [bonds.pod_stalk]            # one table per named set used by the plant
//! kn_n_m3 = 1.3e10
//! kt_n_m3 = 5.3e9
//! sigma_c_pa = 9.35e5
//! tau_c_pa = 9.35e5
//! radius_m = 1.1e-3            # seed 001 Table 4
//!
//! [[part]]
//! name = "stem"
//! kind = "main_stem"
//! direction = [0, 0, 1]
//!
//! [[part]]
//! name = "stalk1"
//! kind = "pod_stalk"
//! parent = "stem"
//! at = 0.2                     # fraction of the parent's length
//! direction = [1, 0, -1]
//!
//! [[part]]
//! name = "pod1"
//! kind = "pod"
//! parent = "stalk1"
//! ```

use std::collections::BTreeMap;

use serde::Deserialize;

use super::error::PlantError;
use crate::plausible::PLANT_ORGAN_MM;

/// Part kinds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// The main stem (exactly one; its first sphere is the root).
    MainStem,
    /// A lateral stem on a stem.
    LateralStem,
    /// A pod stalk (peg) on a stem; must carry a pod.
    PodStalk,
    /// A pod at the end of a pod stalk.
    Pod,
    /// A simplified leaf on a stem.
    Leaf,
}

impl Kind {
    /// Name as written in the file.
    pub fn name(self) -> &'static str {
        match self {
            Kind::MainStem => "main_stem",
            Kind::LateralStem => "lateral_stem",
            Kind::PodStalk => "pod_stalk",
            Kind::Pod => "pod",
            Kind::Leaf => "leaf",
        }
    }
    /// Whether this kind may hang on `parent`.
    pub fn may_attach_to(self, parent: Kind) -> bool {
        let stem = matches!(parent, Kind::MainStem | Kind::LateralStem);
        match self {
            Kind::MainStem => false,
            Kind::LateralStem | Kind::PodStalk | Kind::Leaf => stem,
            Kind::Pod => parent == Kind::PodStalk,
        }
    }
}

/// Default spheres per pod: enough for the normal pod's two lobes and waist, few enough
/// that a plant of tens of pods steps cheaply (seed 001 prints no pod sphere count).
pub const DEFAULT_POD_SPHERES: usize = 5;
/// Most spheres per pod.
pub const MAX_POD_SPHERES: usize = 64;
/// Default fill resolution, voxels along the pod length (about 1.1 mm voxels).
pub const DEFAULT_POD_FILL_RESOLUTION: usize = 32;
/// Coarsest fill resolution (a coarser grid cannot tell the waist from the lobes).
pub const MIN_POD_FILL_RESOLUTION: usize = 8;
/// Finest fill resolution (the filling's cost grows with its cube).
pub const MAX_POD_FILL_RESOLUTION: usize = 128;

/// Dimensions, mm (defaults: seed 001 Table 1; leaf: assumed, the seed gives none).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Dimensions {
    /// Main stem length L, mm (763.81).
    pub stem_length_mm: f64,
    /// Stem diameter D, mm (6.74).
    pub stem_diameter_mm: f64,
    /// Lateral stem length, mm (assumed: half the main stem).
    pub lateral_length_mm: f64,
    /// Pod stalk length, mm (108.26).
    pub stalk_length_mm: f64,
    /// Pod stalk diameter, mm (1.93).
    pub stalk_diameter_mm: f64,
    /// Pod length L, mm (34.27).
    pub pod_length_mm: f64,
    /// Pod width W, mm (18.29).
    pub pod_width_mm: f64,
    /// Pod thickness H, mm (15.76).
    pub pod_thickness_mm: f64,
    /// Spheres filling each pod (a normal pod of `crate::shapes`, L × W × H), 1 to
    /// [`MAX_POD_SPHERES`]; default [`DEFAULT_POD_SPHERES`] (few, so plants stay cheap).
    pub pod_spheres: usize,
    /// Voxels along the pod's length for the filling (`crate::shapes::FillOptions`),
    /// [`MIN_POD_FILL_RESOLUTION`] to [`MAX_POD_FILL_RESOLUTION`]; default
    /// [`DEFAULT_POD_FILL_RESOLUTION`].
    pub pod_fill_resolution: usize,
    /// Leaf length, mm (assumed 40).
    pub leaf_length_mm: f64,
    /// Leaf sphere diameter, mm (assumed 4).
    pub leaf_diameter_mm: f64,
    /// Mass of each pod, g. When given, every pod clump gets this mass (its inertia scaled
    /// with it); when not, the mass of its spheres' union at the pod material's density.
    pub pod_mass_g: Option<f64>,
}

impl Default for Dimensions {
    fn default() -> Self {
        Dimensions {
            stem_length_mm: 763.81,
            stem_diameter_mm: 6.74,
            lateral_length_mm: 763.81 / 2.0,
            stalk_length_mm: 108.26,
            stalk_diameter_mm: 1.93,
            pod_length_mm: 34.27,
            pod_width_mm: 18.29,
            pod_thickness_mm: 15.76,
            pod_spheres: DEFAULT_POD_SPHERES,
            pod_fill_resolution: DEFAULT_POD_FILL_RESOLUTION,
            leaf_length_mm: 40.0,
            leaf_diameter_mm: 4.0,
            pod_mass_g: None,
        }
    }
}

/// One bond set (SI).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BondSet {
    /// Normal stiffness per unit area, N/m³.
    pub kn_n_m3: f64,
    /// Tangential stiffness per unit area, N/m³.
    pub kt_n_m3: f64,
    /// Normal critical stress, Pa.
    pub sigma_c_pa: f64,
    /// Tangential critical stress, Pa.
    pub tau_c_pa: f64,
    /// Bond radius, m.
    pub radius_m: f64,
}

/// One part.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Part {
    /// Unique name.
    pub name: String,
    /// Kind.
    pub kind: Kind,
    /// Parent part (all but the main stem).
    #[serde(default)]
    pub parent: Option<String>,
    /// Attachment point as a fraction of the parent's length, in [0, 1] (pods: ignored, they
    /// sit at the stalk's end).
    #[serde(default = "one")]
    pub at: f64,
    /// Growth direction (any length > 0).
    #[serde(default = "up")]
    pub direction: [f64; 3],
    /// Length override, mm.
    #[serde(default)]
    pub length_mm: Option<f64>,
}

fn one() -> f64 {
    1.0
}
fn up() -> [f64; 3] {
    [0.0, 0.0, 1.0]
}

/// A whole topology file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Topology {
    /// Dimensions (defaults: seed 001 Table 1).
    #[serde(default)]
    pub dimensions: Dimensions,
    /// Bond sets by name.
    #[serde(default)]
    pub bonds: BTreeMap<String, BondSet>,
    /// Parts, parents before children.
    #[serde(default, rename = "part")]
    pub parts: Vec<Part>,
}

impl Topology {
    /// Parse and check a topology.
    pub fn from_toml(text: &str) -> Result<Self, PlantError> {
        let t: Topology = toml::from_str(text).map_err(|e| PlantError::Parse(e.to_string()))?;
        t.check()?;
        Ok(t)
    }

    /// Check names, parents, dangling stalks, numbers and bond sets.
    pub fn check(&self) -> Result<(), PlantError> {
        let d = &self.dimensions;
        for (what, v) in [
            ("stem_length_mm", d.stem_length_mm),
            ("stem_diameter_mm", d.stem_diameter_mm),
            ("lateral_length_mm", d.lateral_length_mm),
            ("stalk_length_mm", d.stalk_length_mm),
            ("stalk_diameter_mm", d.stalk_diameter_mm),
            ("pod_length_mm", d.pod_length_mm),
            ("pod_width_mm", d.pod_width_mm),
            ("pod_thickness_mm", d.pod_thickness_mm),
            ("leaf_length_mm", d.leaf_length_mm),
            ("leaf_diameter_mm", d.leaf_diameter_mm),
        ] {
            let what = format!("dimensions.{what}");
            positive(&what, v)?;
            PLANT_ORGAN_MM
                .check(v)
                .map_err(|reason| PlantError::Implausible { what, reason })?;
        }
        if let Some(m) = d.pod_mass_g {
            positive("dimensions.pod_mass_g", m)?;
        }
        for (what, v, lo, hi, rule) in [
            (
                "pod_spheres",
                d.pod_spheres,
                1,
                MAX_POD_SPHERES,
                "a whole number from 1 to 64",
            ),
            (
                "pod_fill_resolution",
                d.pod_fill_resolution,
                MIN_POD_FILL_RESOLUTION,
                MAX_POD_FILL_RESOLUTION,
                "a whole number from 8 to 128",
            ),
        ] {
            if !(lo..=hi).contains(&v) {
                return Err(PlantError::BadValue {
                    what: format!("dimensions.{what}"),
                    rule,
                    value: v as f64,
                });
            }
        }
        for (name, s) in &self.bonds {
            if !(s.radius_m.is_finite() && s.radius_m > 0.0) {
                return Err(PlantError::NonPositiveBondRadius {
                    set: name.clone(),
                    radius_m: s.radius_m,
                });
            }
            for (what, v) in [
                ("kn_n_m3", s.kn_n_m3),
                ("kt_n_m3", s.kt_n_m3),
                ("sigma_c_pa", s.sigma_c_pa),
                ("tau_c_pa", s.tau_c_pa),
            ] {
                positive(&format!("bonds.{name}.{what}"), v)?;
            }
        }
        let mains = self
            .parts
            .iter()
            .filter(|p| p.kind == Kind::MainStem)
            .count();
        if mains != 1 {
            return Err(PlantError::MainStemCount(mains));
        }
        let mut kinds: BTreeMap<&str, Kind> = BTreeMap::new();
        for p in &self.parts {
            if kinds.insert(&p.name, p.kind).is_some() {
                return Err(PlantError::DuplicateName(p.name.clone()));
            }
        }
        for p in &self.parts {
            let n2: f64 = p.direction.iter().map(|x| x * x).sum();
            positive(&format!("part `{}` direction length", p.name), n2.sqrt())?;
            if !(0.0..=1.0).contains(&p.at) {
                return Err(PlantError::BadValue {
                    what: format!("part `{}` at", p.name),
                    rule: "in [0, 1]",
                    value: p.at,
                });
            }
            if let Some(l) = p.length_mm {
                positive(&format!("part `{}` length_mm", p.name), l)?;
            }
            match (&p.parent, p.kind) {
                (None, Kind::MainStem) => {}
                (Some(parent), kind) => {
                    let pk =
                        *kinds
                            .get(parent.as_str())
                            .ok_or_else(|| PlantError::UnknownPart {
                                part: p.name.clone(),
                                parent: parent.clone(),
                            })?;
                    if !kind.may_attach_to(pk) {
                        return Err(PlantError::BadParent {
                            part: p.name.clone(),
                            kind: kind.name(),
                            parent: parent.clone(),
                            parent_kind: pk.name(),
                        });
                    }
                }
                (None, kind) => {
                    return Err(PlantError::UnknownPart {
                        part: format!("{} ({})", p.name, kind.name()),
                        parent: "(none given)".into(),
                    })
                }
            }
        }
        for p in self.parts.iter().filter(|p| p.kind == Kind::PodStalk) {
            let has_pod = self
                .parts
                .iter()
                .any(|c| c.kind == Kind::Pod && c.parent.as_deref() == Some(p.name.as_str()));
            if !has_pod {
                return Err(PlantError::DanglingStalk(p.name.clone()));
            }
        }
        Ok(())
    }
}

fn positive(what: &str, v: f64) -> Result<(), PlantError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(PlantError::BadValue {
            what: what.to_string(),
            rule: "> 0",
            value: v,
        })
    }
}
