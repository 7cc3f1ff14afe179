//! Orifice plate: a thin flat plate with a circular hole, the bottom of a flat-bottomed hopper
//! or silo. With h the signed height of a sphere centre above the plate (along the unit
//! normal), ρ its distance from the hole's axis, R the sphere's radius and Rₒ the hole's
//! radius:
//! - over the plate (ρ ≥ Rₒ), α = R − |h|, the normal from the centre straight to the plate
//!   (the plate is solid from both sides, so a sphere that fell through and drifted under it
//!   is pushed down, not pulled up through it);
//! - over the hole (ρ < Rₒ), the sphere touches the hole's rim, the circle of radius Rₒ in the
//!   plate, at its nearest point: α = R − √((Rₒ − ρ)² + h²), the normal towards that point.
//!
//! The two agree on the circle ρ = Rₒ, so a sphere sliding off the edge into the hole feels
//! no jump. A sphere whose centre lies on the axis is Rₒ from every rim point; it touches
//! nothing unless R > Rₒ, a hole smaller than the sphere, which the rim then cannot push in a
//! defined direction (no contact, as for a cylinder's axis).
//!
//! ```
//! use arachis_core::num::Vec3;
//! use arachis_core::wall::OrificePlate;
//! // A plate at z = 0 with a hole of radius 10 mm; spheres of radius 2 mm.
//! let p = OrificePlate { centre: Vec3::new(0.0, 0.0, 0.0), normal: Vec3::new(0.0, 0.0, 1.0),
//!     hole_radius: 10.0 };
//! // Resting on the plate beside the hole, 0.5 mm into it: pushed up.
//! let (n, overlap) = p.contact(Vec3::new(15.0, 0.0, 1.5), 2.0).unwrap();
//! assert!((overlap - 0.5).abs() < 1e-12 && (n.z + 1.0).abs() < 1e-12);
//! // Over the middle of the hole: nothing to touch, it falls through.
//! assert!(p.contact(Vec3::new(0.0, 0.0, 1.0), 2.0).is_none());
//! // Passing the rim 1.5 mm from it: pushed away from the rim point (10, 0, 0).
//! let (n, overlap) = p.contact(Vec3::new(8.5, 0.0, 0.0), 2.0).unwrap();
//! assert!((overlap - 0.5).abs() < 1e-12 && (n.x - 1.0).abs() < 1e-12);
//! ```

use crate::num::{Scalar, Vec3};

/// A flat plate through `centre` with unit `normal`, pierced by a hole of radius
/// `hole_radius` centred on `centre`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct OrificePlate<S> {
    /// The hole's centre, on the plate, mm.
    pub centre: Vec3<S>,
    /// Unit normal of the plate (either side: the plate is solid from both).
    pub normal: Vec3<S>,
    /// Radius of the hole, mm.
    pub hole_radius: S,
}

impl<S: Scalar> OrificePlate<S> {
    /// The point `c` (mm) as its signed height above the plate (mm) and its offset from the
    /// hole's axis, in the plate (mm).
    #[inline(always)]
    fn height_radial(&self, c: Vec3<S>) -> (S, Vec3<S>) {
        let rel = c - self.centre;
        let h = rel.dot(self.normal);
        (h, rel - self.normal.scale(h))
    }

    /// See [`super::WallShape::contact`]. One face (0).
    #[inline(always)]
    pub fn contact(&self, c: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        let (h, radial) = self.height_radial(c);
        // Both the plate and the rim lie in the plane h = 0: nothing within reach otherwise.
        // An invalid (overflowed) height goes on, so the overlap carries it to the contact
        // law, which reports it.
        if h.is_valid() && h.abs() >= r {
            return None;
        }
        let rho2 = radial.norm2();
        if rho2 >= self.hole_radius * self.hole_radius {
            // A centre in the plate (h = 0) is pushed to the normal's side.
            let towards_plate = if h >= S::ZERO {
                -self.normal
            } else {
                self.normal
            };
            return Some((towards_plate, r - h.abs()));
        }
        let (outward, rho) = radial.normalize_with_len()?;
        let to_rim = outward.scale(self.hole_radius - rho) - self.normal.scale(h);
        let (normal, distance) = to_rim.normalize_with_len()?;
        let overlap = r - distance;
        (overlap > S::ZERO).then_some((normal, overlap))
    }

    /// See [`super::WallShape::faces_near`]: near when the centre lies within reach plus
    /// `margin` of the plate's plane (the plate and the rim both lie in it).
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        let (h, _) = self.height_radial(c);
        u8::from(!(h.is_valid() && h.abs() >= r + margin))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plate() -> OrificePlate<f64> {
        OrificePlate {
            centre: Vec3::new(1.0, 2.0, 3.0),
            normal: Vec3::new(0.0, 0.0, 1.0),
            hole_radius: 10.0,
        }
    }

    #[test]
    fn the_plate_pushes_from_both_sides() {
        let p = plate();
        let (n, a) = p.contact(Vec3::new(20.0, 2.0, 3.0 - 1.5), 2.0).unwrap();
        assert!(
            (a - 0.5).abs() < 1e-12 && (n.z - 1.0).abs() < 1e-12,
            "{n:?}"
        );
        let (n, a) = p.contact(Vec3::new(20.0, 2.0, 3.0), 2.0).unwrap();
        assert!(
            (a - 2.0).abs() < 1e-12 && (n.z + 1.0).abs() < 1e-12,
            "{n:?}"
        );
        assert!(p.contact(Vec3::new(20.0, 2.0, 5.0), 2.0).is_none());
    }

    #[test]
    fn the_rim_pushes_along_the_line_to_its_nearest_point() {
        let p = plate();
        // 0.6 mm inside the hole's radius and 0.8 mm above: 1 mm from the rim.
        let (n, a) = p.contact(Vec3::new(1.0 + 9.4, 2.0, 3.8), 1.5).unwrap();
        assert!((a - 0.5).abs() < 1e-12);
        assert!(
            (n.x - 0.6).abs() < 1e-12 && (n.z + 0.8).abs() < 1e-12,
            "{n:?}"
        );
        // Below the plate the rim pushes down.
        let (n, _) = p.contact(Vec3::new(1.0 + 9.4, 2.0, 2.2), 1.5).unwrap();
        assert!((n.z - 0.8).abs() < 1e-12, "{n:?}");
        // Far from the rim inside the hole, or on the axis: none.
        assert!(p.contact(Vec3::new(1.0 + 7.0, 2.0, 3.5), 1.5).is_none());
        assert!(p.contact(Vec3::new(1.0, 2.0, 3.0), 1.5).is_none());
    }

    #[test]
    fn plate_and_rim_agree_at_the_edge_of_the_hole() {
        let p = plate();
        for h in [-1.2, -0.3, 0.4, 1.1] {
            let inside = p.contact(Vec3::new(1.0 + 10.0 - 1e-9, 2.0, 3.0 + h), 1.5);
            let outside = p.contact(Vec3::new(1.0 + 10.0 + 1e-9, 2.0, 3.0 + h), 1.5);
            let ((ni, ai), (no, ao)) = (inside.unwrap(), outside.unwrap());
            assert!((ai - ao).abs() < 1e-8, "overlap jumps at h = {h}");
            assert!((ni - no).norm() < 1e-8, "normal jumps at h = {h}");
        }
    }

    #[test]
    fn only_spheres_near_the_plane_are_candidates() {
        let p = plate();
        assert_eq!(p.faces_near(Vec3::new(0.0, 0.0, 4.5), 1.5, 0.1), 1);
        assert_eq!(p.faces_near(Vec3::new(0.0, 0.0, 1.5), 1.5, 0.1), 1);
        assert_eq!(p.faces_near(Vec3::new(0.0, 0.0, 4.7), 1.5, 0.1), 0);
        assert_eq!(p.faces_near(Vec3::new(30.0, 0.0, 1.3), 1.5, 0.1), 0);
    }
}
