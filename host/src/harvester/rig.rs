//! The harvester mounted in a field's world, and a run of it along the ridge.
//!
//! [`Rig::mount`] adds the machine's parts ([`super::parts`]) to a world that holds a field
//! ([`crate::field::Field::load_into`], with storage from
//! [`crate::field::Field::storage_lengths_with`]) as kinematic steel clumps, ahead of the
//! bed's front face by the file's start gap, and sets the time step again (steel spheres may
//! lower the contact bound). Steel meets pods and plants as in seed 001 Table 2 (the
//! harvest's [`POD_STEEL_CONTACT`] and [`STALK_STEEL_CONTACT`]) and the soil as the file
//! says.
//!
//! The machine stands still for the file's settling time while the loose bed falls into
//! place, then sets off. [`Rig::advance`] runs one chunk: each part is given the velocity
//! that brings it where the motion law puts it at the chunk's end ([`super::motion`]), the
//! world steps, each root the shovel's edge has passed is let go (the taproot is cut), and
//! every pod is checked ([`super::loss`]). Pods are attached while a chain of live bonds joins them to their
//! plant's root. A collected pod is held in the collector and travels with the machine; a
//! pod that went down is held where it lies: neither costs more.

use arachis_core::prelude::*;
use arachis_core::scenario::materials::STEEL;
use arachis_core::units::LENGTH_M_TO_MM;
use serde::{Deserialize, Serialize};

use super::loss::{at_end, check_detached, LossTally, PodEnd};
use super::motion::{tracking_velocity_m_s, Travel};
use super::parts::{Layout, PartKind};
use super::HarvesterSpec;
use crate::field::world::{set_safe_timestep, Loaded};
use crate::field::Field;
use crate::harvest::pass::{root, POD_STEEL_CONTACT, STALK_STEEL_CONTACT};

/// Steps between checks of the pods and updates of the parts' velocities: the field's chunk
/// ([`crate::field::CHUNK_STEPS`]).
pub use crate::field::CHUNK_STEPS;
/// Steel against steel (kinematic parts only meet each other, so only its validity matters).
const STEEL_STEEL_CONTACT: PairSpec = POD_STEEL_CONTACT;

/// One pod followed through the run.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Watched {
    body: BodyId,
    plant: usize,
    lifted: bool,
    end: Option<PodEnd>,
}

/// A rig's own state between chunks ([`Rig::state`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RigState {
    /// Whether each plant's root has been cut (the shovel's edge passed it).
    pub roots_cut: Vec<bool>,
    /// Each pod: whether it has been above the ground, and its end once known.
    pub pods: Vec<(bool, Option<PodEnd>)>,
}

/// A harvester mounted in a field's world.
#[derive(Debug, Clone)]
pub struct Rig {
    /// The machine at rest in its frame.
    pub layout: Layout,
    /// Its travel.
    pub travel: Travel,
    /// The steel of its parts.
    pub steel: MaterialId,
    parts: Vec<BodyId>,
    roots: Vec<(BodyId, f64, bool)>,
    pods: Vec<Watched>,
    start_time_s: f64,
    end_time_s: f64,
}

fn mm_to_m(v: [f64; 3]) -> [f64; 3] {
    v.map(|x| x / LENGTH_M_TO_MM)
}

impl Rig {
    /// Bodies and spheres the machine of `spec` adds to a world.
    pub fn extra_storage(spec: &HarvesterSpec) -> (usize, usize) {
        let layout = Layout::of(spec);
        (layout.parts.len(), layout.spheres())
    }

    /// Mounts the machine of `spec` in `world`, which holds `field` as `loaded`.
    pub fn mount<S: Scalar>(
        spec: &HarvesterSpec,
        field: &Field,
        loaded: &Loaded,
        world: &mut World<'_, S>,
    ) -> Result<Rig, String> {
        let core = |e: &dyn std::fmt::Display| e.to_string();
        let layout = Layout::of(spec);
        let steel = world.add_material(STEEL).map_err(|e| core(&e))?;
        let m = loaded.materials;
        let soil = spec.steel_contacts.soil;
        for (other, pair) in [
            (
                m.soil,
                PairSpec::hertz_mindlin(soil.restitution, soil.friction, soil.rolling_friction),
            ),
            (m.pod, POD_STEEL_CONTACT),
            (m.plant, STALK_STEEL_CONTACT),
            (steel, STEEL_STEEL_CONTACT),
        ] {
            world.set_pair(steel, other, pair).map_err(|e| core(&e))?;
        }
        let travel = Travel {
            start_x_m: field.bed_min_m[0] - spec.harvester.start_gap_m,
            speed_m_s: spec.harvester.forward_speed_m_s,
            settle_s: spec.harvester.settle_s,
        };
        let start_time_s = world.time_s();
        let mut parts = Vec::with_capacity(layout.parts.len());
        for p in &layout.parts {
            let at = travel.centre_m(p, 0.0);
            let shift = [
                at[0] - p.centre_m[0],
                at[1] - p.centre_m[1],
                at[2] - p.centre_m[2],
            ];
            let spheres: Vec<ClumpSphere> = p
                .spheres_m
                .iter()
                .map(|c| ClumpSphere {
                    center_m: [c[0] + shift[0], c[1] + shift[1], c[2] + shift[2]],
                    radius_m: p.radius_m,
                    material: steel,
                })
                .collect();
            // Kinematic: the mass properties need only be valid (a rod of steel spheres).
            let mass = STEEL.density_kg_m3 * 4.0 / 3.0
                * std::f64::consts::PI
                * p.radius_m.powi(3)
                * spheres.len() as f64;
            let inertia = mass * (spec.harvester.width_m.powi(2) / 12.0 + p.radius_m.powi(2));
            let id = world
                .add_clump_with_mass(
                    &ClumpSpec {
                        spheres: &spheres,
                        velocity_m_s: [0.0; 3],
                        angular_velocity_rad_s: p.spin_rad_s,
                    },
                    &MassProperties {
                        mass_kg: mass,
                        center_of_mass_m: at,
                        principal_inertia_kg_m2: [inertia; 3],
                        principal_axes: [1.0, 0.0, 0.0, 0.0],
                    },
                )
                .map_err(|e| core(&e))?;
            world.set_body_kinematic(id).map_err(|e| core(&e))?;
            parts.push(id);
        }
        // The machine's parts, the anchored roots and the pods that have ended all move as
        // prescribed: their contacts with each other and with the floor would move nothing
        // (and the parts' long levers send them to the checked terms).
        world.set_prescribed_contacts(false);
        set_safe_timestep(world)?;
        let roots = field
            .plants
            .iter()
            .zip(&loaded.roots)
            .map(|(p, &id)| (id, p.root_m[0], false))
            .collect();
        let mut pods = Vec::with_capacity(loaded.pods.len());
        let mut next = loaded.pods.iter();
        for (plant, p) in field.plants.iter().enumerate() {
            for _ in 0..p.model.pods() {
                let &body = next.next().ok_or("fewer pod bodies than pods")?;
                pods.push(Watched {
                    body,
                    plant,
                    lifted: false,
                    end: None,
                });
            }
        }
        // The field has settled, then the whole bed has passed over the shovel, up the chain
        // and past the collector.
        let travel_m = field.bed_max_m[0] - layout.opening.x_m.0 - travel.start_x_m;
        let end_time_s = start_time_s + travel.settle_s + travel_m / travel.speed_m_s;
        Ok(Rig {
            layout,
            travel,
            steel,
            parts,
            roots,
            pods,
            start_time_s,
            end_time_s,
        })
    }

    /// Seconds since the machine started.
    pub fn elapsed_s<S: Scalar>(&self, world: &World<'_, S>) -> f64 {
        world.time_s() - self.start_time_s
    }

    /// Steps from the start until the collector has passed the bed's rear end, at `dt_s`,
    /// rounded up to whole cycles of `stride` steps (the soil's, [`crate::field::Soil::slow_stride`]).
    pub fn pass_steps(&self, dt_s: f64, stride: u32) -> u64 {
        let steps = ((self.end_time_s - self.start_time_s) / dt_s).ceil() as u64;
        steps.div_ceil(u64::from(stride.max(1))) * u64::from(stride.max(1))
    }

    /// Runs `steps` steps (in chunks of [`CHUNK_STEPS`]), moving the machine and checking
    /// the pods after each chunk.
    pub fn advance<S: Scalar>(
        &mut self,
        world: &mut World<'_, S>,
        steps: u64,
    ) -> Result<(), String> {
        let core = |e: &dyn std::fmt::Display| e.to_string();
        let mut done = 0;
        while done < steps {
            let n = CHUNK_STEPS.min(steps - done);
            let dt = world.timestep_s();
            let t_end = self.elapsed_s(world) + n as f64 * dt;
            for (part, &id) in self.layout.parts.iter().zip(&self.parts) {
                let now = mm_to_m(world.body(id).position.to_f64());
                let v =
                    tracking_velocity_m_s(now, self.travel.centre_m(part, t_end), n as f64 * dt);
                world
                    .set_body_velocity(id, v, part.spin_rad_s)
                    .map_err(|e| core(&e))?;
            }
            crate::stepping::run(world, n)
                .map_err(|e| format!("step failed at t = {} s: {e}", world.time_s()))?;
            done += n;
            let edge_x = self.travel.origin_x_m(self.elapsed_s(world));
            for (id, x, let_go) in &mut self.roots {
                if !*let_go && edge_x >= *x {
                    world.set_body_dynamic(*id).map_err(|e| core(&e))?;
                    *let_go = true;
                }
            }
            self.check_pods(world)?;
        }
        Ok(())
    }

    /// Checks every pod not yet collected or down.
    fn check_pods<S: Scalar>(&mut self, world: &mut World<'_, S>) -> Result<(), String> {
        let core = |e: &dyn std::fmt::Display| e.to_string();
        let attached = self.attached(world);
        let t = self.elapsed_s(world);
        for (w, &on) in self.pods.iter_mut().zip(&attached) {
            if w.end.is_some() {
                continue;
            }
            let p = mm_to_m(world.body(w.body).position.to_f64());
            w.lifted = w.lifted || p[2] > 0.0;
            if on || !w.lifted {
                continue;
            }
            let Some(end) = check_detached(&self.layout, self.travel.to_machine_m(p, t)) else {
                continue;
            };
            w.end = Some(end);
            let v = match end {
                PodEnd::Collected => [self.travel.speed_m_s, 0.0, 0.0],
                _ => [0.0; 3],
            };
            world.set_body_kinematic(w.body).map_err(|e| core(&e))?;
            world
                .set_body_velocity(w.body, v, [0.0; 3])
                .map_err(|e| core(&e))?;
        }
        Ok(())
    }

    /// For each watched pod, whether live bonds join it to its plant's root.
    fn attached<S: Scalar>(&self, world: &World<'_, S>) -> Vec<bool> {
        let n = world.bodies().len();
        let mut parent: Vec<usize> = (0..n).collect();
        let spheres = world.spheres();
        for b in world.bonds().bonds() {
            let i = spheres[b.sphere_a as usize].body as usize;
            let j = spheres[b.sphere_b as usize].body as usize;
            let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
            parent[ri] = rj;
        }
        self.pods
            .iter()
            .map(|w| {
                let r = self.roots[w.plant].0 .0 as usize;
                root(&mut parent, w.body.0 as usize) == root(&mut parent, r)
            })
            .collect()
    }

    /// Every pod's end as things stand: those not yet collected or down are placed by
    /// [`at_end`].
    pub fn ends<S: Scalar>(&self, world: &World<'_, S>) -> Vec<(BodyId, PodEnd)> {
        let attached = self.attached(world);
        self.pods
            .iter()
            .zip(attached)
            .map(|(w, on)| (w.body, w.end.unwrap_or_else(|| at_end(on, w.lifted))))
            .collect()
    }

    /// The tally of [`Rig::ends`].
    pub fn tally<S: Scalar>(&self, world: &World<'_, S>) -> LossTally {
        let mut t = LossTally::default();
        for (_, e) in self.ends(world) {
            t.add(e);
        }
        t
    }

    /// What the rig keeps between chunks beyond the world: which roots are cut, and each
    /// pod's progress. With the world's checkpoint it resumes a run
    /// ([`crate::checkpoint`]).
    pub fn state(&self) -> RigState {
        RigState {
            roots_cut: self.roots.iter().map(|r| r.2).collect(),
            pods: self.pods.iter().map(|w| (w.lifted, w.end)).collect(),
        }
    }

    /// Takes up `state` (of a rig mounted on the same field).
    pub fn resume(&mut self, state: &RigState) -> Result<(), String> {
        if state.roots_cut.len() != self.roots.len() || state.pods.len() != self.pods.len() {
            return Err(format!(
                "the checkpoint's machine followed {} roots and {} pods, this one {} and {}",
                state.roots_cut.len(),
                state.pods.len(),
                self.roots.len(),
                self.pods.len()
            ));
        }
        for (r, &cut) in self.roots.iter_mut().zip(&state.roots_cut) {
            r.2 = cut;
        }
        for (w, &(lifted, end)) in self.pods.iter_mut().zip(&state.pods) {
            w.lifted = lifted;
            w.end = end;
        }
        Ok(())
    }

    /// Roots let go so far.
    pub fn roots_let_go(&self) -> usize {
        self.roots.iter().filter(|r| r.2).count()
    }

    /// Bodies of the parts of `kind`.
    pub fn bodies_of(&self, kind: PartKind) -> Vec<BodyId> {
        self.layout
            .parts
            .iter()
            .zip(&self.parts)
            .filter(|(p, _)| p.kind == kind)
            .map(|(_, &id)| id)
            .collect()
    }
}
