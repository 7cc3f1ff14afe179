//! The bench bed of DESIGN §8: the throughput and fixed-vs-f64 scenario.
//!
//! DESIGN §8, quoted:
//! - "Spheres: radius 4 mm, pod material (ρ 582 kg/m³, E 8.43 MPa, ν 0.386)."
//! - "Container: a cylinder of radius 50 mm with a floor at z = 0, both 65Mn steel
//!   (E 2.05e11 Pa, ν 0.3)."
//! - "Pairs: pod–pod e 0.335, μs 0.854, μr 0.346; pod–steel e 0.339, μs 0.589, μr 0.159."
//! - "Run: insert at random, without overlap, in the region r ≤ 45 mm, 10 mm ≤ z ≤ 400 mm,
//!   moving down at 0.2 m/s; dt = 2e-5 s; gravity 9.81 m/s². With N = 2 000 the bed has
//!   settled (kinetic energy below 1e-6 J) by step 20 000."
//!
//! Reading: the region bounds the sphere *centres*; the 1 mm between r = 45 + 4 mm and the
//! 50 mm wall keeps every sphere clear of the cylinder at insertion. The cylinder is infinite
//! (no sphere ever rises above its insertion height) and the floor an infinite plane.
//! Once placed, the spheres are numbered layer by layer ([`order_by_layers`]), as DEM codes
//! sort their particles, so that neighbours sit near each other in memory.

use super::insertion::{insert_random_spheres, order_by_layers, InsertionRegion, InsertionRequest};
use super::materials::{GRAVITY_M_S2, POD, POD_POD, POD_STEEL, STEEL};
use super::{ScenarioError, SplitMix64};
use crate::body::{Storage, StorageLengths};
use crate::material::MaterialId;
use crate::num::Scalar;
use crate::pair::PairSpec;
use crate::wall::{WallGeometry, WallSpec};
use crate::world::World;
use core::f64::consts::PI;

/// Sphere radius, µm ("radius 4 mm").
pub const SPHERE_RADIUS_UM: i64 = 4_000;
/// Container cylinder radius, m ("a cylinder of radius 50 mm").
pub const CYLINDER_RADIUS_M: f64 = 0.050;
/// Largest distance of an inserted centre from the axis, µm ("r ≤ 45 mm").
pub const INSERT_RADIUS_UM: i64 = 45_000;
/// Lowest inserted centre, µm ("10 mm ≤ z").
pub const INSERT_Z_MIN_UM: i64 = 10_000;
/// Highest inserted centre, µm ("z ≤ 400 mm").
pub const INSERT_Z_MAX_UM: i64 = 400_000;
/// Initial velocity, m/s ("moving down at 0.2 m/s").
pub const INITIAL_VELOCITY_M_S: [f64; 3] = [0.0, 0.0, -0.2];
/// Time step, s ("dt = 2e-5 s").
pub const TIMESTEP_S: f64 = 2e-5;
/// Particle count of the throughput figure ("With N = 2 000").
pub const DESIGN_PARTICLES: u32 = 2_000;
/// Steps by which the DESIGN bed has settled ("by step 20 000").
pub const DESIGN_SETTLE_STEPS: u64 = 20_000;
/// Kinetic energy below which the bed counts as settled, J ("below 1e-6 J").
pub const SETTLED_KINETIC_ENERGY_J: f64 = 1e-6;
/// Seed of the insertion draws unless the caller picks another.
pub const DEFAULT_SEED: u64 = 0x5EED_0008;

/// Largest solid fraction accepted, counted over the envelope the spheres can occupy
/// (centre region grown by R). Random sequential addition of equal spheres jams near 0.38;
/// near that limit a fill needs very many candidates, each checked against every placed
/// sphere, so requests above this fraction are refused at once with a clear error instead.
pub const MAX_FILL_FRACTION: f64 = 0.30;
/// Thickness of the layers and rows the inserted spheres are numbered by
/// ([`order_by_layers`]), µm: two diameters. Measured on the 2 000-sphere run, layer order
/// takes about 10 % off the CPU time against draw order.
pub const ORDER_LAYER_UM: i64 = 4 * SPHERE_RADIUS_UM;

/// Candidates drawn per sphere before insertion gives up (a backstop; [`MAX_FILL_FRACTION`]
/// normally refuses impossible requests first).
pub const MAX_ATTEMPTS_PER_SPHERE: u32 = 100_000;

/// The material of the bed's spheres (the first one the bed adds).
pub const POD_MATERIAL: MaterialId = MaterialId(0);
/// The material of the bed's floor and cylinder (the second one).
pub const STEEL_MATERIAL: MaterialId = MaterialId(1);

/// The DESIGN §8 bench bed with `particles` spheres, inserted from `seed`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BenchBed {
    /// Number of spheres (the DESIGN figure uses [`DESIGN_PARTICLES`]).
    pub particles: u32,
    /// Seed of the insertion draws.
    pub seed: u64,
}

impl BenchBed {
    /// The bed with `particles` spheres and the default seed.
    pub const fn with_particles(particles: u32) -> Self {
        BenchBed {
            particles,
            seed: DEFAULT_SEED,
        }
    }

    /// The bed of the DESIGN figure: [`DESIGN_PARTICLES`] spheres.
    pub const fn design() -> Self {
        Self::with_particles(DESIGN_PARTICLES)
    }

    /// Set the bed's two pairs, pod–pod and pod–steel, in a world built by
    /// [`BenchBed::build_with_timestep`] (DESIGN §8's own are [`POD_POD`] and [`POD_STEEL`]):
    /// how a calibration or a convention cross-check varies them.
    pub fn set_pairs<S: Scalar>(
        world: &mut World<'_, S>,
        pod_pod: PairSpec,
        pod_steel: PairSpec,
    ) -> Result<(), ScenarioError> {
        world.set_pair(POD_MATERIAL, POD_MATERIAL, pod_pod)?;
        world.set_pair(POD_MATERIAL, STEEL_MATERIAL, pod_steel)?;
        Ok(())
    }

    /// Largest particle count the insertion region accepts ([`MAX_FILL_FRACTION`]).
    pub fn max_particles() -> u32 {
        let r = SPHERE_RADIUS_UM as f64;
        let envelope_radius = INSERT_RADIUS_UM as f64 + r;
        let envelope_height = (INSERT_Z_MAX_UM - INSERT_Z_MIN_UM) as f64 + 2.0 * r;
        fill_limit(PI * envelope_radius * envelope_radius * envelope_height)
    }

    /// Arena lengths this bed needs (one body and one sphere per particle).
    pub fn storage_lengths(&self) -> StorageLengths {
        let n = self.particles as usize;
        StorageLengths::for_spheres(n, n)
    }

    /// Build the bed over `storage`, with dt = [`TIMESTEP_S`].
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        self.build_with_timestep(storage, TIMESTEP_S)
    }

    /// Build the bed over `storage` with time step `dt_s` (s). The world refuses a dt that is
    /// not positive or above its stable bound ([`crate::timestep`]).
    pub fn build_with_timestep<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
        dt_s: f64,
    ) -> Result<World<'a, S>, ScenarioError> {
        check_count(self.particles, Self::max_particles())?;
        let mut world = pod_steel_world(storage)?;
        let steel = STEEL_MATERIAL;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal: [0.0, 0.0, 1.0],
            },
            steel,
        ))?;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Cylinder {
                base_m: [0.0; 3],
                axis: [0.0, 0.0, 1.0],
                radius_m: CYLINDER_RADIUS_M,
                length_m: None,
            },
            steel,
        ))?;
        let region = InsertionRegion::VerticalCylinder {
            radius_um: INSERT_RADIUS_UM,
            z_min_um: INSERT_Z_MIN_UM,
            z_max_um: INSERT_Z_MAX_UM,
        };
        pour_pod_spheres(
            &mut world,
            self.particles,
            self.seed,
            &region,
            INITIAL_VELOCITY_M_S,
        )?;
        world.set_timestep_s(dt_s)?;
        Ok(world)
    }
}

/// Whether `particles` spheres can be inserted where at most `max` fit: at least one.
pub(crate) fn check_count(particles: u32, max: u32) -> Result<(), ScenarioError> {
    if particles == 0 {
        return Err(ScenarioError::NoParticles);
    }
    if particles > max {
        return Err(ScenarioError::TooManyParticles {
            requested: particles,
            max,
        });
    }
    Ok(())
}

/// Most pod spheres random insertion places in a region whose sphere envelope (the centres'
/// region grown by a radius) has `envelope_um3` µm³: [`MAX_FILL_FRACTION`] of it.
pub(crate) fn fill_limit(envelope_um3: f64) -> u32 {
    let r = SPHERE_RADIUS_UM as f64;
    let sphere = 4.0 / 3.0 * PI * r * r * r;
    libm::floor(MAX_FILL_FRACTION * envelope_um3 / sphere) as u32
}

/// A world over `storage` with the pod material ([`POD_MATERIAL`]) and the steel
/// ([`STEEL_MATERIAL`]), their pod–pod and pod–steel pairs of DESIGN §8 and standard gravity:
/// how the scenarios of pod spheres in steel rigs start.
pub(crate) fn pod_steel_world<'a, S: Scalar>(
    storage: Storage<'a, S>,
) -> Result<World<'a, S>, ScenarioError> {
    let mut world = World::new(storage)?;
    let pod = world.add_material(POD)?;
    let steel = world.add_material(STEEL)?;
    debug_assert_eq!((pod, steel), (POD_MATERIAL, STEEL_MATERIAL));
    BenchBed::set_pairs(&mut world, POD_POD, POD_STEEL)?;
    world.set_gravity_m_s2(GRAVITY_M_S2)?;
    Ok(world)
}

/// Insert `count` pod spheres of radius [`SPHERE_RADIUS_UM`] at random free places in
/// `region`, drawn from `seed`, moving at `velocity_m_s`, and number them by layers: how the
/// poured scenarios fill. The caller sets the time step.
pub(crate) fn pour_pod_spheres<S: Scalar>(
    world: &mut World<'_, S>,
    count: u32,
    seed: u64,
    region: &InsertionRegion,
    velocity_m_s: [f64; 3],
) -> Result<(), ScenarioError> {
    let request = InsertionRequest {
        count,
        radius_um: SPHERE_RADIUS_UM,
        material: POD_MATERIAL,
        velocity_m_s,
        max_attempts_per_sphere: MAX_ATTEMPTS_PER_SPHERE,
    };
    insert_random_spheres(world, &mut SplitMix64::new(seed), region, &request)?;
    order_by_layers(world, ORDER_LAYER_UM)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::num::Fx;
    use crate::owned::OwnedStorage;
    use std::vec::Vec;

    /// Sphere centres in mm.
    fn centres<S: Scalar>(bed: &BenchBed) -> Vec<[f64; 3]> {
        let mut arenas = OwnedStorage::<S>::new(bed.storage_lengths());
        let world = bed.build(arenas.storage()).unwrap();
        world
            .spheres()
            .iter()
            .map(|s| s.position.to_f64())
            .collect()
    }

    #[test]
    fn design_bed_is_inside_the_region_and_free_of_overlap() {
        let bed = BenchBed::design();
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let world = bed.build(arenas.storage()).unwrap();
        assert_eq!(world.spheres().len(), DESIGN_PARTICLES as usize);
        let c: Vec<[f64; 3]> = world
            .spheres()
            .iter()
            .map(|s| s.position.to_f64())
            .collect();
        let (r_max, z_min, z_max) = (45.0, 10.0, 400.0); // mm, DESIGN §8
        let quantum = 1e-9; // mm: Q32.32 rounding of the µm lattice points
        for p in &c {
            assert!(libm::hypot(p[0], p[1]) <= r_max + quantum, "{p:?}");
            assert!(p[2] >= z_min - quantum && p[2] <= z_max + quantum, "{p:?}");
        }
        let diameter = 2.0 * SPHERE_RADIUS_UM as f64 / 1_000.0;
        for (i, a) in c.iter().enumerate() {
            for b in &c[i + 1..] {
                let d2 = (0..3).map(|k| (a[k] - b[k]) * (a[k] - b[k])).sum::<f64>();
                assert!(d2 >= diameter * diameter - 1e-6, "overlap: {a:?} {b:?}");
            }
        }
        for b in world.bodies() {
            assert_eq!(b.velocity.to_f64(), [0.0, 0.0, Fx::from_f64(-0.2).to_f64()]);
        }
    }

    #[test]
    fn fixed_and_f64_beds_from_one_seed_differ_only_by_quantisation() {
        let bed = BenchBed::with_particles(500);
        let fixed = centres::<Fx>(&bed);
        let reference = centres::<f64>(&bed);
        assert_eq!(fixed.len(), reference.len());
        // Q32.32 rounds to nearest: at most half a unit, 2⁻³³ mm.
        let half_unit = libm::exp2(-33.0);
        for (a, b) in fixed.iter().zip(&reference) {
            for k in 0..3 {
                assert!((a[k] - b[k]).abs() <= half_unit, "{a:?} vs {b:?}");
            }
        }
    }

    #[test]
    fn another_seed_gives_another_bed() {
        let a = centres::<Fx>(&BenchBed::with_particles(50));
        let b = centres::<Fx>(&BenchBed {
            seed: DEFAULT_SEED ^ 1,
            ..BenchBed::with_particles(50)
        });
        assert_ne!(a, b);
    }

    #[test]
    fn impossible_counts_are_refused_before_insertion() {
        let mut arenas = OwnedStorage::<Fx>::new(BenchBed::with_particles(1).storage_lengths());
        let zero = BenchBed::with_particles(0).build(arenas.storage());
        assert_eq!(zero.err(), Some(ScenarioError::NoParticles));
        let max = BenchBed::max_particles();
        let too_many = BenchBed::with_particles(max + 1).build(arenas.storage());
        assert_eq!(
            too_many.err(),
            Some(ScenarioError::TooManyParticles {
                requested: max + 1,
                max
            })
        );
    }

    #[test]
    #[cfg_attr(
        debug_assertions,
        ignore = "release only: fills the region (≈2 s in release)"
    )]
    fn the_largest_accepted_count_can_be_inserted() {
        let bed = BenchBed::with_particles(BenchBed::max_particles());
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let world = bed.build(arenas.storage()).unwrap();
        assert_eq!(world.spheres().len(), bed.particles as usize);
    }

    #[test]
    fn a_time_step_above_the_stable_bound_is_refused() {
        let bed = BenchBed::with_particles(3);
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let err = bed.build_with_timestep(arenas.storage(), 1e-3).err();
        assert!(
            matches!(
                err,
                Some(ScenarioError::Setup(
                    crate::error::SetupError::TimeStepTooLarge { .. }
                ))
            ),
            "{err:?}"
        );
    }

    #[test]
    fn spheres_are_numbered_by_layers_rows_then_x() {
        let bed = BenchBed::design();
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let world = bed.build(arenas.storage()).unwrap();
        let um = |x: Fx| libm::round(x.to_f64() * 1_000.0) as i64;
        let keys: Vec<(i64, i64, i64)> = world
            .spheres()
            .iter()
            .map(|s| {
                let p = s.position;
                (
                    um(p.z).div_euclid(ORDER_LAYER_UM),
                    um(p.y).div_euclid(ORDER_LAYER_UM),
                    um(p.x),
                )
            })
            .collect();
        assert!(keys.windows(2).all(|w| w[0] <= w[1]), "not in layer order");
        // Renumbering keeps each body with its own sphere.
        for (i, (b, s)) in world.bodies().iter().zip(world.spheres()).enumerate() {
            assert_eq!((b.first_sphere, s.body), (i as u32, i as u32));
            assert_eq!(b.position, s.position);
        }
    }

    #[test]
    fn ordering_by_layers_refuses_a_world_that_has_stepped() {
        let bed = BenchBed::with_particles(20);
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut world = bed.build(arenas.storage()).unwrap();
        world.step().unwrap();
        assert_eq!(
            order_by_layers(&mut world, ORDER_LAYER_UM),
            Err(ScenarioError::NotReorderable)
        );
        let mut arenas = OwnedStorage::<Fx>::new(bed.storage_lengths());
        let mut world = bed.build(arenas.storage()).unwrap();
        assert_eq!(
            order_by_layers(&mut world, 0),
            Err(ScenarioError::NotReorderable)
        );
    }
}
