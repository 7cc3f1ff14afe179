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
//!    [`crate::field::Soil::settle_s`]; every stem, stalk and leaf sphere that reaches into
//!    the bed is a kinematic obstacle of the stalk's material, and every pod a clump of the
//!    pod's, held while the bed compacts around it and free for the last
//!    [`POD_FREE_FRACTION`], so that it comes to rest on the compacted soil. Its peg
//!    follows it ([`super::peg`]) and stands still again for the last
//!    [`PEG_REST_FRACTION`], so the grains settle around the peg's new place. The pods' and
//!    pegs' places are then the plants' ([`Settled::pod_sink_mm`]): the field's run bonds
//!    each pod to its peg where they lie, unstressed.
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

use std::collections::BTreeMap;

use arachis_core::contact::fused::fixed::MAX_TIMESTEP_S;
use arachis_core::prelude::*;
use arachis_core::scenario::pull_off::{POD_MATERIAL, STALK_MATERIAL};
use arachis_core::timestep::rayleigh_time_s;
use arachis_core::units::LENGTH_M_TO_MM;

use super::peg::Peg;
use super::world::{
    add_field_materials, add_floor, add_soil_plane, storage_lengths_for, TIMESTEP_SAFETY,
};
use super::{Field, FieldSpec, Soil};
use crate::arena::OwnedStorage;
use crate::plant::generate::PlantBody;
use crate::plant::topology::Kind;
use crate::plant::PlantModel;

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

/// Fraction of the settling, at its end, in which the pods are free: held, a pod carries the
/// soil above it while the bed compacts, and the soil below it never carries the pod, so a
/// pod held to the end sank about 2 mm once the field's run let it go and the stalk, fixed
/// to its lateral above ground, took its weight in tension (pod–stalk bonds of the shipped
/// field broke at steps 44 279–53 128; `core/API_NOTES.md`, "The soil settles before the
/// field's run"). Free for the last third (0.1 s of the default 0.3 s), a pod settles onto
/// the compacted soil first, and the field's run bonds it where it came to rest.
pub const POD_FREE_FRACTION: f64 = 1.0 / 3.0;

/// Fraction of the settling, at its end, in which the pegs that followed their pods
/// ([`super::peg`]) stand still again, so that the grains they pushed aside settle around
/// them before the field's run starts.
pub const PEG_REST_FRACTION: f64 = 0.1;

/// Steps of the settling between two reports of its progress.
pub const SETTLE_CHUNK_STEPS: u64 = 100;

/// What the settling did.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Settled {
    /// Steps taken.
    pub steps: u64,
    /// Its time step, s.
    pub timestep_s: f64,
    /// Plant spheres held as obstacles (stems, stalks and leaves).
    pub obstacles: usize,
    /// Pods that settled with the soil (free for the last [`POD_FREE_FRACTION`]).
    pub pods: usize,
    /// How far the pods sank while free (their centres of mass), mean and largest, mm.
    pub pod_sink_mm: [f64; 2],
    /// Grains laid out.
    pub laid: usize,
    /// Grains kept (centre at or below the surface).
    pub kept: usize,
    /// The grains' kinetic energy at the end, J.
    pub kinetic_energy_j: f64,
}

/// A stem, stalk or leaf sphere held still during the settling (a peg's moves with its pod),
/// with its plant and its index in the plant's model.
struct Obstacle {
    centre_m: [f64; 3],
    radius_m: f64,
    plant: usize,
    sphere: usize,
}

/// A pod in the settling world: its plant, its body in the plant's model and in the world,
/// and its peg. The plant's model keeps where the pod was held until the settling ends.
struct SettlingPod {
    plant: usize,
    body: usize,
    id: BodyId,
    peg: Option<Peg>,
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
        let reachable = |o: &Obstacle| {
            o.centre_m[2] - o.radius_m < top_m + 2.0 * largest_grain_m && within_walls(o)
        };
        let spheres_of = |plant: usize, b: &PlantBody| {
            let model = &self.plants[plant].model;
            b.spheres
                .iter()
                .map(|&i| Obstacle {
                    centre_m: model.spheres[i].centre_m,
                    radius_m: model.spheres[i].radius_m,
                    plant,
                    sphere: i,
                })
                .collect::<Vec<_>>()
        };
        // A pod free to move must touch no side wall (a wall has no part in the field's run).
        let clear_of_walls = |o: &Obstacle| {
            (0..2).all(|k| {
                o.centre_m[k] - o.radius_m > min_m[k] && o.centre_m[k] + o.radius_m < max_m[k]
            })
        };
        let mut obstacles = Vec::new();
        // (plant, body) of every pod inside the walls the grains can reach.
        let mut pod_bodies = Vec::new();
        for (plant, p) in self.plants.iter().enumerate() {
            for (body, b) in p.model.bodies.iter().enumerate() {
                let spheres = spheres_of(plant, b);
                let free = b.kind == Kind::Pod
                    && spheres.iter().all(|o| reachable(o) && clear_of_walls(o));
                if free {
                    pod_bodies.push((plant, body));
                } else {
                    obstacles.extend(spheres.into_iter().filter(reachable));
                }
            }
        }
        let pod_spheres: usize = pod_bodies
            .iter()
            .map(|&(plant, body)| self.plants[plant].model.bodies[body].spheres.len())
            .sum();
        let bodies = obstacles.len() + pod_bodies.len() + laid;
        let spheres = obstacles.len() + pod_spheres + laid;
        let mut arena = OwnedStorage::<Fx>::new(storage_lengths_for(spec, bodies, spheres));
        let mut world = World::new(arena.storage()).map_err(|e| core(&e))?;
        let s = &spec.soil;
        let grain_rayleigh_s = self
            .grains
            .iter()
            .map(|g| rayleigh_time_s(g.radius_m, s.density_kg_m3, s.youngs_modulus_pa, s.poisson))
            .fold(f64::INFINITY, f64::min);
        let smallest_stalk_m = obstacles
            .iter()
            .map(|o| o.radius_m)
            .fold(f64::INFINITY, f64::min);
        let smallest_pod_m = pod_bodies
            .iter()
            .flat_map(|&(plant, body)| {
                let model = &self.plants[plant].model;
                model.bodies[body]
                    .spheres
                    .iter()
                    .map(|&i| model.spheres[i].radius_m)
            })
            .fold(f64::INFINITY, f64::min);
        let materials = add_field_materials(
            spec,
            &mut world,
            obstacle_material(STALK_MATERIAL, smallest_stalk_m, grain_rayleigh_s),
            obstacle_material(POD_MATERIAL, smallest_pod_m, grain_rayleigh_s),
        )?;
        let mut held = BTreeMap::new();
        for o in &obstacles {
            let id = world
                .add_sphere(SphereSpec::at_rest(materials.plant, o.radius_m, o.centre_m))
                .map_err(|e| core(&e))?;
            world.set_body_kinematic(id).map_err(|e| core(&e))?;
            held.insert((o.plant, o.sphere), id);
        }
        // A pod weighs what it weighs in the field (its material's density is raised for the
        // time step's bound only); it is held until its last fraction of the settling.
        let mut pods = Vec::with_capacity(pod_bodies.len());
        for (plant, body) in pod_bodies {
            let model = &self.plants[plant].model;
            let kg = model.pod_mass_or(body, POD_MATERIAL.density_kg_m3);
            let id = kg
                .and_then(|kg| model.add_pod(&mut world, body, materials.pod, Some(kg)))
                .map_err(|e| core(&e))?;
            world.set_body_kinematic(id).map_err(|e| core(&e))?;
            pods.push(SettlingPod {
                plant,
                body,
                id,
                peg: Peg::of(model, body),
            });
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
        let last = |fraction: f64| steps - (fraction * steps as f64).round() as u64;
        let (free_at, rest_at) = (last(POD_FREE_FRACTION), last(PEG_REST_FRACTION));
        let held_z_mm: Vec<f64> = pods
            .iter()
            .map(|p| world.body(p.id).position.to_f64()[2])
            .collect();
        let mut done = 0;
        while done < steps {
            if done == free_at {
                for p in &pods {
                    world.set_body_dynamic(p.id).map_err(|e| core(&e))?;
                }
            }
            let until = [free_at, rest_at, steps]
                .into_iter()
                .find(|&b| b > done)
                .unwrap_or(steps);
            let n = SETTLE_CHUNK_STEPS.min(until - done);
            if (free_at..=rest_at).contains(&done) {
                let span = (done < rest_at).then_some(n);
                for p in &pods {
                    steer_peg(&mut world, p, &self.plants[p.plant].model, &held, span)?;
                }
            }
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
        let sink_mm: Vec<f64> = pods
            .iter()
            .zip(&held_z_mm)
            .map(|(p, z)| z - world.body(p.id).position.to_f64()[2])
            .collect();
        for p in &pods {
            let fall_mm = tip_fall_mm(&world, p, &self.plants[p.plant].model);
            let body = world.body(p.id);
            let placed = world.spheres()[body.first_sphere as usize..].iter();
            let model = &mut self.plants[p.plant].model;
            for (&i, sphere) in model.bodies[p.body].spheres.iter().zip(placed) {
                model.spheres[i].centre_m = sphere.position.to_f64().map(|x| x / LENGTH_M_TO_MM);
            }
            // A peg sphere in the world stays where the grains settled around it, the rest
            // (above the soil) takes its share of the pod's fall.
            let Some(peg) = &p.peg else { continue };
            for (k, &i) in peg.chain.iter().enumerate() {
                let c = &mut model.spheres[i].centre_m;
                *c = match held.get(&(p.plant, i)) {
                    Some(&id) => world.body(id).position.to_f64().map(|x| x / LENGTH_M_TO_MM),
                    None => {
                        std::array::from_fn(|d| c[d] + peg.share(k) * fall_mm[d] / LENGTH_M_TO_MM)
                    }
                };
            }
        }
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
            pods: pods.len(),
            pod_sink_mm: [
                sink_mm.iter().fold(0.0, |a, b| a + b) / sink_mm.len().max(1) as f64,
                sink_mm.iter().copied().fold(0.0, f64::max),
            ],
            laid,
            kept: self.grains.len(),
            kinetic_energy_j,
        })
    }
}

/// How far pod `p`'s sphere bonded to its peg has moved from where `model` (not yet updated)
/// holds it, mm (zero for a pod without a peg).
fn tip_fall_mm(world: &World<'_, Fx>, p: &SettlingPod, model: &PlantModel) -> [f64; 3] {
    let Some(peg) = &p.peg else {
        return [0.0; 3];
    };
    let slot = model.bodies[p.body]
        .spheres
        .iter()
        .position(|&i| i == peg.tip)
        .expect("a peg's tip is a sphere of its pod");
    let first = world.body(p.id).first_sphere as usize;
    let now = world.spheres()[first + slot].position.to_f64();
    let held_mm = model.spheres[peg.tip].centre_m.map(|x| x * LENGTH_M_TO_MM);
    std::array::from_fn(|k| now[k] - held_mm[k])
}

/// Sets the velocities of pod `p`'s held peg spheres (those in the world, `held` by plant and
/// model sphere) so that in the next `steps` steps each reaches its share of the pod's move so
/// far ([`Peg::share`]): the peg follows its pod through the soil, a chunk behind. `None`
/// stops them.
fn steer_peg(
    world: &mut World<'_, Fx>,
    p: &SettlingPod,
    model: &PlantModel,
    held: &BTreeMap<(usize, usize), BodyId>,
    steps: Option<u64>,
) -> Result<(), String> {
    let Some(peg) = &p.peg else {
        return Ok(());
    };
    let fall_mm = tip_fall_mm(world, p, model);
    // No steps: no time to move in, so no velocity.
    let span_s = steps.map_or(f64::INFINITY, |n| n as f64 * world.timestep_s());
    for (k, &i) in peg.chain.iter().enumerate() {
        let Some(&id) = held.get(&(p.plant, i)) else {
            continue;
        };
        let now_mm = world.body(id).position.to_f64();
        let start_mm = model.spheres[i].centre_m.map(|x| x * LENGTH_M_TO_MM);
        // mm / s = 1e-3 m/s.
        let v_m_s: [f64; 3] = std::array::from_fn(|d| {
            (start_mm[d] + peg.share(k) * fall_mm[d] - now_mm[d]) / LENGTH_M_TO_MM / span_s
        });
        world
            .set_body_velocity(id, v_m_s, [0.0; 3])
            .map_err(|e| e.to_string())?;
    }
    Ok(())
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
