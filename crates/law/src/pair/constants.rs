//! Per-pair constants (built once per pair of materials), the bodies and the geometry of a contact.

use super::damping_coefficient;
use crate::LawError;
use crate::material::{Material, PairMaterial, Surface};
use crate::rolling_torque::RollingModel;
use crate::steady_law::{CreepModel, SteadyLaw};
use crate::vector::Vec3;

/// Constants of a pair of materials, computed once (radius-independent: the effective radius
/// `R*` and the reduced mass `m*` come from the two bodies at each call).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairConstants {
    /// Combined moduli `E*`, `G*`, Kalker's `G`, `nu`, `C11` and the friction `mu`; its `r_star`
    /// and surfaces are replaced per contact ([`PairConstants::pair_material`]).
    pub(super) material: PairMaterial,
    /// Tsuji damping coefficient `alpha` [-] ([`damping_coefficient`] of the restitution).
    pub(super) alpha: f64,
    /// Creep term's steady law (Kuhn's: Kalker's `F_ss`), or `None` for plain Coulomb-Mindlin.
    pub(super) creep: Option<CreepModel>,
    /// The steady law's coefficients for `creep` (Kuhn's `C11`, or the fitted law's).
    pub(super) steady: SteadyLaw,
    /// Optional contact-torque rolling resistance.
    pub(super) rolling: Option<RollingModel>,
}

impl PairConstants {
    /// The constants of materials `p` and `q` with the pair's friction `mu` [-] (>= 0, may be
    /// `+inf`), restitution `e` [-] in `[MIN_RESTITUTION, 1]`, creep model (`None`: no creep)
    /// and rolling resistance.
    pub fn new(
        p: &Material,
        q: &Material,
        mu: f64,
        restitution: f64,
        creep: Option<CreepModel>,
        rolling: Option<RollingModel>,
    ) -> Result<Self, LawError> {
        let material = PairMaterial::new(p, q, Surface::Sphere(1.0), Surface::Sphere(1.0))?
            .with_friction(mu)?;
        let alpha = damping_coefficient(restitution)?;
        Self::from_parts(&material, alpha, creep, rolling)
    }

    /// The constants from an already combined pair (its `r_star` and surfaces are ignored) and
    /// a damping coefficient `alpha` [-] (finite, >= 0; e.g. cached by the host).
    pub fn from_parts(
        material: &PairMaterial,
        alpha: f64,
        creep: Option<CreepModel>,
        rolling: Option<RollingModel>,
    ) -> Result<Self, LawError> {
        if !(alpha.is_finite() && alpha >= 0.0) {
            return Err(LawError::Negative {
                name: "damping coefficient alpha",
                value: alpha,
                unit: "-",
            });
        }
        let model = creep.unwrap_or(CreepModel::Kuhn);
        Ok(Self {
            material: *material,
            alpha,
            creep,
            steady: SteadyLaw::with_c11(model, material.nu, material.c11),
            rolling,
        })
    }

    /// Friction coefficient `mu` [-].
    #[inline]
    pub fn mu(&self) -> f64 {
        self.material.mu
    }
    /// Damping coefficient `alpha` [-].
    #[inline]
    pub fn alpha(&self) -> f64 {
        self.alpha
    }
    /// The creep model, `None` without creep.
    #[inline]
    pub fn creep(&self) -> Option<CreepModel> {
        self.creep
    }
    /// The rolling resistance model.
    #[inline]
    pub fn rolling(&self) -> Option<RollingModel> {
        self.rolling
    }

    /// The pair material of a contact between surfaces `sp` and `sq`: the combined moduli with
    /// `1/R* = 1/R_p + 1/R_q` (Johnson 1985, §4.2; infinite for two planes, which the kernel
    /// treats as no contact). Radii must be finite and > 0 (hosts validate them once).
    #[inline]
    pub fn pair_material(&self, sp: Surface, sq: Surface) -> PairMaterial {
        // `R_p R_q / (R_p + R_q)`: one division where `1/(1/R_p + 1/R_q)` takes three.
        let r_star = match (sp, sq) {
            (Surface::Sphere(rp), Surface::Sphere(rq)) => rp * rq / (rp + rq),
            (Surface::Sphere(r), Surface::Plane) | (Surface::Plane, Surface::Sphere(r)) => r,
            (Surface::Plane, Surface::Plane) => f64::INFINITY,
        };
        PairMaterial {
            r_star,
            surface_p: sp,
            surface_q: sq,
            ..self.material
        }
    }
}

/// One body of a pair: its motion, surface and mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairBody {
    /// Centre (of mass; of a sphere, its centre; of a wall, any point) \[m\].
    pub position: Vec3,
    /// Velocity of the centre [m/s].
    pub velocity: Vec3,
    /// Angular velocity [rad/s].
    pub angular_velocity: Vec3,
    /// Surface at the contact.
    pub surface: Surface,
    /// Mass \[kg\]; `f64::INFINITY` for a wall or any body the contact cannot move.
    pub mass: f64,
}

impl PairBody {
    /// Whether the contact can move the body (finite mass > 0).
    #[inline]
    fn movable(&self) -> bool {
        self.mass > 0.0 && super::kernel::finite(self.mass)
    }

    /// The reduced mass `m* = 1/(1/m_p + 1/m_q)` \[kg\] of a pair, an immovable body counting
    /// as `1/m = 0`; `None` when neither can move. Evaluated as `m_p m_q/(m_p + m_q)`: one
    /// division where the reciprocals take three.
    #[inline]
    pub(super) fn reduced_mass(p: &PairBody, q: &PairBody) -> Option<f64> {
        match (p.movable(), q.movable()) {
            (true, true) => Some(p.mass * q.mass / (p.mass + q.mass)),
            (true, false) => Some(p.mass),
            (false, true) => Some(q.mass),
            (false, false) => None,
        }
    }
}

/// Where and how deep two surfaces touch.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactGeometry {
    /// Unit normal from body p to body q [-].
    pub normal: Vec3,
    /// Contact point: the middle of the overlap along the normal \[m\].
    pub point: Vec3,
    /// Overlap `delta` \[m\]; <= 0 when apart.
    pub overlap: f64,
}

impl ContactGeometry {
    /// Sphere p (centre `xp`, radius `rp` \[m\]) and sphere q: `n = (x_q - x_p)/|x_q - x_p|`,
    /// `delta = r_p + r_q - |x_q - x_p|`, point at `x_p + n (r_p - delta/2)`. `None` for
    /// coincident centres.
    #[inline]
    pub fn sphere_sphere(xp: Vec3, rp: f64, xq: Vec3, rq: f64) -> Option<Self> {
        let d = xq - xp;
        let dist = d.length();
        if !(dist > f64::MIN_POSITIVE && super::kernel::finite(dist)) {
            return None;
        }
        let normal = d * (1.0 / dist);
        let overlap = rp + rq - dist;
        Some(Self {
            normal,
            point: xp + normal * (rp - 0.5 * overlap),
            overlap,
        })
    }

    /// Plane p (a point `x0` on it, outward unit normal `n`) and sphere q (centre `xq`, radius
    /// `rq` \[m\]): `delta = r_q - (x_q - x0) . n`, point half the overlap below the plane's
    /// point under the centre.
    #[inline]
    pub fn plane_sphere(x0: Vec3, n: Vec3, xq: Vec3, rq: f64) -> Self {
        let dist = (xq - x0).dot(n);
        let overlap = rq - dist;
        let closest = xq - n * dist;
        Self {
            normal: n,
            point: closest - n * (0.5 * overlap),
            overlap,
        }
    }
}
