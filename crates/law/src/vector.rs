//! Minimal 2-D and 3-D vector types (f64), so the law crate needs no linear-algebra dependency.
//! Engines convert at their boundary (e.g. from glam's `DVec3`/`Vec3`).

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// A 3-D vector [units of the quantity it holds].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec3 {
    /// x component.
    pub x: f64,
    /// y component.
    pub y: f64,
    /// z component.
    pub z: f64,
}

/// A 2-D vector in a contact's tangent plane [units of the quantity it holds].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Vec2 {
    /// First tangent component.
    pub x: f64,
    /// Second tangent component.
    pub y: f64,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Self = Self::new(0.0, 0.0, 0.0);
    /// Unit x.
    pub const X: Self = Self::new(1.0, 0.0, 0.0);
    /// Unit y.
    pub const Y: Self = Self::new(0.0, 1.0, 0.0);
    /// Unit z.
    pub const Z: Self = Self::new(0.0, 0.0, 1.0);

    /// Builds a vector from components.
    #[inline]
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }
    /// Cross product `self x o`.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }
    /// Euclidean length.
    #[inline]
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }
    /// The part of `self` orthogonal to the unit vector `n`: `self - (self . n) n`.
    #[inline]
    pub fn reject(self, n: Self) -> Self {
        self - n * self.dot(n)
    }
    /// True when every component is finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }
    /// Unit vector along `self`, or `None` for a zero, tiny or non-finite vector.
    #[inline]
    pub fn try_normalize(self) -> Option<Self> {
        let l = self.length();
        (l.is_finite() && l > f64::MIN_POSITIVE).then(|| self * (1.0 / l))
    }
    /// An orthonormal tangent basis `(t1, t2)` with `t1 x t2 = self` for a unit vector `self`
    /// (Duff et al. 2017, "Building an orthonormal basis, revisited", JCGT 6(1)).
    pub fn tangent_basis(self) -> (Self, Self) {
        let sign = 1.0_f64.copysign(self.z);
        let a = -1.0 / (sign + self.z);
        let b = self.x * self.y * a;
        let t1 = Self::new(1.0 + sign * self.x * self.x * a, sign * b, -sign * self.x);
        let t2 = Self::new(b, sign + self.y * self.y * a, -self.y);
        (t1, t2)
    }
}

impl Vec2 {
    /// The zero vector.
    pub const ZERO: Self = Self::new(0.0, 0.0);

    /// Builds a vector from components.
    #[inline]
    pub const fn new(x: f64, y: f64) -> Self {
        Self { x, y }
    }
    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> f64 {
        self.x * o.x + self.y * o.y
    }
    /// Squared length.
    #[inline]
    pub fn length_squared(self) -> f64 {
        self.dot(self)
    }
    /// Euclidean length (`sqrt(x^2 + y^2)`: overflows to infinity only beyond ~1e154, far above
    /// any displacement or force this crate lets through).
    #[inline]
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }
    /// True when both components are finite.
    #[inline]
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite()
    }
    /// Components of a 3-D tangent vector in the basis `(t1, t2)`.
    #[inline]
    pub fn from_basis(v: Vec3, t1: Vec3, t2: Vec3) -> Self {
        Self::new(v.dot(t1), v.dot(t2))
    }
    /// The 3-D vector `x t1 + y t2`.
    #[inline]
    pub fn to_3d(self, t1: Vec3, t2: Vec3) -> Vec3 {
        t1 * self.x + t2 * self.y
    }
}

macro_rules! impl_ops {
    ($t:ident { $($f:ident),+ }) => {
        impl Add for $t { type Output = Self; #[inline] fn add(self, o: Self) -> Self { Self { $($f: self.$f + o.$f),+ } } }
        impl Sub for $t { type Output = Self; #[inline] fn sub(self, o: Self) -> Self { Self { $($f: self.$f - o.$f),+ } } }
        impl Neg for $t { type Output = Self; #[inline] fn neg(self) -> Self { Self { $($f: -self.$f),+ } } }
        impl Mul<f64> for $t { type Output = Self; #[inline] fn mul(self, s: f64) -> Self { Self { $($f: self.$f * s),+ } } }
        impl Mul<$t> for f64 { type Output = $t; #[inline] fn mul(self, v: $t) -> $t { v * self } }
        impl AddAssign for $t { #[inline] fn add_assign(&mut self, o: Self) { $(self.$f += o.$f;)+ } }
        impl SubAssign for $t { #[inline] fn sub_assign(&mut self, o: Self) { $(self.$f -= o.$f;)+ } }
    };
}
impl_ops!(Vec3 { x, y, z });
impl_ops!(Vec2 { x, y });

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_basis_is_orthonormal_and_right_handed() {
        for n in [
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.3, -0.4, 0.866).try_normalize().unwrap(),
        ] {
            let (t1, t2) = n.tangent_basis();
            assert!((t1.length() - 1.0).abs() < 1e-14 && (t2.length() - 1.0).abs() < 1e-14);
            assert!(t1.dot(n).abs() < 1e-14 && t2.dot(n).abs() < 1e-14 && t1.dot(t2).abs() < 1e-14);
            assert!((t1.cross(t2) - n).length() < 1e-14, "n = {n:?}");
        }
    }
}
