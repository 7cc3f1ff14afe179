//! Deterministic, allocation-free set-ups of the standard scenarios.
//!
//! Each scenario builds a [`World`](crate::world::World) over arenas the caller provides
//! (ask the scenario for its [`StorageLengths`](crate::body::StorageLengths)), for any
//! [`Scalar`](crate::num::Scalar): a fixed-point and an `f64` world built from the same seed
//! start from the same state up to quantisation, so their difference is a measured figure.
//! Randomness comes from [`SplitMix64`], an integer-only generator, and random positions are
//! drawn on an integer micrometre lattice ([`insertion`]), so a set-up is identical on every
//! machine and in debug and release builds.
//!
//! | scenario | file | what it exercises |
//! |---|---|---|
//! | [`BenchBed`] | `bench_bed.rs` | DESIGN §8 pour into a steel cylinder: many sphere–sphere and sphere–wall contacts |
//! | [`BulkDensity`] | `bulk_density.rs` | pod spheres falling from a drop height into a steel measuring cylinder: impacts on a growing bed |
//! | [`Hopper`] | `hopper.rs` | a silo of pod spheres discharging through an orifice plate onto a catch floor: a wall with a hole, a wall set moving and stopped mid-run |
//! | [`Drum`] | `drum.rs` | pod spheres in a drum spinning about a horizontal axis, end plates spinning with it: spinning walls |
//! | [`ClumpSlide`] | `clump_slide.rs` | two- and three-sphere clumps sliding down a steel incline into each other and a stop wall |
//! | [`MovingWallPile`] | `moving_wall.rs` | a small pile settled on a floor, then a plane blade moving through it at a prescribed velocity |
//! | [`PackedBlock`] | `packed_block.rs` | spheres on a cubic lattice pressed into each other and a steel box: a dense contact network at any size (throughput at scale) |
//! | [`PullOff`] | `pull_off.rs` | a bonded pod stalk clamped at one end, a pod clump bonded to the other and pulled off at constant speed (bonds, breakage, kinematic bodies) |
//!
//! [`measure`] holds the figures reported for a bed (bed height, centre-of-mass height).
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::BenchBed;
//! let bed = BenchBed::with_particles(20);
//! let mut arenas = arachis_core::owned::OwnedStorage::<Fx>::new(bed.storage_lengths());
//! let mut world = bed.build(arenas.storage()).unwrap();
//! world.run(10).unwrap();
//! assert_eq!(world.bodies().len(), 20);
//! ```

pub mod bench_bed;
pub mod bulk_density;
pub mod clump_slide;
pub mod drum;
pub mod hopper;
pub mod insertion;
pub mod materials;
pub mod measure;
pub mod moving_wall;
pub mod packed_block;
pub mod prng;
pub mod pull_off;

pub use bench_bed::BenchBed;
pub use bulk_density::BulkDensity;
pub use clump_slide::ClumpSlide;
pub use drum::Drum;
pub use hopper::Hopper;
pub use moving_wall::MovingWallPile;
pub use packed_block::PackedBlock;
pub use prng::SplitMix64;
pub use pull_off::PullOff;

use crate::error::{SetupError, StepError};
use core::fmt;

/// Why a scenario could not be built or run.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ScenarioError {
    /// The world refused an input (capacity, range, time step): see the inner error.
    Setup(SetupError),
    /// A step failed while the scenario prepared its initial state (e.g. settling a pile).
    Step(StepError),
    /// The scenario needs at least one particle.
    NoParticles,
    /// The bond set-up refused an input (see the inner error).
    Bond(crate::bond::BondError),
    /// More particles than random insertion can place in the scenario's region.
    TooManyParticles {
        /// Particles requested.
        requested: u32,
        /// Largest count the region accepts.
        max: u32,
    },
    /// Random insertion found no free place for a sphere within its attempt budget.
    InsertionFailed {
        /// Spheres placed before the failure.
        placed: u32,
        /// Spheres requested.
        requested: u32,
        /// Candidates drawn for the sphere that failed.
        attempts_per_sphere: u32,
    },
    /// Ordering by layers ([`insertion::order_by_layers`]) needs a world of single spheres,
    /// without bonds, that has not stepped yet, and a positive layer thickness.
    NotReorderable,
    /// A length of a scenario's geometry outside what the scenario can hold (the hopper's
    /// orifice diameter, the bulk-density pour's drop height).
    LengthOutOfRange {
        /// What the length is, e.g. "orifice diameter".
        what: &'static str,
        /// The length asked for, µm.
        value_um: i64,
        /// Smallest accepted, µm.
        min_um: i64,
        /// Largest accepted, µm.
        max_um: i64,
    },
}

impl From<SetupError> for ScenarioError {
    fn from(e: SetupError) -> Self {
        ScenarioError::Setup(e)
    }
}

impl From<crate::bond::BondError> for ScenarioError {
    fn from(e: crate::bond::BondError) -> Self {
        ScenarioError::Bond(e)
    }
}

impl From<StepError> for ScenarioError {
    fn from(e: StepError) -> Self {
        ScenarioError::Step(e)
    }
}

impl fmt::Display for ScenarioError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            ScenarioError::Setup(e) => write!(f, "{e}"),
            ScenarioError::Step(e) => write!(f, "while preparing the scenario: {e}"),
            ScenarioError::NoParticles => write!(f, "the number of particles must be at least 1"),
            ScenarioError::Bond(e) => write!(f, "{e}"),
            ScenarioError::TooManyParticles { requested, max } => write!(
                f,
                "{requested} particles do not fit the insertion region without overlap; \
                 at most {max} can be inserted"
            ),
            ScenarioError::InsertionFailed {
                placed,
                requested,
                attempts_per_sphere,
            } => write!(
                f,
                "random insertion placed only {placed} of {requested} particles: no free \
                 place found in {attempts_per_sphere} attempts; ask for fewer particles"
            ),
            ScenarioError::NotReorderable => write!(
                f,
                "spheres can only be ordered by layers in a world of single spheres, \
                 without bonds, that has not stepped yet, and with a positive layer thickness"
            ),
            ScenarioError::LengthOutOfRange {
                what,
                value_um,
                min_um,
                max_um,
            } => write!(
                f,
                "a {what} of {value_um} µm is outside the scenario's range {min_um}–{max_um} µm"
            ),
        }
    }
}

impl core::error::Error for ScenarioError {}
