//! Owned storage for core worlds. The core never allocates: it steps in arenas the caller
//! provides. On the host those arenas are `Vec`s, sized by the core's own
//! [`StorageLengths`](arachis_core::body::StorageLengths) (and a bond count for bonded
//! worlds); the core's `alloc` feature builds them ([`arachis_core::owned`]), the same way for
//! every command, benchmark and test.
//!
//! ```
//! use arachis::arena::OwnedStorage;
//! use arachis_core::prelude::*;
//! let mut arena = OwnedStorage::<Fx>::new(StorageLengths::for_spheres(1, 1));
//! let world = World::new(arena.storage()).unwrap();
//! assert_eq!(world.bodies().len(), 0);
//! ```

pub use arachis_core::owned::{OwnedBonds, OwnedStorage, OwnedThreadScratch};
