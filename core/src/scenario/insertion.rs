//! Random sequential insertion of non-overlapping spheres, exact and scalar-independent.
//!
//! Candidate centres are drawn as **integer micrometres** from [`SplitMix64`] and tested for
//! overlap in integer arithmetic (`i128` squared distances), so the accept/reject decisions
//! are the same whatever the world's scalar. The spheres already placed are read back from
//! the world: a centre of `k` µm is stored as `k·1e-3` mm, which both Q32.32 (resolution
//! 2.3e-10 mm) and `f64` hold to far better than half a micrometre, so rounding it back gives
//! `k` exactly. A fixed-point and an `f64` world built from the same seed therefore receive
//! identical SI inputs and differ only by quantisation (DESIGN §5: set-up may use `f64`, then
//! quantise).
//!
//! Cost: each candidate is checked against every sphere already in the world, O(N) per
//! candidate and O(N²) per fill. No scratch memory is needed, which keeps the set-up
//! allocation-free. Measured in release (loaded machine): the bench bed fill takes 0.1 s for
//! N = 2 000 and 1.9 s for the largest accepted N = 3 359.

use super::{ScenarioError, SplitMix64};
use crate::body::SphereSpec;
use crate::material::MaterialId;
use crate::num::Scalar;
use crate::units::LENGTH_M_TO_MM;
use crate::world::World;

/// Micrometres per metre: the insertion lattice is 1 µm.
pub const MICROMETRES_PER_M: f64 = 1.0e6;
/// Micrometres per millimetre (internal length unit → insertion lattice).
const MICROMETRES_PER_MM: f64 = MICROMETRES_PER_M / LENGTH_M_TO_MM;

/// Where sphere centres may be drawn, in integer micrometres.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InsertionRegion {
    /// A vertical cylinder of centres: `x² + y² ≤ radius²`, `z_min ≤ z ≤ z_max`.
    VerticalCylinder {
        /// Largest distance of a centre from the z axis, µm.
        radius_um: i64,
        /// Lowest centre height, µm.
        z_min_um: i64,
        /// Highest centre height, µm.
        z_max_um: i64,
    },
    /// An axis-aligned box of centres, corners in µm.
    Box {
        /// Lower corner, µm.
        min_um: [i64; 3],
        /// Upper corner, µm.
        max_um: [i64; 3],
    },
}

impl InsertionRegion {
    /// Draw one candidate centre (µm). Cylinders use rejection from the bounding square, so
    /// the points are uniform over the disc.
    fn draw(&self, rng: &mut SplitMix64) -> [i64; 3] {
        match *self {
            InsertionRegion::VerticalCylinder {
                radius_um,
                z_min_um,
                z_max_um,
            } => loop {
                let x = rng.range_i64(-radius_um, radius_um);
                let y = rng.range_i64(-radius_um, radius_um);
                if i128::from(x) * i128::from(x) + i128::from(y) * i128::from(y)
                    <= i128::from(radius_um) * i128::from(radius_um)
                {
                    return [x, y, rng.range_i64(z_min_um, z_max_um)];
                }
            },
            InsertionRegion::Box { min_um, max_um } => [
                rng.range_i64(min_um[0], max_um[0]),
                rng.range_i64(min_um[1], max_um[1]),
                rng.range_i64(min_um[2], max_um[2]),
            ],
        }
    }
}

/// What to insert and how hard to try.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InsertionRequest {
    /// Number of spheres to place.
    pub count: u32,
    /// Sphere radius, µm.
    pub radius_um: i64,
    /// Material of every sphere.
    pub material: MaterialId,
    /// Initial velocity of every sphere, m/s.
    pub velocity_m_s: [f64; 3],
    /// Candidates drawn per sphere before giving up (the region is then too full).
    pub max_attempts_per_sphere: u32,
}

/// A sphere's centre and radius read back from the world onto the µm lattice.
fn placed_um<S: Scalar>(s: &crate::body::Sphere<S>) -> ([i64; 3], i64) {
    (centre_um(s.position), to_um(s.radius))
}

/// A length in mm rounded to whole micrometres (exact for inserted values, module docs).
fn to_um<S: Scalar>(x: S) -> i64 {
    libm::round(x.to_f64() * MICROMETRES_PER_MM) as i64
}

/// [`to_um`] of each coordinate.
fn centre_um<S: Scalar>(p: crate::num::Vec3<S>) -> [i64; 3] {
    [to_um(p.x), to_um(p.y), to_um(p.z)]
}

/// `true` when a sphere of radius `r` at `c` (µm) overlaps no sphere already in `world`.
/// Touching (distance exactly R₁ + R₂) counts as free.
fn is_free<S: Scalar>(world: &World<'_, S>, c: [i64; 3], r: i64) -> bool {
    world.spheres().iter().all(|s| {
        // Quick reject on height alone, with a 1 µm margin so that it only skips spheres the
        // exact lattice test below would also find clear: the decision stays exact.
        let z_um = s.position.z.to_f64() * MICROMETRES_PER_MM;
        let reach_um = (r as f64) + s.radius.to_f64() * MICROMETRES_PER_MM;
        if libm::fabs(c[2] as f64 - z_um) > reach_um + 1.0 {
            return true;
        }
        let (p, rs) = placed_um(s);
        let d = [c[0] - p[0], c[1] - p[1], c[2] - p[2]].map(i128::from);
        let reach = i128::from(r + rs);
        d[0] * d[0] + d[1] * d[1] + d[2] * d[2] >= reach * reach
    })
}

/// Place `request.count` spheres at random free centres in `region`, in draw order.
///
/// Errors: [`ScenarioError::InsertionFailed`] when a sphere finds no free place within its
/// attempt budget (the spheres placed so far stay in the world), or a
/// [`ScenarioError::Setup`] from the world (capacity, invalid values).
pub fn insert_random_spheres<S: Scalar>(
    world: &mut World<'_, S>,
    rng: &mut SplitMix64,
    region: &InsertionRegion,
    request: &InsertionRequest,
) -> Result<(), ScenarioError> {
    for placed in 0..request.count {
        let mut found = None;
        for _ in 0..request.max_attempts_per_sphere {
            let c = region.draw(rng);
            if is_free(world, c, request.radius_um) {
                found = Some(c);
                break;
            }
        }
        let c = found.ok_or(ScenarioError::InsertionFailed {
            placed,
            requested: request.count,
            attempts_per_sphere: request.max_attempts_per_sphere,
        })?;
        world.add_sphere(SphereSpec {
            material: request.material,
            radius_m: request.radius_um as f64 / MICROMETRES_PER_M,
            position_m: c.map(|x| x as f64 / MICROMETRES_PER_M),
            velocity_m_s: request.velocity_m_s,
            angular_velocity_rad_s: [0.0; 3],
        })?;
    }
    Ok(())
}

/// Renumber the bodies of a freshly filled world of single spheres layer by layer: by
/// height in layers `layer_um` thick, then by y in rows as thick, then by x. Insertion draws
/// centres in random order, so neighbours get unrelated ids and the contact loop, which walks
/// spheres by id, fetches each partner from a random place in memory; in layer order a
/// sphere's partners sit near it in the arenas (the bench bed steps about 10 % faster).
///
/// The order uses the exact integer-micrometre centres of the insertion, so a fixed-point
/// and an `f64` world built from one seed get the same ids. In place, allocation-free.
///
/// Errors: [`ScenarioError::NotReorderable`] if a body is a clump, bonds exist or are
/// scheduled, the world has stepped (ids already handed out would change meaning), or
/// `layer_um` ≤ 0.
pub fn order_by_layers<S: Scalar>(
    world: &mut World<'_, S>,
    layer_um: i64,
) -> Result<(), ScenarioError> {
    let n = world.n_bodies as usize;
    if world.steps != 0
        || layer_um <= 0
        || world.n_spheres as usize != n
        || world.bond_table.n != 0
        || !world.bond_table.schedule.is_empty()
    {
        return Err(ScenarioError::NotReorderable);
    }
    if world.bodies[..n].iter().any(|b| b.is_clump) {
        return Err(ScenarioError::NotReorderable);
    }
    // Centres are distinct (no overlap) and the key ends with the whole centre, so no two
    // keys tie and the sort orders spheres and bodies alike.
    let key = |p: [i64; 3]| {
        (
            p[2].div_euclid(layer_um),
            p[1].div_euclid(layer_um),
            p[0],
            p[1],
            p[2],
        )
    };
    world.spheres[..n].sort_unstable_by_key(|s| key(centre_um(s.position)));
    world.bodies[..n].sort_unstable_by_key(|b| key(centre_um(b.position)));
    for (i, (b, s)) in world.bodies[..n]
        .iter_mut()
        .zip(world.spheres[..n].iter_mut())
        .enumerate()
    {
        if b.position != s.position {
            return Err(ScenarioError::NotReorderable);
        }
        b.first_sphere = i as u32;
        s.body = i as u32;
    }
    world.list.invalidate();
    Ok(())
}
