//! A rotating drum: pod spheres of the bench bed (DESIGN §8: radius 4 mm, pod material) fill a
//! quarter of a steel drum of radius 60 mm and length 40 mm (five sphere diameters) whose
//! axis is horizontal (+y); the drum and its two end plates spin together about that axis
//! ([`Drum::spin`], [`crate::world::World::set_wall_spin_rad_s`]). The figure of a drum is
//! its dynamic angle of repose ([`bed_angle_deg`]).
//!
//! Why the bed's centre of mass gives the angle: a bed with a flat free surface in a circular
//! drum is a circular segment, symmetric about the perpendicular dropped from the drum's axis
//! onto its surface, so its centre of mass lies on that perpendicular. The angle of the line
//! from the axis to the centre of mass, from the vertical, is therefore the surface's angle
//! from the horizontal, with no surface to detect and no bins to choose. An S-shaped surface
//! (fast drums) gives its mean inclination.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::drum::{bed_angle_deg, Drum};
//! let drum = Drum { particles: 30, seed: 1 };
//! let mut arenas = arachis_core::owned::OwnedStorage::<Fx>::new(drum.storage_lengths());
//! let mut world = drum.build(arenas.storage()).unwrap();
//! Drum::spin(&mut world, 1.0).unwrap();
//! world.run(10).unwrap();
//! assert!(bed_angle_deg(&world, 1.0).is_finite()); // the bed has not settled yet
//! ```

use super::insertion::InsertionRegion;
use super::{bench_bed, ScenarioError};
use crate::body::{Storage, StorageLengths};
use crate::num::Scalar;
use crate::wall::{WallGeometry, WallId, WallSpec};
use crate::world::World;
use core::f64::consts::PI;

/// Radius of the drum, m: fifteen sphere radii.
pub const DRUM_RADIUS_M: f64 = 0.060;
/// Length of the drum between its end plates, m: five sphere diameters.
pub const DRUM_LENGTH_M: f64 = 0.040;
/// Insertion region: centres within this of the axis in x and z, µm (the box's corners lie
/// a sphere radius and 2 mm inside the drum).
pub const INSERT_HALF_WIDTH_UM: i64 = 38_000;
/// Insertion region: centres within this of the drum's middle along the axis, µm (half a
/// millimetre clear of the end plates).
pub const INSERT_HALF_LENGTH_UM: i64 =
    (DRUM_LENGTH_M / 2.0 * UM_PER_M) as i64 - bench_bed::SPHERE_RADIUS_UM - 500;
/// The drum's wall id.
pub const SHELL: WallId = WallId(0);
/// The end plate at y = −L/2 (normal +y).
pub const NEAR_END: WallId = WallId(1);
/// The end plate at y = +L/2 (normal −y).
pub const FAR_END: WallId = WallId(2);
/// Micrometres per metre.
const UM_PER_M: f64 = 1.0e6;

/// A drum with `particles` spheres inserted from `seed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Drum {
    /// Number of spheres.
    pub particles: u32,
    /// Seed of the insertion draws.
    pub seed: u64,
}

impl Drum {
    /// Largest particle count the insertion region accepts (the bench bed's fill fraction).
    pub fn max_particles() -> u32 {
        let r = bench_bed::SPHERE_RADIUS_UM as f64;
        let width = 2.0 * (INSERT_HALF_WIDTH_UM as f64 + r);
        let length = 2.0 * (INSERT_HALF_LENGTH_UM as f64 + r);
        bench_bed::fill_limit(width * width * length)
    }

    /// Arena lengths this drum needs (one body and one sphere per particle).
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = self.particles as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Build the drum at rest over `storage`, spheres inserted at rest, with the bench bed's
    /// time step and pairs (pod material 0, steel 1; [`bench_bed::BenchBed::set_pairs`]
    /// changes the pairs).
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        bench_bed::check_count(self.particles, Self::max_particles())?;
        let mut world = bench_bed::pod_steel_world(storage)?;
        let steel = bench_bed::STEEL_MATERIAL;
        let half = DRUM_LENGTH_M / 2.0;
        let shell = world.add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 1.0, 0.0],
                radius_m: DRUM_RADIUS_M,
                length_m: None,
            },
            steel,
        ))?;
        let near = world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0, -half, 0.0],
                normal: [0.0, 1.0, 0.0],
            },
            steel,
        ))?;
        let far = world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0, half, 0.0],
                normal: [0.0, -1.0, 0.0],
            },
            steel,
        ))?;
        debug_assert_eq!((shell, near, far), (SHELL, NEAR_END, FAR_END));
        let region = InsertionRegion::Box {
            min_um: [
                -INSERT_HALF_WIDTH_UM,
                -INSERT_HALF_LENGTH_UM,
                -INSERT_HALF_WIDTH_UM,
            ],
            max_um: [
                INSERT_HALF_WIDTH_UM,
                INSERT_HALF_LENGTH_UM,
                INSERT_HALF_WIDTH_UM,
            ],
        };
        bench_bed::pour_pod_spheres(&mut world, self.particles, self.seed, &region, [0.0; 3])?;
        world.set_timestep_s(bench_bed::TIMESTEP_S)?;
        Ok(world)
    }

    /// Spin the drum and its end plates together at `omega_rad_s` (rad/s, right-handed about
    /// +y); 0 stops them. The far plate's normal is −y, so it spins at −ω about its own.
    pub fn spin<S: Scalar>(
        world: &mut World<'_, S>,
        omega_rad_s: f64,
    ) -> Result<(), ScenarioError> {
        world.set_wall_spin_rad_s(SHELL, omega_rad_s)?;
        world.set_wall_spin_rad_s(NEAR_END, omega_rad_s)?;
        world.set_wall_spin_rad_s(FAR_END, -omega_rad_s)?;
        Ok(())
    }
}

/// The bed's dynamic angle of repose, degrees (module docs): the angle from the downward
/// vertical of the line from the drum's axis to the bed's centre of mass, positive on the
/// side the drum lifts the bed when it spins at `omega_rad_s` of that sign (the bottom moves
/// towards −x for ω > 0 about +y, carrying the bed up the −x side). `NaN` for an empty drum.
pub fn bed_angle_deg<S: Scalar>(world: &World<'_, S>, omega_rad_s: f64) -> f64 {
    let (mut mx, mut mz, mut m) = (0.0, 0.0, 0.0);
    for b in world.bodies() {
        let [x, _, z] = b.position.to_f64();
        let mass = b.mass.to_f64();
        mx += mass * x;
        mz += mass * z;
        m += mass;
    }
    let side = if omega_rad_s < 0.0 { 1.0 } else { -1.0 };
    libm::atan2(side * mx / m, -mz / m) * 180.0 / PI
}
