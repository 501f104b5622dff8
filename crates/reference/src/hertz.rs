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

/// `integral_0^1 (1 - x^(5/2))^(-1/2) dx = Gamma(7/5) Gamma(1/2) / Gamma(9/10)`, the time
/// integral of Hertz's impact (Johnson 1985, §11.4, eq. 11.23; Gamma values to 16 digits).
pub const IMPACT_INTEGRAL: f64 = 1.471_637_592_162_353;

/// The normal impact of two elastic spheres (or a sphere on a fixed plane) with relative
/// approach speed `v`, in Hertz's quasi-static theory (Hertz 1882; Johnson 1985, *Contact
/// Mechanics*, §11.4, eqs. 11.22-11.24): the energy balance
/// `(1/2) m* v^2 = (8/15) E* sqrt(R*) delta_max^(5/2)` gives
/// `delta_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5)`, the peak force is Hertz's at
/// `delta_max`, `P_max = (4/3) E* sqrt(R*) delta_max^(3/2)`, and the contact lasts
/// `t_c = 2 I delta_max / v` with `I =` [`IMPACT_INTEGRAL`] (`2 I = 2.943`; in closed form
/// `t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5)`, Johnson's 2.87).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzImpact {
    /// Largest overlap `delta_max` \[m\].
    pub max_overlap: f64,
    /// Peak normal force `P_max` \[N\].
    pub peak_force: f64,
    /// Contact duration `t_c` \[s\].
    pub duration: f64,
}

impl HertzImpact {
    /// From the effective mass `m_star = m_p m_q / (m_p + m_q)` \[kg\] (the sphere's mass on a
    /// fixed plane), relative radius `r_star` \[m\], contact modulus `e_star` \[Pa\] and approach
    /// speed `v` \[m/s\], each finite and > 0.
    pub fn new(m_star: f64, r_star: f64, e_star: f64, v: f64) -> Result<Self, RefError> {
        let m_star = check_positive("m_star", m_star)?;
        let r_star = check_positive("r_star", r_star)?;
        let e_star = check_positive("e_star", e_star)?;
        let v = check_positive("v", v)?;
        let k = 4.0 / 3.0 * e_star * r_star.sqrt();
        let max_overlap = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
        Ok(HertzImpact {
            max_overlap,
            peak_force: k * max_overlap.powf(1.5),
            duration: 2.0 * IMPACT_INTEGRAL * max_overlap / v,
        })
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

    #[test]
    fn impact_matches_johnsons_closed_form() {
        // t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5) (Johnson 1985, eq. 11.24), to Johnson's digits.
        let (m, r, e, v) = (0.01, 0.005, 37.6e9, 1.0);
        let imp = HertzImpact::new(m, r, e, v).unwrap();
        let johnson = 2.87 * (m * m / (r * e * e * v)).powf(0.2);
        assert!(
            (imp.duration / johnson - 1.0).abs() < 2e-3,
            "{imp:?} {johnson}"
        );
        // Energy balance: the elastic energy at delta_max is the kinetic energy.
        let elastic = 8.0 / 15.0 * e * r.sqrt() * imp.max_overlap.powf(2.5);
        assert!((elastic / (0.5 * m * v * v) - 1.0).abs() < 1e-12);
        assert!(HertzImpact::new(m, r, e, 0.0).is_err());
        assert!(HertzImpact::new(f64::NAN, r, e, v).is_err());
    }
}
