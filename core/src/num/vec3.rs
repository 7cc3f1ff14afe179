//! [`Vec3`]: a 3-vector generic over [`Scalar`].

use super::scalar::Scalar;
use core::ops::{Add, AddAssign, Neg, Sub, SubAssign};

/// A 3-vector. Units are those of the quantity it holds (stated where it is used).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct Vec3<S> {
    /// x component.
    pub x: S,
    /// y component.
    pub y: S,
    /// z component.
    pub z: S,
}

impl<S: Scalar> Vec3<S> {
    /// The zero vector.
    pub const ZERO: Self = Vec3 {
        x: S::ZERO,
        y: S::ZERO,
        z: S::ZERO,
    };
    /// Build from components.
    #[inline(always)]
    pub fn new(x: S, y: S, z: S) -> Self {
        Vec3 { x, y, z }
    }
    /// Quantise from `f64` components (set-up only).
    pub fn from_f64(v: [f64; 3]) -> Self {
        Vec3::new(S::from_f64(v[0]), S::from_f64(v[1]), S::from_f64(v[2]))
    }
    /// Apply `f` to each component (e.g. to change the scalar type).
    #[inline(always)]
    pub fn map<T: Scalar>(self, f: impl Fn(S) -> T) -> Vec3<T> {
        Vec3::new(f(self.x), f(self.y), f(self.z))
    }
    /// Convert to `f64` components.
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.to_f64(), self.y.to_f64(), self.z.to_f64()]
    }
    /// Dot product.
    #[inline(always)]
    pub fn dot(self, o: Self) -> S {
        S::dot3(self.x, o.x, self.y, o.y, self.z, o.z)
    }
    /// Cross product.
    #[inline(always)]
    pub fn cross(self, o: Self) -> Self {
        Vec3::new(
            S::mul_sub(self.y, o.z, self.z, o.y),
            S::mul_sub(self.z, o.x, self.x, o.z),
            S::mul_sub(self.x, o.y, self.y, o.x),
        )
    }
    /// Scale by a scalar.
    #[inline(always)]
    pub fn scale(self, s: S) -> Self {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
    /// The part of `self` in the plane normal to the unit vector `n`: self − n·(self·n)
    /// (a contact's tangent plane: tangential history, rolling spin).
    #[inline(always)]
    pub fn in_plane_of(self, n: Self) -> Self {
        self - n.scale(self.dot(n))
    }
    /// Squared length.
    #[inline(always)]
    pub fn norm2(self) -> S {
        self.dot(self)
    }
    /// Length.
    #[inline]
    pub fn norm(self) -> S {
        self.norm2().sqrt()
    }
    /// `true` when all components are valid (no overflow poison / NaN).
    #[inline(always)]
    pub fn is_valid(self) -> bool {
        self.x.is_valid() & self.y.is_valid() & self.z.is_valid()
    }
    /// Unit vector along `self` and the length, or `None` for the zero vector.
    ///
    /// The vector is first scaled exactly by a power of two so that its largest component lies
    /// in [1, 2): then |u|² ∈ [1, 12) keeps full relative precision even for vectors whose
    /// squared length would round to (nearly) zero in Q32.32, and the result is a unit vector
    /// to about 2⁻³¹ (fuzz finding F4). u·rsqrt(|u|²) needs no division or square root.
    ///
    /// Floating point needs no scaling ([`Scalar::Q32_32`] is false for `f64`).
    #[inline]
    pub fn normalize_with_len(self) -> Option<(Self, S)> {
        let m = self.x.abs().max(self.y.abs()).max(self.z.abs());
        if m == S::ZERO {
            return None;
        }
        if !S::Q32_32 {
            let q = self.norm2();
            let r = q.rsqrt();
            return Some((self.scale(r), q * r));
        }
        let k = -m.log2_floor();
        let u = Vec3::new(self.x.mul_pow2(k), self.y.mul_pow2(k), self.z.mul_pow2(k));
        let q = u.norm2();
        let r = q.rsqrt();
        Some((u.scale(r), (q * r).mul_pow2(-k)))
    }

    /// |x| + |y| + |z|, an upper bound on the length without a square root.
    #[inline(always)]
    pub fn l1_norm(self) -> S {
        self.x.abs() + self.y.abs() + self.z.abs()
    }

    /// Component-wise product.
    #[inline(always)]
    pub fn mul_elem(self, o: Self) -> Self {
        Vec3::new(self.x * o.x, self.y * o.y, self.z * o.z)
    }
}

impl<S: Scalar> Add for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn add(self, o: Self) -> Self {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}
impl<S: Scalar> Sub for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn sub(self, o: Self) -> Self {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}
impl<S: Scalar> Neg for Vec3<S> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}
impl<S: Scalar> AddAssign for Vec3<S> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<S: Scalar> SubAssign for Vec3<S> {
    #[inline(always)]
    fn sub_assign(&mut self, o: Self) {
        *self = *self - o;
    }
}
