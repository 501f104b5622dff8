//! Cattaneo-Mindlin tangential loading of a Hertz contact at constant normal force, with
//! Mindlin & Deresiewicz's unloading and reloading.
//!
//! Sources: Cattaneo 1938 ("Sul contatto di due corpi elastici: distribuzione locale degli
//! sforzi", Rend. Accad. Naz. Lincei 27); Mindlin 1949 ("Compliance of elastic bodies in
//! contact", J. Appl. Mech. 16); Mindlin & Deresiewicz 1953 ("Elastic spheres in contact under
//! varying oblique forces", J. Appl. Mech. 20); Johnson 1985, *Contact Mechanics*, §7.2.
//!
//! With `K = 3 mu P / (16 G* a)` and `1/G* = (2 - nu_p)/G_p + (2 - nu_q)/G_q` (docs/ARCHITECTURE.md §4):
//!
//! * loading from rest to `Q`: `delta = K [1 - (1 - Q/(mu P))^(2/3)]`, stick radius
//!   `c = a (1 - Q/(mu P))^(1/3)`;
//! * unloading from `Q*` to `Q`: `delta = delta* - 2 K [1 - (1 - (Q* - Q)/(2 mu P))^(2/3)]`;
//! * reloading from `-Q*` to `Q`: `delta = -delta* + 2 K [1 - (1 - (Q* + Q)/(2 mu P))^(2/3)]`.
//!
//! For a sphere pair and a sphere on a plane the formulas are the same; only `a` (Hertz, through
//! `R*` and `E*`) and `G*` differ: see [`Mindlin::sphere_pair`] and [`Mindlin::sphere_plane`].

use crate::error::{RefError, check_positive, check_range};
use crate::hertz::Hertz;
use crate::material::Pair;

/// A Cattaneo-Mindlin contact: Coulomb limit `mu P`, tangential modulus `G*`, contact radius `a`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mindlin {
    mu_p: f64,
    g_star: f64,
    a: f64,
}

impl Mindlin {
    /// From the Coulomb limit `mu_p = mu P` \[N\] (> 0), Mindlin's modulus `g_star` \[Pa\] (> 0)
    /// and the contact radius `a` \[m\] (> 0).
    pub fn new(mu_p: f64, g_star: f64, a: f64) -> Result<Self, RefError> {
        Ok(Mindlin {
            mu_p: check_positive("mu_p", mu_p)?,
            g_star: check_positive("g_star", g_star)?,
            a: check_positive("a", a)?,
        })
    }

    /// Two spheres of radii `r_p`, `r_q` \[m\], materials `pair`, normal force `p` \[N\], friction
    /// coefficient `mu` (> 0).
    pub fn sphere_pair(r_p: f64, r_q: f64, pair: &Pair, p: f64, mu: f64) -> Result<Self, RefError> {
        let h = Hertz::sphere_pair(r_p, r_q, pair, p)?;
        Self::new(check_positive("mu", mu)? * p, pair.g_star(), h.a())
    }

    /// A sphere of radius `r` \[m\] on a plane, materials `pair` (p the sphere, q the plane), normal
    /// force `p` \[N\], friction coefficient `mu` (> 0).
    pub fn sphere_plane(r: f64, pair: &Pair, p: f64, mu: f64) -> Result<Self, RefError> {
        let h = Hertz::sphere_plane(r, pair, p)?;
        Self::new(check_positive("mu", mu)? * p, pair.g_star(), h.a())
    }

    /// Contact radius `a` \[m\].
    pub fn a(&self) -> f64 {
        self.a
    }
    /// Coulomb limit `mu P` \[N\].
    pub fn mu_p(&self) -> f64 {
        self.mu_p
    }
    /// Initial tangential stiffness `8 G* a` \[N/m\] (Mindlin 1949).
    pub fn stiffness(&self) -> f64 {
        8.0 * self.g_star * self.a
    }
    /// Shift at the onset of full sliding, `K = 3 mu P / (16 G* a)` \[m\].
    pub fn sliding_shift(&self) -> f64 {
        3.0 * self.mu_p / (16.0 * self.g_star * self.a)
    }

    fn ratio(&self, name: &'static str, q: f64) -> Result<f64, RefError> {
        let q = crate::error::check_finite(name, q)?;
        if q.abs() > self.mu_p * (1.0 + 1e-12) {
            return Err(RefError::InvalidParameter {
                name,
                value: q,
                expected: "|Q| <= mu P",
            });
        }
        Ok((q / self.mu_p).clamp(-1.0, 1.0))
    }

    /// Shift `delta` \[m\] of monotonic loading from rest to `q` \[N\] (`|q| <= mu P`, odd in `q`):
    /// `delta = K [1 - (1 - |Q|/(mu P))^(2/3)] sign(Q)` (Mindlin 1949; Johnson 1985, eq. 7.44
    /// form).
    pub fn loading_shift(&self, q: f64) -> Result<f64, RefError> {
        let s = self.ratio("q", q)?;
        Ok(self.sliding_shift() * (1.0 - (1.0 - s.abs()).powf(2.0 / 3.0)) * s.signum())
    }

    /// Inverse of [`Mindlin::loading_shift`]: force \[N\] for a shift `delta` \[m\] (finite); beyond
    /// the sliding shift the force is `mu P sign(delta)`.
    pub fn loading_force(&self, delta: f64) -> Result<f64, RefError> {
        let d = crate::error::check_finite("delta", delta)?;
        let x = (d.abs() / self.sliding_shift()).min(1.0);
        Ok(self.mu_p * (1.0 - (1.0 - x).powf(1.5)) * d.signum())
    }

    /// Radius of the stick zone `c = a (1 - |Q|/(mu P))^(1/3)` \[m\] under monotonic loading
    /// (Cattaneo 1938; Mindlin 1949).
    pub fn stick_radius(&self, q: f64) -> Result<f64, RefError> {
        let s = self.ratio("q", q)?;
        Ok(self.a * (1.0 - s.abs()).cbrt())
    }

    /// Shift \[m\] on unloading from the turning point `q_star` \[N\] (`0 < q_star <= mu P`) down to
    /// `q` \[N\] (`-q_star <= q <= q_star`) (Mindlin & Deresiewicz 1953).
    pub fn unloading_shift(&self, q_star: f64, q: f64) -> Result<f64, RefError> {
        let s_star = self.ratio("q_star", q_star)?;
        check_range("q_star", s_star, f64::MIN_POSITIVE, 1.0, "0 < Q* <= mu P")?;
        let s = self.ratio("q", q)?;
        check_range("q", s, -s_star, s_star, "-Q* <= Q <= Q*")?;
        let k = self.sliding_shift();
        let d_star = k * (1.0 - (1.0 - s_star).powf(2.0 / 3.0));
        Ok(d_star - 2.0 * k * (1.0 - (1.0 - (s_star - s) / 2.0).powf(2.0 / 3.0)))
    }

    /// Shift \[m\] on reloading from `-q_star` \[N\] (`0 < q_star <= mu P`) up to `q` \[N\]
    /// (`-q_star <= q <= q_star`) (Mindlin & Deresiewicz 1953; by symmetry of the unloading
    /// branch).
    pub fn reloading_shift(&self, q_star: f64, q: f64) -> Result<f64, RefError> {
        Ok(-self.unloading_shift(q_star, -q)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;

    fn m() -> Mindlin {
        Mindlin::new(30.0, 20e9, 1e-4).unwrap()
    }

    #[test]
    fn loading_starts_with_stiffness_8_g_star_a_and_inverts() {
        let m = m();
        let dq = 1e-6 * m.mu_p();
        let k = dq / m.loading_shift(dq).unwrap();
        assert!((k / m.stiffness() - 1.0).abs() < 1e-6);
        for i in 0..=20 {
            let q = m.mu_p() * (i as f64 / 20.0 - 0.5) * 1.98;
            let back = m.loading_force(m.loading_shift(q).unwrap()).unwrap();
            assert!((back - q).abs() < 1e-9 * m.mu_p());
        }
        assert!((m.loading_shift(m.mu_p()).unwrap() - m.sliding_shift()).abs() < 1e-20);
        assert!(m.loading_shift(1.01 * m.mu_p()).is_err());
        assert!((m.stick_radius(0.875 * m.mu_p()).unwrap() - 0.5 * m.a()).abs() < 1e-15);
    }

    #[test]
    fn hysteresis_loop_closes_and_is_masing() {
        let m = m();
        let qs = 0.7 * m.mu_p();
        let ds = m.loading_shift(qs).unwrap();
        // Unloading starts at the turning point and ends at its mirror image.
        assert!((m.unloading_shift(qs, qs).unwrap() - ds).abs() < 1e-18);
        assert!((m.unloading_shift(qs, -qs).unwrap() + ds).abs() < 1e-18);
        assert!((m.reloading_shift(qs, qs).unwrap() - ds).abs() < 1e-18);
        // Masing: the unloading branch is the loading curve scaled by 2 about the turning point.
        let q = 0.1 * m.mu_p();
        let masing = ds - 2.0 * m.loading_shift((qs - q) / 2.0).unwrap();
        assert!((m.unloading_shift(qs, q).unwrap() - masing).abs() < 1e-18);
        // Unloading stiffness at the turning point is the initial stiffness again.
        let dq = 1e-6 * m.mu_p();
        let k = dq / (ds - m.unloading_shift(qs, qs - dq).unwrap());
        assert!((k / m.stiffness() - 1.0).abs() < 1e-5);
    }

    #[test]
    fn sphere_pair_versus_sphere_plane() {
        let steel = Elastic::from_young(210e9, 0.3).unwrap();
        let pair = Pair::same(steel);
        let a = Mindlin::sphere_pair(0.01, 0.01, &pair, 100.0, 0.3).unwrap();
        let b = Mindlin::sphere_plane(0.01, &pair, 100.0, 0.3).unwrap();
        // Same G*, R* halves for the pair: a scales as R*^(1/3).
        assert!((a.a() / b.a() - 0.5f64.cbrt()).abs() < 1e-12);
        assert!((a.stiffness() / b.stiffness() - 0.5f64.cbrt()).abs() < 1e-12);
    }
}
