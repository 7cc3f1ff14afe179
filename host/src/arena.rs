//! Owned storage for core worlds. The core never allocates: it steps in arenas the caller
//! provides. On the host those arenas are `Vec`s, sized by the core's own
//! [`StorageLengths`] (and a bond count for bonded worlds), kept here once for every command.
//!
//! ```
//! use arachis::arena::OwnedStorage;
//! use arachis_core::prelude::*;
//! let mut arena = OwnedStorage::<Fx>::new(StorageLengths::for_spheres(1, 1));
//! let world = World::new(arena.storage()).unwrap();
//! assert_eq!(world.bodies().len(), 0);
//! ```

use arachis_core::bond::{Bond, BondBreak, BondStorage};
use arachis_core::prelude::*;

/// The body, sphere, contact and grid arenas of one world.
pub struct OwnedStorage<S: Scalar> {
    bodies: Vec<Body<S>>,
    spheres: Vec<Sphere<S>>,
    contacts: Vec<ContactSlot<S>>,
    index: Vec<u32>,
    cells: Vec<u32>,
}

impl<S: Scalar> OwnedStorage<S> {
    /// Arenas of the given lengths.
    pub fn new(lengths: StorageLengths) -> Self {
        OwnedStorage {
            bodies: vec![Body::default(); lengths.bodies],
            spheres: vec![Sphere::default(); lengths.spheres],
            contacts: vec![ContactSlot::default(); lengths.contacts],
            index: vec![0; lengths.sphere_index],
            cells: vec![0; lengths.cells],
        }
    }

    /// The arenas as the core's [`Storage`].
    pub fn storage(&mut self) -> Storage<'_, S> {
        Storage {
            bodies: &mut self.bodies,
            spheres: &mut self.spheres,
            contacts: &mut self.contacts,
            sphere_index: &mut self.index,
            cells: &mut self.cells,
        }
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
