//! Carter's exact solution of two-dimensional steady rolling of elastic cylinders with a
//! tractive force (Carter 1926, "On the action of a locomotive driving wheel", Proc. R. Soc. A
//! 112; Johnson 1985, *Contact Mechanics*, §8.2).
//!
//! Plane strain, quasi-identical cylinders, Hertz contact of half-width `a` and peak pressure
//! `p0`, relative radius `R` (`1/R = 1/R_1 + 1/R_2`), friction `mu`, tangential force `Q` per unit
//! length below `mu P`. The traction is the difference of two Hertz-shaped distributions,
//! `q(x) = mu p0 [sqrt(1 - x^2/a^2) - (c/a) sqrt(1 - (x - d)^2/c^2)]`, the second acting only in
//! the stick zone `|x - d| < c` adjacent to the leading edge (`d = a - c`), with
//!
//! `c/a = sqrt(1 - Q/(mu P))` and creepage `xi = (mu a / R) (1 - sqrt(1 - Q/(mu P)))`.
//!
//! (In the stick zone the displacement gradient of each distribution is that of a Hertz pressure,
//! `mu x / R` and `mu (x - d)/R`, so the rigid creepage is their difference `mu d / R`.) The sign
//! convention is the crate's: creepage of body q relative to body p, force on body p, leading edge
//! at `x = +a`; `xi` has the sign of `Q`.

use crate::error::{RefError, check_positive, check_range};

/// A two-dimensional Carter contact: half-width `a` \[m\], relative radius `R` \[m\], friction `mu`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Carter {
    a: f64,
    r: f64,
    mu: f64,
}

impl Carter {
    /// Half-width `a` \[m\] (> 0), relative radius `r` \[m\] (> 0), friction coefficient `mu` (> 0).
    pub fn new(a: f64, r: f64, mu: f64) -> Result<Self, RefError> {
        Ok(Carter {
            a: check_positive("a", a)?,
            r: check_positive("r", r)?,
            mu: check_positive("mu", mu)?,
        })
    }

    /// From the normal load per unit length `p` \[N/m\] (> 0), relative radius `r` \[m\] and plane
    /// strain contact modulus `e_star` \[Pa\]: Hertz's half-width `a = sqrt(4 p R / (pi E*))`
    /// (Johnson 1985, eq. 4.43).
    pub fn from_load(p: f64, r: f64, e_star: f64, mu: f64) -> Result<Self, RefError> {
        let p = check_positive("p", p)?;
        let r = check_positive("r", r)?;
        let e = check_positive("e_star", e_star)?;
        Self::new((4.0 * p * r / (std::f64::consts::PI * e)).sqrt(), r, mu)
    }

    /// Half-width `a` \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }

    /// Creepage scale `mu a / R` \[dimensionless\]: the creepage at the onset of full sliding.
    pub fn creepage_scale(&self) -> f64 {
        self.mu * self.a / self.r
    }

    /// Creepage \[dimensionless\] at force ratio `s = Q/(mu P)` in `[-1, 1]`:
    /// `xi = (mu a/R)(1 - sqrt(1 - |s|)) sign(s)`.
    pub fn creepage(&self, s: f64) -> Result<f64, RefError> {
        let s = check_range("force ratio", s, -1.0, 1.0, "in [-1, 1]")?;
        Ok(self.creepage_scale() * (1.0 - (1.0 - s.abs()).sqrt()) * s.signum())
    }

    /// Force ratio `Q/(mu P)` at creepage `xi` (finite): the inverse of [`Carter::creepage`],
    /// `s = 1 - (1 - |xi|/(mu a/R))^2` below full sliding, `sign(xi)` beyond.
    pub fn force_ratio(&self, xi: f64) -> Result<f64, RefError> {
        let xi = crate::error::check_finite("creepage", xi)?;
        let x = (xi.abs() / self.creepage_scale()).min(1.0);
        Ok((1.0 - (1.0 - x) * (1.0 - x)) * xi.signum())
    }

    /// Stick-zone half-width over the contact half-width, `c/a = sqrt(1 - |s|)`, for `s` in
    /// `[-1, 1]`. The stick zone is `[a - 2c, a]` (at the leading edge).
    pub fn stick_ratio(s: f64) -> Result<f64, RefError> {
        let s = check_range("force ratio", s, -1.0, 1.0, "in [-1, 1]")?;
        Ok((1.0 - s.abs()).sqrt())
    }

    /// Traction over the Coulomb scale, `q(x)/(mu p0)`, at `x` \[m\] for the force ratio `s` in
    /// `[-1, 1]` (sign of `s`); 0 outside the contact.
    pub fn traction(&self, x: f64, s: f64) -> Result<f64, RefError> {
        let c = Self::stick_ratio(s)? * self.a;
        let x = crate::error::check_finite("x", x)?;
        let half = |x: f64, w: f64| {
            let t = 1.0 - (x / w) * (x / w);
            if t > 0.0 { t.sqrt() } else { 0.0 }
        };
        let d = self.a - c;
        let inner = if c > 0.0 {
            c / self.a * half(x - d, c)
        } else {
            0.0
        };
        Ok((half(x, self.a) - inner) * s.signum())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_and_inverse() {
        let c = Carter::new(1e-3, 0.05, 0.3).unwrap();
        assert_eq!(c.creepage(0.0).unwrap(), 0.0);
        assert!((c.creepage(1.0).unwrap() - 0.3 * 1e-3 / 0.05).abs() < 1e-18);
        // Small force: xi ~ (mu a / R) s / 2, the linear 2-D creep law.
        let s = 1e-6;
        assert!((c.creepage(s).unwrap() / (c.creepage_scale() * s / 2.0) - 1.0).abs() < 1e-5);
        for i in -10..=10 {
            let s = i as f64 / 10.0;
            let back = c.force_ratio(c.creepage(s).unwrap()).unwrap();
            assert!((back - s).abs() < 1e-12);
        }
        assert!(c.creepage(1.5).is_err());
        assert_eq!(Carter::stick_ratio(0.75).unwrap(), 0.5);
    }

    #[test]
    fn traction_integrates_to_q_and_respects_coulomb() {
        // Integral of mu p0 sqrt(1 - x^2/a^2) is mu P; the stick-zone term removes (c/a)^2 of it.
        let c = Carter::new(1.0, 10.0, 0.5).unwrap();
        for s in [0.2, 0.5, 0.9] {
            let m = 20000;
            let mut total = 0.0;
            let mut over = 0.0f64;
            for i in 0..m {
                let x = -1.0 + (i as f64 + 0.5) * 2.0 / m as f64;
                let q = c.traction(x, s).unwrap();
                total += q * 2.0 / m as f64;
                over = over.max(q - (1.0 - x * x).sqrt());
            }
            // mu P corresponds to pi/2 in units of mu p0 a.
            let ratio = total / (std::f64::consts::PI / 2.0);
            assert!((ratio - s).abs() < 1e-4, "s={s}: {ratio}");
            assert!(over <= 1e-12);
        }
    }
}
