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
        if self.is_valid() {
            // Every step but the last is bounded by the scaling: |u| < 2 per component (2^33
            // raw), |u|² < 12, 1/|u| ≤ 1, so the unchecked arithmetic (the same bits as the
            // checked one inside the range) cannot overflow. Only the length, scaled back by
            // 2^-k, can leave the range, and stays checked. The reciprocal root is the world
            // scalar's own, so the bits are those of [`Vec3::scaled_unit_checked`].
            let f = S::to_fast;
            let u = Vec3::new(
                f(self.x).mul_pow2(k),
                f(self.y).mul_pow2(k),
                f(self.z).mul_pow2(k),
            );
            let q = u.norm2();
            let r = S::from_fast(q).rsqrt().to_fast();
            return Some((
                u.scale(r).map(S::from_fast),
                S::from_fast(q * r).mul_pow2(-k),
            ));
        }
        Some(self.scaled_unit_checked(k))
    }

    /// The unit vector and length of a vector whose largest component times 2^k lies in
    /// [1, 2), every operation checked: the path of a vector holding the overflow poison,
    /// and the reference the unchecked path must match.
    fn scaled_unit_checked(self, k: i32) -> (Self, S) {
        let u = Vec3::new(self.x.mul_pow2(k), self.y.mul_pow2(k), self.z.mul_pow2(k));
        let q = u.norm2();
        let r = q.rsqrt();
        (u.scale(r), (q * r).mul_pow2(-k))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::fused::random_contacts::Stream;
    use crate::num::Fx;

    /// The checked normalisation, operation by operation: the reference for the unchecked one.
    fn normalize_checked(v: Vec3<Fx>) -> Option<(Vec3<Fx>, Fx)> {
        let m = Scalar::max(Scalar::max(v.x.abs(), v.y.abs()), v.z.abs());
        (m != Fx::ZERO).then(|| v.scaled_unit_checked(-m.log2_floor()))
    }

    /// A raw component of any magnitude from one unit to the edge of the range, either sign.
    fn component(x: u64) -> Fx {
        let shift = (x >> 58) as u32; // 0..=63
        let raw = ((x << 6) >> shift.max(1)) as i64;
        Fx::from_raw(if x & 1 == 0 { raw } else { -raw })
    }

    #[test]
    fn unchecked_normalisation_gives_the_checked_bits() {
        let mut stream = Stream(0x9E37_79B9_7F4A_7C15);
        let mut next = || stream.bits();
        let mut overflowed = 0;
        for i in 0..400_000 {
            let mut v = Vec3::new(component(next()), component(next()), component(next()));
            match i % 50 {
                0 => v.y = Fx::ZERO,
                1 => v = Vec3::new(Fx::ZERO, Fx::ZERO, v.z),
                2 => v.x = Fx::POISON,
                3 => v = Vec3::new(Fx::from_raw(i64::MAX), Fx::from_raw(i64::MAX), v.z),
                _ => {}
            }
            let want = normalize_checked(v);
            assert_eq!(v.normalize_with_len(), want, "{v:?}");
            overflowed += want.is_some_and(|(_, len)| !len.is_valid()) as u32;
        }
        // Long vectors whose length leaves the range are among them, and are still reported.
        assert!(overflowed > 100, "{overflowed}");
    }
}
