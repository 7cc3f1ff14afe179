//! Cylinder wall, particles inside. With ρ the distance of the centre from the axis and Rc the
//! cylinder radius, α = R + ρ − Rc; the normal points radially outwards. A finite cylinder has
//! open ends (add planes as caps) with solid rims: a sphere whose centre lies beyond an end
//! touches that end's rim, the circle of radius Rc in the end's plane, at its nearest point,
//! with α = R − (distance to that point) and the normal towards it. Without the rims a sphere
//! at the floor would pass under a rising cylinder once the gap exceeds its radius instead of
//! its diameter (found against LIGGGHTS' mesh cylinder, whose edges are solid).
//!
//! ```
//! use arachis_core::num::Vec3;
//! use arachis_core::wall::Cylinder;
//! // R_c 10 mm from z = 2 mm up; a sphere of R 1 mm below the rim, 0.5 mm from it.
//! let c = Cylinder { base: Vec3::new(0.0, 0.0, 2.0), axis: Vec3::new(0.0, 0.0, 1.0),
//!     radius: 10.0, length: 50.0, finite: true };
//! let (n, overlap) = c.contact(Vec3::new(10.0, 0.0, 1.5), 1.0).unwrap();
//! assert!((overlap - 0.5).abs() < 1e-12);
//! assert!((n.z - 1.0).abs() < 1e-12); // pushed down, away from the rim
//! assert!(c.contact(Vec3::new(5.0, 0.0, 1.5), 1.0).is_none());
//! ```

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
            let beyond = if h < S::ZERO { h } else { h - self.length };
            return self.rim_contact(beyond, radial, r);
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

    /// Contact with the rim of the end that the centre lies `beyond` (mm, signed along the
    /// axis: negative below the base, positive above the top), with `radial` the centre's
    /// offset from the axis. The rim point nearest the centre lies in the centre's radial
    /// direction; a centre on the axis is `Rc` from every rim point.
    #[inline]
    fn rim_contact(&self, beyond: S, radial: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        if beyond.abs() >= r {
            return None;
        }
        let (outward, d) = radial.normalize_with_len()?;
        let to_rim = outward.scale(self.radius - d) - self.axis.scale(beyond);
        let (normal, distance) = to_rim.normalize_with_len()?;
        let overlap = r - distance;
        (overlap > S::ZERO).then_some((normal, overlap))
    }

    /// See [`super::WallShape::faces_near`]: the ends are widened by `margin` and the
    /// sphere's radius too, since a finite cylinder's reach, rims included, depends on where
    /// the centre lies along the axis.
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        let (h, radial) = self.axial_radial(c);
        if !h.is_valid() {
            return 1;
        }
        if self.finite && (h < -(r + margin) || h > self.length + r + margin) {
            return 0;
        }
        let d2 = radial.norm2();
        let inner = self.radius - r - margin;
        u8::from(!(d2.is_valid() && inner > S::ZERO && d2 < inner * inner))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cylinder() -> Cylinder<f64> {
        Cylinder {
            base: Vec3::new(0.0, 0.0, 0.0),
            axis: Vec3::new(0.0, 0.0, 1.0),
            radius: 10.0,
            length: 20.0,
            finite: true,
        }
    }

    #[test]
    fn rims_push_along_the_line_to_their_nearest_point() {
        let c = cylinder();
        // Below the base, 0.6 mm inside the radius and 0.8 mm below: 1 mm from the rim.
        let (n, overlap) = c.contact(Vec3::new(9.4, 0.0, -0.8), 1.5).unwrap();
        assert!((overlap - 0.5).abs() < 1e-12);
        assert!(
            (n.x - 0.6).abs() < 1e-12 && (n.z - 0.8).abs() < 1e-12,
            "{n:?}"
        );
        // Above the top, outside the radius: the rim pushes outwards and up.
        let (n, overlap) = c.contact(Vec3::new(0.0, 10.6, 20.8), 1.5).unwrap();
        assert!((overlap - 0.5).abs() < 1e-12);
        assert!(
            (n.y + 0.6).abs() < 1e-12 && (n.z + 0.8).abs() < 1e-12,
            "{n:?}"
        );
        // Beyond the end by the radius or more, or far from the rim, or on the axis: none.
        assert!(c.contact(Vec3::new(9.9, 0.0, -1.5), 1.5).is_none());
        assert!(c.contact(Vec3::new(7.0, 0.0, -0.5), 1.5).is_none());
        assert!(c.contact(Vec3::new(0.0, 0.0, -0.5), 1.5).is_none());
        // Inside the span nothing changed: α = R + ρ − Rc, radially outwards.
        let (n, overlap) = c.contact(Vec3::new(9.0, 0.0, 0.5), 1.5).unwrap();
        assert!((overlap - 0.5).abs() < 1e-12 && (n.x - 1.0).abs() < 1e-12);
    }

    #[test]
    fn spheres_near_a_rim_are_candidates() {
        let c = cylinder();
        assert_eq!(c.faces_near(Vec3::new(9.4, 0.0, -0.8), 1.5, 0.1), 1);
        assert_eq!(c.faces_near(Vec3::new(9.4, 0.0, -1.7), 1.5, 0.1), 0);
        assert_eq!(c.faces_near(Vec3::new(0.0, 0.0, 5.0), 1.5, 0.1), 0);
    }
}
