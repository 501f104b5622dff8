//! The circular Hertz contact that the numerical references (FASTSIM, boundary elements) solve:
//! contact radius, normal force, combined elastic constants and friction coefficient.

use crate::error::{RefError, check_positive, check_range};
use std::f64::consts::PI;

/// A circular Hertz contact between two quasi-identical elastic bodies (validated inputs).
///
/// The normal pressure is Hertz's, `p(r) = p0 sqrt(1 - r^2/a^2)` with `p0 = 3 P / (2 pi a^2)`
/// (Hertz 1882; Johnson 1985, *Contact Mechanics*, eq. 4.22 form for the sphere). `G` and `nu`
/// are the pair's combined constants in Kalker's sense, see [`crate::material::Pair`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CircularContact {
    a: f64,
    p: f64,
    g: f64,
    nu: f64,
    mu: f64,
}

impl CircularContact {
    /// Validates and builds a contact.
    ///
    /// * `a` — contact radius \[m\], finite and > 0;
    /// * `p` — normal force \[N\], finite and > 0;
    /// * `g` — combined shear modulus \[Pa\], finite and > 0;
    /// * `nu` — combined Poisson ratio, in `[0, 0.5]`;
    /// * `mu` — Coulomb friction coefficient, finite and > 0.
    pub fn new(a: f64, p: f64, g: f64, nu: f64, mu: f64) -> Result<Self, RefError> {
        Ok(CircularContact {
            a: check_positive("a", a)?,
            p: check_positive("p", p)?,
            g: check_positive("g", g)?,
            nu: check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?,
            mu: check_positive("mu", mu)?,
        })
    }

    /// A contact in normalised units: `a = 1`, `G = 1`, `mu P = 1` (`mu = 1`, `P = 1`). Results
    /// for any other contact follow by scaling forces with `mu P` and creepages with
    /// `mu P / (G a^2)`.
    pub fn normalised(nu: f64) -> Result<Self, RefError> {
        Self::new(1.0, 1.0, 1.0, nu, 1.0)
    }

    /// Contact radius `a` \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Normal force `P` \[N\].
    pub fn p(&self) -> f64 {
        self.p
    }
    /// Combined shear modulus `G` \[Pa\].
    pub fn g(&self) -> f64 {
        self.g
    }
    /// Combined Poisson ratio `nu`.
    pub fn nu(&self) -> f64 {
        self.nu
    }
    /// Friction coefficient `mu`.
    pub fn mu(&self) -> f64 {
        self.mu
    }
    /// Coulomb limit of the tangential force, `mu P` \[N\].
    pub fn mu_p(&self) -> f64 {
        self.mu * self.p
    }
    /// Peak Hertz pressure `p0 = 3 P / (2 pi a^2)` \[Pa\] (Johnson 1985, eq. 4.22).
    pub fn p0(&self) -> f64 {
        1.5 * self.p / (PI * self.a * self.a)
    }
    /// Hertz pressure at `(x, y)` \[m\] from the centre, `p0 sqrt(1 - r^2/a^2)` \[Pa\], 0 outside.
    pub fn pressure(&self, x: f64, y: f64) -> f64 {
        let s = 1.0 - (x * x + y * y) / (self.a * self.a);
        if s > 0.0 { self.p0() * s.sqrt() } else { 0.0 }
    }
    /// Creepage scale `mu P / (G a^2)` \[dimensionless\]: the normalised creepage is
    /// `xi_n = xi / creepage_scale()` (the project's convention, docs/ARCHITECTURE.md §4).
    pub fn creepage_scale(&self) -> f64 {
        self.mu * self.p / (self.g * self.a * self.a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn validates_inputs() {
        assert!(CircularContact::new(0.0, 1.0, 1.0, 0.3, 0.3).is_err());
        assert!(CircularContact::new(1.0, -1.0, 1.0, 0.3, 0.3).is_err());
        assert!(CircularContact::new(1.0, 1.0, f64::NAN, 0.3, 0.3).is_err());
        assert!(CircularContact::new(1.0, 1.0, 1.0, 0.51, 0.3).is_err());
        assert!(CircularContact::new(1.0, 1.0, 1.0, 0.3, 0.0).is_err());
        assert!(CircularContact::new(1e-3, 100.0, 80e9, 0.3, 0.3).is_ok());
    }

    #[test]
    fn hertz_pressure_integrates_to_p() {
        // Integral of p0 sqrt(1 - r^2/a^2) over the disc is (2/3) p0 pi a^2 = P.
        let c = CircularContact::new(2e-3, 50.0, 1e9, 0.25, 0.4).unwrap();
        let m = 2000;
        let mut total = 0.0;
        for i in 0..m {
            let r = (i as f64 + 0.5) / m as f64 * c.a();
            total += c.pressure(r, 0.0) * 2.0 * PI * r * c.a() / m as f64;
        }
        assert!((total / c.p() - 1.0).abs() < 1e-5, "{total}");
        assert_eq!(c.pressure(c.a(), 0.0), 0.0);
        assert!((c.creepage_scale() - 0.4 * 50.0 / (1e9 * 4e-6)).abs() < 1e-15);
    }
}
