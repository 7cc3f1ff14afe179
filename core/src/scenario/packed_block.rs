//! A packed block: pod spheres on a cubic lattice, each pressed a little into its six
//! neighbours, inside a steel box, under gravity. Every sphere touches from the first step,
//! so a short run measures the cost of a dense contact network at any size, and the cost per
//! particle-step of a 2 000-sphere and a 200 000-sphere block can be compared directly
//! (`benches/benches/scale.rs`).
//!
//! The spheres, materials, pairs and time step are those of the bench bed (DESIGN §8).
//! Lattice spacing 2R − [`LATTICE_OVERLAP_UM`]; the block fills an n×n×m box of lattice
//! sites (n² sites per layer, m layers, the last one partly filled) and the box walls lie at
//! the lattice's outer surfaces, also pressed in by the same overlap. Spheres are numbered
//! layer by layer, row by row, like the bench bed's.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::PackedBlock;
//! let block = PackedBlock { particles: 64 };
//! let mut arenas = arachis_core::owned::OwnedStorage::<Fx>::new(block.storage_lengths());
//! let mut world = block.build(arenas.storage()).unwrap();
//! world.run(5).unwrap();
//! assert!(world.contact_count() >= 3 * 48); // at least the lattice bonds of a 4×4×4 block
//! ```

use super::bench_bed::{SPHERE_RADIUS_UM, TIMESTEP_S};
use super::materials::{GRAVITY_M_S2, POD, POD_POD, POD_STEEL, STEEL};
use super::ScenarioError;
use crate::body::{SphereSpec, Storage, StorageLengths};
use crate::num::Scalar;
use crate::wall::{WallGeometry, WallSpec};
use crate::world::World;

/// Overlap of lattice neighbours and of the outer spheres with the walls, µm: about the
/// overlap of a pod sphere under a few sphere weights (DESIGN §4 gives 18 µm for a pod on
/// R* = 2 mm under its own weight).
pub const LATTICE_OVERLAP_UM: i64 = 10;

/// A packed block of `particles` pod spheres (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PackedBlock {
    /// Number of spheres (≥ 1).
    pub particles: u32,
}

impl PackedBlock {
    /// Arena lengths the block needs (one body and one sphere per particle).
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = self.particles as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Lattice sites per row and per layer side: the smallest n with n³ ≥ particles.
    fn side(&self) -> u32 {
        let mut n = 1u32;
        while (n as u64).pow(3) < self.particles as u64 {
            n += 1;
        }
        n
    }

    /// Build the block over `storage`, dt as the bench bed's.
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        if self.particles == 0 {
            return Err(ScenarioError::NoParticles);
        }
        let mut world = World::new(storage)?;
        let pod = world.add_material(POD)?;
        let steel = world.add_material(STEEL)?;
        world.set_pair(pod, pod, POD_POD)?;
        world.set_pair(pod, steel, POD_STEEL)?;
        world.set_gravity_m_s2(GRAVITY_M_S2)?;
        let n = self.side();
        let layers = self.particles.div_ceil(n * n);
        let um = 1e-6;
        let r_um = SPHERE_RADIUS_UM;
        let spacing_um = 2 * r_um - LATTICE_OVERLAP_UM;
        // Walls at the outer surfaces of the lattice, pressed in by the overlap.
        let far = |sites: u32| ((sites as i64 - 1) * spacing_um + r_um - LATTICE_OVERLAP_UM) as f64;
        let near = -(r_um - LATTICE_OVERLAP_UM) as f64;
        world.add_wall(WallSpec::fixed(
            WallGeometry::AaBox {
                min_m: [near * um, near * um, near * um],
                max_m: [far(n) * um, far(n) * um, far(layers) * um],
            },
            steel,
        ))?;
        for k in 0..self.particles {
            let (x, y, z) = (k % n, (k / n) % n, k / (n * n));
            let at = |i: u32| (i as i64 * spacing_um) as f64 * um;
            world.add_sphere(SphereSpec::at_rest(
                pod,
                r_um as f64 * um,
                [at(x), at(y), at(z)],
            ))?;
        }
        world.set_timestep_s(TIMESTEP_S)?;
        Ok(world)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;
    use crate::owned::OwnedStorage;

    /// A full 3×3×3 block: 54 lattice contacts (3 directions × 2 × 9) and 54 wall contacts
    /// (6 faces × 9 spheres), all touching from the first step.
    #[test]
    fn every_lattice_neighbour_and_wall_touches() {
        let block = PackedBlock { particles: 27 };
        let mut arenas = OwnedStorage::<Fx>::new(block.storage_lengths());
        let mut world = block.build(arenas.storage()).unwrap();
        world.step().unwrap();
        assert_eq!(world.contact_count(), 54 + 54);
    }

    #[test]
    fn refuses_an_empty_block() {
        let block = PackedBlock { particles: 0 };
        let mut arenas = OwnedStorage::<Fx>::new(block.storage_lengths());
        assert_eq!(
            block.build(arenas.storage()).err(),
            Some(ScenarioError::NoParticles)
        );
    }
}
