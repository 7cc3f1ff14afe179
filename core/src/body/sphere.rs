//! [`Sphere`]: the contact primitive. A free sphere is a body with one sphere at zero offset.
//!
//! Besides its geometry a sphere carries a snapshot of its body's motion at the sphere
//! (centre velocity, angular velocity, masses, lever from the centre of mass): what the
//! contact stage needs, in one record, so that a contact reads two spheres and no bodies. The
//! world refreshes it whenever a body moves or is set ([`Sphere::sync_motion`]); it is derived
//! state, not hashed in the digest.

use crate::material::MaterialId;
use crate::num::{Scalar, Vec3};

/// A sphere in the arena (internal units).
///
/// Laid out for the two loops that read it (`repr(C)`, one record per 192 bytes, aligned to
/// a cache line): the neighbour-list rebuild reads position, radius and body from the first
/// line; the contact stage reads that line and the motion snapshot in the second; the
/// body-frame offset, which only the integrator reads, comes last.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
#[repr(C, align(64))]
pub struct Sphere<S> {
    /// World position of the sphere centre, mm (updated from its body each step).
    pub position: Vec3<S>,
    /// Radius, mm.
    pub radius: S,
    /// Owning body id.
    pub body: u32,
    /// Material id.
    pub material: u16,
    /// Whether its body is slow ([`crate::step::multirate`]); in the padding after
    /// `material`, so the record keeps its size.
    pub slow: bool,
    /// Velocity of the sphere centre, mm/ms (= m/s): v + ω × arm of its body.
    pub velocity: Vec3<S>,
    /// Angular velocity of its body, rad/ms.
    pub spin: Vec3<S>,
    /// Centre minus its body's centre of mass, world frame, mm (zero for a free sphere).
    pub arm: Vec3<S>,
    /// Mass of its body, g.
    pub mass: S,
    /// Inverse mass of its body, 1/g (zero for a kinematic body).
    pub inv_mass: S,
    /// Offset of the centre from the body's centre of mass, body frame, mm.
    pub offset: Vec3<S>,
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
    /// Refresh the motion snapshot from the sphere's body `b` (its position must be current):
    /// arm = centre − centre of mass, velocity = v + ω × arm.
    #[inline]
    pub fn sync_motion(&mut self, b: &super::Body<S>) {
        if b.is_clump {
            self.arm = self.position - b.position;
            self.velocity = b.velocity + b.angular_velocity.cross(self.arm);
        } else {
            self.arm = Vec3::ZERO;
            self.velocity = b.velocity;
        }
        self.spin = b.angular_velocity;
        self.mass = b.mass;
        self.inv_mass = b.inv_mass;
    }

    /// Whether the sphere's centre lies off its body's centre of mass (a clump sphere, by
    /// its non-zero arm; field by field, which compiles to three comparisons).
    #[inline(always)]
    pub fn in_clump(&self) -> bool {
        (self.arm.x != S::ZERO) | (self.arm.y != S::ZERO) | (self.arm.z != S::ZERO)
    }

    /// Radius in m.
    pub fn radius_m(&self) -> f64 {
        self.radius.to_f64() / crate::units::LENGTH_M_TO_MM
    }
}
