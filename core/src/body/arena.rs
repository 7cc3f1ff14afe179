//! [`Storage`]: the caller-provided fixed-capacity arenas a world runs in. The core never
//! allocates; the caller builds these slices from arrays (embedded) or `Vec`s (host).
//! [`StorageLengths`] gives lengths that fit a number of bodies and spheres.
//!
//! ```
//! use arachis_core::body::{Body, BodyForce, Sphere, Storage, StorageLengths};
//! use arachis_core::contact::NeighbourEntry;
//! use arachis_core::num::Fx;
//! let len = StorageLengths::for_spheres(4, 4);
//! let mut bodies = [Body::<Fx>::default(); 4];
//! let mut forces = [BodyForce::<Fx>::default(); 4];
//! let mut spheres = [Sphere::<Fx>::default(); 4];
//! let mut neighbours = [NeighbourEntry::<Fx>::default(); 2 * 4 * 12];
//! let mut index = [0u32; 4 * 4 + 2];
//! let mut cells = [0u32; 64];
//! assert_eq!(len.neighbours, neighbours.len());
//! assert_eq!(len.index, index.len());
//! let storage = Storage {
//!     bodies: &mut bodies, forces: &mut forces, spheres: &mut spheres,
//!     neighbours: &mut neighbours, effect_history: &mut [],
//!     index: &mut index, cells: &mut cells,
//! };
//! # let _ = storage;
//! ```

use super::{Body, BodyForce, Sphere};
use crate::contact::{EffectHistory, NeighbourEntry};
use crate::num::Scalar;

/// Neighbour-list entries per sphere that [`StorageLengths::for_spheres`] provides, on
/// average over the world (the list is packed, so a crowded sphere borrows room from a lonely
/// one). Each pair is owned by its lower id. With the skin R/4, the list held at most 2.9
/// entries per sphere on the DESIGN §8 bed and 2.6 in the quick pod pile (averages over the
/// world, the largest over every rebuild; core/API_NOTES.md). A single pod sphere in a pile
/// of clumps owns up to about 8; the rest is margin. Running out is
/// [`crate::error::StepError::ContactCapacity`].
pub const DEFAULT_NEIGHBOURS_PER_SPHERE: usize = 12;

/// Grid cells per sphere that [`StorageLengths::for_spheres`] provides (plus
/// [`EXTRA_GRID_CELLS`]); more cells give a finer grid for spread-out particles.
pub const GRID_CELLS_PER_SPHERE: usize = 8;

/// Grid cells [`StorageLengths::for_spheres`] adds for small worlds.
pub const EXTRA_GRID_CELLS: usize = 64;

/// The arenas of one world.
pub struct Storage<'a, S: Scalar> {
    /// Body arena; its length is the body capacity.
    pub bodies: &'a mut [Body<S>],
    /// Per-body force sums of the current step: at least as long as `bodies`.
    pub forces: &'a mut [BodyForce<S>],
    /// Sphere arena; its length is the sphere capacity.
    pub spheres: &'a mut [Sphere<S>],
    /// The neighbour list with its contact history, double-buffered: two halves of equal
    /// length, each the entry capacity shared by all spheres.
    pub neighbours: &'a mut [NeighbourEntry<S>],
    /// History of the optional effects ([`crate::effects`]) beside each neighbour-list entry:
    /// empty (effects that keep history are then refused at set-up) or as long as
    /// `neighbours`.
    pub effect_history: &'a mut [EffectHistory<S>],
    /// Per-sphere scratch indices (grid binning and the list's entry offsets): at least
    /// 4 × sphere capacity + 2.
    pub index: &'a mut [u32],
    /// Grid cell table, length ≥ 2; more cells give a finer grid (≥ 4 × sphere capacity is
    /// comfortable). When the particles' bounding box needs more cells, cells are merged.
    pub cells: &'a mut [u32],
}

/// Recommended slice lengths for a given capacity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StorageLengths {
    /// `bodies` and `forces` length.
    pub bodies: usize,
    /// `spheres` length.
    pub spheres: usize,
    /// `neighbours` length (both halves).
    pub neighbours: usize,
    /// `effect_history` length (0 or `neighbours`).
    pub effect_history: usize,
    /// `index` length.
    pub index: usize,
    /// `cells` length.
    pub cells: usize,
}

impl StorageLengths {
    /// Lengths for `bodies` bodies and `spheres` spheres with
    /// [`DEFAULT_NEIGHBOURS_PER_SPHERE`] list entries per sphere, no effect history, and
    /// [`GRID_CELLS_PER_SPHERE`] grid cells per sphere (+ [`EXTRA_GRID_CELLS`]).
    pub fn for_spheres(bodies: usize, spheres: usize) -> Self {
        StorageLengths {
            bodies,
            spheres,
            neighbours: 2 * spheres * DEFAULT_NEIGHBOURS_PER_SPHERE,
            effect_history: 0,
            index: index_len(spheres),
            cells: GRID_CELLS_PER_SPHERE * spheres + EXTRA_GRID_CELLS,
        }
    }

    /// The same lengths with room for the history of optional effects (hysteresis, EPSD
    /// rolling, JKR), which [`crate::world::World::set_pair_effects`] needs.
    pub fn with_effects(self) -> Self {
        StorageLengths {
            effect_history: self.neighbours,
            ..self
        }
    }

    /// The same lengths, with room for effect history when one of `pairs` keeps some
    /// ([`crate::pair::PairSpec::needs_effect_history`]: LIGGGHTS' `epsd2` rolling).
    pub fn with_effects_for(self, pairs: &[crate::pair::PairSpec]) -> Self {
        if pairs.iter().any(|p| p.needs_effect_history()) {
            self.with_effects()
        } else {
            self
        }
    }

    /// The same lengths with `per_sphere` neighbour-list entries per sphere on average.
    pub fn with_neighbours_per_sphere(self, per_sphere: usize) -> Self {
        let neighbours = 2 * self.spheres * per_sphere;
        StorageLengths {
            neighbours,
            effect_history: if self.effect_history > 0 {
                neighbours
            } else {
                0
            },
            ..self
        }
    }
}

/// Length of [`Storage::index`] for a sphere capacity: the cell of each sphere, the spheres
/// sorted by cell, and the list's entry offsets of both halves (n + 1 each).
pub const fn index_len(spheres: usize) -> usize {
    4 * spheres + 2
}
