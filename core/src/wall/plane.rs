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
    /// See [`super::WallShape::contact`]. One face (0).
    #[inline(always)]
    pub fn contact(&self, c: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        let dist = (c - self.point).dot(self.normal);
        let overlap = r - dist;
        (overlap > S::ZERO).then(|| (-self.normal, overlap))
    }

    /// See [`super::WallShape::faces_near`].
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        let dist = (c - self.point).dot(self.normal);
        u8::from(!(dist.is_valid() && dist >= r + margin))
    }
}
