//! Wall motion: each wall translates by its prescribed velocity × dt (mm/ms × ms). The
//! largest wall displacement joins the neighbour list's drift bound, which keeps the
//! near-wall sets of [`super::neighbour_list`] valid.

use crate::error::{Other, Stage, StepError};
use crate::num::Scalar;
use crate::wall::{Wall, WallShape};

/// Move every wall by its velocity × `dt` (ms); returns the largest wall displacement (L1
/// norm, mm) for the neighbour list's drift bound.
pub(crate) fn move_walls<S: Scalar>(walls: &mut [Wall<S>], dt: S) -> Result<S, StepError> {
    let mut max_disp = S::ZERO;
    for (i, w) in walls.iter_mut().enumerate() {
        let d = w.velocity.scale(dt);
        if d.x == S::ZERO && d.y == S::ZERO && d.z == S::ZERO {
            continue;
        }
        max_disp = max_disp.max(d.l1_norm());
        w.shape.translate(d);
        let ok = d.is_valid()
            & match &w.shape {
                WallShape::Plane(p) => p.point.is_valid(),
                WallShape::Cylinder(c) => c.base.is_valid(),
                WallShape::AaBox(b) => b.min.is_valid() & b.max.is_valid(),
                WallShape::OrificePlate(o) => o.centre.is_valid(),
            };
        if !ok {
            return Err(StepError::Overflow {
                stage: Stage::WallMotion,
                body: i as u32,
                other: Other::Wall(i as u32),
            });
        }
    }
    Ok(max_disp)
}
