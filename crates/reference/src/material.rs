//! Elastic constants of one body and of a contacting pair (combined constants in the senses of
//! Hertz, Mindlin and Kalker).

use crate::error::{RefError, check_positive, check_range};

/// Isotropic linear elastic constants of one body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Elastic {
    g: f64,
    nu: f64,
}

impl Elastic {
    /// Shear modulus `g` \[Pa\] (finite, > 0) and Poisson ratio `nu` (in `[0, 0.5]`).
    pub fn new(g: f64, nu: f64) -> Result<Self, RefError> {
        Ok(Elastic {
            g: check_positive("g", g)?,
            nu: check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?,
        })
    }

    /// From Young's modulus `e` \[Pa\] (finite, > 0) and Poisson ratio `nu` (in `[0, 0.5]`):
    /// `G = E / (2 (1 + nu))`.
    pub fn from_young(e: f64, nu: f64) -> Result<Self, RefError> {
        let nu = check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?;
        Self::new(check_positive("e", e)? / (2.0 * (1.0 + nu)), nu)
    }

    /// Shear modulus `G` \[Pa\].
    pub fn g(&self) -> f64 {
        self.g
    }
    /// Poisson ratio `nu`.
    pub fn nu(&self) -> f64 {
        self.nu
    }
    /// Young's modulus `E = 2 G (1 + nu)` \[Pa\].
    pub fn e(&self) -> f64 {
        2.0 * self.g * (1.0 + self.nu)
    }
}

/// The elastic constants of a contacting pair of bodies p and q.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    /// Body p.
    pub p: Elastic,
    /// Body q.
    pub q: Elastic,
}

impl Pair {
    /// A pair of two bodies.
    pub fn new(p: Elastic, q: Elastic) -> Self {
        Pair { p, q }
    }

    /// Two bodies of the same material.
    pub fn same(m: Elastic) -> Self {
        Pair { p: m, q: m }
    }

    /// Hertz's contact modulus `E*` \[Pa\]: `1/E* = (1 - nu_p^2)/E_p + (1 - nu_q^2)/E_q`
    /// (Johnson 1985, *Contact Mechanics*, eq. 4.22; docs/ARCHITECTURE.md §4).
    pub fn e_star(&self) -> f64 {
        let c = |m: &Elastic| (1.0 - m.nu * m.nu) / m.e();
        1.0 / (c(&self.p) + c(&self.q))
    }

    /// Mindlin's tangential modulus `G*` \[Pa\]: `1/G* = (2 - nu_p)/G_p + (2 - nu_q)/G_q`, so that
    /// the initial tangential stiffness is `8 G* a` (Mindlin 1949, "Compliance of elastic bodies in
    /// contact", J. Appl. Mech. 16; Johnson 1985, §7.2; docs/ARCHITECTURE.md §4).
    pub fn g_star(&self) -> f64 {
        let c = |m: &Elastic| (2.0 - m.nu) / m.g;
        1.0 / (c(&self.p) + c(&self.q))
    }

    /// Kalker's combined shear modulus `G` \[Pa\]: `2/G = 1/G_p + 1/G_q` (Kalker 1990,
    /// *Three-dimensional elastic bodies in rolling contact*, §1.5).
    pub fn kalker_g(&self) -> f64 {
        2.0 / (1.0 / self.p.g + 1.0 / self.q.g)
    }

    /// Kalker's combined Poisson ratio: `nu = G/2 (nu_p/G_p + nu_q/G_q)` (Kalker 1990, §1.5).
    pub fn kalker_nu(&self) -> f64 {
        0.5 * self.kalker_g() * (self.p.nu / self.p.g + self.q.nu / self.q.g)
    }

    /// Dundurs' second constant `beta` times 2, up to a positive factor: the bodies are
    /// quasi-identical (normal and tangential problems uncoupled) when
    /// `(1 - 2 nu_p)/G_p = (1 - 2 nu_q)/G_q` (Kalker 1990, §1.5; Johnson 1985, §5.9). Returns
    /// `|(1 - 2 nu_p)/G_p - (1 - 2 nu_q)/G_q| / ((1 - 2 nu_p)/G_p + (1 - 2 nu_q)/G_q)`, 0 when
    /// both are incompressible.
    pub fn coupling(&self) -> f64 {
        let c = |m: &Elastic| (1.0 - 2.0 * m.nu) / m.g;
        let s = c(&self.p) + c(&self.q);
        if s > 0.0 {
            (c(&self.p) - c(&self.q)).abs() / s
        } else {
            0.0
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_material_combinations() {
        let m = Elastic::from_young(210e9, 0.3).unwrap();
        let pair = Pair::same(m);
        // Same material: Kalker's G, nu are the material's; E* = E / (2 (1 - nu^2));
        // G* = G / (2 (2 - nu)).
        assert!((pair.kalker_g() / m.g() - 1.0).abs() < 1e-14);
        assert!((pair.kalker_nu() - 0.3).abs() < 1e-14);
        assert!((pair.e_star() / (210e9 / (2.0 * 0.91)) - 1.0).abs() < 1e-14);
        assert!((pair.g_star() / (m.g() / (2.0 * 1.7)) - 1.0).abs() < 1e-14);
        assert_eq!(pair.coupling(), 0.0);
    }

    #[test]
    fn g_star_in_kalker_constants() {
        // 1/G* = sum (2 - nu_i)/G_i = 2 (2 - nu)/G with Kalker's combined G and nu, exactly.
        let pair = Pair::new(
            Elastic::new(80e9, 0.3).unwrap(),
            Elastic::new(30e9, 0.2).unwrap(),
        );
        let expect = pair.kalker_g() / (2.0 * (2.0 - pair.kalker_nu()));
        assert!((pair.g_star() / expect - 1.0).abs() < 1e-14);
        assert!(pair.coupling() > 0.0);
    }

    #[test]
    fn rejects_bad_constants() {
        assert!(Elastic::new(0.0, 0.3).is_err());
        assert!(Elastic::new(1e9, 0.7).is_err());
        assert!(Elastic::from_young(f64::NAN, 0.3).is_err());
    }
}
