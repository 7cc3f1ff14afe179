//! Axis-aligned box wall, particles inside: six planes facing inwards. Faces are numbered
//! 0 = −x, 1 = +x, 2 = −y, 3 = +y, 4 = −z, 5 = +z.

use crate::num::{Scalar, Vec3};

/// Axis-aligned box between `min` and `max`, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AaBox<S> {
    /// Lower corner, mm.
    pub min: Vec3<S>,
    /// Upper corner, mm.
    pub max: Vec3<S>,
}

impl<S: Scalar> AaBox<S> {
    /// See [`super::WallShape::for_each_contact`]. Up to six faces.
    #[inline(always)]
    pub fn for_each_contact(&self, c: Vec3<S>, r: S, mut hit: impl FnMut(u32, Vec3<S>, S)) {
        let (o, z) = (S::ONE, S::ZERO);
        let lo = [c.x - self.min.x, c.y - self.min.y, c.z - self.min.z];
        let hi = [self.max.x - c.x, self.max.y - c.y, self.max.z - c.z];
        let axes = [Vec3::new(o, z, z), Vec3::new(z, o, z), Vec3::new(z, z, o)];
        for k in 0..3 {
            let a = r - lo[k];
            if a > S::ZERO {
                hit(2 * k as u32, -axes[k], a);
            }
            let b = r - hi[k];
            if b > S::ZERO {
                hit(2 * k as u32 + 1, axes[k], b);
            }
        }
    }

    /// See [`super::WallShape::may_touch`]: some face is nearer than `r + margin`.
    #[inline]
    pub fn may_touch(&self, c: Vec3<S>, r: S, margin: S) -> bool {
        let reach = r + margin;
        let gaps = [
            c.x - self.min.x,
            c.y - self.min.y,
            c.z - self.min.z,
            self.max.x - c.x,
            self.max.y - c.y,
            self.max.z - c.z,
        ];
        gaps.iter().any(|&g| !(g.is_valid() && g >= reach))
    }
}
