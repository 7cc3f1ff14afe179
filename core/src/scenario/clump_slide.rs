//! Clumps sliding and colliding: two- and three-sphere pod clumps on a steel incline steeper
//! than the pod–steel friction angle, launched so that the upper ones catch up with the lower
//! ones and the chain piles into a stop wall at the foot of the slope.
//!
//! Geometry, in the incline's frame: `downhill` d = (cos θ, 0, −sin θ), `across` = (0, 1, 0),
//! `normal` n = (sin θ, 0, cos θ). The incline is the plane n·x = 0; the stop wall is the
//! plane through [`STOP_DISTANCE_MM`]·d facing uphill. Each clump lies flat on the incline
//! (every sphere [`RESTING_GAP_MM`] above it), turned about n by a random yaw and shifted
//! across the slope by a random offset from [`SplitMix64`], so the collisions are oblique and
//! set the clumps spinning. The incline angle exceeds atan(μs) = 30.5° of pod–steel, so a
//! clump accelerates at g(sin θ − μs cos θ) ≈ 0.89 m/s² (DESIGN §7 incline benchmark).

use super::materials::{GRAVITY_M_S2, POD, POD_POD, POD_STEEL, STEEL};
use super::{ScenarioError, SplitMix64};
use crate::body::{ClumpSphere, Storage, StorageLengths};
use crate::material::MaterialId;
use crate::num::Scalar;
use crate::units::LENGTH_M_TO_MM;
use crate::wall::{WallGeometry, WallSpec};
use crate::world::{ClumpSpec, World};

/// Incline angle, degrees: above the pod–steel friction angle atan(0.589) = 30.5°.
pub const INCLINE_DEG: f64 = 35.0;
/// Distance of the stop wall from the origin, down the slope, mm.
pub const STOP_DISTANCE_MM: f64 = 60.0;
/// Clearance between each sphere and the incline at set-up, mm (no initial overlap).
pub const RESTING_GAP_MM: f64 = 0.01;
/// Largest random shift of a clump across the slope, µm.
pub const MAX_ACROSS_SHIFT_UM: i64 = 3_000;
/// Time step, s (the bench bed's dt, DESIGN §8).
pub const TIMESTEP_S: f64 = 2e-5;
/// Default seed of the yaw and shift draws.
pub const DEFAULT_SEED: u64 = 0xC1_0B5;

/// One clump shape, in its own flat frame (mm): sphere centres `[along, across]` and radii.
struct Shape {
    centres_mm: &'static [[f64; 2]],
    radii_mm: &'static [f64],
}

/// A dumbbell: two R 4 mm spheres 5 mm apart (overlapping, like a two-kernel pod).
const DUMBBELL: Shape = Shape {
    centres_mm: &[[-2.5, 0.0], [2.5, 0.0]],
    radii_mm: &[4.0, 4.0],
};
/// A three-kernel pod: a thicker middle sphere between two R 4 mm ends.
const THREE_KERNEL: Shape = Shape {
    centres_mm: &[[-5.5, 0.0], [0.0, 0.0], [5.5, 0.0]],
    radii_mm: &[4.0, 4.5, 4.0],
};
/// A bent three-sphere clump (an L of spheres), which rolls and tumbles unevenly.
const BENT: Shape = Shape {
    centres_mm: &[[-3.0, -2.0], [2.0, -2.0], [2.0, 3.0]],
    radii_mm: &[3.5, 4.0, 3.5],
};

/// A clump placed on the slope: shape, distance up the slope from the stop wall to its
/// centre (mm) and launch speed down the slope (m/s).
struct Placement {
    shape: &'static Shape,
    uphill_of_stop_mm: f64,
    speed_m_s: f64,
}

/// The lowest clump starts near the wall, slow; each higher clump starts faster, so the
/// chain closes its gaps within a few hundred steps.
const PLACEMENTS: [Placement; 4] = [
    Placement {
        shape: &THREE_KERNEL,
        uphill_of_stop_mm: 12.0,
        speed_m_s: 0.0,
    },
    Placement {
        shape: &DUMBBELL,
        uphill_of_stop_mm: 32.0,
        speed_m_s: 0.3,
    },
    Placement {
        shape: &BENT,
        uphill_of_stop_mm: 52.0,
        speed_m_s: 0.6,
    },
    Placement {
        shape: &THREE_KERNEL,
        uphill_of_stop_mm: 74.0,
        speed_m_s: 1.0,
    },
];

/// Largest number of spheres in one clump shape (arena sizing).
const MAX_SPHERES_PER_CLUMP: usize = 3;

/// The clump-slide scenario.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ClumpSlide {
    /// Seed of the yaw and across-slope shift of each clump.
    pub seed: u64,
}

impl Default for ClumpSlide {
    fn default() -> Self {
        ClumpSlide { seed: DEFAULT_SEED }
    }
}

/// The incline frame: downhill, across and normal unit vectors.
fn incline_frame() -> ([f64; 3], [f64; 3], [f64; 3]) {
    let theta = INCLINE_DEG.to_radians();
    let (s, c) = (libm::sin(theta), libm::cos(theta));
    ([c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c])
}

/// `a·u + b·v + h·w`, mm → m.
fn combine_m(a: f64, u: [f64; 3], b: f64, v: [f64; 3], h: f64, w: [f64; 3]) -> [f64; 3] {
    core::array::from_fn(|k| (a * u[k] + b * v[k] + h * w[k]) / LENGTH_M_TO_MM)
}

impl ClumpSlide {
    /// Number of clumps.
    pub const CLUMPS: usize = PLACEMENTS.len();

    /// Arena lengths this scenario needs.
    pub fn storage_lengths(&self) -> StorageLengths {
        StorageLengths::for_spheres(Self::CLUMPS, Self::CLUMPS * MAX_SPHERES_PER_CLUMP)
    }

    /// Build the scenario over `storage`.
    pub fn build<'a, S: Scalar>(
        &self,
        storage: Storage<'a, S>,
    ) -> Result<World<'a, S>, ScenarioError> {
        let (downhill, across, normal) = incline_frame();
        let mut world = World::new(storage)?;
        let pod = world.add_material(POD)?;
        let steel = world.add_material(STEEL)?;
        world.set_pair(pod, pod, POD_POD)?;
        world.set_pair(pod, steel, POD_STEEL)?;
        world.set_gravity_m_s2(GRAVITY_M_S2)?;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: [0.0; 3],
                normal,
            },
            steel,
        ))?;
        world.add_wall(WallSpec::fixed(
            WallGeometry::Plane {
                point_m: combine_m(STOP_DISTANCE_MM, downhill, 0.0, across, 0.0, normal),
                normal: downhill.map(|x| -x),
            },
            steel,
        ))?;
        let mut rng = SplitMix64::new(self.seed);
        for p in &PLACEMENTS {
            self.add_clump(&mut world, &mut rng, p, pod, (downhill, across, normal))?;
        }
        world.set_timestep_s(TIMESTEP_S)?;
        Ok(world)
    }

    fn add_clump<S: Scalar>(
        &self,
        world: &mut World<'_, S>,
        rng: &mut SplitMix64,
        p: &Placement,
        pod: MaterialId,
        (downhill, across, normal): ([f64; 3], [f64; 3], [f64; 3]),
    ) -> Result<(), ScenarioError> {
        let yaw = (rng.below(360) as f64).to_radians();
        let shift_mm = rng.range_i64(-MAX_ACROSS_SHIFT_UM, MAX_ACROSS_SHIFT_UM) as f64 / 1_000.0;
        let (s, c) = (libm::sin(yaw), libm::cos(yaw));
        let centre_along = STOP_DISTANCE_MM - p.uphill_of_stop_mm;
        let mut spheres = [ClumpSphere {
            center_m: [0.0; 3],
            radius_m: 0.0,
            material: pod,
        }; MAX_SPHERES_PER_CLUMP];
        let n = p.shape.radii_mm.len();
        for (k, sphere) in spheres.iter_mut().enumerate().take(n) {
            let [a, b] = p.shape.centres_mm[k];
            let r = p.shape.radii_mm[k];
            let along = centre_along + c * a - s * b;
            let side = shift_mm + s * a + c * b;
            *sphere = ClumpSphere {
                center_m: combine_m(along, downhill, side, across, r + RESTING_GAP_MM, normal),
                radius_m: r / LENGTH_M_TO_MM,
                material: pod,
            };
        }
        world.add_clump(&ClumpSpec {
            spheres: &spheres[..n],
            velocity_m_s: downhill.map(|x| x * p.speed_m_s),
            angular_velocity_rad_s: [0.0; 3],
        })?;
        Ok(())
    }
}
