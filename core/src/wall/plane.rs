//! Infinite plane wall. Overlap α = R − (c − p)·n̂, with n̂ the normal towards the particles.

use crate::num::{Scalar, Vec3};

/// Infinite plane through `point` with unit `normal` pointing to the particle side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane<S> {
    /// A point on the plane, mm.
    pub point: Vec3<S>,
    /// Unit normal towards the particles.
    pub normal: Vec3<S>,
}

impl<S: Scalar> Plane<S> {
    /// See [`super::WallShape::for_each_contact`]. One face (0).
    #[inline(always)]
    pub fn for_each_contact(&self, c: Vec3<S>, r: S, mut hit: impl FnMut(u32, Vec3<S>, S)) {
        let dist = (c - self.point).dot(self.normal);
        let overlap = r - dist;
        if overlap > S::ZERO {
            hit(0, -self.normal, overlap);
        }
    }

    /// See [`super::WallShape::may_touch`].
    #[inline]
    pub fn may_touch(&self, c: Vec3<S>, r: S, margin: S) -> bool {
        let dist = (c - self.point).dot(self.normal);
        !(dist.is_valid() && dist >= r + margin)
    }
}
