//! [`Quat`] (unit quaternion orientation) and [`Mat3`] (rotation matrix), generic over
//! [`Scalar`].
//!
//! Orientation update: q ← normalise(q + ½·dt·(ω ⊗ q)), with ω in the world frame (rad/ms).
//! The renormalisation keeps |q| = 1 to the format's resolution at every step.

use super::scalar::Scalar;
use super::vec3::Vec3;

/// Unit quaternion `w + xi + yj + zk` (body frame → world frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quat<S> {
    /// Real part.
    pub w: S,
    /// i part.
    pub x: S,
    /// j part.
    pub y: S,
    /// k part.
    pub z: S,
}

impl<S: Scalar> Default for Quat<S> {
    fn default() -> Self {
        Self::IDENTITY
    }
}

/// Row-major 3×3 matrix.
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Mat3<S> {
    /// Rows.
    pub r: [Vec3<S>; 3],
}

impl<S: Scalar> Mat3<S> {
    /// M·v.
    #[inline(always)]
    pub fn mul_vec(&self, v: Vec3<S>) -> Vec3<S> {
        Vec3::new(self.r[0].dot(v), self.r[1].dot(v), self.r[2].dot(v))
    }
    /// Mᵀ·v.
    #[inline(always)]
    pub fn mul_t_vec(&self, v: Vec3<S>) -> Vec3<S> {
        self.r[0].scale(v.x) + self.r[1].scale(v.y) + self.r[2].scale(v.z)
    }
}

impl<S: Scalar> Quat<S> {
    /// No rotation.
    pub const IDENTITY: Self = Quat {
        w: S::ONE,
        x: S::ZERO,
        y: S::ZERO,
        z: S::ZERO,
    };

    /// Quantise from `f64` `[w, x, y, z]` and normalise (set-up only).
    pub fn from_f64(q: [f64; 4]) -> Self {
        let n = libm::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
        Quat {
            w: S::from_f64(q[0] / n),
            x: S::from_f64(q[1] / n),
            y: S::from_f64(q[2] / n),
            z: S::from_f64(q[3] / n),
        }
    }
    /// `[w, x, y, z]` as `f64`.
    pub fn to_f64(self) -> [f64; 4] {
        [
            self.w.to_f64(),
            self.x.to_f64(),
            self.y.to_f64(),
            self.z.to_f64(),
        ]
    }
    /// `true` when all components are valid.
    pub fn is_valid(self) -> bool {
        self.w.is_valid() & self.x.is_valid() & self.y.is_valid() & self.z.is_valid()
    }

    /// Rotation matrix (body → world).
    pub fn to_mat3(self) -> Mat3<S> {
        let (w, x, y, z) = (self.w, self.x, self.y, self.z);
        let one = S::ONE;
        let (xx, yy, zz) = (x * x, y * y, z * z);
        let (xy, xz, yz) = (x * y, x * z, y * z);
        let (wx, wy, wz) = (w * x, w * y, w * z);
        Mat3 {
            r: [
                Vec3::new(
                    one - (yy + zz).mul_int(2),
                    (xy - wz).mul_int(2),
                    (xz + wy).mul_int(2),
                ),
                Vec3::new(
                    (xy + wz).mul_int(2),
                    one - (xx + zz).mul_int(2),
                    (yz - wx).mul_int(2),
                ),
                Vec3::new(
                    (xz - wy).mul_int(2),
                    (yz + wx).mul_int(2),
                    one - (xx + yy).mul_int(2),
                ),
            ],
        }
    }

    /// Advance by angular velocity `omega` (world frame, rad/ms) over `dt` (ms), then
    /// renormalise: q ← normalise(q + ½·dt·(ω ⊗ q)). The norm is within a few 1e-9 of 1
    /// before renormalising (|½·dt·ω| ≪ 1 for any stable step), so the scale 1/|q| comes
    /// from the fast reciprocal root of [`Scalar::Fast`] (the same bits in the checked and
    /// unchecked arithmetic; no square root and no division).
    pub fn integrate(self, omega: Vec3<S>, dt: S) -> Self {
        let h = dt * S::HALF;
        let (ox, oy, oz) = (omega.x * h, omega.y * h, omega.z * h);
        // (0, o) ⊗ (w, v) = (−o·v, w o + o × v)
        let w = self.w - (ox * self.x + oy * self.y + oz * self.z);
        let x = self.x + (ox * self.w + (oy * self.z - oz * self.y));
        let y = self.y + (oy * self.w + (oz * self.x - ox * self.z));
        let z = self.z + (oz * self.w + (ox * self.y - oy * self.x));
        let n2 = w * w + x * x + y * y + z * z;
        let inv = if n2.is_valid() {
            S::from_fast(n2.to_fast().rsqrt())
        } else {
            n2
        };
        Quat {
            w: w * inv,
            x: x * inv,
            y: y * inv,
            z: z * inv,
        }
    }
}
