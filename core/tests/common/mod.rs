//! Test support: owned storage and small world builders.
#![allow(dead_code)]

use arachis_core::prelude::*;

/// Owned arenas for a world (the core never allocates; tests use `Vec`s).
pub struct Owned<S: Scalar> {
    pub bodies: Vec<Body<S>>,
    pub spheres: Vec<Sphere<S>>,
    pub contacts: Vec<ContactSlot<S>>,
    pub index: Vec<u32>,
    pub cells: Vec<u32>,
}

impl<S: Scalar> Owned<S> {
    pub fn new(bodies: usize, spheres: usize) -> Self {
        let l = StorageLengths::for_spheres(bodies, spheres);
        Owned {
            bodies: vec![Body::default(); l.bodies],
            spheres: vec![Sphere::default(); l.spheres],
            contacts: vec![ContactSlot::default(); l.contacts],
            index: vec![0; l.sphere_index],
            cells: vec![0; l.cells],
        }
    }
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

/// Peanut pod material (seed 000 §3.1).
pub const POD: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 8.43e6,
    poisson: 0.386,
    density_kg_m3: 582.36,
};
/// 65Mn steel (DESIGN §8).
pub const STEEL: MaterialSpec = MaterialSpec {
    youngs_modulus_pa: 2.05e11,
    poisson: 0.3,
    density_kg_m3: 7865.0,
};
