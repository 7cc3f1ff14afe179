//! State digest and per-body dump, for bit-exact regression tests and divergence hunting
//! (DESIGN §5).
//!
//! The world's `digest` is 64-bit FNV-1a over the raw bits (Q32.32 integers or `f64::to_bits`,
//! little-endian) of the whole state: time and step count, dt, gravity, every body (all
//! fields), every sphere, the live contact history (per sphere: count, then partner keys and δt,
//! plus α_max, the rolling angle θr and the JKR neck flag only when set),
//! and every wall (geometry, velocity, material). No `usize` enters the hash, so the digest is
//! the same on 32- and 64-bit targets. The world's `body_records` yields one record per body
//! whose `Display` is a single line, with the body's own FNV-1a hash: diff two dumps to find
//! the first body that diverged.

use crate::body::Body;
use crate::num::{Quat, Scalar, Vec3};
use core::fmt;

/// FNV-1a 64-bit offset basis.
pub const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// FNV-1a 64-bit prime.
pub const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// Incremental FNV-1a 64 hasher over little-endian words.
#[derive(Clone, Copy, Debug)]
pub struct Fnv1a(u64);

impl Default for Fnv1a {
    fn default() -> Self {
        Fnv1a(FNV_OFFSET)
    }
}

impl Fnv1a {
    /// Hash 8 bytes (little-endian).
    #[inline]
    pub fn u64(&mut self, x: u64) {
        for b in x.to_le_bytes() {
            self.0 ^= b as u64;
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
    }
    /// Hash a scalar's raw bits.
    #[inline]
    pub fn s<S: Scalar>(&mut self, x: S) {
        self.u64(x.to_bits());
    }
    /// Hash a vector's raw bits.
    #[inline]
    pub fn v<S: Scalar>(&mut self, v: Vec3<S>) {
        self.s(v.x);
        self.s(v.y);
        self.s(v.z);
    }
    /// Hash a quaternion's raw bits.
    pub fn q<S: Scalar>(&mut self, q: Quat<S>) {
        self.s(q.w);
        self.s(q.x);
        self.s(q.y);
        self.s(q.z);
    }
    /// Hash a body's state.
    pub fn body<S: Scalar>(&mut self, b: &Body<S>) {
        self.v(b.position);
        self.v(b.velocity);
        self.v(b.angular_velocity);
        self.q(b.orientation);
        self.s(b.mass);
        self.s(b.inv_mass);
        self.v(b.inertia);
        self.v(b.inv_inertia);
        self.v(b.force);
        self.v(b.torque);
        self.s(b.roll_torque);
        self.u64(b.first_sphere as u64);
        self.u64(b.sphere_count as u64);
        self.u64(b.is_clump as u64);
    }
    /// The hash value.
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// One body's state for a dump (internal units: mm, mm/ms, rad/ms).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BodyRecord {
    /// Body id.
    pub id: u32,
    /// Centre of mass, mm.
    pub position_mm: [f64; 3],
    /// Velocity, mm/ms (= m/s).
    pub velocity_mm_ms: [f64; 3],
    /// Angular velocity, rad/ms.
    pub angular_velocity_rad_ms: [f64; 3],
    /// Orientation `[w, x, y, z]`.
    pub orientation: [f64; 4],
    /// FNV-1a 64 of the body's raw state.
    pub hash: u64,
}

impl fmt::Display for BodyRecord {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let p = self.position_mm;
        let v = self.velocity_mm_ms;
        let w = self.angular_velocity_rad_ms;
        let q = self.orientation;
        write!(
            f,
            "body {} hash {:016x} x_mm {:.10e} {:.10e} {:.10e} v_m_s {:.10e} {:.10e} {:.10e} \
             w_rad_ms {:.10e} {:.10e} {:.10e} q {:.10e} {:.10e} {:.10e} {:.10e}",
            self.id,
            self.hash,
            p[0],
            p[1],
            p[2],
            v[0],
            v[1],
            v[2],
            w[0],
            w[1],
            w[2],
            q[0],
            q[1],
            q[2],
            q[3]
        )
    }
}
