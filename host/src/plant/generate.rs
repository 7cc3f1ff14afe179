//! From a checked [`Topology`] to spheres, bodies and named bonds ([`PlantModel`]), and from
//! there into a core world ([`PlantModel::load_into`]).
//!
//! Stems, laterals, stalks and leaves are straight chains of n = max(2, round(L/D)) touching
//! spheres of radius D/2 (one body each), grown from the attachment point: the child's first
//! sphere touches the parent's sphere nearest to the point `at·L` along the parent and is
//! bonded to it. Chain neighbours are bonded with the part's own set (`stem`, `stalk`,
//! `leaf`), attachments with `stem` (lateral), `stalk_stem`, `stem_leaf` or `pod_stalk`.
//!
//! A pod is one clump: the normal pod of `crate::shapes` (two ellipsoidal kernels with a
//! waist, seed 000 §2.2) of the topology's L × W × H (default seed 001 Table 1:
//! 34.27 × 18.29 × 15.76 mm), filled with `dimensions.pod_spheres` spheres
//! ([`fill_with_spheres`], deterministic). The filling is computed once per plant and placed
//! at every stalk end with its length along the stalk's direction and its width
//! perpendicular to it and to world z (world x when the stalk is vertical). The pod sphere
//! reaching furthest toward the stalk — the tip sphere — sits on the stalk axis and carries
//! the `pod_stalk` bond. Bonded neighbours are placed with a 1 µm gap so nothing overlaps at
//! set-up.

use std::collections::BTreeMap;

use arachis_core::body::{clump_mass_properties, MassProperties, MassSphere, DEFAULT_MASS_GRID};
use arachis_core::bond::{BondSetId, BondSetSpec};
use arachis_core::prelude::*;
use arachis_core::units::{LENGTH_M_TO_MM as MM_PER_M, MASS_KG_TO_G as GRAMS_PER_KG};

use super::error::PlantError;
use super::topology::{Dimensions, Kind, Topology};
use crate::shapes::{fill_with_spheres, FillOptions, FillTarget, PodKind, PodShape, Sphere};

/// Gap between neighbouring spheres at set-up, mm.
pub(crate) const GAP_MM: f64 = 0.001;
/// Density at which a pod's sphere union is integrated before its mass is scaled to the
/// stated pod mass, kg/m³ (any positive value gives the same scaled result).
const REFERENCE_DENSITY_KG_M3: f64 = 1000.0;

/// One sphere of the plant (SI).
#[derive(Debug, Clone, PartialEq)]
pub struct PlantSphere {
    /// Centre, m.
    pub centre_m: [f64; 3],
    /// Radius, m.
    pub radius_m: f64,
    /// Index of its body in [`PlantModel::bodies`].
    pub body: usize,
}

/// One rigid body: a chain sphere or a pod clump.
#[derive(Debug, Clone, PartialEq)]
pub struct PlantBody {
    /// Name of the part it belongs to.
    pub part: String,
    /// Kind of that part.
    pub kind: Kind,
    /// Its spheres (indices into [`PlantModel::spheres`]).
    pub spheres: Vec<usize>,
}

/// One bond between two spheres, with the name of its set.
#[derive(Debug, Clone, PartialEq)]
pub struct PlantBond {
    /// First sphere.
    pub a: usize,
    /// Second sphere.
    pub b: usize,
    /// Bond-set name.
    pub set: &'static str,
}

/// A generated plant.
#[derive(Debug, Clone, PartialEq)]
pub struct PlantModel {
    /// Spheres, body by body.
    pub spheres: Vec<PlantSphere>,
    /// Bodies in generation order (parents before children); body 0 is the stem root.
    pub bodies: Vec<PlantBody>,
    /// Bonds.
    pub bonds: Vec<PlantBond>,
    /// Bond sets used, by name (from the topology).
    pub sets: BTreeMap<&'static str, BondSetSpec>,
    /// Mass of each pod, kg, when the topology states it (`dimensions.pod_mass_g`).
    pub pod_mass_kg: Option<f64>,
}

/// Where a placed part lies: its sphere indices and unit direction.
struct Placed {
    spheres: Vec<usize>,
    dir: [f64; 3],
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|x| x / n)
}

fn along(p: [f64; 3], u: [f64; 3], s: f64) -> [f64; 3] {
    [p[0] + u[0] * s, p[1] + u[1] * s, p[2] + u[2] * s]
}

/// Generate the plant of `t` (checked again here).
pub fn generate(t: &Topology) -> Result<PlantModel, PlantError> {
    t.check()?;
    let d = &t.dimensions;
    let mut m = PlantModel {
        spheres: Vec::new(),
        bodies: Vec::new(),
        bonds: Vec::new(),
        sets: BTreeMap::new(),
        pod_mass_kg: d.pod_mass_g.map(|g| g / GRAMS_PER_KG),
    };
    let pod = pod_filling(d)?;
    let mut placed: BTreeMap<&str, Placed> = BTreeMap::new();
    let mut remaining: Vec<&super::topology::Part> = t.parts.iter().collect();
    while !remaining.is_empty() {
        let before = remaining.len();
        let mut k = 0;
        while k < remaining.len() {
            let p = remaining[k];
            let parent = p.parent.as_deref().and_then(|n| placed.get(n));
            if p.kind != Kind::MainStem && parent.is_none() {
                k += 1;
                continue;
            }
            let u = unit(p.direction);
            let (spheres, set_attach) = match p.kind {
                Kind::Pod => {
                    let parent = parent.expect("checked above");
                    let end = *parent.spheres.last().expect("chains have ≥ 2 spheres");
                    let e = m.spheres[end].clone();
                    let body = m.bodies.len();
                    let first = m.spheres.len();
                    let (centres, tip) = place_pod(
                        &pod,
                        e.centre_m.map(|x| x * MM_PER_M),
                        e.radius_m * MM_PER_M,
                        parent.dir,
                    );
                    for (c, s) in centres.iter().zip(&pod) {
                        m.spheres.push(PlantSphere {
                            centre_m: c.map(|x| x / MM_PER_M),
                            radius_m: s.radius_mm / MM_PER_M,
                            body,
                        });
                    }
                    let members: Vec<usize> = (first..first + pod.len()).collect();
                    m.bodies.push(PlantBody {
                        part: p.name.clone(),
                        kind: p.kind,
                        spheres: members.clone(),
                    });
                    m.bonds.push(PlantBond {
                        a: end,
                        b: first + tip,
                        set: "pod_stalk",
                    });
                    placed.insert(
                        &p.name,
                        Placed {
                            spheres: members,
                            dir: parent.dir,
                        },
                    );
                    remaining.remove(k);
                    continue;
                }
                Kind::MainStem => (
                    chain(d.stem_length_mm, d.stem_diameter_mm, p.length_mm),
                    None,
                ),
                Kind::LateralStem => (
                    chain(d.lateral_length_mm, d.stem_diameter_mm, p.length_mm),
                    Some("stem"),
                ),
                Kind::PodStalk => (
                    chain(d.stalk_length_mm, d.stalk_diameter_mm, p.length_mm),
                    Some("stalk_stem"),
                ),
                Kind::Leaf => (
                    chain(d.leaf_length_mm, d.leaf_diameter_mm, p.length_mm),
                    Some("stem_leaf"),
                ),
            };
            let (n, r_mm) = spheres;
            let internal = match p.kind {
                Kind::MainStem | Kind::LateralStem => "stem",
                Kind::PodStalk => "stalk",
                _ => "leaf",
            };
            // Start point and the parent sphere to bond to.
            let (start, anchor) = match parent {
                None => ([0.0; 3], None),
                Some(par) => {
                    let idx =
                        par.spheres[((p.at * (par.spheres.len() - 1) as f64).round()) as usize];
                    let s = &m.spheres[idx];
                    let c = s.centre_m.map(|x| x * MM_PER_M);
                    (
                        along(c, u, s.radius_m * MM_PER_M + GAP_MM + r_mm),
                        Some(idx),
                    )
                }
            };
            let body0 = m.bodies.len();
            let first = m.spheres.len();
            for i in 0..n {
                let c = along(start, u, i as f64 * (2.0 * r_mm + GAP_MM));
                m.spheres.push(PlantSphere {
                    centre_m: c.map(|x| x / MM_PER_M),
                    radius_m: r_mm / MM_PER_M,
                    body: body0 + i,
                });
                m.bodies.push(PlantBody {
                    part: p.name.clone(),
                    kind: p.kind,
                    spheres: vec![first + i],
                });
                if i > 0 {
                    m.bonds.push(PlantBond {
                        a: first + i - 1,
                        b: first + i,
                        set: internal,
                    });
                }
            }
            if let (Some(a), Some(set)) = (anchor, set_attach) {
                m.bonds.push(PlantBond { a, b: first, set });
            }
            placed.insert(
                &p.name,
                Placed {
                    spheres: (first..first + n).collect(),
                    dir: u,
                },
            );
            remaining.remove(k);
        }
        if remaining.len() == before {
            return Err(PlantError::Unconnected(remaining[0].name.clone()));
        }
    }
    for b in &m.bonds {
        if !m.sets.contains_key(b.set) {
            let s = t
                .bonds
                .get(b.set)
                .ok_or(PlantError::MissingBondSet(b.set))?;
            m.sets.insert(
                b.set,
                BondSetSpec {
                    tag: 0,
                    normal_stiffness_n_m3: s.kn_n_m3,
                    tangential_stiffness_n_m3: s.kt_n_m3,
                    normal_strength_pa: s.sigma_c_pa,
                    tangential_strength_pa: s.tau_c_pa,
                    radius_m: s.radius_m,
                },
            );
        }
    }
    // A defined set no bond uses is a typo of one that is used (`[bonds.stemm]` was once
    // accepted silently).
    if let Some(unused) = t.bonds.keys().find(|k| !m.sets.contains_key(k.as_str())) {
        return Err(PlantError::UnusedBondSet {
            set: unused.clone(),
            used: m.sets.keys().copied().collect::<Vec<_>>().join(", "),
        });
    }
    // Tags in name order, so the host can map break records back to set names.
    for (tag, spec) in m.sets.values_mut().enumerate() {
        spec.tag = tag as u16;
    }
    Ok(m)
}

/// The normal pod of `d`'s L × W × H filled with `d.pod_spheres` spheres, body frame, mm
/// (origin at the pod's centre, z along the length, x along the width, y along the
/// thickness: `crate::shapes`).
pub fn pod_filling(d: &Dimensions) -> Result<Vec<Sphere>, PlantError> {
    let shape_err = |e: crate::shapes::ShapeError| PlantError::PodShape(e.to_string());
    let shape = PodShape::new(
        PodKind::Normal,
        d.pod_length_mm,
        d.pod_width_mm,
        d.pod_thickness_mm,
    )
    .map_err(shape_err)?;
    let filling = fill_with_spheres(
        &shape,
        &FillOptions {
            resolution: d.pod_fill_resolution,
            target: FillTarget::SphereCount(d.pod_spheres),
        },
    )
    .map_err(shape_err)?;
    if filling.spheres.is_empty() {
        return Err(PlantError::PodShape("the filling has no sphere".into()));
    }
    Ok(filling.spheres)
}

/// World centres (mm) of the pod spheres `pod` hung from a stalk end sphere at `end_mm`
/// of radius `end_r_mm` along unit `dir`, and the index of the tip sphere (the one whose
/// surface reaches lowest along body z, i.e. toward the stalk): the body frame is rotated
/// so z → `dir`, x → a unit vector ⊥ `dir` and world z, y → `dir` × x, and shifted so the
/// tip sphere's centre lies on the stalk axis with a [`GAP_MM`] gap to the end sphere. No
/// other pod sphere reaches below the tip sphere's lowest point, so none overlaps the
/// stalk's end sphere.
fn place_pod(
    pod: &[Sphere],
    end_mm: [f64; 3],
    end_r_mm: f64,
    dir: [f64; 3],
) -> (Vec<[f64; 3]>, usize) {
    let tip = (0..pod.len())
        .min_by(|&a, &b| {
            let low = |s: &Sphere| s.centre_mm[2] - s.radius_mm;
            low(&pod[a]).total_cmp(&low(&pod[b]))
        })
        .expect("pod_filling never returns an empty pod");
    let reference = if dir[2].abs() > VERTICAL_COSINE {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 0.0, 1.0]
    };
    let ex = unit(cross(dir, reference));
    let ey = cross(dir, ex);
    let to_world = |p: [f64; 3]| -> [f64; 3] {
        core::array::from_fn(|k| ex[k] * p[0] + ey[k] * p[1] + dir[k] * p[2])
    };
    let t = &pod[tip];
    let anchor = along(end_mm, dir, end_r_mm + GAP_MM + t.radius_mm);
    let tip_world = to_world(t.centre_mm);
    let centres = pod
        .iter()
        .map(|s| {
            let w = to_world(s.centre_mm);
            core::array::from_fn(|k| anchor[k] + w[k] - tip_world[k])
        })
        .collect();
    (centres, tip)
}

/// |cos| between a stalk direction and world z above which the stalk counts as vertical
/// (the pod's width axis is then taken ⊥ world x instead of world z).
const VERTICAL_COSINE: f64 = 0.99;

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Sphere count and radius (mm) of a chain of length `l` and diameter `dia`.
fn chain(l: f64, dia: f64, over: Option<f64>) -> (usize, f64) {
    let l = over.unwrap_or(l);
    (chain_spheres(l, dia), dia / 2.0)
}

/// Spheres of a chain part of length `length_mm` and diameter `diameter_mm`:
/// n = max(2, round(L/D)); neighbours lie one pitch D + [`GAP_MM`] apart.
pub(crate) fn chain_spheres(length_mm: f64, diameter_mm: f64) -> usize {
    ((length_mm / diameter_mm).round() as usize).max(2)
}

/// Mass properties of the union of `spheres` with its mass set to `mass_kg`: the union is
/// integrated at a reference density ([`clump_mass_properties`]) and its mass and moments
/// scaled by one factor, so the centre of mass and principal axes are the union's own.
fn scaled_mass(spheres: &[ClumpSphere], mass_kg: f64) -> Result<MassProperties, SetupError> {
    let mut props = union_mass(spheres, REFERENCE_DENSITY_KG_M3)?;
    let k = mass_kg / props.mass_kg;
    props.mass_kg = mass_kg;
    props.principal_inertia_kg_m2 = props.principal_inertia_kg_m2.map(|i| i * k);
    Ok(props)
}

/// Mass properties of the union of `spheres` at `density_kg_m3`.
fn union_mass(spheres: &[ClumpSphere], density_kg_m3: f64) -> Result<MassProperties, SetupError> {
    let union: Vec<MassSphere> = spheres
        .iter()
        .map(|s| MassSphere {
            center_m: s.center_m,
            radius_m: s.radius_m,
            density_kg_m3,
        })
        .collect();
    clump_mass_properties(&union, DEFAULT_MASS_GRID)
}

impl PlantModel {
    /// Number of pod bodies.
    pub fn pods(&self) -> usize {
        self.bodies.iter().filter(|b| b.kind == Kind::Pod).count()
    }

    /// Number of bonds of the named set.
    pub fn bond_count(&self, set: &str) -> usize {
        self.bonds.iter().filter(|b| b.set == set).count()
    }

    /// Bond-set name of a tag (as stored in break records).
    pub fn set_name(&self, tag: u16) -> Option<&'static str> {
        self.sets.keys().nth(tag as usize).copied()
    }

    /// Adds pod `body` (an index into [`PlantModel::bodies`]) to `world` as one clump of
    /// `material`, at rest: of `mass_kg` when given (its moments scaled with it), else of the
    /// material's density.
    pub fn add_pod<S: Scalar>(
        &self,
        world: &mut World<'_, S>,
        body: usize,
        material: MaterialId,
        mass_kg: Option<f64>,
    ) -> Result<BodyId, PlantError> {
        let spheres = self.pod_spheres(body, material);
        let spec = ClumpSpec {
            spheres: &spheres,
            velocity_m_s: [0.0; 3],
            angular_velocity_rad_s: [0.0; 3],
        };
        match mass_kg {
            None => world.add_clump(&spec),
            Some(kg) => {
                scaled_mass(&spheres, kg).and_then(|mass| world.add_clump_with_mass(&spec, &mass))
            }
        }
        .map_err(|e| PlantError::Core(e.to_string()))
    }

    /// The mass of pod `body`, kg: the variety's pod mass when the topology states one, else
    /// the volume of its spheres' union at `density_kg_m3`.
    pub fn pod_mass_or(&self, body: usize, density_kg_m3: f64) -> Result<f64, PlantError> {
        if let Some(kg) = self.pod_mass_kg {
            return Ok(kg);
        }
        // The spheres' material plays no part in their union's volume.
        union_mass(&self.pod_spheres(body, MaterialId(0)), density_kg_m3)
            .map(|props| props.mass_kg)
            .map_err(|e| PlantError::Core(e.to_string()))
    }

    fn pod_spheres(&self, body: usize, material: MaterialId) -> Vec<ClumpSphere> {
        self.bodies[body]
            .spheres
            .iter()
            .map(|&i| ClumpSphere {
                center_m: self.spheres[i].centre_m,
                radius_m: self.spheres[i].radius_m,
                material,
            })
            .collect()
    }

    /// Add the plant to `world` (stems, stalks and leaves of `plant_material`, pods of
    /// `pod_material`): spheres, pod clumps, bond sets and bonds. The world needs bond storage
    /// for [`PlantModel::bonds`]. Returns the body id of the stem root (the caller may clamp
    /// it with `set_body_kinematic`).
    pub fn load_into<S: Scalar>(
        &self,
        world: &mut World<'_, S>,
        plant_material: MaterialId,
        pod_material: MaterialId,
    ) -> Result<BodyId, PlantError> {
        let sets = self.add_bond_sets(world)?;
        self.load_sharing_sets(world, plant_material, pod_material, &sets)
    }

    /// Adds the plant's bond sets to `world`, by name (plants of one variety share them: a
    /// world holds at most 16 sets).
    pub fn add_bond_sets<S: Scalar>(
        &self,
        world: &mut World<'_, S>,
    ) -> Result<BTreeMap<&'static str, BondSetId>, PlantError> {
        self.sets
            .iter()
            .map(|(&name, spec)| {
                world
                    .add_bond_set(spec)
                    .map(|id| (name, id))
                    .map_err(|e| PlantError::Core(e.to_string()))
            })
            .collect()
    }

    /// As [`PlantModel::load_into`], with bond sets already in the world (`sets`, by name,
    /// from [`PlantModel::add_bond_sets`] of a plant with the same sets).
    pub fn load_sharing_sets<S: Scalar>(
        &self,
        world: &mut World<'_, S>,
        plant_material: MaterialId,
        pod_material: MaterialId,
        sets: &BTreeMap<&'static str, BondSetId>,
    ) -> Result<BodyId, PlantError> {
        let core = |e: &dyn std::fmt::Display| PlantError::Core(e.to_string());
        let ids = sets;
        if let Some(missing) = self.sets.keys().find(|name| !ids.contains_key(*name)) {
            return Err(PlantError::Core(format!(
                "bond set {missing} is not in the world"
            )));
        }
        let first_sphere = world.spheres().len();
        let mut root = None;
        for (i, b) in self.bodies.iter().enumerate() {
            let id = if b.kind == Kind::Pod {
                self.add_pod(world, i, pod_material, self.pod_mass_kg)?
            } else {
                let s = &self.spheres[b.spheres[0]];
                world
                    .add_sphere(SphereSpec::at_rest(plant_material, s.radius_m, s.centre_m))
                    .map_err(|e| core(&e))?
            };
            root.get_or_insert(id);
        }
        for b in &self.bonds {
            world
                .add_bond(
                    (first_sphere + b.a) as u32,
                    (first_sphere + b.b) as u32,
                    ids[b.set],
                )
                .map_err(|e| core(&e))?;
        }
        root.ok_or(PlantError::MainStemCount(0))
    }
}
