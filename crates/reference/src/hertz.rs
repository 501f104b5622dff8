//! Hertz's frictionless contact of two elastic spheres (or a sphere and a plane).

use crate::error::{RefError, check_positive};
use crate::material::Pair;
use std::f64::consts::PI;

/// A Hertz contact at normal force `P` (Hertz 1882, "Über die Berührung fester elastischer
/// Körper", J. reine angew. Math. 92; Johnson 1985, *Contact Mechanics*, §4.2, eqs. 4.22-4.23):
///
/// `a = (3 P R* / (4 E*))^(1/3)`, `delta = a^2 / R*`, `p0 = 3 P / (2 pi a^2)`,
/// `P = (4/3) E* sqrt(R*) delta^(3/2)`, with `1/R* = 1/R_p + 1/R_q`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hertz {
    r_star: f64,
    e_star: f64,
    p: f64,
    a: f64,
}

impl Hertz {
    /// From the relative radius `r_star` \[m\] (> 0), contact modulus `e_star` \[Pa\] (> 0) and normal
    /// force `p` \[N\] (> 0).
    pub fn new(r_star: f64, e_star: f64, p: f64) -> Result<Self, RefError> {
        let r_star = check_positive("r_star", r_star)?;
        let e_star = check_positive("e_star", e_star)?;
        let p = check_positive("p", p)?;
        let a = (0.75 * p * r_star / e_star).cbrt();
        Ok(Hertz {
            r_star,
            e_star,
            p,
            a,
        })
    }

    /// Two spheres of radii `r_p`, `r_q` \[m\] (> 0) and materials `pair`, pressed by `p` \[N\].
    pub fn sphere_pair(r_p: f64, r_q: f64, pair: &Pair, p: f64) -> Result<Self, RefError> {
        let r_p = check_positive("r_p", r_p)?;
        let r_q = check_positive("r_q", r_q)?;
        Self::new(r_p * r_q / (r_p + r_q), pair.e_star(), p)
    }

    /// A sphere of radius `r` \[m\] (> 0) on a plane (`R* = r`), materials `pair`, force `p` \[N\].
    pub fn sphere_plane(r: f64, pair: &Pair, p: f64) -> Result<Self, RefError> {
        Self::new(r, pair.e_star(), p)
    }

    /// Normal force for an overlap `delta` \[m\] (>= 0): `P = (4/3) E* sqrt(R*) delta^(3/2)`
    /// (Johnson 1985, eq. 4.23).
    pub fn force_from_overlap(r_star: f64, e_star: f64, delta: f64) -> Result<f64, RefError> {
        let r_star = check_positive("r_star", r_star)?;
        let e_star = check_positive("e_star", e_star)?;
        let delta = crate::error::check_range("delta", delta, 0.0, f64::MAX, ">= 0")?;
        Ok(4.0 / 3.0 * e_star * r_star.sqrt() * delta.powf(1.5))
    }

    /// Contact radius `a` \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Normal force `P` \[N\].
    pub fn p(&self) -> f64 {
        self.p
    }
    /// Relative radius `R*` \[m\].
    pub fn r_star(&self) -> f64 {
        self.r_star
    }
    /// Contact modulus `E*` \[Pa\].
    pub fn e_star(&self) -> f64 {
        self.e_star
    }
    /// Overlap (approach of distant points) `delta = a^2 / R*` \[m\].
    pub fn overlap(&self) -> f64 {
        self.a * self.a / self.r_star
    }
    /// Peak pressure `p0 = 3 P / (2 pi a^2)` \[Pa\].
    pub fn p0(&self) -> f64 {
        1.5 * self.p / (PI * self.a * self.a)
    }
    /// Pressure at radius `r` \[m\]: `p0 sqrt(1 - r^2/a^2)`, 0 outside \[Pa\].
    pub fn pressure(&self, r: f64) -> f64 {
        let s = 1.0 - r * r / (self.a * self.a);
        if s > 0.0 { self.p0() * s.sqrt() } else { 0.0 }
    }
    /// Normal contact stiffness `dP/d delta = 2 E* a` \[N/m\].
    pub fn stiffness(&self) -> f64 {
        2.0 * self.e_star * self.a
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;

    #[test]
    fn hertz_relations_are_consistent() {
        let pair = Pair::same(Elastic::from_young(210e9, 0.3).unwrap());
        let h = Hertz::sphere_pair(0.01, 0.02, &pair, 100.0).unwrap();
        // P(delta) inverts a(P).
        let p = Hertz::force_from_overlap(h.r_star(), h.e_star(), h.overlap()).unwrap();
        assert!((p / 100.0 - 1.0).abs() < 1e-12);
        // Pressure integrates to P: (2/3) p0 pi a^2.
        assert!((2.0 / 3.0 * h.p0() * PI * h.a() * h.a() / 100.0 - 1.0).abs() < 1e-12);
        // Stiffness = dP/d delta by finite difference.
        let d = h.overlap();
        let k = (Hertz::force_from_overlap(h.r_star(), h.e_star(), d * 1.000001).unwrap()
            - Hertz::force_from_overlap(h.r_star(), h.e_star(), d * 0.999999).unwrap())
            / (2e-6 * d);
        assert!((k / h.stiffness() - 1.0).abs() < 1e-8);
        // Sphere on a plane = sphere pair with an infinite partner radius.
        let plane = Hertz::sphere_plane(0.01, &pair, 100.0).unwrap();
        assert!((plane.r_star() - 0.01).abs() < 1e-15);
        assert!(plane.a() > h.a());
    }

    #[test]
    fn known_steel_ball_value() {
        // Steel ball R = 10 mm on a steel flat, P = 100 N, E = 210 GPa, nu = 0.3:
        // E* = 115.4 GPa, a = (3 P R / 4 E*)^(1/3) = 0.18663 mm (hand calculation).
        let pair = Pair::same(Elastic::from_young(210e9, 0.3).unwrap());
        let h = Hertz::sphere_plane(0.01, &pair, 100.0).unwrap();
        assert!((h.a() / 1.8663e-4 - 1.0).abs() < 1e-4, "{}", h.a());
        assert!(Hertz::new(0.0, 1e9, 1.0).is_err());
        assert!(Hertz::new(1.0, 1e9, -1.0).is_err());
    }
}
