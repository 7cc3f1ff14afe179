//! Walls: infinite planes ([`Plane`]), finite or infinite cylinders with particles inside
//! ([`Cylinder`]), axis-aligned boxes with particles inside ([`AaBox`]) and flat plates with a
//! circular hole ([`OrificePlate`], a hopper's bottom). Each wall moves at a prescribed
//! velocity (mm/ms = m/s), e.g. the repose test lifts a cylinder at 0.05 m/s, and may spin
//! about its own axis of symmetry ([`Wall::spin`], a rotating drum).
//!
//! Seam for triangle meshes: [`WallShape`] is `#[non_exhaustive]`; a mesh wall becomes a new
//! variant whose contact routine reports (normal, overlap) per face ([`WallShape::contact`])
//! like the shapes here, so the contact law does not change.
//!
//! A wall has infinite mass: m* = m_i and R* = R_i (DESIGN §2).

pub mod aabox;
pub mod cylinder;
pub mod orifice;
pub mod plane;

pub use aabox::AaBox;
pub use cylinder::Cylinder;
pub use orifice::OrificePlate;
pub use plane::Plane;

use crate::error::SetupError;
use crate::material::{finite, MaterialId};
use crate::num::{Scalar, Vec3};
use crate::units::{LENGTH_M_TO_MM, VELOCITY_M_S_TO_MM_MS};

/// Largest number of walls in one world.
pub const MAX_WALLS: usize = 16;

/// Largest number of faces of one wall (a box has six; the wall key keeps four bits).
pub const MAX_FACES: u32 = aabox::BOX_FACES;

/// Index of a wall in the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct WallId(pub u32);

/// Geometry of a wall (internal units, mm).
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum WallShape<S> {
    /// Infinite plane.
    Plane(Plane<S>),
    /// Cylinder, particles inside.
    Cylinder(Cylinder<S>),
    /// Axis-aligned box, particles inside.
    AaBox(AaBox<S>),
    /// Flat plate with a circular hole.
    OrificePlate(OrificePlate<S>),
}

/// A wall in the world.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wall<S> {
    /// Geometry (current position).
    pub shape: WallShape<S>,
    /// Prescribed velocity, mm/ms (= m/s).
    pub velocity: Vec3<S>,
    /// Spin about the wall's own axis of symmetry ([`WallShape::spin_axis`]), rad/ms,
    /// right-handed: a rotating drum or turntable. The shape does not change as it spins;
    /// only its surface moves ([`Wall::velocity_at`]).
    pub spin: S,
    /// Material id.
    pub material: u16,
    /// Total contact force the particles exert on this wall in the last step, N.
    pub force: Vec3<S>,
}

impl<S: Scalar> Wall<S> {
    /// The velocity of the wall's surface at point `p` (mm), mm/ms: its translation plus, for
    /// a spinning wall, Ω·â × (p − o) with â and o its axis and a point on it. The same bits
    /// as `velocity` for a wall that does not spin.
    #[inline(always)]
    pub fn velocity_at(&self, p: Vec3<S>) -> Vec3<S> {
        if self.spin == S::ZERO {
            return self.velocity;
        }
        match self.shape.spin_axis() {
            Some((origin, axis)) => self.velocity + axis.scale(self.spin).cross(p - origin),
            None => self.velocity,
        }
    }
}

impl<S: Scalar> WallShape<S> {
    /// The axis about which the shape may spin without changing: a point on it and its unit
    /// direction. A cylinder's own axis; the normal of a plane or an orifice plate through
    /// its point or the hole's centre; none for a box.
    pub fn spin_axis(&self) -> Option<(Vec3<S>, Vec3<S>)> {
        match self {
            WallShape::Plane(p) => Some((p.point, p.normal)),
            WallShape::Cylinder(c) => Some((c.base, c.axis)),
            WallShape::OrificePlate(o) => Some((o.centre, o.normal)),
            WallShape::AaBox(_) => None,
        }
    }

    /// The contact of a sphere (centre `c`, radius `r`, mm) with face `face` of this wall, if
    /// they overlap: the unit normal from the sphere centre towards the wall and the overlap
    /// α > 0, mm. Planes and cylinders have one face (0), boxes six ([`aabox`]).
    #[inline(always)]
    pub fn contact(&self, face: u32, c: Vec3<S>, r: S) -> Option<(Vec3<S>, S)> {
        match self {
            WallShape::Plane(p) => p.contact(c, r),
            WallShape::Cylinder(y) => y.contact(c, r),
            WallShape::AaBox(b) => b.contact(face, c, r),
            WallShape::OrificePlate(o) => o.contact(c, r),
        }
    }

    /// Number of faces: 1 for planes, cylinders and orifice plates, 6 for boxes.
    pub fn face_count(&self) -> u32 {
        match self {
            WallShape::Plane(_) | WallShape::Cylinder(_) | WallShape::OrificePlate(_) => 1,
            WallShape::AaBox(_) => aabox::BOX_FACES,
        }
    }

    /// Call `hit(face, normal, overlap)` for each face the sphere (centre `c`, radius `r`, mm)
    /// overlaps ([`WallShape::contact`]), in face order.
    pub fn for_each_contact(&self, c: Vec3<S>, r: S, mut hit: impl FnMut(u32, Vec3<S>, S)) {
        for face in 0..self.face_count() {
            if let Some((n, a)) = self.contact(face, c, r) {
                hit(face, n, a);
            }
        }
    }

    /// The faces (one bit each) that a sphere (centre `c`, radius `r`, mm) lies within
    /// `margin` (mm) of touching. Conservative: a face is left out only when no contact with
    /// it is possible until the sphere and the wall have moved by `margin` between them; any
    /// overflow counts as near. The neighbour list keeps an entry for each near face
    /// ([`crate::step::neighbour_list`]).
    #[inline]
    pub fn faces_near(&self, c: Vec3<S>, r: S, margin: S) -> u8 {
        match self {
            WallShape::Plane(p) => p.faces_near(c, r, margin),
            WallShape::Cylinder(y) => y.faces_near(c, r, margin),
            WallShape::AaBox(b) => b.faces_near(c, r, margin),
            WallShape::OrificePlate(o) => o.faces_near(c, r, margin),
        }
    }

    /// Whether a sphere lies within `margin` of touching any face ([`WallShape::faces_near`]).
    #[inline]
    pub fn may_touch(&self, c: Vec3<S>, r: S, margin: S) -> bool {
        self.faces_near(c, r, margin) != 0
    }

    /// Translate by `d`, mm.
    pub fn translate(&mut self, d: Vec3<S>) {
        match self {
            WallShape::Plane(p) => p.point += d,
            WallShape::Cylinder(y) => y.base += d,
            WallShape::AaBox(b) => {
                b.min += d;
                b.max += d;
            }
            WallShape::OrificePlate(o) => o.centre += d,
        }
    }

    /// Raw bits of all geometry fields, for the digest.
    pub fn for_each_bits(&self, mut f: impl FnMut(u64)) {
        let v = |v: Vec3<S>, f: &mut dyn FnMut(u64)| {
            f(v.x.to_bits());
            f(v.y.to_bits());
            f(v.z.to_bits());
        };
        match self {
            WallShape::Plane(p) => {
                f(1);
                v(p.point, &mut f);
                v(p.normal, &mut f);
            }
            WallShape::Cylinder(y) => {
                f(2);
                v(y.base, &mut f);
                v(y.axis, &mut f);
                f(y.radius.to_bits());
                f(y.length.to_bits());
                f(y.finite as u64);
            }
            WallShape::AaBox(b) => {
                f(3);
                v(b.min, &mut f);
                v(b.max, &mut f);
            }
            WallShape::OrificePlate(o) => {
                f(4);
                v(o.centre, &mut f);
                v(o.normal, &mut f);
                f(o.hole_radius.to_bits());
            }
        }
    }
}

/// Wall geometry as given by the user (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WallGeometry {
    /// Infinite plane through `point_m` with unit `normal` pointing to the particle side.
    Plane {
        /// A point on the plane, m.
        point_m: [f64; 3],
        /// Normal towards the particles (normalised at set-up).
        normal: [f64; 3],
    },
    /// Cylinder around the axis through `base_m` along `axis`, particles inside.
    Cylinder {
        /// A point on the axis, m (the bottom end when finite).
        base_m: [f64; 3],
        /// Axis direction (normalised at set-up).
        axis: [f64; 3],
        /// Radius, m.
        radius_m: f64,
        /// Length along the axis from `base_m`, m; `None` for infinite.
        length_m: Option<f64>,
    },
    /// Axis-aligned box, particles inside.
    AaBox {
        /// Lower corner, m.
        min_m: [f64; 3],
        /// Upper corner, m.
        max_m: [f64; 3],
    },
    /// Flat plate through `centre_m` with unit `normal`, pierced by a circular hole of
    /// radius `hole_radius_m` centred on `centre_m` ([`OrificePlate`]).
    OrificePlate {
        /// The hole's centre, m.
        centre_m: [f64; 3],
        /// Normal of the plate (normalised at set-up; either side).
        normal: [f64; 3],
        /// Radius of the hole, m.
        hole_radius_m: f64,
    },
}

/// A wall as given by the user.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WallSpec {
    /// Geometry.
    pub geometry: WallGeometry,
    /// Material.
    pub material: MaterialId,
    /// Prescribed velocity, m/s.
    pub velocity_m_s: [f64; 3],
}

fn fin3(v: [f64; 3], what: &'static str) -> Result<[f64; 3], SetupError> {
    for x in v {
        finite(x, what)?;
    }
    Ok(v)
}

fn unit(v: [f64; 3], what: &'static str) -> Result<[f64; 3], SetupError> {
    let v = fin3(v, what)?;
    let n = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if n == 0.0 {
        return Err(SetupError::BadWall {
            reason: "zero normal or axis",
        });
    }
    Ok([v[0] / n, v[1] / n, v[2] / n])
}

pub(crate) fn q3<S: Scalar>(
    v: [f64; 3],
    scale: f64,
    what: &'static str,
) -> Result<Vec3<S>, SetupError> {
    let v = fin3(v, what)?;
    let mut out = [S::ZERO; 3];
    for k in 0..3 {
        out[k] = crate::num::quantise::quantise_coordinate(v[k] * scale, what)?;
    }
    Ok(Vec3::new(out[0], out[1], out[2]))
}

impl WallSpec {
    /// A wall at rest.
    pub fn fixed(geometry: WallGeometry, material: MaterialId) -> Self {
        WallSpec {
            geometry,
            material,
            velocity_m_s: [0.0; 3],
        }
    }

    /// Validate and convert to internal units.
    pub fn build<S: Scalar>(&self) -> Result<Wall<S>, SetupError> {
        let shape = match self.geometry {
            WallGeometry::Plane { point_m, normal } => WallShape::Plane(Plane {
                point: q3(point_m, LENGTH_M_TO_MM, "plane point")?,
                normal: q3(unit(normal, "plane normal")?, 1.0, "plane normal")?,
            }),
            WallGeometry::Cylinder {
                base_m,
                axis,
                radius_m,
                length_m,
            } => {
                let r = finite(radius_m, "cylinder radius")?;
                if r <= 0.0 {
                    return Err(SetupError::BadWall {
                        reason: "cylinder radius must be > 0",
                    });
                }
                let (len, fin) = match length_m {
                    Some(l) => {
                        let l = finite(l, "cylinder length")?;
                        if l <= 0.0 {
                            return Err(SetupError::BadWall {
                                reason: "cylinder length must be > 0",
                            });
                        }
                        (l, true)
                    }
                    None => (0.0, false),
                };
                WallShape::Cylinder(Cylinder {
                    base: q3(base_m, LENGTH_M_TO_MM, "cylinder base")?,
                    axis: q3(unit(axis, "cylinder axis")?, 1.0, "cylinder axis")?,
                    radius: crate::num::quantise::quantise(r * LENGTH_M_TO_MM, "cylinder radius")?,
                    length: crate::num::quantise::quantise(
                        len * LENGTH_M_TO_MM,
                        "cylinder length",
                    )?,
                    finite: fin,
                })
            }
            WallGeometry::AaBox { min_m, max_m } => {
                let lo = fin3(min_m, "box corner")?;
                let hi = fin3(max_m, "box corner")?;
                if (0..3).any(|k| hi[k] <= lo[k]) {
                    return Err(SetupError::BadWall {
                        reason: "box max must exceed min on every axis",
                    });
                }
                WallShape::AaBox(AaBox {
                    min: q3(lo, LENGTH_M_TO_MM, "box corner")?,
                    max: q3(hi, LENGTH_M_TO_MM, "box corner")?,
                })
            }
            WallGeometry::OrificePlate {
                centre_m,
                normal,
                hole_radius_m,
            } => {
                let r = finite(hole_radius_m, "orifice radius")?;
                if r <= 0.0 {
                    return Err(SetupError::BadWall {
                        reason: "orifice radius must be > 0",
                    });
                }
                WallShape::OrificePlate(OrificePlate {
                    centre: q3(centre_m, LENGTH_M_TO_MM, "orifice centre")?,
                    normal: q3(
                        unit(normal, "orifice plate normal")?,
                        1.0,
                        "orifice plate normal",
                    )?,
                    hole_radius: crate::num::quantise::quantise(
                        r * LENGTH_M_TO_MM,
                        "orifice radius",
                    )?,
                })
            }
        };
        Ok(Wall {
            shape,
            velocity: q3(self.velocity_m_s, VELOCITY_M_S_TO_MM_MS, "wall velocity")?,
            spin: S::ZERO,
            material: self.material.0,
            force: Vec3::ZERO,
        })
    }
}
