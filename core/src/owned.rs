//! Owned arenas for hosts with a heap (feature `alloc`, off by default): `Vec`s sized by
//! [`StorageLengths`] that lend themselves to a world as its [`Storage`], so every host,
//! benchmark, fuzz target and test builds them the same way. The core itself never
//! allocates; embedded users pass arrays instead.
//!
//! ```
//! use arachis_core::owned::OwnedStorage;
//! use arachis_core::prelude::*;
//! let mut arena = OwnedStorage::<Fx>::new(StorageLengths::for_spheres(1, 1));
//! let world = World::new(arena.storage()).unwrap();
//! assert_eq!(world.bodies().len(), 0);
//! ```

use crate::body::{Body, BodyForce, Sphere, Storage, StorageLengths};
use crate::bond::{Bond, BondBreak, BondStorage};
use crate::contact::{EffectHistory, NeighbourEntry};
use crate::num::Scalar;
use alloc::vec;
use alloc::vec::Vec;

/// The arenas of one world.
pub struct OwnedStorage<S: Scalar> {
    bodies: Vec<Body<S>>,
    forces: Vec<BodyForce<S>>,
    spheres: Vec<Sphere<S>>,
    neighbours: Vec<NeighbourEntry<S>>,
    effect_history: Vec<EffectHistory<S>>,
    index: Vec<u32>,
    cells: Vec<u32>,
}

impl<S: Scalar> OwnedStorage<S> {
    /// Arenas of the given lengths.
    pub fn new(lengths: StorageLengths) -> Self {
        OwnedStorage {
            bodies: vec![Body::default(); lengths.bodies],
            forces: vec![BodyForce::default(); lengths.bodies],
            spheres: vec![Sphere::default(); lengths.spheres],
            neighbours: vec![NeighbourEntry::default(); lengths.neighbours],
            effect_history: vec![EffectHistory::default(); lengths.effect_history],
            index: vec![0; lengths.index],
            cells: vec![0; lengths.cells],
        }
    }

    /// The arenas as the core's [`Storage`].
    pub fn storage(&mut self) -> Storage<'_, S> {
        Storage {
            bodies: &mut self.bodies,
            forces: &mut self.forces,
            spheres: &mut self.spheres,
            neighbours: &mut self.neighbours,
            effect_history: &mut self.effect_history,
            index: &mut self.index,
            cells: &mut self.cells,
        }
    }

    /// Bytes the arenas take (for memory reports).
    pub fn bytes(&self) -> usize {
        use core::mem::size_of;
        self.bodies.len() * size_of::<Body<S>>()
            + self.forces.len() * size_of::<BodyForce<S>>()
            + self.spheres.len() * size_of::<Sphere<S>>()
            + self.neighbours.len() * size_of::<NeighbourEntry<S>>()
            + self.effect_history.len() * size_of::<EffectHistory<S>>()
            + (self.index.len() + self.cells.len()) * size_of::<u32>()
    }
}

/// The bond arena and break log of one bonded world.
pub struct OwnedBonds<S: Scalar> {
    bonds: Vec<Bond<S>>,
    log: Vec<BondBreak<S>>,
}

impl<S: Scalar> OwnedBonds<S> {
    /// Room for `bonds` bonds, and a break log as long (every bond can break once).
    pub fn new(bonds: usize) -> Self {
        OwnedBonds {
            bonds: vec![Bond::default(); bonds],
            log: vec![BondBreak::default(); bonds],
        }
    }

    /// The arenas as the core's [`BondStorage`].
    pub fn storage(&mut self) -> BondStorage<'_, S> {
        BondStorage {
            bonds: &mut self.bonds,
            log: &mut self.log,
        }
    }
}

/// The private force sums of the parts of a threaded step
/// ([`crate::world::World::step_with`]): one arena per part, each as long as the body arena.
pub struct OwnedThreadScratch<S: Scalar> {
    arenas: Vec<Vec<BodyForce<S>>>,
}

impl<S: Scalar> OwnedThreadScratch<S> {
    /// Arenas for `parts` parts of a world with `bodies` body slots (none for one part, which
    /// needs no private sums).
    pub fn new(parts: usize, bodies: usize) -> Self {
        let n = if parts > 1 { parts } else { 0 };
        OwnedThreadScratch {
            arenas: (0..n).map(|_| vec![BodyForce::default(); bodies]).collect(),
        }
    }

    /// The arenas as the slices [`crate::world::World::step_with`] takes.
    pub fn arenas(&mut self) -> Vec<&mut [BodyForce<S>]> {
        self.arenas.iter_mut().map(|a| &mut a[..]).collect()
    }

    /// Bytes the arenas take.
    pub fn bytes(&self) -> usize {
        self.arenas.iter().map(|a| a.len()).sum::<usize>() * core::mem::size_of::<BodyForce<S>>()
    }
}
