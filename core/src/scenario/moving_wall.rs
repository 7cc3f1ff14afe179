//! A wall moving through a pile: a small pile of pod spheres (two sizes) is poured onto a
//! steel floor and left to settle next to a steel blade (a plane); then the blade moves
//! through the pile at a prescribed velocity, like a bulldozer blade or a digging share.
//!
//! The blade is the plane x = [`BLADE_START_X_MM`] facing +x. It is present while the pile
//! settles (so no sphere can end up behind it: a plane contact is only meaningful on its
//! particle side) and is set moving at [`BLADE_VELOCITY_M_S`] once the settle steps are done.
//! Nothing stands on the far side, so the pushed spheres heap up and spill forward instead of
//! being crushed against another wall.

use super::insertion::{insert_random_spheres, InsertionRegion, InsertionRequest};
use super::materials::{GRAVITY_M_S2, POD, POD_POD, POD_STEEL, STEEL};
use super::{ScenarioError, SplitMix64};
use crate::body::{Storage, StorageLengths};
use crate::num::Scalar;
use crate::wall::{WallGeometry, WallId, WallSpec};
use crate::world::World;

/// Spheres of each size in the pile.
pub const SPHERES_PER_SIZE: u32 = 75;
/// The two sphere radii, µm: pod-sized spheres, polydisperse so the pile does not crystallise.
pub const RADII_UM: [i64; 2] = [4_000, 3_000];
/// Half width of the square footprint of inserted centres, µm.
pub const PILE_HALF_WIDTH_UM: i64 = 30_000;
/// Lowest inserted centre, µm (above the floor by more than the largest radius).
pub const PILE_Z_MIN_UM: i64 = 4_500;
/// Highest inserted centre, µm.
pub const PILE_Z_MAX_UM: i64 = 30_000;
/// Blade position at set-up, mm: 3 mm clear of the nearest possible sphere surface
/// (−30 mm centre − 4 mm radius).
pub const BLADE_START_X_MM: f64 = -37.0;
/// Blade velocity once the pile has settled, m/s: 40 mm in 2 000 steps of 2e-5 s.
pub const BLADE_VELOCITY_M_S: [f64; 3] = [1.0, 0.0, 0.0];
/// Steps the pile settles before the blade moves: 0.12 s, longer than the 78 ms free fall
/// from the highest insertion point.
pub const DEFAULT_SETTLE_STEPS: u64 = 6_000;
/// Time step, s (the bench bed's dt, DESIGN §8).
pub const TIMESTEP_S: f64 = 2e-5;
/// Default seed of the insertion draws.
pub const DEFAULT_SEED: u64 = 0xB1_ADE;
/// Candidates drawn per sphere before insertion gives up (the pile fills ~18 % of its
/// envelope, so a few candidates per sphere suffice).
const MAX_ATTEMPTS_PER_SPHERE: u32 = 10_000;

/// Index of the blade among the scenario's walls (the floor is wall 0).
pub const BLADE: WallId = WallId(1);

/// The moving-wall scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MovingWallPile {
    /// Seed of the insertion draws.
    pub seed: u64,
    /// Steps run inside [`MovingWallPile::build`] before the blade starts moving.
    pub settle_steps: u64,
}

impl Default for MovingWallPile {
    fn default() -> Self {
        MovingWallPile {
            seed: DEFAULT_SEED,
            settle_steps: DEFAULT_SETTLE_STEPS,
        }
    }
}

impl MovingWallPile {
    /// Number of spheres in the pile.
    pub const SPHERES: u32 = SPHERES_PER_SIZE * RADII_UM.len() as u32;

    /// Arena lengths this scenario needs.
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = Self::SPHERES as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Build the pile over `storage`, let it settle for `settle_steps`, and set the blade
    /// moving. The returned world is at step `settle_steps`.
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        let mut world = World::new(storage)?;
        let pod = world.add_material(POD)?;
        let steel = world.add_material(STEEL)?;
        world.set_pair(pod, pod, POD_POD)?;
        world.set_pair(pod, steel, POD_STEEL)?;
        world.set_gravity_m_s2(GRAVITY_M_S2)?;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: [0.0, 0.0, 1.0],
            },
            steel,
        ))?;
        let blade = world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [BLADE_START_X_MM / crate::units::LENGTH_M_TO_MM, 0.0, 0.0],
                normal: [1.0, 0.0, 0.0],
            },
            steel,
        ))?;
        debug_assert_eq!(blade, BLADE);
        let region = InsertionRegion::Box {
            min_um: [-PILE_HALF_WIDTH_UM, -PILE_HALF_WIDTH_UM, PILE_Z_MIN_UM],
            max_um: [PILE_HALF_WIDTH_UM, PILE_HALF_WIDTH_UM, PILE_Z_MAX_UM],
        };
        let mut rng = SplitMix64::new(self.seed);
        for radius_um in RADII_UM {
            let request = InsertionRequest {
                count: SPHERES_PER_SIZE,
                radius_um,
                material: pod,
                velocity_m_s: [0.0; 3],
                max_attempts_per_sphere: MAX_ATTEMPTS_PER_SPHERE,
            };
            insert_random_spheres(&mut world, &mut rng, &region, &request)?;
        }
        world.set_timestep_s(TIMESTEP_S)?;
        world.run(self.settle_steps)?;
        world.set_wall_velocity_m_s(BLADE, BLADE_VELOCITY_M_S)?;
        Ok(world)
    }
}
