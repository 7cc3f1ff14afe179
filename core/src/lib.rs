//! # Arachis core
//!
//! A `no_std`, allocation-free discrete-element (DEM) core for peanut pods: Hertz–Mindlin
//! (no slip) contacts with CDT rolling friction (seed 000 eqs. (1)–(7), EDEM conventions of
//! DESIGN §2), spheres and rigid multi-sphere clumps, moving walls, and bit-exact stepping in
//! fixed point, with an `f64` reference path running the same code.
//!
//! ## Numbers and units
//! Stepping is generic over [`num::Scalar`]: [`num::Fx`] (Q32.32 fixed point: integer
//! arithmetic only, round-to-nearest products, overflow poisoning reported as
//! [`error::StepError::Overflow`]) or `f64`. Set-up may use `f64` (through `libm`) and then
//! quantises.
//!
//! Internal units are **mm, g, ms** (DESIGN §4, confirmed): force N, stress MPa, velocity m/s,
//! energy mJ, torque N·mm, angular velocity rad/ms, gravity 9.81e-3 mm/ms². Q32.32 has
//! resolution 2.3e-10 and range ±2.1e9. Typical magnitudes (peanut-pod bed of DESIGN §8):
//!
//! | quantity | unit | typical | Q32.32 relative resolution |
//! |---|---|---|---|
//! | radius | mm | 2–10 | 1e-10 |
//! | overlap α (own weight, R* 2 mm) | mm | 0.018 (down to 1e-5) | 1.3e-8 (2e-5) |
//! | contact radius a | mm | 0.19 | 1.2e-9 |
//! | mass (R 4 mm pod sphere / pod) | g | 0.16 / 2.3 | 1.5e-9 |
//! | inertia 0.4mR² | g·mm² | 1 | 2e-10 |
//! | weight | N | 1.5e-3 – 0.022 | 1.5e-7 |
//! | E* pod–pod / pod–steel | MPa | 5 / 9.9 | ≪1e-9 |
//! | 8G* pod–steel | MPa | 36 | ≪1e-9 |
//! | steel G | MPa | 7.9e4 | ≪1e-9 |
//! | velocity (pour / drum tip) | mm/ms | 0.2 / 20 | 1e-9 |
//! | dt | ms | 5e-4 – 5e-2 | 4.6e-7 (at 5e-4) |
//! | v·dt per step | mm | 4e-3 | 6e-8 |
//! | g·dt per step | mm/ms | 2e-4 | 1.2e-6 |
//! | kinetic energy of a pod at 1 m/s | mJ | 1.2 | 2e-10 |
//!
//! Why not SI or other scalings: in SI, overlaps (1e-8 m) and moduli (1e11 Pa) cannot share
//! one Q32.32 format. With mm-g-ms the largest working values (steel G 7.9e4 MPa, positions of
//! a few hundred mm, forces of ≲1e3 N in impacts) leave ≥ 4 decades of headroom and the
//! smallest (per-step increments g·dt ≈ 2e-4) keep ≥ 6 significant digits; the
//! round-to-nearest product keeps the rounding error unbiased. The per-step gravity kick is
//! the most quantised quantity (1.2e-6 relative at dt 0.02 ms), which is why the fixed-vs-f64
//! figures are measured, not argued.
//!
//! ### Determinism of division and square root
//! `Fx` division and square root are defined as exact integer functions (quotient rounded to
//! nearest, ties away from zero; square root rounded to nearest). Division is computed with
//! 128-bit integer division and the square root, below 2^64, with multiplications and
//! comparisons only (a table, one Newton step, one residual step and an exact branch-free
//! finish; `core`'s integer `isqrt` above), so stepping is integer-only by default (DESIGN §5),
//! as targets without an FPU need. The opt-in `float-estimate` feature computes the square
//! root from a hardware `f64` estimate corrected to the exact integer answer with integer
//! multiply-and-compare, so the result never depends on the estimate (measured 23 ns against
//! 54 ns for `core`'s `isqrt`, which the default no longer uses below 2^64); unit tests check
//! both give identical bits on 200 000 random operands.
//!
//! ### Overflow
//! Every `Fx` operation that overflows returns a poison value that propagates like a NaN; the
//! stepper checks validity once per contact (force, torques, history) and once per body (after
//! integration), and returns [`error::StepError::Overflow`] naming the stage and the bodies or
//! wall. Nothing wraps and nothing panics.
//!
//! ## Contact law in one paragraph
//! Seed 000 eqs. (1)–(7) with the EDEM conventions of DESIGN §2, as separate terms
//! ([`contact`]): Hertz normal, normal damping (β from e), **total normal force clipped at ≥ 0
//! (never attractive)**, Mindlin tangential spring with history projected on the tangent
//! plane, tangential damping, Coulomb limit with history rescale, EDEM CDT rolling friction
//! T = −μr·Fn·Ri·ω̂i (body ω, lever from the centre of mass) capped so it never reverses ω.
//! Integration is kick–drift (symplectic Euler = leapfrog form of velocity Verlet).
//!
//! ## Layout
//! - [`num`]: `Scalar`, `Fx`, `Vec3`, `Quat`; [`units`]: conversion factors;
//! - [`material`], [`pair`]: materials and precomputed pair constants;
//! - [`contact`]: one file per contact term; [`contact::history`]: tangential history;
//! - [`body`]: bodies, spheres, clump mass properties, caller-provided [`body::Storage`];
//! - [`wall`]: planes, cylinders, boxes;
//! - [`bond`]: bonded-particle model (seed 001 §2.4): bond sets, storage, formation, breakage;
//! - [`step`]: broad phase, narrow phase, body forces, integration, wall motion;
//! - [`timestep`]: Rayleigh time; [`digest`]: state hash and dump; [`error`]: typed errors;
//! - [`world`]: the [`world::World`] and its set-up API.
//!
//! ## Determinism
//! Insertion or sorted order only, no hash maps, no `usize` in hashed data (DESIGN §5).
#![no_std]
#![deny(missing_docs)]

#[cfg(any(test, feature = "alloc"))]
extern crate alloc;

pub mod body;
pub mod bond;
pub mod contact;
pub mod digest;
pub mod effects;
pub mod error;
pub mod material;
pub mod num;
#[cfg(any(test, feature = "alloc"))]
pub mod owned;
pub mod pair;
pub mod scenario;
pub mod state_words;
pub mod step;
pub mod timestep;
pub mod units;
pub mod wall;
pub mod world;

/// The names most users need.
pub mod prelude {
    pub use crate::body::{
        Body, BodyForce, BodyId, ClumpSpec, ClumpSphere, MassProperties, Sphere, SphereSpec,
        Storage, StorageLengths,
    };
    pub use crate::contact::{
        ContactSlot, Conventions, EffectHistory, FrictionConvention, NeighbourEntry,
        RollingConvention,
    };
    pub use crate::error::{SetupError, StepError};
    pub use crate::material::{MaterialId, MaterialSpec, PoissonRange};
    pub use crate::num::{Fx, Scalar, Vec3};
    pub use crate::pair::{PairSpec, TermSwitches};
    pub use crate::step::parts::{Parallel, Serial};
    pub use crate::wall::{WallGeometry, WallId, WallSpec};
    pub use crate::world::{ThreadScratch, World};
}
