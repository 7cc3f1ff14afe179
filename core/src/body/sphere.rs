//! [`Sphere`]: the contact primitive. A free sphere is a body with one sphere at zero offset.

use crate::material::MaterialId;
use crate::num::{Scalar, Vec3};

/// A sphere in the arena (internal units).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Sphere<S> {
    /// World position of the sphere centre, mm (updated from its body each step).
    pub position: Vec3<S>,
    /// Radius, mm.
    pub radius: S,
    /// Offset of the centre from the body's centre of mass, body frame, mm.
    pub offset: Vec3<S>,
    /// Owning body id.
    pub body: u32,
    /// Material id.
    pub material: u16,
}

/// A free sphere as given by the user (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SphereSpec {
    /// Material (its density sets the mass).
    pub material: MaterialId,
    /// Radius, m (> 0).
    pub radius_m: f64,
    /// Centre position, m.
    pub position_m: [f64; 3],
    /// Velocity, m/s.
    pub velocity_m_s: [f64; 3],
    /// Angular velocity, rad/s.
    pub angular_velocity_rad_s: [f64; 3],
}

impl SphereSpec {
    /// A sphere at rest.
    pub fn at_rest(material: MaterialId, radius_m: f64, position_m: [f64; 3]) -> Self {
        SphereSpec {
            material,
            radius_m,
            position_m,
            velocity_m_s: [0.0; 3],
            angular_velocity_rad_s: [0.0; 3],
        }
    }
}

impl<S: Scalar> Sphere<S> {
    /// Radius in m.
    pub fn radius_m(&self) -> f64 {
        self.radius.to_f64() / crate::units::LENGTH_M_TO_MM
    }
}
