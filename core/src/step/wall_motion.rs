//! Wall motion: each wall translates by its prescribed velocity × dt (mm/ms × ms). The
//! largest wall displacement joins the neighbour list's drift bound, which keeps the
//! near-wall sets of [`super::neighbour_list`] valid.

use crate::error::{Other, Stage, StepError};
use crate::num::Scalar;
use crate::world::World;

impl<S: Scalar> World<'_, S> {
    pub(crate) fn move_walls(&mut self) -> Result<(), StepError> {
        let dt = self.dt;
        let mut max_disp = S::ZERO;
        for (i, w) in self.walls.iter_mut().enumerate() {
            let d = w.velocity.scale(dt);
            if d.x == S::ZERO && d.y == S::ZERO && d.z == S::ZERO {
                continue;
            }
            max_disp = max_disp.max(d.l1_norm());
            w.shape.translate(d);
            let mut ok = d.is_valid();
            w.shape.for_each_bits(|_| ());
            match &w.shape {
                crate::wall::WallShape::Plane(p) => ok &= p.point.is_valid(),
                crate::wall::WallShape::Cylinder(c) => ok &= c.base.is_valid(),
                crate::wall::WallShape::AaBox(b) => ok &= b.min.is_valid() & b.max.is_valid(),
            }
            if !ok {
                return Err(StepError::Overflow {
                    stage: Stage::WallMotion,
                    body: i as u32,
                    other: Other::Wall(i as u32),
                });
            }
        }
        if max_disp != S::ZERO {
            self.note_drift(max_disp);
        }
        Ok(())
    }
}
