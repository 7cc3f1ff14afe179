//! A laid-out field in one core world.
//!
//! Materials: stems, stalks and leaves of the stalk material and pods of the pod material of
//! `arachis_core::scenario::pull_off` (seed 001 Tables 2–3, as the pull-off rig and the
//! harvest use), grains of the field file's soil. Pairs: plant–plant and plant–pod as the
//! harvest sets them (so contacts between plants, and between pods of different plants, are
//! on); every soil pair from the field file, each with its JKR work of adhesion. The bed's
//! floor is a plane of soil at the bed's depth (the subsoil); the bed has no side walls, so
//! its edges slump as a ridge's flanks do. Each plant's root sphere is kinematic: the taproot
//! holds it in the subsoil until a digger cuts it. Gravity −z.
//!
//! The time step is [`TIMESTEP_SAFETY`] × the smaller of the contact bound (Rayleigh) and the
//! bond bound.

use arachis_core::effects::EffectSpec;
use arachis_core::prelude::*;
use arachis_core::scenario::materials::GRAVITY_M_S2;
use arachis_core::scenario::pull_off::{POD_CONTACT, POD_MATERIAL, STALK_CONTACT, STALK_MATERIAL};

use super::{ContactValues, Field, FieldSpec};

/// Fraction of the stable time step used (margin under both bounds).
pub const TIMESTEP_SAFETY: f64 = 0.9;

/// Where the field's parts are in the world.
#[derive(Debug, Clone, PartialEq)]
pub struct Loaded {
    /// The root body of each plant (kinematic).
    pub roots: Vec<BodyId>,
    /// Every pod body, plant by plant.
    pub pods: Vec<BodyId>,
    /// The grains' bodies, in [`Field::grains`] order.
    pub grains: Vec<BodyId>,
    /// The bed's floor.
    pub floor: WallId,
    /// The materials of plants (stems, stalks, leaves), pods and soil.
    pub materials: FieldMaterials,
}

/// The field's materials in its world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FieldMaterials {
    /// Stems, stalks and leaves.
    pub plant: MaterialId,
    /// Pods.
    pub pod: MaterialId,
    /// Soil grains.
    pub soil: MaterialId,
}

impl Field {
    /// Storage for this field's world: its bodies and spheres, and the effect history its
    /// soil pairs need.
    pub fn storage_lengths(&self, spec: &FieldSpec) -> StorageLengths {
        self.storage_lengths_with(spec, 0, 0)
    }

    /// [`Field::storage_lengths`] with room for `extra_bodies` more bodies of
    /// `extra_spheres` spheres in all (a machine).
    pub fn storage_lengths_with(
        &self,
        spec: &FieldSpec,
        extra_bodies: usize,
        extra_spheres: usize,
    ) -> StorageLengths {
        let bodies: usize = extra_bodies
            + self
                .plants
                .iter()
                .map(|p| p.model.bodies.len())
                .sum::<usize>()
            + self.grains.len();
        let spheres = self.spheres() + extra_spheres;
        storage_lengths_for(spec, bodies, spheres)
    }

    /// Bonds of every plant.
    pub fn bond_count(&self) -> usize {
        self.plants.iter().map(|p| p.model.bonds.len()).sum()
    }

    /// Puts the field into `world` (which needs [`Field::storage_lengths`] and bond storage
    /// for [`Field::bond_count`] bonds), sets gravity and the time step.
    pub fn load_into<S: Scalar>(
        &self,
        spec: &FieldSpec,
        world: &mut World<'_, S>,
    ) -> Result<Loaded, String> {
        let core = |e: &dyn std::fmt::Display| e.to_string();
        let s = &spec.soil;
        let materials = add_field_materials(spec, world, STALK_MATERIAL, POD_MATERIAL)?;
        let FieldMaterials { plant, pod, soil } = materials;
        let mut roots = Vec::with_capacity(self.plants.len());
        let mut pods = Vec::new();
        // The plants of one variety share their bond sets: the first plant's serve them all.
        let sets = match self.plants.first() {
            Some(p) => p.model.add_bond_sets(world).map_err(|e| core(&e))?,
            None => Default::default(),
        };
        for p in &self.plants {
            let first = world.bodies().len() as u32;
            let root = p
                .model
                .load_sharing_sets(world, plant, pod, &sets)
                .map_err(|e| core(&e))?;
            world.set_body_kinematic(root).map_err(|e| core(&e))?;
            roots.push(root);
            pods.extend(
                p.model
                    .bodies
                    .iter()
                    .enumerate()
                    .filter(|(_, b)| b.kind == crate::plant::topology::Kind::Pod)
                    .map(|(i, _)| BodyId(first + i as u32)),
            );
        }
        let grains = self
            .grains
            .iter()
            .map(|g| {
                world
                    .add_sphere(SphereSpec::at_rest(soil, g.radius_m, g.centre_m))
                    .map_err(|e| core(&e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let floor = add_floor(world, self.bed_min_m, soil)?;
        set_safe_timestep(world)?;
        for &g in &grains {
            world.set_body_slow(g, true).map_err(|e| core(&e))?;
        }
        world
            .set_slow_stride(soil_stride(s.slow_stride, world))
            .map_err(|e| core(&e))?;
        Ok(Loaded {
            roots,
            pods,
            grains,
            floor,
            materials,
        })
    }
}

/// Adds the field's materials to `world`: stems, stalks and leaves of `plant`, pods of `pod`
/// (the field's own are [`STALK_MATERIAL`] and [`POD_MATERIAL`]; the soil's settling holds
/// them with raised densities, [`super::settle`]) and the field file's soil; sets every pair
/// (the soil's with their JKR cohesion) and gravity.
pub fn add_field_materials<S: Scalar>(
    spec: &FieldSpec,
    world: &mut World<'_, S>,
    plant: MaterialSpec,
    pod: MaterialSpec,
) -> Result<FieldMaterials, String> {
    let core = |e: &dyn std::fmt::Display| e.to_string();
    let s = &spec.soil;
    let plant = world.add_material(plant).map_err(|e| core(&e))?;
    let pod = world.add_material(pod).map_err(|e| core(&e))?;
    let soil = world
        .add_material(MaterialSpec {
            youngs_modulus_pa: s.youngs_modulus_pa,
            poisson: s.poisson,
            density_kg_m3: s.density_kg_m3,
        })
        .map_err(|e| core(&e))?;
    let pair =
        |c: ContactValues| PairSpec::hertz_mindlin(c.restitution, c.friction, c.rolling_friction);
    let cohesion = soil_cohesion(spec);
    for (a, b, spec, sticky) in [
        (plant, plant, STALK_CONTACT, false),
        (plant, pod, POD_CONTACT, false),
        (pod, pod, POD_CONTACT, false),
        (soil, soil, pair(s.contacts.soil), true),
        (soil, pod, pair(s.contacts.pod), true),
        (soil, plant, pair(s.contacts.plant), true),
    ] {
        world.set_pair(a, b, spec).map_err(|e| core(&e))?;
        if sticky && cohesion != EffectSpec::default() {
            world
                .set_pair_effects(a, b, cohesion)
                .map_err(|e| core(&e))?;
        }
    }
    world.set_gravity_m_s2(GRAVITY_M_S2).map_err(|e| core(&e))?;
    Ok(FieldMaterials { plant, pod, soil })
}

/// Storage for `bodies` bodies of `spheres` spheres in a world of `spec`'s soil, with the
/// effect history its JKR cohesion keeps.
pub fn storage_lengths_for(spec: &FieldSpec, bodies: usize, spheres: usize) -> StorageLengths {
    let lengths = StorageLengths::for_spheres(bodies.max(1), spheres.max(1));
    if soil_cohesion(spec).needs_history() {
        lengths.with_effects()
    } else {
        lengths
    }
}

/// Adds a fixed plane of `soil` through `point_m` facing along `normal` (a unit vector).
pub fn add_soil_plane<S: Scalar>(
    world: &mut World<'_, S>,
    point_m: [f64; 3],
    normal: [f64; 3],
    soil: MaterialId,
) -> Result<WallId, String> {
    world
        .add_wall(WallSpec::fixed(
            WallGeometry::Plane { point_m, normal },
            soil,
        ))
        .map_err(|e| e.to_string())
}

/// Adds the bed's floor: a plane of `soil` through `bed_min_m` (the subsoil).
pub fn add_floor<S: Scalar>(
    world: &mut World<'_, S>,
    bed_min_m: [f64; 3],
    soil: MaterialId,
) -> Result<WallId, String> {
    add_soil_plane(world, bed_min_m, [0.0, 0.0, 1.0], soil)
}

/// Sets `world`'s time step to [`TIMESTEP_SAFETY`] × the smaller of its contact bound
/// (Rayleigh) and its bond bound; again whenever bodies are added.
pub fn set_safe_timestep<S: Scalar>(world: &mut World<'_, S>) -> Result<(), String> {
    let dt = TIMESTEP_SAFETY * world.max_timestep_s().min(world.bond_max_timestep_s());
    world.set_timestep_s(dt).map_err(|e| e.to_string())
}

/// The soil's steps per field step: the largest divisor of `wanted` (the field file's
/// [`crate::field::Soil::slow_stride`], a divisor of the field's chunk) whose long step
/// stays within [`TIMESTEP_SAFETY`] × the grains' stable bound. A bed whose time step the
/// grains set themselves (no plants) steps them every step.
fn soil_stride<S: Scalar>(wanted: u32, world: &World<'_, S>) -> u32 {
    let bound_s = TIMESTEP_SAFETY * world.max_slow_timestep_s();
    (1..=wanted.max(1))
        .rev()
        .find(|k| wanted % k == 0 && f64::from(*k) * world.timestep_s() <= bound_s)
        .unwrap_or(1)
}

/// The effects of every soil pair: JKR cohesion of the field file's work of adhesion.
fn soil_cohesion(spec: &FieldSpec) -> EffectSpec {
    EffectSpec {
        jkr_work_of_adhesion_j_m2: spec.soil.jkr_work_of_adhesion_j_m2,
        ..EffectSpec::default()
    }
}
