//! Figures of a bed: bed height (95th percentile of sphere tops) and centre-of-mass height,
//! as printed by `arachis pour` and compared fixed vs f64 (issue 2).
//!
//! These are reports, computed in `f64` from the state; they never feed back into stepping.

use crate::num::Scalar;
use crate::world::World;

/// The percentile used for the bed height: "the 95th percentile of z + R over all
/// particles" (issue 2). A percentile rather than the maximum ignores the few spheres that
/// bounce or perch on top of the bed.
pub const BED_HEIGHT_PERCENTILE: u32 = 95;

/// Bed height, mm: the [`BED_HEIGHT_PERCENTILE`]th percentile of the sphere tops z + R, by the
/// nearest-rank rule (the ⌈p·n/100⌉-th smallest value). `scratch` must hold at least one
/// `f64` per sphere (the core does not allocate); returns `None` for a world without spheres
/// or a too-short scratch.
pub fn bed_height_mm<S: Scalar>(world: &World<'_, S>, scratch: &mut [f64]) -> Option<f64> {
    let spheres = world.spheres();
    let n = spheres.len();
    if n == 0 || scratch.len() < n {
        return None;
    }
    let tops = &mut scratch[..n];
    for (top, s) in tops.iter_mut().zip(spheres) {
        *top = s.position.z.to_f64() + s.radius.to_f64();
    }
    let p = BED_HEIGHT_PERCENTILE as usize;
    let rank = (p * n).div_ceil(100).max(1);
    let (_, kth, _) = tops.select_nth_unstable_by(rank - 1, f64::total_cmp);
    Some(*kth)
}

/// Height of the centre of mass of all bodies, mm: Σ mᵢzᵢ / Σ mᵢ. For the bench bed (equal
/// spheres) this is the mean z of the sphere centres. Returns `None` without bodies.
pub fn com_height_mm<S: Scalar>(world: &World<'_, S>) -> Option<f64> {
    let (mut mz, mut m) = (0.0, 0.0);
    for b in world.bodies() {
        mz += b.mass.to_f64() * b.position.z.to_f64();
        m += b.mass.to_f64();
    }
    (m > 0.0).then(|| mz / m)
}
