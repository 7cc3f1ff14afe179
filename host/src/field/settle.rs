//! Settling the soil around the held plants, before anything else moves.
//!
//! The bed is laid out as a loose lattice ([`super::soil`], about 41 % full) that compacts
//! by about 2 cm under gravity. Left to do that in the field's own run, it drags the pods
//! down while the laterals hold their pegs, and pod–stalk bonds break in tension before any
//! machine arrives (a one-plant field: the bond next to a pod 62 mm deep broke at step
//! 78 373, 0.065 s, at either soil stride; `core/API_NOTES.md`, "The loose bed's settling").
//! So the soil settles first, in a world of its own, with every plant held still:
//!
//! 1. The lattice is laid [`OVERFILL`] × the bed's depth and two grain diameters higher than
//!    the surface ([`FieldSpec::lay_out`], [`lattice_above_surface_m`]), so that once
//!    compacted it still reaches it.
//! 2. [`Field::settle`] steps the grains, their floor and their JKR contacts as the field
//!    has them, inside four side walls (a soil bin: the bed compacts straight down), for
//!    [`crate::field::Soil::settle_s`]; every plant sphere that reaches into
//!    the bed is a kinematic obstacle of its own material (pods the pod's, the rest the
//!    stalk's), so the soil packs around pods and stalks as they hang.
//! 3. Every grain whose centre ended above the surface (z = 0) is taken away; the others
//!    keep their settled places and start the field's run at rest, without the side walls.
//!    A bed that trimmed nothing may not reach its surface, and is refused.
//!
//! Why a world of its own: the field's time step is set by the stalks' bonds (about 8e-7 s),
//! the grains' by their own Rayleigh time (about 2.2e-4 s): held plants need no bonds, so
//! the settling steps at 0.12 ms ([`FUSED_STEP_FRACTION`]), some 2 500 steps for the default
//! 0.3 s instead of 360 000 of the field's. A kinematic obstacle's density
//! enters no force (the contact's effective mass with an immovable partner,
//! 1/(1/m_a + 1/m_b), is the grain's own mass) but does enter the world's Rayleigh bound
//! (T_R = πR√(ρ/G)/(0.1631ν + 0.8766), DESIGN §2), so each obstacle material's density is
//! raised until its smallest sphere's Rayleigh time is the smallest grain's
//! ([`obstacle_material`]).
//!
//! ```
//! use arachis::field::FieldSpec;
//! let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../testdata/peanut-plant"));
//! let mut spec = FieldSpec::read(&dir.join("field-huayu.toml")).unwrap();
//! // A bare bed, 20 cm by 10 cm and 3 cm deep, settled for 0.2 s.
//! spec.field.plants_per_hole = 0;
//! (spec.field.rows, spec.field.ridge_length_m) = (1, 0.1);
//! (spec.soil.margin_m, spec.soil.depth_m, spec.soil.settle_s) = (0.05, 0.03, 0.2);
//! let mut field = spec.lay_out(1).unwrap();
//! let laid = field.grains.len();
//! let settled = field.settle(&spec, |_, _| {}).unwrap();
//! assert_eq!(settled.laid, laid);
//! assert_eq!(settled.kept, field.grains.len());
//! assert!(settled.kept < laid, "the grains above the surface are trimmed");
//! assert!(field.grains.iter().all(|g| g.centre_m[2] <= 0.0));
//! ```

use arachis_core::contact::fused::fixed::MAX_TIMESTEP_S;
use arachis_core::prelude::*;
use arachis_core::scenario::pull_off::{POD_MATERIAL, STALK_MATERIAL};
use arachis_core::timestep::rayleigh_time_s;
use arachis_core::units::LENGTH_M_TO_MM;

use super::world::{
    add_field_materials, add_floor, add_soil_plane, storage_lengths_for, TIMESTEP_SAFETY,
};
use super::{Field, FieldSpec, Soil};
use crate::arena::OwnedStorage;
use crate::plant::topology::Kind;

/// Height of the loose lattice above the surface, as a fraction of the bed's depth (with
/// [`OVERFILL_GRAIN_DIAMETERS`] more). The lattice fills about 41 % of its box and a bed of
/// these grains settles to about 60 % (a one-plant field's bed: its mean grain sank from
/// −50.8 mm to −63.3 mm of a 100 mm bed), so it shrinks to about 0.41/0.60 ≈ 0.68 of its
/// height: (1 + 0.5)·0.68 ≈ 1.02 × the depth.
pub const OVERFILL: f64 = 0.5;

/// Grain diameters of lattice laid above [`OVERFILL`] × the depth, so that every bed settles
/// above its surface by about 0.68 × 2 × 2 ≈ 2.7 grain radii whatever its depth: a lattice
/// 1.5 × the depth alone left a one-plant field's 10 cm bed just at its surface (9 512 of
/// 9 523 grains kept) and a 6 cm bed short of it (top grain centre −0.6 mm), as the lattice
/// has whole layers only. The trim then leaves a level surface.
pub const OVERFILL_GRAIN_DIAMETERS: f64 = 2.0;

/// How far above the surface the loose lattice is laid for `soil`, m.
pub fn lattice_above_surface_m(soil: &Soil) -> f64 {
    let diameter_m = 2.0 * soil.grain_radius_mm.mean / LENGTH_M_TO_MM;
    OVERFILL * soil.depth_m + OVERFILL_GRAIN_DIAMETERS * diameter_m
}

/// The settling's longest time step, as a fraction of the fast contact kernel's bound
/// ([`MAX_TIMESTEP_S`], 0.125 ms): the grains' own stable step (about 0.22 ms for the shipped
/// soil) lies beyond it, where every contact would take the checked terms. Measured on a
/// one-plant field (9 523 grains, 0.5 s, 2 threads): 2 284 steps of 0.219 ms took 18.7 s,
/// 4 167 steps of 0.12 ms 16.0 s, and the grains' kinetic energy at the end fell from
/// 0.076 J to 0.002 J.
pub const FUSED_STEP_FRACTION: f64 = 0.96;

/// Steps of the settling between two reports of its progress.
pub const SETTLE_CHUNK_STEPS: u64 = 100;

/// What the settling did.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Settled {
    /// Steps taken.
    pub steps: u64,
    /// Its time step, s.
    pub timestep_s: f64,
    /// Plant spheres held as obstacles.
    pub obstacles: usize,
    /// Grains laid out.
    pub laid: usize,
    /// Grains kept (centre at or below the surface).
    pub kept: usize,
    /// The grains' kinetic energy at the end, J.
    pub kinetic_energy_j: f64,
}

/// A plant sphere held still during the settling.
struct Obstacle {
    centre_m: [f64; 3],
    radius_m: f64,
    pod: bool,
}

impl Field {
    /// Lets the grains settle around the held plants for the field file's
    /// [`crate::field::Soil::settle_s`], then takes away every grain whose centre is above
    /// the surface (see the module's notes). `progress` hears (steps done, steps in all)
    /// every [`SETTLE_CHUNK_STEPS`] steps. Runs on the ambient thread count
    /// ([`crate::stepping`]), with the same bits on any.
    pub fn settle(
        &mut self,
        spec: &FieldSpec,
        mut progress: impl FnMut(u64, u64),
    ) -> Result<Settled, String> {
        let core = |e: &dyn std::fmt::Display| e.to_string();
        let laid = self.grains.len();
        let largest_grain_m = self.grains.iter().map(|g| g.radius_m).fold(0.0, f64::max);
        let top_m = self
            .grains
            .iter()
            .map(|g| g.centre_m[2] + g.radius_m)
            .fold(f64::MIN, f64::max);
        // A plant sphere a grain could reach: below the lattice's top and one more grain, and
        // within a radius of the side walls (a sphere further out touches no grain, and its
        // overlap with a wall's half-space could leave the fixed-point range).
        let (min_m, max_m) = (self.bed_min_m, self.bed_max_m);
        let within_walls = |o: &Obstacle| {
            (0..2).all(|k| {
                o.centre_m[k] > min_m[k] - o.radius_m && o.centre_m[k] < max_m[k] + o.radius_m
            })
        };
        let obstacles: Vec<Obstacle> = self
            .plants
            .iter()
            .flat_map(|p| {
                p.model.spheres.iter().map(|s| Obstacle {
                    centre_m: s.centre_m,
                    radius_m: s.radius_m,
                    pod: p.model.bodies[s.body].kind == Kind::Pod,
                })
            })
            .filter(|o| o.centre_m[2] - o.radius_m < top_m + 2.0 * largest_grain_m)
            .filter(within_walls)
            .collect();
        let bodies = obstacles.len() + laid;
        let mut arena = OwnedStorage::<Fx>::new(storage_lengths_for(spec, bodies, bodies));
        let mut world = World::new(arena.storage()).map_err(|e| core(&e))?;
        let s = &spec.soil;
        let grain_rayleigh_s = self
            .grains
            .iter()
            .map(|g| rayleigh_time_s(g.radius_m, s.density_kg_m3, s.youngs_modulus_pa, s.poisson))
            .fold(f64::INFINITY, f64::min);
        let smallest = |pod: bool| {
            obstacles
                .iter()
                .filter(|o| o.pod == pod)
                .map(|o| o.radius_m)
                .fold(f64::INFINITY, f64::min)
        };
        let materials = add_field_materials(
            spec,
            &mut world,
            obstacle_material(STALK_MATERIAL, smallest(false), grain_rayleigh_s),
            obstacle_material(POD_MATERIAL, smallest(true), grain_rayleigh_s),
        )?;
        for o in &obstacles {
            let material = if o.pod {
                materials.pod
            } else {
                materials.plant
            };
            let id = world
                .add_sphere(SphereSpec::at_rest(material, o.radius_m, o.centre_m))
                .map_err(|e| core(&e))?;
            world.set_body_kinematic(id).map_err(|e| core(&e))?;
        }
        let grains = self
            .grains
            .iter()
            .map(|g| {
                world
                    .add_sphere(SphereSpec::at_rest(materials.soil, g.radius_m, g.centre_m))
                    .map_err(|e| core(&e))
            })
            .collect::<Result<Vec<_>, _>>()?;
        add_floor(&mut world, self.bed_min_m, materials.soil)?;
        add_side_walls(&mut world, self.bed_min_m, self.bed_max_m, materials.soil)?;
        let timestep_s =
            (TIMESTEP_SAFETY * world.max_timestep_s()).min(FUSED_STEP_FRACTION * MAX_TIMESTEP_S);
        world.set_timestep_s(timestep_s).map_err(|e| core(&e))?;
        let steps = (s.settle_s / timestep_s).ceil() as u64;
        let mut done = 0;
        while done < steps {
            let n = SETTLE_CHUNK_STEPS.min(steps - done);
            crate::stepping::run(&mut world, n)
                .map_err(|e| format!("a step at t = {} s failed: {e}", world.time_s()))?;
            done += n;
            progress(done, steps);
        }
        // Energies are in mJ.
        let kinetic_energy_j = grains
            .iter()
            .map(|&g| world.body(g).kinetic_energy_mj())
            .sum::<f64>()
            / 1000.0;
        for (grain, &id) in self.grains.iter_mut().zip(&grains) {
            grain.centre_m = world.body(id).position.to_f64().map(|x| x / LENGTH_M_TO_MM);
        }
        self.grains.retain(|g| g.centre_m[2] <= self.bed_max_m[2]);
        if laid > 0 && self.grains.len() == laid {
            let top_mm = self
                .grains
                .iter()
                .map(|g| g.centre_m[2])
                .fold(f64::MIN, f64::max)
                * LENGTH_M_TO_MM;
            return Err(format!(
                "the settled soil does not reach the surface: its highest grain centre lies at \
                 {top_mm:.1} mm (the loose lattice was laid {:.1} mm above it, too little for \
                 this soil's packing)",
                lattice_above_surface_m(&spec.soil) * LENGTH_M_TO_MM
            ));
        }
        Ok(Settled {
            steps,
            timestep_s,
            obstacles: obstacles.len(),
            laid,
            kept: self.grains.len(),
            kinetic_energy_j,
        })
    }
}

/// Adds four vertical walls of `soil` around the bed from `bed_min_m` to `bed_max_m`, facing
/// in: the grains settle straight down, as in a soil bin, so that the bed compacts by the
/// same fraction everywhere (without them its edges slump while it settles, and a 6 cm bed
/// with 15 cm margins fell short of its surface). The field's run has none: there the edges
/// slump as a ridge's flanks do.
fn add_side_walls<S: Scalar>(
    world: &mut World<'_, S>,
    bed_min_m: [f64; 3],
    bed_max_m: [f64; 3],
    soil: MaterialId,
) -> Result<(), String> {
    for axis in 0..2 {
        for (point_m, inward) in [(bed_min_m, 1.0), (bed_max_m, -1.0)] {
            let mut normal = [0.0; 3];
            normal[axis] = inward;
            add_soil_plane(world, point_m, normal, soil)?;
        }
    }
    Ok(())
}

/// `material` with its density raised, if need be, until a sphere of `smallest_radius_m`
/// has a Rayleigh time of at least `rayleigh_s`: T_R ∝ √ρ, so ρ' = ρ (T_R,wanted / T_R)².
/// For a kinematic obstacle only (see the module's notes); `smallest_radius_m` = ∞ (no
/// obstacle of this material) leaves it as it is.
pub fn obstacle_material(
    material: MaterialSpec,
    smallest_radius_m: f64,
    rayleigh_s: f64,
) -> MaterialSpec {
    let own_s = rayleigh_time_s(
        smallest_radius_m,
        material.density_kg_m3,
        material.youngs_modulus_pa,
        material.poisson,
    );
    let scale = (rayleigh_s / own_s).powi(2);
    MaterialSpec {
        density_kg_m3: material.density_kg_m3 * scale.max(1.0),
        ..material
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_obstacle_material_reaches_the_grains_rayleigh_time_and_no_further() {
        let grain_s = rayleigh_time_s(0.0076, 2650.0, 1e7, 0.3);
        // A 1 mm stalk sphere of the stalk material is far quicker than a 7.6 mm grain.
        let raised = obstacle_material(STALK_MATERIAL, 0.001, grain_s);
        let t = rayleigh_time_s(
            0.001,
            raised.density_kg_m3,
            raised.youngs_modulus_pa,
            raised.poisson,
        );
        assert!((t / grain_s - 1.0).abs() < 1e-12, "{t} against {grain_s}");
        assert_eq!(raised.youngs_modulus_pa, STALK_MATERIAL.youngs_modulus_pa);
        // A sphere already slower than the grain keeps its density; no sphere, no change.
        let slow = obstacle_material(STALK_MATERIAL, 1.0, grain_s);
        assert_eq!(slow, STALK_MATERIAL);
        assert_eq!(
            obstacle_material(POD_MATERIAL, f64::INFINITY, grain_s),
            POD_MATERIAL
        );
    }
}
