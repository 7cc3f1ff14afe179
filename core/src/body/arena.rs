//! [`Storage`]: the caller-provided fixed-capacity arenas a world runs in. The core never
//! allocates; the caller builds these slices from arrays (embedded) or `Vec`s (host).
//!
//! ```
//! use arachis_core::body::{Body, Sphere, Storage, StorageLengths};
//! use arachis_core::contact::ContactSlot;
//! use arachis_core::num::Fx;
//! let len = StorageLengths::for_spheres(4, 4);
//! let mut bodies = [Body::<Fx>::default(); 4];
//! let mut spheres = [Sphere::<Fx>::default(); 4];
//! let mut contacts = [ContactSlot::<Fx>::default(); 2 * 4 * 16];
//! let mut index = [0u32; 16];
//! let mut cells = [0u32; 64];
//! assert_eq!(len.contacts, contacts.len());
//! let storage = Storage {
//!     bodies: &mut bodies, spheres: &mut spheres, contacts: &mut contacts,
//!     sphere_index: &mut index, cells: &mut cells,
//! };
//! # let _ = storage;
//! ```

use super::{Body, Sphere};
use crate::contact::ContactSlot;

/// Contact-history slots per sphere recommended for monodisperse packings (12 sphere
/// neighbours at most, each owned by the lower id, plus wall contacts, with margin).
pub const DEFAULT_SLOTS_PER_SPHERE: usize = 16;

/// The arenas of one world.
pub struct Storage<'a, S> {
    /// Body arena; its length is the body capacity.
    pub bodies: &'a mut [Body<S>],
    /// Sphere arena; its length is the sphere capacity.
    pub spheres: &'a mut [Sphere<S>],
    /// Contact history, double-buffered: length 2 × sphere capacity × slots per sphere
    /// (slots per sphere = `contacts.len() / (2 × spheres.len())`, at least 1).
    pub contacts: &'a mut [ContactSlot<S>],
    /// Per-sphere scratch indices: length ≥ 4 × sphere capacity.
    pub sphere_index: &'a mut [u32],
    /// Grid cell table, length ≥ 2; more cells give a finer grid (≥ 4 × sphere capacity is
    /// comfortable). When the particles' bounding box needs more cells, cells are merged.
    pub cells: &'a mut [u32],
}

/// Recommended slice lengths for a given capacity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StorageLengths {
    /// `bodies` length.
    pub bodies: usize,
    /// `spheres` length.
    pub spheres: usize,
    /// `contacts` length.
    pub contacts: usize,
    /// `sphere_index` length.
    pub sphere_index: usize,
    /// `cells` length.
    pub cells: usize,
}

impl StorageLengths {
    /// Lengths for `bodies` bodies and `spheres` spheres with
    /// [`DEFAULT_SLOTS_PER_SPHERE`] history slots and 8 grid cells per sphere (+64).
    pub fn for_spheres(bodies: usize, spheres: usize) -> Self {
        StorageLengths {
            bodies,
            spheres,
            contacts: 2 * spheres * DEFAULT_SLOTS_PER_SPHERE,
            sphere_index: 4 * spheres,
            cells: 8 * spheres + 64,
        }
    }
}
