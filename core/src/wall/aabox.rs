//! Axis-aligned box wall, particles inside: six planes facing inwards. Faces are numbered
//! 0 = −x, 1 = +x, 2 = −y, 3 = +y, 4 = −z, 5 = +z.

use crate::num::{Scalar, Vec3};

/// Number of faces of a box.
pub const BOX_FACES: u32 = 6;

/// Axis-aligned box between `min` and `max`, mm.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AaBox<S> {
    /// Lower corner, mm.
    pub min: Vec3<S>,
    /// Upper corner, mm.
    pub max: Vec3<S>,
}

impl<S: Scalar> AaBox<S> {
    /// Distance from `c` to face `face` (0..6) on the inner side, mm.
    #[inline(always)]
    fn gap(&self, face: u32, c: Vec3<S>) -> S {
        let k = (face / 2) as usize;
        let (cc, lo, hi) = [
            (c.x, self.min.x, self.max.x),
            (c.y, self.min.y, self.max.y),
            (c.z, self.min.z, self.max.z),
        ][k];
        if face % 2 == 0 {
            cc - lo
        } else {
            hi - cc
        }
    }

    /// See [`super::WallShape::contact`]. Faces 0–5.
    #[inline(always)]
    pub fn contact(&self, face: u32, c: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        let overlap = r - self.gap(face, c);
        if overlap <= S::ZERO {
            return None;
        }
        let (o, z) = (S::ONE, S::ZERO);
        let axis =
            [Vec3::new(o, z, z), Vec3::new(z, o, z), Vec3::new(z, z, o)][(face / 2) as usize];
        Some((if face % 2 == 0 { -axis } else { axis }, overlap))
    }

    /// See [`super::WallShape::faces_near`]: the faces nearer than `r + margin`.
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        let reach = r + margin;
        (0..BOX_FACES).fold(0, |mask, f| {
            let g = self.gap(f, c);
            if g.is_valid() && g >= reach {
                mask
            } else {
                mask | 1 << f
            }
        })
    }
}
