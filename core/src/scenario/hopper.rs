//! A flat-bottomed hopper (a silo) discharging through a circular orifice: pod spheres of
//! the bench bed (DESIGN §8: radius 4 mm, pod material, the steel of 65Mn) fill a steel
//! cylinder of radius 40 mm standing on an orifice plate ([`crate::wall::OrificePlate`]),
//! with a shutter under the plate; once the fill has settled the shutter drops away
//! ([`Hopper::open`]), the spheres run out through the orifice and land on the shutter, now a
//! catch floor [`CATCH_DEPTH_M`] below ([`Hopper::catch`]). The figure of a discharge is its
//! mass flow rate, measured from the mass below the plate ([`discharged_mass_g`]).
//!
//! Beverloo's law (Beverloo, Leniger & van de Velde 1961) gives the steady rate of a
//! cohesionless material through an orifice of diameter D: W = C·ρ_b·√g·(D − k·d)^(5/2),
//! with ρ_b the bulk density, d the particle diameter and, for spheres, C ≈ 0.55–0.65 and
//! k ≈ 1.3–2.9. It does not depend on the fill height while the fill is higher than about D.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::hopper::{discharged_mass_g, Hopper};
//! let hopper = Hopper { particles: 40, seed: 1, orifice_diameter_um: 40_000 };
//! let mut arenas = arachis_core::owned::OwnedStorage::<Fx>::new(hopper.storage_lengths());
//! let mut world = hopper.build(arenas.storage()).unwrap();
//! world.run(10).unwrap();
//! assert_eq!(discharged_mass_g(&world), 0.0);
//! ```

use super::insertion::{InsertionRegion, MICROMETRES_PER_M};
use super::{bench_bed, ScenarioError};
use crate::body::{Storage, StorageLengths};
use crate::num::Scalar;
use crate::wall::{WallGeometry, WallId, WallSpec};
use crate::world::World;
use core::f64::consts::PI;

/// Radius of the silo (the steel cylinder), m: ten sphere diameters across.
pub const SILO_RADIUS_M: f64 = 0.040;
/// Height of the silo above the orifice plate, m.
pub const SILO_HEIGHT_M: f64 = 0.300;
/// Insertion region: centres at most this far from the axis, µm (a sphere radius and 1 mm
/// inside the silo).
pub const INSERT_RADIUS_UM: i64 = 35_000;
/// Insertion region: lowest centre height, µm.
pub const INSERT_Z_MIN_UM: i64 = 10_000;
/// Insertion region: highest centre height, µm.
pub const INSERT_Z_MAX_UM: i64 = 240_000;
/// Smallest orifice diameter, µm: three sphere diameters (smaller ones jam at once).
pub const MIN_ORIFICE_DIAMETER_UM: i64 = 6 * bench_bed::SPHERE_RADIUS_UM;
/// Largest orifice diameter, µm: a sphere diameter less than the silo's.
pub const MAX_ORIFICE_DIAMETER_UM: i64 = 70_000;
/// Depth of the catch floor below the orifice plate, m: the shutter stops here.
pub const CATCH_DEPTH_M: f64 = 0.200;
/// Speed at which the shutter drops away, m/s: faster than a sphere falling from rest can
/// follow over [`CATCH_DEPTH_M`] (it reaches 2 m/s only after 0.2 m).
pub const SHUTTER_SPEED_M_S: f64 = 2.0;
/// Time the shutter takes to reach the catch floor, s.
pub const SHUTTER_TRAVEL_S: f64 = CATCH_DEPTH_M / SHUTTER_SPEED_M_S;
/// The orifice plate's wall id.
pub const PLATE: WallId = WallId(0);
/// The silo's wall id.
pub const SILO: WallId = WallId(1);
/// The shutter's (then catch floor's) wall id.
pub const SHUTTER: WallId = WallId(2);

/// A hopper with `particles` spheres inserted from `seed`, discharging through an orifice of
/// diameter `orifice_diameter_um` (µm).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hopper {
    /// Number of spheres.
    pub particles: u32,
    /// Seed of the insertion draws.
    pub seed: u64,
    /// Orifice diameter, µm, in [`MIN_ORIFICE_DIAMETER_UM`, `MAX_ORIFICE_DIAMETER_UM`].
    pub orifice_diameter_um: i64,
}

impl Hopper {
    /// Largest particle count the insertion region accepts (the bench bed's fill fraction).
    pub fn max_particles() -> u32 {
        let r = bench_bed::SPHERE_RADIUS_UM as f64;
        let envelope_radius = INSERT_RADIUS_UM as f64 + r;
        let envelope_height = (INSERT_Z_MAX_UM - INSERT_Z_MIN_UM) as f64 + 2.0 * r;
        bench_bed::fill_limit(PI * envelope_radius * envelope_radius * envelope_height)
    }

    /// Arena lengths this hopper needs (one body and one sphere per particle).
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = self.particles as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Build the filled hopper over `storage`, shutter closed, with the bench bed's time
    /// step and pairs (pod material 0, steel 1; [`bench_bed::BenchBed::set_pairs`] changes
    /// the pairs).
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        bench_bed::check_count(self.particles, Self::max_particles())?;
        if !(MIN_ORIFICE_DIAMETER_UM..=MAX_ORIFICE_DIAMETER_UM).contains(&self.orifice_diameter_um)
        {
            return Err(ScenarioError::LengthOutOfRange {
                what: "orifice diameter",
                value_um: self.orifice_diameter_um,
                min_um: MIN_ORIFICE_DIAMETER_UM,
                max_um: MAX_ORIFICE_DIAMETER_UM,
            });
        }
        let mut world = bench_bed::pod_steel_world(storage)?;
        let steel = bench_bed::STEEL_MATERIAL;
        let up = [0.0, 0.0, 1.0];
        let plate = world.add_wall(WallSpec::fixed(
            WallGeometry::OrificePlate {
                centre_m: [0.0; 3],
                normal: up,
                hole_radius_m: self.orifice_diameter_um as f64 / 2.0 / MICROMETRES_PER_M,
            },
            steel,
        ))?;
        let silo = world.add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: up,
                radius_m: SILO_RADIUS_M,
                length_m: Some(SILO_HEIGHT_M),
            },
            steel,
        ))?;
        let shutter = world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: up,
            },
            steel,
        ))?;
        debug_assert_eq!((plate, silo, shutter), (PLATE, SILO, SHUTTER));
        let region = InsertionRegion::VerticalCylinder {
            radius_um: INSERT_RADIUS_UM,
            z_min_um: INSERT_Z_MIN_UM,
            z_max_um: INSERT_Z_MAX_UM,
        };
        bench_bed::pour_pod_spheres(
            &mut world,
            self.particles,
            self.seed,
            &region,
            bench_bed::INITIAL_VELOCITY_M_S,
        )?;
        world.set_timestep_s(bench_bed::TIMESTEP_S)?;
        Ok(world)
    }

    /// Open the orifice: the shutter starts to drop at [`SHUTTER_SPEED_M_S`]. Step
    /// [`SHUTTER_TRAVEL_S`], then [`Hopper::catch`].
    pub fn open<S: Scalar>(world: &mut World<'_, S>) -> Result<(), ScenarioError> {
        world.set_wall_velocity_m_s(SHUTTER, [0.0, 0.0, -SHUTTER_SPEED_M_S])?;
        Ok(())
    }

    /// Stop the shutter where it is, [`CATCH_DEPTH_M`] below the plate after
    /// [`SHUTTER_TRAVEL_S`]: it catches the discharge (a moving wall would keep the
    /// neighbour list rebuilding).
    pub fn catch<S: Scalar>(world: &mut World<'_, S>) -> Result<(), ScenarioError> {
        world.set_wall_velocity_m_s(SHUTTER, [0.0; 3])?;
        Ok(())
    }
}

/// Mass of the spheres whose centres lie below the orifice plate, g (the core's mass unit):
/// what has left the hopper.
pub fn discharged_mass_g<S: Scalar>(world: &World<'_, S>) -> f64 {
    world
        .bodies()
        .iter()
        .filter(|b| b.position.z < S::ZERO)
        .map(|b| b.mass.to_f64())
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;
    use crate::owned::OwnedStorage;

    #[test]
    fn an_orifice_outside_its_range_is_refused() {
        for d in [MIN_ORIFICE_DIAMETER_UM - 1, MAX_ORIFICE_DIAMETER_UM + 1] {
            let h = Hopper {
                particles: 10,
                seed: 1,
                orifice_diameter_um: d,
            };
            let mut arenas = OwnedStorage::<Fx>::new(h.storage_lengths());
            assert!(matches!(
                h.build(arenas.storage()),
                Err(ScenarioError::LengthOutOfRange { .. })
            ));
        }
    }
}
