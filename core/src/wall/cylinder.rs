//! Cylinder wall, particles inside. With ρ the distance of the centre from the axis and Rc the
//! cylinder radius, α = R + ρ − Rc; the normal points radially outwards. A finite cylinder only
//! acts on spheres whose centre lies between its ends (its ends are open: add planes as caps).

use crate::num::{Scalar, Vec3};

/// Cylinder around the axis through `base` along unit `axis`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder<S> {
    /// A point on the axis (the bottom end when finite), mm.
    pub base: Vec3<S>,
    /// Unit axis.
    pub axis: Vec3<S>,
    /// Radius, mm.
    pub radius: S,
    /// Length from `base` along `axis`, mm (ignored when not `finite`).
    pub length: S,
    /// Finite (`true`) or infinite.
    pub finite: bool,
}

impl<S: Scalar> Cylinder<S> {
    /// The point `c` (mm) as its height along the axis from `base` (mm) and its radial
    /// offset from the axis (mm).
    #[inline(always)]
    fn axial_radial(&self, c: Vec3<S>) -> (S, Vec3<S>) {
        let rel = c - self.base;
        let h = rel.dot(self.axis);
        (h, rel - self.axis.scale(h))
    }

    /// See [`super::WallShape::contact`]. One face (0).
    #[inline(always)]
    pub fn contact(&self, c: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        let (h, radial) = self.axial_radial(c);
        if self.finite && (h < S::ZERO || h > self.length) {
            return None;
        }
        let d2 = radial.norm2();
        let inner = self.radius - r;
        // Cheap rejection without a square root: fully inside the contact-free core.
        if inner > S::ZERO && d2 < inner * inner {
            return None;
        }
        let d = d2.sqrt();
        if d == S::ZERO {
            // On the axis: no defined radial direction (only possible when R ≥ Rc).
            return None;
        }
        let overlap = r + d - self.radius;
        (overlap > S::ZERO).then(|| (radial.scale(S::ONE / d), overlap))
    }

    /// See [`super::WallShape::faces_near`]: the ends are widened by `margin` too, since a
    /// finite cylinder's reach depends on where the centre lies along the axis.
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        let (h, radial) = self.axial_radial(c);
        if !h.is_valid() {
            return 1;
        }
        if self.finite && (h < -margin || h > self.length + margin) {
            return 0;
        }
        let d2 = radial.norm2();
        let inner = self.radius - r - margin;
        u8::from(!(d2.is_valid() && inner > S::ZERO && d2 < inner * inner))
    }
}
