//! Elastic and frictional properties of one body ([`Material`]), the surface shape at a contact
//! ([`Surface`]) and the combined properties of a contacting pair ([`PairMaterial`]).

use crate::error::{LawError, finite_non_negative, non_negative, positive};
use crate::kalker;

/// Elastic and frictional properties of one body. Construct with [`Material::new`], which
/// validates every field.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    g: f64,
    nu: f64,
    mu: f64,
    density: f64,
}

impl Material {
    /// A validated material.
    ///
    /// * `shear_modulus` — G \[Pa\], finite and > 0;
    /// * `poisson_ratio` — nu [-], in (-1, 0.5] (0.5: incompressible);
    /// * `friction` — Coulomb coefficient mu [-], >= 0; `f64::INFINITY` means no slip ever;
    /// * `density` — rho [kg/m^3], finite and >= 0 (0 for massless walls; the Rayleigh time step
    ///   of a massless body is 0).
    pub fn new(
        shear_modulus: f64,
        poisson_ratio: f64,
        friction: f64,
        density: f64,
    ) -> Result<Self, LawError> {
        let g = positive("shear modulus G", shear_modulus, "Pa")?;
        if !(poisson_ratio > -1.0 && poisson_ratio <= 0.5) {
            return Err(LawError::PoissonRatio(poisson_ratio));
        }
        let mu = non_negative("friction coefficient mu", friction, "-")?;
        let density = finite_non_negative("density", density, "kg/m^3")?;
        Ok(Self {
            g,
            nu: poisson_ratio,
            mu,
            density,
        })
    }

    /// Structural steel: G = 79.3 GPa, nu = 0.29, mu = 0.3, rho = 7850 kg/m^3.
    pub fn steel() -> Self {
        Self {
            g: 79.3e9,
            nu: 0.29,
            mu: 0.3,
            density: 7850.0,
        }
    }

    /// Soda-lime glass (ballotini, the talk's DEM material class): G = 29 GPa, nu = 0.23,
    /// mu = 0.5, rho = 2500 kg/m^3.
    pub fn glass() -> Self {
        Self {
            g: 29e9,
            nu: 0.23,
            mu: 0.5,
            density: 2500.0,
        }
    }

    /// Soft rubber: G = 1 MPa, nu = 0.49, mu = 0.9, rho = 1100 kg/m^3.
    pub fn rubber() -> Self {
        Self {
            g: 1e6,
            nu: 0.49,
            mu: 0.9,
            density: 1100.0,
        }
    }

    /// Shear modulus G \[Pa\].
    pub fn shear_modulus(&self) -> f64 {
        self.g
    }
    /// Poisson ratio nu [-].
    pub fn poisson_ratio(&self) -> f64 {
        self.nu
    }
    /// Friction coefficient mu [-].
    pub fn friction(&self) -> f64 {
        self.mu
    }
    /// Density rho [kg/m^3].
    pub fn density(&self) -> f64 {
        self.density
    }
    /// Young's modulus E = 2 G (1 + nu) \[Pa\] (isotropic elasticity).
    pub fn young_modulus(&self) -> f64 {
        2.0 * self.g * (1.0 + self.nu)
    }
    /// This material with another friction coefficient (validated as in [`Material::new`]).
    pub fn with_friction(self, friction: f64) -> Result<Self, LawError> {
        Self::new(self.g, self.nu, friction, self.density)
    }
}

/// The shape of a body's surface at a contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Surface {
    /// A sphere of the given radius \[m\] (finite, > 0).
    Sphere(f64),
    /// A plane (infinite radius of curvature).
    Plane,
}

impl Surface {
    /// Radius of curvature \[m\]; `f64::INFINITY` for a plane.
    #[inline]
    pub fn radius(self) -> f64 {
        match self {
            Surface::Sphere(r) => r,
            Surface::Plane => f64::INFINITY,
        }
    }
    /// Curvature 1/R [1/m]; 0 for a plane.
    #[inline]
    pub fn curvature(self) -> f64 {
        match self {
            Surface::Sphere(r) => 1.0 / r,
            Surface::Plane => 0.0,
        }
    }
    fn validate(self) -> Result<Self, LawError> {
        match self {
            Surface::Sphere(r) if !(r.is_finite() && r > 0.0) => Err(LawError::Radius(r)),
            s => Ok(s),
        }
    }
}

/// How the pair's friction coefficient is made from the two bodies' (Rapier's
/// `CoefficientCombineRule`, whose default is `Average`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FrictionCombine {
    /// (mu_p + mu_q) / 2.
    #[default]
    Average,
    /// min(mu_p, mu_q).
    Min,
    /// mu_p mu_q.
    Multiply,
    /// max(mu_p, mu_q).
    Max,
}

impl FrictionCombine {
    /// Combines two friction coefficients.
    pub fn combine(self, a: f64, b: f64) -> f64 {
        match self {
            FrictionCombine::Average => 0.5 * (a + b),
            FrictionCombine::Min => a.min(b),
            FrictionCombine::Multiply => a * b,
            FrictionCombine::Max => a.max(b),
        }
    }
}

/// Combined properties of a contacting pair p, q (p is Rapier's collider1).
///
/// * Hertz (Johnson 1985, *Contact Mechanics*, §4.2): `1/R* = 1/R_p + 1/R_q`,
///   `1/E* = (1 - nu_p^2)/E_p + (1 - nu_q^2)/E_q`.
/// * Mindlin (1949; Johnson 1985, ch. 7; generalised to two dissimilar bodies as DEM codes do):
///   `1/G* = (2 - nu_p)/G_p + (2 - nu_q)/G_q`, so the initial tangential stiffness is `8 G* a`.
/// * Kalker's combined modulus and Poisson ratio for quasi-identical bodies (Kalker 1990,
///   *Three-dimensional elastic bodies in rolling contact*): `2/G = 1/G_p + 1/G_q`,
///   `nu = (G/2) (nu_p/G_p + nu_q/G_q)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairMaterial {
    /// Effective radius R* \[m\] (finite: two planes are rejected).
    pub r_star: f64,
    /// Effective Young's modulus E* \[Pa\].
    pub e_star: f64,
    /// Mindlin's effective shear modulus G* \[Pa\].
    pub g_star: f64,
    /// Kalker's combined shear modulus G \[Pa\].
    pub g: f64,
    /// Kalker's combined Poisson ratio nu [-].
    pub nu: f64,
    /// Friction coefficient of the pair mu [-] (may be `+inf`: no slip).
    pub mu: f64,
    /// Kalker's `C11(nu)` for circular contact at the combined nu [-] (cached).
    pub c11: f64,
    /// Surface of body p.
    pub surface_p: Surface,
    /// Surface of body q.
    pub surface_q: Surface,
}

impl PairMaterial {
    /// Combines two materials and surfaces; the pair's friction is the `Average` of the two.
    pub fn new(
        p: &Material,
        q: &Material,
        surface_p: Surface,
        surface_q: Surface,
    ) -> Result<Self, LawError> {
        Self::with_rule(p, q, surface_p, surface_q, FrictionCombine::Average)
    }

    /// Combines two materials and surfaces with the given friction rule.
    pub fn with_rule(
        p: &Material,
        q: &Material,
        surface_p: Surface,
        surface_q: Surface,
        rule: FrictionCombine,
    ) -> Result<Self, LawError> {
        let surface_p = surface_p.validate()?;
        let surface_q = surface_q.validate()?;
        let curvature = surface_p.curvature() + surface_q.curvature();
        if curvature <= 0.0 {
            return Err(LawError::TwoPlanes);
        }
        let r_star = 1.0 / curvature;
        let e_star = 1.0
            / ((1.0 - p.nu * p.nu) / p.young_modulus() + (1.0 - q.nu * q.nu) / q.young_modulus());
        let g_star = 1.0 / ((2.0 - p.nu) / p.g + (2.0 - q.nu) / q.g);
        let g = 2.0 / (1.0 / p.g + 1.0 / q.g);
        let nu = 0.5 * g * (p.nu / p.g + q.nu / q.g);
        let mu = rule.combine(p.mu, q.mu);
        if mu.is_nan() {
            return Err(LawError::Negative {
                name: "combined friction mu",
                value: mu,
                unit: "-",
            });
        }
        Ok(Self {
            r_star,
            e_star,
            g_star,
            g,
            nu,
            mu,
            c11: kalker::c11(nu),
            surface_p,
            surface_q,
        })
    }

    /// This pair with another friction coefficient mu [-] (>= 0, may be `+inf`).
    pub fn with_friction(mut self, mu: f64) -> Result<Self, LawError> {
        self.mu = non_negative("friction coefficient mu", mu, "-")?;
        Ok(self)
    }

    /// Initial Cattaneo-Mindlin tangential stiffness `k_t = 8 G* a` [N/m] at contact radius `a` \[m\]
    /// (Mindlin 1949).
    #[inline]
    pub fn tangential_stiffness(&self, a: f64) -> f64 {
        8.0 * self.g_star * a
    }
}

/// The test fixture of the crate's unit tests: a 10 mm steel sphere on a steel plane.
#[cfg(test)]
pub(crate) fn steel_ball_on_plane() -> PairMaterial {
    let m = Material::steel();
    PairMaterial::new(&m, &m, Surface::Sphere(0.01), Surface::Plane).expect("valid fixture")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_inputs() {
        assert!(Material::new(0.0, 0.3, 0.5, 1.0).is_err());
        assert!(Material::new(-1.0, 0.3, 0.5, 1.0).is_err());
        assert!(Material::new(f64::NAN, 0.3, 0.5, 1.0).is_err());
        assert!(Material::new(f64::INFINITY, 0.3, 0.5, 1.0).is_err());
        assert!(Material::new(1e9, 0.51, 0.5, 1.0).is_err());
        assert!(Material::new(1e9, -1.0, 0.5, 1.0).is_err());
        assert!(Material::new(1e9, f64::NAN, 0.5, 1.0).is_err());
        assert!(Material::new(1e9, 0.3, -0.1, 1.0).is_err());
        assert!(Material::new(1e9, 0.3, f64::NAN, 1.0).is_err());
        assert!(Material::new(1e9, 0.3, 0.5, -1.0).is_err());
        assert!(Material::new(1e9, 0.3, 0.5, f64::INFINITY).is_err());
        assert!(Material::new(1e9, 0.5, f64::INFINITY, 0.0).is_ok());
        let m = Material::steel();
        assert!(
            PairMaterial::new(&m, &m, Surface::Plane, Surface::Plane) == Err(LawError::TwoPlanes)
        );
        assert!(PairMaterial::new(&m, &m, Surface::Sphere(0.0), Surface::Plane).is_err());
        assert!(PairMaterial::new(&m, &m, Surface::Sphere(f64::NAN), Surface::Plane).is_err());
    }

    #[test]
    fn identical_bodies_combine_as_textbook() {
        let m = Material::new(80e9, 0.3, 0.4, 7800.0).unwrap();
        let e = m.young_modulus();
        let pair = PairMaterial::new(&m, &m, Surface::Sphere(0.01), Surface::Sphere(0.01)).unwrap();
        assert!((pair.r_star - 0.005).abs() < 1e-15);
        assert!((pair.e_star - e / (2.0 * (1.0 - 0.09))).abs() / e < 1e-14);
        assert!((pair.g_star - 80e9 / (2.0 * 1.7)).abs() / 80e9 < 1e-14);
        assert!((pair.g - 80e9).abs() < 1e-3 && (pair.nu - 0.3).abs() < 1e-14);
        assert!((pair.mu - 0.4).abs() < 1e-15);
        let plane = PairMaterial::new(&m, &m, Surface::Plane, Surface::Sphere(0.01)).unwrap();
        assert!((plane.r_star - 0.01).abs() < 1e-15);
    }

    #[test]
    fn kalker_combination_is_harmonic() {
        let p = Material::new(1e9, 0.5, 0.3, 1.0).unwrap();
        let q = Material::new(3e9, 0.0, 0.3, 1.0).unwrap();
        let pair = PairMaterial::new(&p, &q, Surface::Sphere(1.0), Surface::Plane).unwrap();
        assert!((pair.g - 1.5e9).abs() < 1e-3);
        assert!((pair.nu - 0.5 * 1.5e9 * (0.5 / 1e9)).abs() < 1e-14);
        assert!((pair.c11 - kalker::c11(pair.nu)).abs() < 1e-15);
    }

    #[test]
    fn friction_rules() {
        assert_eq!(
            FrictionCombine::Average.combine(0.2, 0.4),
            0.30000000000000004
        );
        assert_eq!(FrictionCombine::Min.combine(0.2, 0.4), 0.2);
        assert_eq!(FrictionCombine::Max.combine(0.2, 0.4), 0.4);
        assert!((FrictionCombine::Multiply.combine(0.2, 0.4) - 0.08).abs() < 1e-16);
    }
}
