//! [`World`]: the simulation state over caller-provided storage, its set-up API, and the step
//! that runs the stages of [`crate::step`] on it.
//!
//! Set-up takes SI values and validates them (typed [`SetupError`]s); each stage of the step
//! is a function of the parts of the world it needs, so the world is the only module that
//! knows them all. A world is generic over the [`Scalar`]: `World<Fx>` is the deterministic
//! fixed-point production path, `World<f64>` the reference.
//!
//! ```
//! use arachis_core::prelude::*;
//! let len = StorageLengths::for_spheres(1, 1);
//! let mut bodies = vec![Body::<Fx>::default(); len.bodies];
//! let mut forces = vec![BodyForce::<Fx>::default(); len.bodies];
//! let mut spheres = vec![Sphere::<Fx>::default(); len.spheres];
//! let mut neighbours = vec![NeighbourEntry::<Fx>::default(); len.neighbours];
//! let mut index = vec![0u32; len.index];
//! let mut cells = vec![0u32; len.cells];
//! let mut w = World::new(Storage {
//!     bodies: &mut bodies, forces: &mut forces, spheres: &mut spheres,
//!     neighbours: &mut neighbours, effect_history: &mut [],
//!     index: &mut index, cells: &mut cells,
//! }).unwrap();
//! let pod = w.add_material(MaterialSpec { youngs_modulus_pa: 8.43e6, poisson: 0.386, density_kg_m3: 582.0 }).unwrap();
//! let steel = w.add_material(MaterialSpec { youngs_modulus_pa: 2.05e11, poisson: 0.3, density_kg_m3: 7865.0 }).unwrap();
//! w.set_pair(pod, steel, PairSpec::hertz_mindlin(0.339, 0.589, 0.159)).unwrap();
//! w.set_gravity_m_s2([0.0, 0.0, -9.81]).unwrap();
//! w.add_wall(WallSpec::fixed(WallGeometry::Plane { point_m: [0.0; 3], normal: [0.0, 0.0, 1.0] }, steel)).unwrap();
//! w.add_sphere(SphereSpec::at_rest(pod, 0.004, [0.0, 0.0, 0.01])).unwrap();
//! w.set_timestep_s(2e-5).unwrap();
//! for _ in 0..100 { w.step().unwrap(); }
//! assert!(w.body(BodyId(0)).position.z.to_f64() < 10.0); // fell (mm)
//! let _digest: u64 = w.digest();
//! ```

mod bonds;
pub mod checkpoint;
mod digest;
mod effects;
mod setup;
mod step;

pub use crate::body::clump::{ClumpSpec, MAX_CLUMP_SPHERES};
pub use crate::num::quantise::{quantise, quantise_coordinate, MAX_INTERNAL_MAGNITUDE};
pub use step::ThreadScratch;

use crate::body::{Body, BodyForce, Sphere, Storage};
use crate::bond::Bonds;
use crate::contact::{ContactSlot, ContactState};
use crate::error::{CapacityKind, SetupError};
use crate::material::{Material, MAX_MATERIALS};
use crate::num::{Scalar, Vec3};
use crate::pair::PairParams;
use crate::step::air_drag::AirDrag;
use crate::step::balance::StageBalance;
use crate::step::multirate::SlowRuns;
use crate::step::neighbour_list::{key_of, NeighbourList, LIVE_FLAG};
use crate::step::parts::PairTable;
use crate::timestep::max_stable_dt_s;
use crate::units::TIME_S_TO_MS;
use crate::wall::{Wall, MAX_WALLS};

/// Largest sphere capacity: sphere ids and the list's flags share a `u32` key.
const MAX_SPHERE_CAPACITY: usize = u32::MAX as usize / 8;

/// The simulation state. See the module docs for an example.
pub struct World<'a, S: Scalar> {
    pub(crate) bodies: &'a mut [Body<S>],
    pub(crate) n_bodies: u32,
    /// The world's force sums (one per body slot), filled by the step's stages.
    pub(crate) forces: &'a mut [BodyForce<S>],
    pub(crate) spheres: &'a mut [Sphere<S>],
    pub(crate) n_spheres: u32,
    pub(crate) list: NeighbourList<'a, S>,
    pub(crate) walls: heapless::Vec<Wall<S>, MAX_WALLS>,
    pub(crate) materials: heapless::Vec<Material, MAX_MATERIALS>,
    pub(crate) pairs: PairTable<S>,
    pub(crate) gravity: Vec3<S>,
    pub(crate) dt: S,
    pub(crate) dt_s: f64,
    pub(crate) time: S,
    pub(crate) steps: u64,
    pub(crate) max_radius: S,
    pub(crate) min_rayleigh_s: f64,
    /// Steps per cycle of multi-rate stepping, k (1: single-rate; [`crate::step::multirate`]).
    pub(crate) slow_stride: u32,
    /// Smallest Rayleigh time over the spheres of slow bodies, s (∞ with none).
    pub(crate) min_rayleigh_slow_s: f64,
    /// Runs of consecutive slow bodies, for the integration ([`crate::step::multirate`]).
    pub(crate) slow_runs: SlowRuns,
    /// Bonded-particle model state ([`crate::bond`]).
    pub(crate) bond_table: Bonds<'a, S>,
    /// Optional air drag (off by default; [`crate::effects`]).
    pub(crate) air_drag: AirDrag<S>,
    /// Where a threaded step cuts its stages ([`crate::step::balance`]); never hashed, since
    /// it changes no result.
    pub(crate) balance: StepBalance,
}

/// The cost factors of the three stages a threaded step cuts into parts.
#[derive(Clone, Debug, Default)]
pub(crate) struct StepBalance {
    pub contacts: StageBalance,
    pub bonds: StageBalance,
    pub integration: StageBalance,
    /// With slow bodies, the contact stage of a cycle's first step (the slow bodies'
    /// contacts too) and the integration of its last (the slow bodies move): their costs lie
    /// elsewhere among the bodies than at the steps between ([`crate::step::multirate`]).
    pub slow_contacts: StageBalance,
    pub slow_integration: StageBalance,
}

impl<'a, S: Scalar> World<'a, S> {
    /// Build an empty world over `storage`.
    pub fn new(storage: Storage<'a, S>) -> Result<Self, SetupError> {
        let ns = storage.spheres.len();
        if ns > MAX_SPHERE_CAPACITY || storage.bodies.len() > u32::MAX as usize / 2 {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Spheres,
                capacity: MAX_SPHERE_CAPACITY as u32,
            });
        }
        if storage.forces.len() < storage.bodies.len() {
            return Err(SetupError::Capacity {
                kind: CapacityKind::Bodies,
                capacity: storage.forces.len() as u32,
            });
        }
        let list = NeighbourList::new(
            storage.neighbours,
            storage.effect_history,
            storage.index,
            storage.cells,
            ns,
        )?;
        storage.forces.fill(BodyForce::default());
        Ok(World {
            bodies: storage.bodies,
            n_bodies: 0,
            forces: storage.forces,
            spheres: storage.spheres,
            n_spheres: 0,
            list,
            walls: heapless::Vec::new(),
            materials: heapless::Vec::new(),
            pairs: [[PairParams::default(); MAX_MATERIALS]; MAX_MATERIALS],
            gravity: Vec3::ZERO,
            dt: S::ZERO,
            dt_s: 0.0,
            time: S::ZERO,
            steps: 0,
            max_radius: S::ZERO,
            min_rayleigh_s: f64::INFINITY,
            slow_stride: 1,
            min_rayleigh_slow_s: f64::INFINITY,
            slow_runs: SlowRuns::default(),
            bond_table: Bonds::empty(),
            air_drag: AirDrag::default(),
            balance: StepBalance::default(),
        })
    }

    /// Largest accepted time step, s (∞ while the world has no sphere).
    pub fn max_timestep_s(&self) -> f64 {
        max_stable_dt_s(self.min_rayleigh_s)
    }

    /// Largest accepted long step k·dt of slow bodies, s (∞ with none;
    /// [`crate::step::multirate`]).
    pub fn max_slow_timestep_s(&self) -> f64 {
        max_stable_dt_s(self.min_rayleigh_slow_s)
    }

    /// Steps per cycle of multi-rate stepping (1: single-rate).
    pub fn slow_stride(&self) -> u32 {
        self.slow_stride
    }

    /// Smallest Rayleigh time over all spheres, s.
    pub fn min_rayleigh_time_s(&self) -> f64 {
        self.min_rayleigh_s
    }

    /// Time step, s.
    pub fn timestep_s(&self) -> f64 {
        self.dt_s
    }

    /// Simulated time, s.
    pub fn time_s(&self) -> f64 {
        self.time.to_f64() / TIME_S_TO_MS
    }

    /// Number of completed steps.
    pub fn step_count(&self) -> u64 {
        self.steps
    }

    /// How many times the neighbour list has been built: a measure of the stepping's
    /// overhead, which does not change the results (`step::neighbour_list`).
    pub fn neighbour_list_builds(&self) -> u64 {
        self.list.builds()
    }

    /// Bodies in insertion order.
    pub fn bodies(&self) -> &[Body<S>] {
        &self.bodies[..self.n_bodies as usize]
    }

    /// One body (panics if `id` is out of range, like slice indexing).
    pub fn body(&self, id: crate::body::BodyId) -> &Body<S> {
        &self.bodies()[id.0 as usize]
    }

    /// Spheres in insertion order.
    pub fn spheres(&self) -> &[Sphere<S>] {
        &self.spheres[..self.n_spheres as usize]
    }

    /// Walls in insertion order.
    pub fn walls(&self) -> &[Wall<S>] {
        &self.walls
    }

    /// Materials in insertion order.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// Gravity, mm/ms².
    pub fn gravity(&self) -> Vec3<S> {
        self.gravity
    }

    /// Neighbour-list entries the world can hold (contacts and near pairs of all spheres).
    pub fn neighbour_capacity(&self) -> usize {
        self.list.capacity()
    }

    /// The live contacts of sphere `s` that carry history (sphere–sphere contacts it owns,
    /// then its wall contacts; in a multi-rate world a slow sphere's contacts with other slow
    /// spheres come last), in list order; empty if out of range. Neighbour-list entries of
    /// pairs that are not touching are skipped.
    pub fn contact_slots(&self, s: u32) -> impl Iterator<Item = ContactSlot<S>> + '_ {
        let live = self.list.live();
        let range = if s < self.n_spheres {
            live.range(s as usize)
        } else {
            0..0
        };
        range
            .filter(move |&e| live.entries[e].partner & LIVE_FLAG != 0)
            .map(move |e| ContactSlot {
                partner: key_of(live.entries[e].partner),
                state: ContactState::join(&live.entries[e], live.effects.get(e)),
            })
    }

    /// Number of live contacts (sphere–sphere and sphere–wall) with stored history.
    pub fn contact_count(&self) -> u32 {
        (0..self.n_spheres)
            .map(|s| self.contact_slots(s).count() as u32)
            .sum()
    }

    /// Total kinetic energy (translational + rotational), mJ.
    pub fn kinetic_energy_mj(&self) -> f64 {
        self.bodies().iter().map(|b| b.kinetic_energy_mj()).sum()
    }
}
