//! Bodies: rigid bodies ([`Body`]) made of one sphere or of a clump of overlapping spheres
//! ([`Sphere`]), stored in caller-provided arenas ([`Storage`]).
//!
//! A body carries mass (g), centre of mass (mm), principal inertia (g·mm²), a unit quaternion
//! orientation (body → world), velocity (mm/ms = m/s) and angular velocity (rad/ms, world frame).
//! A sphere belongs to one body, has a radius (mm), a material and an offset from the body's
//! centre of mass in the body (principal) frame.

pub mod arena;
pub mod clump;
pub mod force;
pub mod sphere;

pub use arena::{Storage, StorageLengths, DEFAULT_NEIGHBOURS_PER_SPHERE};
pub use clump::{
    clump_mass_properties, ClumpSpec, ClumpSphere, MassProperties, MassSphere, DEFAULT_MASS_GRID,
    MAX_CLUMP_SPHERES,
};
pub use force::{BodyForce, Loads};
pub use sphere::{Sphere, SphereSpec};

use crate::num::{Quat, Scalar, Vec3};

/// Index of a body in the world.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct BodyId(pub u32);

/// A rigid body (internal units). Public fields are readable state; change them only through
/// the world's methods unless you know the invariants (inverse mass etc.). A body whose
/// inverse mass and inverse inertia are zero is *kinematic*: it moves only with its
/// prescribed velocities, whatever acts on it (a clamp, a gripper).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Body<S> {
    /// Centre of mass, mm.
    pub position: Vec3<S>,
    /// Velocity of the centre of mass, mm/ms (= m/s).
    pub velocity: Vec3<S>,
    /// Angular velocity, rad/ms, world frame.
    pub angular_velocity: Vec3<S>,
    /// Orientation, body (principal) frame → world. Single spheres keep the identity: they are
    /// isotropic, so their orientation carries no physics and is not integrated.
    pub orientation: Quat<S>,
    /// Mass, g.
    pub mass: S,
    /// 1/mass, 1/g.
    pub inv_mass: S,
    /// Principal moments of inertia, g·mm².
    pub inertia: Vec3<S>,
    /// Inverse principal moments, 1/(g·mm²).
    pub inv_inertia: Vec3<S>,
    /// Total force of the last step (contacts, bonds, drag and the weight m·g), N.
    pub force: Vec3<S>,
    /// Total torque of the last step (contacts and bonds), N·mm, world frame.
    pub torque: Vec3<S>,
    /// Rolling-resistance torque magnitude of the last step, N·mm, applied along −ω̂.
    pub roll_torque: S,
    /// First sphere of this body in the sphere arena.
    pub first_sphere: u32,
    /// Number of spheres.
    pub sphere_count: u32,
    /// `true` for a multi-sphere clump (orientation integrated, anisotropic inertia).
    pub is_clump: bool,
    /// `true` for a slow body, which moves once a cycle by the long step
    /// ([`crate::step::multirate`]).
    pub slow: bool,
}

impl<S: Scalar> Default for Body<S> {
    fn default() -> Self {
        Body {
            position: Vec3::ZERO,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            orientation: Quat::IDENTITY,
            mass: S::ZERO,
            inv_mass: S::ZERO,
            inertia: Vec3::ZERO,
            inv_inertia: Vec3::ZERO,
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            roll_torque: S::ZERO,
            first_sphere: 0,
            sphere_count: 0,
            is_clump: false,
            slow: false,
        }
    }
}

impl<S: Scalar> Body<S> {
    /// Kinetic energy ½mv² + ½ωᵀIω, mJ (computed in f64; for reports).
    pub fn kinetic_energy_mj(&self) -> f64 {
        let v = self.velocity.to_f64();
        let m = self.mass.to_f64();
        let w_world = self.angular_velocity;
        let w = if self.is_clump {
            self.orientation.to_mat3().mul_t_vec(w_world).to_f64()
        } else {
            w_world.to_f64()
        };
        let i = self.inertia.to_f64();
        0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2])
            + 0.5 * (i[0] * w[0] * w[0] + i[1] * w[1] * w[1] + i[2] * w[2] * w[2])
    }
}
