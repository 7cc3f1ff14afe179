//! The step pipeline (DESIGN §6), one module per stage. Each stage is a function of the parts
//! of the world it needs (bodies, spheres, the neighbour list, walls, bonds, force sums);
//! none of them knows the world, which calls them in order (`World::step_with`):
//!
//! 1. body forces: [`air_drag`] (gravity enters in the integrator as g itself);
//! 2. [`neighbour_list`]: Verlet list with a skin, rebuilt from the [`broad_phase`] cell grid
//!    only when a sphere or wall may have moved by half the skin;
//! 3. [`narrow_phase`]: sphere–sphere and sphere–wall geometry, then the contact terms of
//!    [`crate::pair::PairParams`]; forces and torques are summed per body;
//! 4. [`bonds`]: bonded-particle loads, breakage and scheduled bond formation;
//! 5. [`integration`]: symplectic Euler (kick–drift), the leapfrog form of velocity Verlet,
//!    with rolling friction applied so it never reverses ω; clumps through their quaternion;
//! 6. [`wall_motion`]: walls advance at their prescribed velocity.
//!
//! Stages 3 and 5 run in [`parts`] over disjoint body ranges, and stage 4 over runs of bonds,
//! on as many threads as the caller's runner has, cut where the runner's measured times say
//! the parts take equally long ([`balance`]). In fixed point, forces are summed as exact integers, so the result
//! does not depend on the order of contacts or on the number of parts (DESIGN §5); the order
//! is fixed anyway, so a one-part `f64` run is reproducible too.

pub mod air_drag;
pub mod balance;
pub mod bonds;
pub mod broad_phase;
pub mod integration;
pub mod multirate;
pub mod narrow_phase;
pub mod neighbour_list;
pub mod parts;
pub mod prefetch;
pub mod wall_motion;
