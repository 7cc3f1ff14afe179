//! Poured bulk density: pod spheres of the bench bed (DESIGN §8: radius 4 mm, pod material)
//! fall from a column a chosen drop height above the floor of a steel measuring cylinder of
//! radius 30 mm, land and settle; the figure is the bulk density of the settled bed in a
//! horizontal slab well inside it ([`slab_bulk_density_kg_m3`]).
//!
//! This is the graduated-cylinder pour of the bulk-density standards (a known mass poured
//! from a fixed height, the volume read at its level) with the level replaced by a slab:
//! the slab starts two sphere diameters above the floor, where the floor's layering has
//! faded, and ends well below the free surface, so neither the floor nor the bumpy top
//! enters the figure. The cylinder's wall is in the slab, as in the standard test.
//!
//! The drop height sets the speed √(v₀² + 2gh) at which the spheres reach the bed. Measured
//! on 700 spheres (2026-11-27, two seeds each): smooth spheres (μs 0.3, μr 0.02) pack at
//! about 317 kg/m³ from 150 mm and 323 kg/m³ from 600 mm; nearly frictionless ones at
//! 351 kg/m³ from both. An impact rearranges a frictional bed a little, a frictionless one
//! is already as dense as it gets.
//!
//! ```
//! use arachis_core::prelude::*;
//! use arachis_core::scenario::bulk_density::{slab_bulk_density_kg_m3, BulkDensity};
//! let pour = BulkDensity { particles: 40, seed: 1, drop_height_um: 200_000 };
//! let mut arenas = arachis_core::owned::OwnedStorage::<Fx>::new(pour.storage_lengths());
//! let mut world = pour.build(arenas.storage()).unwrap();
//! world.run(10).unwrap();
//! assert_eq!(slab_bulk_density_kg_m3(&world), 0.0); // nothing has landed yet
//! ```

use super::insertion::{InsertionRegion, MICROMETRES_PER_M};
use super::{bench_bed, ScenarioError};
use crate::body::{Storage, StorageLengths};
use crate::num::Scalar;
use crate::units::{DENSITY_KG_M3_TO_G_MM3, LENGTH_M_TO_MM, STANDARD_GRAVITY_M_S2};
use crate::wall::{WallGeometry, WallSpec};
use crate::world::World;
use core::f64::consts::PI;

/// Radius of the measuring cylinder, m: seven and a half sphere diameters across.
pub const CYLINDER_RADIUS_M: f64 = 0.030;
/// The falling column: centres at most this far from the axis, µm (a sphere radius and
/// 2 mm inside the cylinder, so the spheres rain over its whole floor).
pub const COLUMN_RADIUS_UM: i64 = 24_000;
/// The falling column's height, µm: its lowest centres start at the drop height, its
/// highest this much above.
pub const COLUMN_HEIGHT_UM: i64 = 300_000;
/// Smallest drop height (floor to the column's lowest centres), µm: above the bed of the
/// largest pour.
pub const MIN_DROP_HEIGHT_UM: i64 = 150_000;
/// Largest drop height, µm.
pub const MAX_DROP_HEIGHT_UM: i64 = 1_000_000;
/// Bottom of the measuring slab above the floor, mm: two sphere diameters.
pub const SLAB_BOTTOM_MM: f64 = 16.0;
/// Top of the measuring slab above the floor, mm.
pub const SLAB_TOP_MM: f64 = 64.0;
/// Clearance between the slab's top and the free surface of the densest bed, mm: two
/// sphere diameters of bumpy surface.
pub const SURFACE_CLEARANCE_MM: f64 = 16.0;
/// Solid fraction of random close packing of equal spheres: no poured bed is denser, so a
/// pour of [`BulkDensity::min_particles`] covers the slab whatever its parameters.
pub const RANDOM_CLOSE_PACKING: f64 = 0.64;
/// Time the bed is left to settle after its highest sphere would have reached the floor, s.
pub const SETTLE_AFTER_FILL_S: f64 = 0.25;

/// A pour of `particles` spheres inserted from `seed` in a column whose lowest centres start
/// `drop_height_um` (µm) above the floor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BulkDensity {
    /// Number of spheres.
    pub particles: u32,
    /// Seed of the insertion draws.
    pub seed: u64,
    /// Drop height, µm, in [`MIN_DROP_HEIGHT_UM`, `MAX_DROP_HEIGHT_UM`].
    pub drop_height_um: i64,
}

impl BulkDensity {
    /// Largest particle count the column accepts (the bench bed's fill fraction).
    pub fn max_particles() -> u32 {
        let r = bench_bed::SPHERE_RADIUS_UM as f64;
        let envelope_radius = COLUMN_RADIUS_UM as f64 + r;
        let envelope_height = COLUMN_HEIGHT_UM as f64 + 2.0 * r;
        bench_bed::fill_limit(PI * envelope_radius * envelope_radius * envelope_height)
    }

    /// Fewest spheres whose bed, even at random close packing, reaches
    /// [`SURFACE_CLEARANCE_MM`] above the slab's top.
    pub fn min_particles() -> u32 {
        let r_mm = bench_bed::SPHERE_RADIUS_UM as f64 / MICROMETRES_PER_M * LENGTH_M_TO_MM;
        let bed_mm3 = cylinder_area_mm2() * (SLAB_TOP_MM + SURFACE_CLEARANCE_MM);
        libm::ceil(RANDOM_CLOSE_PACKING * bed_mm3 / ball_volume(r_mm)) as u32
    }

    /// Arena lengths this pour needs (one body and one sphere per particle).
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = self.particles as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Simulated time from insertion until the bed is measured, s: the fall of the column's
    /// highest centre to the floor, launched down at the bench bed's 0.2 m/s
    /// (z₀ = v₀t + ½gt²), and [`SETTLE_AFTER_FILL_S`].
    pub fn run_time_s(&self) -> f64 {
        let z0 = (self.drop_height_um + COLUMN_HEIGHT_UM) as f64 / MICROMETRES_PER_M;
        let v0 = -bench_bed::INITIAL_VELOCITY_M_S[2];
        let g = STANDARD_GRAVITY_M_S2;
        (libm::sqrt(v0 * v0 + 2.0 * g * z0) - v0) / g + SETTLE_AFTER_FILL_S
    }

    /// Build the pour over `storage`, the column in the air, with the bench bed's time step
    /// and pairs (pod material 0, steel 1; [`bench_bed::BenchBed::set_pairs`] changes them).
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        bench_bed::check_count(self.particles, Self::max_particles())?;
        if !(MIN_DROP_HEIGHT_UM..=MAX_DROP_HEIGHT_UM).contains(&self.drop_height_um) {
            return Err(ScenarioError::LengthOutOfRange {
                what: "drop height",
                value_um: self.drop_height_um,
                min_um: MIN_DROP_HEIGHT_UM,
                max_um: MAX_DROP_HEIGHT_UM,
            });
        }
        let mut world = bench_bed::pod_steel_world(storage)?;
        let steel = bench_bed::STEEL_MATERIAL;
        let up = [0.0, 0.0, 1.0];
        world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: up,
            },
            steel,
        ))?;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: up,
                radius_m: CYLINDER_RADIUS_M,
                length_m: None,
            },
            steel,
        ))?;
        let region = InsertionRegion::VerticalCylinder {
            radius_um: COLUMN_RADIUS_UM,
            z_min_um: self.drop_height_um,
            z_max_um: self.drop_height_um + COLUMN_HEIGHT_UM,
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
}

/// The measuring cylinder's cross-section, mm².
fn cylinder_area_mm2() -> f64 {
    let radius_mm = CYLINDER_RADIUS_M * LENGTH_M_TO_MM;
    PI * radius_mm * radius_mm
}

/// Volume of a ball of radius `r`, in the cube of `r`'s unit: 4πr³/3.
fn ball_volume(r: f64) -> f64 {
    4.0 / 3.0 * PI * r * r * r
}

/// Volume of a sphere of radius `r` centred at height `c` that lies between the heights
/// `bottom` and `top` (any one length unit, volume in its cube):
/// V = π[R²t − t³/3] between t = max(bottom − c, −R) and t = min(top − c, R).
pub fn sphere_volume_between(c: f64, r: f64, bottom: f64, top: f64) -> f64 {
    let t0 = (bottom - c).max(-r);
    let t1 = (top - c).min(r);
    if t1 <= t0 {
        return 0.0;
    }
    let primitive = |t: f64| r * r * t - t * t * t / 3.0;
    PI * (primitive(t1) - primitive(t0))
}

/// Bulk density of the bed in the measuring slab, kg/m³: the mass of the spheres' parts
/// between [`SLAB_BOTTOM_MM`] and [`SLAB_TOP_MM`] (each sphere's mass times the fraction of
/// its volume in the slab, [`sphere_volume_between`]) over the slab's volume inside the
/// cylinder. A report in `f64`, never fed back into stepping.
pub fn slab_bulk_density_kg_m3<S: Scalar>(world: &World<'_, S>) -> f64 {
    let bodies = world.bodies();
    let mass_g: f64 = world
        .spheres()
        .iter()
        .map(|s| {
            let r = s.radius.to_f64();
            let inside =
                sphere_volume_between(s.position.z.to_f64(), r, SLAB_BOTTOM_MM, SLAB_TOP_MM);
            bodies[s.body as usize].mass.to_f64() * inside / ball_volume(r)
        })
        .sum();
    let slab_mm3 = cylinder_area_mm2() * (SLAB_TOP_MM - SLAB_BOTTOM_MM);
    mass_g / slab_mm3 / DENSITY_KG_M3_TO_G_MM3
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::Fx;
    use crate::owned::OwnedStorage;

    #[test]
    fn the_slab_volume_of_a_sphere_matches_its_caps() {
        let r = 4.0;
        let whole = ball_volume(r);
        // Wholly inside, wholly outside, cut through its centre: a hemisphere.
        assert!((sphere_volume_between(40.0, r, 16.0, 64.0) - whole).abs() < 1e-9);
        assert_eq!(sphere_volume_between(70.0, r, 16.0, 64.0), 0.0);
        assert!((sphere_volume_between(64.0, r, 16.0, 64.0) - whole / 2.0).abs() < 1e-9);
        // A cap of height h: πh²(3R − h)/3 (the textbook formula, independent of the primitive).
        let h = 1.5;
        let cap = PI * h * h * (3.0 * r - h) / 3.0;
        assert!((sphere_volume_between(16.0 - r + h, r, 16.0, 64.0) - cap).abs() < 1e-9);
    }

    #[test]
    fn a_drop_height_outside_its_range_is_refused() {
        for h in [MIN_DROP_HEIGHT_UM - 1, MAX_DROP_HEIGHT_UM + 1] {
            let pour = BulkDensity {
                particles: 10,
                seed: 1,
                drop_height_um: h,
            };
            let mut arenas = OwnedStorage::<Fx>::new(pour.storage_lengths());
            assert!(matches!(
                pour.build(arenas.storage()),
                Err(ScenarioError::LengthOutOfRange { .. })
            ));
        }
    }

    #[test]
    fn the_run_lasts_the_fall_of_the_highest_sphere_and_the_settling() {
        // From 1.3 m, launched at 0.2 m/s: t = (√(0.04 + 2·9.81·1.3) − 0.2)/9.81 = 0.4948 s.
        let pour = BulkDensity {
            particles: 1,
            seed: 1,
            drop_height_um: MAX_DROP_HEIGHT_UM,
        };
        let fall = (libm::sqrt(0.04 + 2.0 * 9.81 * 1.3) - 0.2) / 9.81;
        assert!((pour.run_time_s() - SETTLE_AFTER_FILL_S - fall).abs() < 1e-12);
        assert!((fall - 0.4948).abs() < 1e-4);
    }
}
