//! The pure pair-force kernel of the soft-sphere (DEM) hosts: one function,
//! [`pair_force`], that takes the two bodies' state, the pair's constants, the contact's history
//! and the time step, and returns the force and torques, updating the history in place and
//! reporting the energy terms. The compliant regime of creep-rapier and the creep-dem engine
//! both call it, so their forces on the same configuration agree to rounding; a LAMMPS pair
//! style can call it through a C ABI (the history is a flat `[f64]`, see
//! [`ContactHistory::write`] / [`ContactHistory::read`]).
//!
//! # The law (all in f64)
//! Bodies p and q, unit normal `n` from p to q, overlap `delta`, contact point `c` in the middle
//! of the overlap (DESIGN §2 conventions: `Q` is the tangential force on p from q).
//! * Normal: Hertz `P_e = (4/3) E* sqrt(R*) delta^(3/2)` (Johnson 1985, §4.2) plus the damping of
//!   Tsuji, Tanaka & Ishida (1992), `alpha sqrt(m* k_H) delta^(1/4) delta_dot`, with `alpha`
//!   chosen so that the impact rebounds with the pair's restitution `e` exactly
//!   ([`damping::damping_coefficient`]); the total is never attractive (`P >= 0`).
//! * Tangential: a [`TangentialLaw`], a generic parameter (monomorphised, no dynamic dispatch per
//!   contact):
//!   - [`Exact`]: Cattaneo-Mindlin with load-history memory and Kuhn's (2011) creep term,
//!     creep-law's [`CreepState`] (the compliant regime's physics);
//!   - [`Cheap`]: an incremental no-slip spring of Mindlin's initial stiffness `k_t = 8 G* a`
//!     (Mindlin 1949), scaled back onto the Coulomb limit `mu P_e` when the trial force exceeds
//!     it (LAMMPS' `granular` `tangential mindlin/force`), with the same creep term
//!     `F_ss(|Q|/(mu P)) Q/|Q| |du_roll|` subtracted from the displacement.
//!
//!   Both are fed `du_disp = v_disp dt` and `du_roll = v_roll dt` (Kuhn & Bagi 2004 rates,
//!   [`contact_rates`](crate::kinematics::contact_rates)) at the contact radius `a = sqrt(R* delta)`; without creep
//!   ([`PairConstants::creep`] `None`) no rolling displacement is fed: plain Coulomb-Mindlin.
//! * The tangential history lives in a tangent basis `(t1, t2)` carried by the contact: each
//!   step the basis turns with the normal (the smallest rotation taking the last normal to the
//!   new one) and about the normal with the pair's mean spin `(w_p + w_q) . n / 2`, then is
//!   re-orthonormalised, so the stored 2-D force follows the contact as a rigid body.
//! * Optional contact-torque rolling resistance (creep-law [`rolling_torque`]).
//!
//! # Energy bookkeeping
//! [`PairForces::dissipation`] holds the step's dissipated energies (damping, slip, creep,
//! rolling) and the truncation energy; the stored energies are
//! [`ContactHistory::elastic_energy`]. Balance over a run: work of the contact forces = change
//! of the stored energy + dissipation - truncation (as creep-rapier's `CompliantEnergy`).
//!
//! [`rolling_torque`]: crate::rolling_torque

pub mod damping;

use crate::LawError;
use crate::creep::{CreepInput, CreepLaw, CreepState};
use crate::hertz;
use crate::kinematics::{BodyMotion, ContactRates, contact_rates_and_approach};
use crate::material::{Material, PairMaterial, Surface};
use crate::mindlin::{MINDLIN_FLAT_LEN, MindlinState};
use crate::rolling_torque::{RollingInput, RollingModel, RollingState, epsd_rolling_inertia};
use crate::steady_law::{CreepModel, SteadyLaw};
use crate::vector::{Vec2, Vec3};

pub use damping::{MIN_RESTITUTION, damping_coefficient};

/// Constants of a pair of materials, computed once (radius-independent: the effective radius
/// `R*` and the reduced mass `m*` come from the two bodies at each call).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairConstants {
    /// Combined moduli `E*`, `G*`, Kalker's `G`, `nu`, `C11` and the friction `mu`; its `r_star`
    /// and surfaces are replaced per contact ([`PairConstants::pair_material`]).
    material: PairMaterial,
    /// Tsuji damping coefficient `alpha` [-] ([`damping_coefficient`] of the restitution).
    alpha: f64,
    /// Creep term's steady law (Kuhn's: Kalker's `F_ss`), or `None` for plain Coulomb-Mindlin.
    creep: Option<CreepModel>,
    /// The steady law's coefficients for `creep` (Kuhn's `C11`, or the fitted law's).
    steady: SteadyLaw,
    /// Optional contact-torque rolling resistance.
    rolling: Option<RollingModel>,
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
        PairMaterial {
            r_star: 1.0 / (sp.curvature() + sq.curvature()),
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
    /// `1/m` [1/kg], 0 for an immovable body.
    #[inline]
    fn inv_mass(&self) -> f64 {
        if self.mass > 0.0 && self.mass.is_finite() {
            1.0 / self.mass
        } else {
            0.0
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
        if !(dist.is_finite() && dist > f64::MIN_POSITIVE) {
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

/// What one tangential update did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TangentialStep {
    /// Tangential force on p from q after the step, in the contact's `(t1, t2)` \[N\].
    pub q: Vec2,
    /// Creep displacement of the step \[m\].
    pub creep_displacement: Vec2,
    /// Energy dissipated by micro-slip and gross slip \[J\].
    pub slip: f64,
    /// Energy dissipated by creep \[J\].
    pub creep: f64,
    /// Energy added by the model's simplifications \[J\] (see each tier).
    pub truncation: f64,
}

/// A tangential contact law: the generic parameter of [`pair_force`].
pub trait TangentialLaw:
    Copy + Clone + Default + std::fmt::Debug + PartialEq + Send + Sync + 'static
{
    /// Per-contact history of the law (flat, `Copy`, all f64).
    type History: Copy + Clone + Default + std::fmt::Debug + PartialEq + Send + Sync;
    /// Name of the tier (`"exact"` or `"cheap"`).
    const NAME: &'static str;
    /// Number of `f64` of the flat history.
    const HISTORY_LEN: usize;
    /// Whether the tier implements the creep model (the cheap tier has no lag state).
    fn supports(model: Option<CreepModel>) -> bool;
    /// One step: elastic normal force `p` \[N\], contact radius `a` \[m\], displacements `du_disp`,
    /// `du_roll` \[m\] in the tangent basis (`du_roll` zero without creep).
    fn step(
        h: &mut Self::History,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep;
    /// The stored tangential force \[N\].
    fn force(h: &Self::History) -> Vec2;
    /// Elastic energy stored in the tangential spring(s) \[J\].
    fn elastic_energy(h: &Self::History, pm: &PairMaterial) -> f64;
    /// Writes the history into `out` (length [`TangentialLaw::HISTORY_LEN`]).
    fn write(h: &Self::History, out: &mut [f64]);
    /// Reads a history written by [`TangentialLaw::write`].
    fn read(v: &[f64]) -> Result<Self::History, LawError>;
}

/// Cattaneo-Mindlin with load-history memory (Popov & Heß's method of dimensionality reduction,
/// creep-law [`MindlinState`]) and Kuhn's (2011) creep term ([`CreepState`]): the exact tier.
/// `truncation` is [`crate::CreepStep::truncation_energy`] (>= 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Exact;

impl TangentialLaw for Exact {
    type History = CreepState;
    const NAME: &'static str = "exact";
    const HISTORY_LEN: usize = MINDLIN_FLAT_LEN + 4;

    #[inline]
    fn supports(_: Option<CreepModel>) -> bool {
        true
    }

    #[inline]
    fn step(
        h: &mut CreepState,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep {
        // The one call into CreepState.
        let model = c.creep.unwrap_or(CreepModel::Kuhn);
        let law = CreepLaw::from_parts(*pm, model, c.steady);
        let s = h.update(&law, CreepInput::new(p, du_disp, du_roll).with_radius(a));
        TangentialStep {
            q: s.q,
            creep_displacement: s.creep_displacement,
            slip: s.slip_dissipation,
            creep: s.creep_dissipation,
            truncation: s.truncation_energy,
        }
    }

    #[inline]
    fn force(h: &CreepState) -> Vec2 {
        h.force()
    }

    fn elastic_energy(h: &CreepState, pm: &PairMaterial) -> f64 {
        h.mindlin().elastic_energy(pm)
    }

    fn write(h: &CreepState, out: &mut [f64]) {
        out[..MINDLIN_FLAT_LEN].copy_from_slice(&h.mindlin().to_array());
        let [l0, l1] = h.lag();
        out[MINDLIN_FLAT_LEN..MINDLIN_FLAT_LEN + 4].copy_from_slice(&[l0.x, l0.y, l1.x, l1.y]);
    }

    fn read(v: &[f64]) -> Result<CreepState, LawError> {
        let mut m = [0.0; MINDLIN_FLAT_LEN];
        m.copy_from_slice(&v[..MINDLIN_FLAT_LEN]);
        let mindlin = MindlinState::from_array(&m)?;
        let l = &v[MINDLIN_FLAT_LEN..MINDLIN_FLAT_LEN + 4];
        if !l.iter().all(|x| x.is_finite()) {
            return Err(LawError::OutOfRange {
                name: "creep lag state",
                value: f64::NAN,
                range: "finite",
            });
        }
        Ok(CreepState::from_parts(
            mindlin,
            [Vec2::new(l[0], l[1]), Vec2::new(l[2], l[3])],
        ))
    }
}

/// History of the [`Cheap`] tier.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CheapHistory {
    /// Tangential force on p from q \[N\], in the contact's `(t1, t2)`.
    pub q: Vec2,
    /// Spring stiffness `8 G* a` of the last step [N/m] (0: virgin).
    pub k: f64,
}

/// The cheap tier: an incremental no-slip spring of Mindlin's (1949) initial stiffness
/// `k_t = 8 G* a`, `Q += k_t du_eff`, scaled back onto `mu P_e` when it exceeds it (LAMMPS
/// `granular` `tangential mindlin/force`, Thornton et al. 2013's incremental form), with Kuhn's
/// creep term `du_eff = du_disp - F_ss(|Q|/(mu P)) Q/|Q| |du_roll|` (the explicit creep step is
/// capped at `|Q|/k_t`, the displacement that unloads the linear spring to zero, so creep relaxes
/// a force and never reverses it). Stored energy `|Q|^2 / (2 k_t)`; slip dissipation
/// `Q . (du_eff - dQ/k_t)` (>= 0); `truncation` books the change of the stored energy when `k_t`
/// changes at fixed `Q`, `|Q|^2 (1/k_t - 1/k_t,old) / 2` (signed: positive when the contact
/// shrinks). Refuses [`CreepModel::FittedTransient`] (no lag state).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Cheap;

impl TangentialLaw for Cheap {
    type History = CheapHistory;
    const NAME: &'static str = "cheap";
    const HISTORY_LEN: usize = 3;

    #[inline]
    fn supports(model: Option<CreepModel>) -> bool {
        model != Some(CreepModel::FittedTransient)
    }

    #[inline]
    fn step(
        h: &mut CheapHistory,
        c: &PairConstants,
        pm: &PairMaterial,
        p: f64,
        a: f64,
        du_disp: Vec2,
        du_roll: Vec2,
    ) -> TangentialStep {
        if !(p > 0.0 && p.is_finite() && a > 0.0 && a.is_finite()) {
            let slip = Self::elastic_energy(h, pm);
            *h = CheapHistory::default();
            return TangentialStep {
                slip,
                ..TangentialStep::default()
            };
        }
        let k = pm.tangential_stiffness(a);
        let mu_p = pm.mu * p;
        let q_old = h.q;
        let q2 = q_old.length_squared();
        let truncation = if q2 > 0.0 && h.k > 0.0 {
            0.5 * q2 * (1.0 / k - 1.0 / h.k)
        } else {
            0.0
        };
        let roll = du_roll.length();
        let mut creep_vec = Vec2::ZERO;
        let mut creep_e = 0.0;
        if roll > 0.0 && roll.is_finite() && q2 > 0.0 {
            let q_abs = q2.sqrt();
            let f = c.steady.creepage_for_force(q_abs, mu_p, pm.g, a);
            let creep = (f * roll).min(q_abs / k);
            if creep.is_finite() && creep > 0.0 {
                creep_vec = q_old * (creep / q_abs);
                creep_e = q_abs * creep;
            }
        }
        let du_eff = if du_disp.is_finite() {
            du_disp - creep_vec
        } else {
            -creep_vec
        };
        let trial = q_old + du_eff * k;
        let t_abs = trial.length();
        let (q, slip) = if mu_p.is_finite() && t_abs > mu_p {
            let q = trial * (mu_p / t_abs);
            (q, q.dot(trial - q) / k)
        } else {
            (trial, 0.0)
        };
        h.q = q;
        h.k = k;
        TangentialStep {
            q,
            creep_displacement: creep_vec,
            slip,
            creep: creep_e,
            truncation,
        }
    }

    #[inline]
    fn force(h: &CheapHistory) -> Vec2 {
        h.q
    }

    #[inline]
    fn elastic_energy(h: &CheapHistory, _: &PairMaterial) -> f64 {
        if h.k > 0.0 {
            0.5 * h.q.length_squared() / h.k
        } else {
            0.0
        }
    }

    fn write(h: &CheapHistory, out: &mut [f64]) {
        out[..3].copy_from_slice(&[h.q.x, h.q.y, h.k]);
    }

    fn read(v: &[f64]) -> Result<CheapHistory, LawError> {
        if !(v[..3].iter().all(|x| x.is_finite()) && v[2] >= 0.0) {
            return Err(LawError::OutOfRange {
                name: "cheap tangential history",
                value: v[2],
                range: "finite, stiffness >= 0",
            });
        }
        Ok(CheapHistory {
            q: Vec2::new(v[0], v[1]),
            k: v[2],
        })
    }
}

/// The history of one contact: the tangential law's memory, the carried tangent basis, the
/// rolling spring and the last overlap. `Default` is a virgin contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactHistory<T: TangentialLaw> {
    /// The tangential law's memory (2-D vectors in `(t1, n x t1)`).
    pub tangential: T::History,
    /// First tangent of the carried basis [-] (zero: virgin).
    pub t1: Vec3,
    /// Unit normal of the last step [-] (zero: virgin).
    pub normal: Vec3,
    /// Contact-torque rolling spring (EPSD).
    pub rolling: RollingState,
    /// Overlap of the last step \[m\].
    pub overlap: f64,
}

impl<T: TangentialLaw> ContactHistory<T> {
    /// Number of `f64` of the flat form: `[t1 (3), normal (3), rolling spring (3), overlap,
    /// tangential history (T::HISTORY_LEN)]`.
    pub const LEN: usize = 10 + T::HISTORY_LEN;

    /// Whether the contact has never been stepped (or was reset).
    #[inline]
    pub fn is_virgin(&self) -> bool {
        self.normal == Vec3::ZERO
    }

    /// Writes the flat form into `out` (length [`ContactHistory::LEN`]).
    pub fn write(&self, out: &mut [f64]) -> Result<(), LawError> {
        if out.len() != Self::LEN {
            return Err(len_error(out.len()));
        }
        let s = self.rolling.spring;
        out[..10].copy_from_slice(&[
            self.t1.x,
            self.t1.y,
            self.t1.z,
            self.normal.x,
            self.normal.y,
            self.normal.z,
            s.x,
            s.y,
            s.z,
            self.overlap,
        ]);
        T::write(&self.tangential, &mut out[10..]);
        Ok(())
    }

    /// Reads the flat form written by [`ContactHistory::write`].
    pub fn read(v: &[f64]) -> Result<Self, LawError> {
        if v.len() != Self::LEN {
            return Err(len_error(v.len()));
        }
        if let Some(&bad) = v[..10].iter().find(|x| !x.is_finite()) {
            return Err(LawError::OutOfRange {
                name: "contact history entry",
                value: bad,
                range: "finite",
            });
        }
        Ok(Self {
            tangential: T::read(&v[10..])?,
            t1: Vec3::new(v[0], v[1], v[2]),
            normal: Vec3::new(v[3], v[4], v[5]),
            rolling: RollingState {
                spring: Vec3::new(v[6], v[7], v[8]),
            },
            overlap: v[9],
        })
    }

    /// Stored elastic energies `(normal, tangential)` \[J\] of the contact as of its last step,
    /// between surfaces `sp` and `sq` with constants `c`: Hertz's `(8/15) E* sqrt(R*)
    /// delta^(5/2)` and the tangential law's.
    pub fn elastic_energy(&self, c: &PairConstants, sp: Surface, sq: Surface) -> (f64, f64) {
        let pm = c.pair_material(sp, sq);
        (
            hertz::normal_energy(&pm, self.overlap),
            T::elastic_energy(&self.tangential, &pm),
        )
    }
}

fn len_error(len: usize) -> LawError {
    LawError::OutOfRange {
        name: "contact history buffer length",
        value: len as f64,
        range: "ContactHistory::LEN",
    }
}

/// Energies of one step of one contact \[J\].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairDissipation {
    /// Dissipated by the normal damping, `(P - P_e) delta_dot dt`.
    pub damping: f64,
    /// Dissipated by micro-slip and gross slip.
    pub slip: f64,
    /// Dissipated by creep.
    pub creep: f64,
    /// Dissipated by contact-torque rolling resistance.
    pub rolling: f64,
    /// Added by the tangential law's simplifications (see the tier).
    pub truncation: f64,
}

/// What [`pair_force`] returns. All zero (`touching == false`) for an open contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairForces {
    /// Whether the contact carries force (overlap > 0, some body movable, a curved surface).
    pub touching: bool,
    /// Force on p at the contact point \[N\] (`-force_p` on q): `Q - n P`.
    pub force_p: Vec3,
    /// Torque on p about its centre [N m]: `(c - x_p) x force_p - M_roll`.
    pub torque_p: Vec3,
    /// Torque on q about its centre [N m]: `(c - x_q) x (-force_p) + M_roll`.
    pub torque_q: Vec3,
    /// Contact point \[m\].
    pub point: Vec3,
    /// Normal force on q along `n` \[N\], damping included (>= 0).
    pub normal_force: f64,
    /// Elastic (Hertz) part of the normal force \[N\].
    pub elastic_normal_force: f64,
    /// Tangential force on p from q, world frame \[N\].
    pub tangential_force: Vec3,
    /// Contact radius `a = sqrt(R* delta)` \[m\].
    pub contact_radius: f64,
    /// Whether the contact is at the Coulomb limit (`|Q| >= mu P_e`).
    pub sliding: bool,
    /// Creep displacement of the step in `(t1, t2)` \[m\] (zero without creep).
    pub creep_displacement: Vec2,
    /// `|du_disp|` of the step \[m\].
    pub slide_length: f64,
    /// Kuhn & Bagi sliding velocity, world frame [m/s].
    pub v_disp: Vec3,
    /// Kuhn & Bagi rolling velocity, world frame [m/s].
    pub v_roll: Vec3,
    /// The step's energies.
    pub dissipation: PairDissipation,
}

/// The pair force of one contact for one step of length `dt` \[s\]: bodies `p` and `q`, the pair's
/// constants `c`, the geometry `g` (normal from p to q) and the contact's history `h` (updated in
/// place; reset when the contact is open). See the module docs for the law.
///
/// Always inlined: a host's loop uses a few of the outputs, and inlining lets the compiler drop
/// the work of the others (e.g. `slide_length`'s square root).
#[inline(always)]
pub fn pair_force<T: TangentialLaw>(
    c: &PairConstants,
    p: &PairBody,
    q: &PairBody,
    g: &ContactGeometry,
    h: &mut ContactHistory<T>,
    dt: f64,
) -> PairForces {
    let delta = g.overlap;
    let inv_sum = p.inv_mass() + q.inv_mass();
    let pm = c.pair_material(p.surface, q.surface);
    if !(delta > 0.0 && inv_sum > 0.0 && pm.r_star.is_finite()) {
        let released = release(c, p.surface, q.surface, h);
        return PairForces {
            dissipation: PairDissipation {
                slip: released,
                ..PairDissipation::default()
            },
            ..PairForces::default()
        };
    }
    let m_star = 1.0 / inv_sum;
    let n = g.normal;
    let cp = g.point;
    let (rates, delta_dot) = rates_and_approach(p, q, cp, n);

    // The tangent basis carried with the contact.
    if h.is_virgin() {
        h.t1 = n.tangent_basis().0;
        h.normal = n;
    }
    let spin = 0.5 * (p.angular_velocity + q.angular_velocity).dot(n);
    let t1 = rotate_to(h.t1, h.normal, n);
    let t1 = rotate_about(t1, n, spin * dt);
    let Some(t1) = t1.reject(n).try_normalize() else {
        *h = ContactHistory::default();
        return PairForces::default();
    };
    let t2 = n.cross(t1);

    // Normal force: Hertz `(4/3) E* sqrt(R* delta) delta = (4/3) E* a delta` (Johnson 1985,
    // §4.2) + Tsuji damping tuned to e, `alpha sqrt(m* k_H) delta^(1/4)` with
    // `k_H = (4/3) E* sqrt(R*)`, i.e. `alpha sqrt((4/3) E* m* a)`; never attractive.
    let a = (pm.r_star * delta).sqrt();
    let e43 = 4.0 / 3.0 * pm.e_star;
    let p_el = e43 * a * delta;
    let damp = c.alpha * (e43 * m_star * a).sqrt();
    let p_tot = (p_el + damp * delta_dot).max(0.0);
    let damping = (p_tot - p_el) * delta_dot * dt;

    // Tangential force.
    let du_disp = Vec2::from_basis(rates.v_disp * dt, t1, t2);
    let du_roll = if c.creep.is_some() {
        Vec2::from_basis(rates.v_roll * dt, t1, t2)
    } else {
        Vec2::ZERO
    };
    let step = T::step(&mut h.tangential, c, &pm, p_el, a, du_disp, du_roll);
    let q_world = step.q.to_3d(t1, t2);
    // `|Q| >= (1 - 1e-9) mu P_e`, squared (both sides >= 0): one square root less per contact.
    let limit = (1.0 - 1e-9) * pm.mu * p_el;
    let sliding = pm.mu.is_finite() && step.q.length_squared() >= limit * limit;

    // Contact-torque rolling resistance (on q; -M on p).
    let mut torque_roll = Vec3::ZERO;
    let mut rolling = 0.0;
    if let Some(model) = c.rolling {
        let term = |b: &PairBody| match b.surface {
            Surface::Sphere(r) if b.mass.is_finite() && b.mass > 0.0 => {
                (b.mass, 0.4 * b.mass * r * r, r)
            }
            _ => (f64::INFINITY, f64::INFINITY, 1.0),
        };
        let (ma, ia, ra) = term(p);
        let (mb, ib, rb) = term(q);
        let input = RollingInput {
            p: p_tot,
            r_star: pm.r_star,
            k_n: hertz::normal_stiffness(&pm, delta),
            w_roll: rates.w_roll,
            normal: n,
            dt,
            rolling_inertia: epsd_rolling_inertia(ma, ia, ra, mb, ib, rb),
        };
        let r = model.torque(&mut h.rolling, &input);
        torque_roll = r.torque;
        rolling = r.dissipation;
    }

    h.t1 = t1;
    h.normal = n;
    h.overlap = delta;

    let f_p = q_world - n * p_tot;
    PairForces {
        touching: true,
        force_p: f_p,
        torque_p: (cp - p.position).cross(f_p) + (-torque_roll),
        torque_q: (cp - q.position).cross(-f_p) + torque_roll,
        point: cp,
        normal_force: p_tot,
        elastic_normal_force: p_el,
        tangential_force: q_world,
        contact_radius: a,
        sliding,
        creep_displacement: step.creep_displacement,
        slide_length: du_disp.length(),
        v_disp: rates.v_disp,
        v_roll: rates.v_roll,
        dissipation: PairDissipation {
            damping,
            slip: step.slip,
            creep: step.creep,
            rolling,
            truncation: step.truncation,
        },
    }
}

/// Kuhn & Bagi's (2004) contact rates of `p` and `q` at `cp` with normal `n`, and the approach
/// rate `delta_dot` \[m/s\]: creep-law's [`crate::kinematics::contact_rates_and_approach`].
#[inline(always)]
fn rates_and_approach(p: &PairBody, q: &PairBody, cp: Vec3, n: Vec3) -> (ContactRates, f64) {
    let motion = |b: &PairBody| BodyMotion {
        position: b.position,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
        surface: b.surface,
    };
    contact_rates_and_approach(&motion(p), &motion(q), cp, n)
}

/// Opens a contact: resets its history and returns the tangential elastic energy it still
/// held \[J\], which the springs release as they leave the contact (booked as slip dissipation,
/// as creep-law's Cattaneo-Mindlin memory books springs leaving a shrinking contact). Hosts
/// call it when they find a contact apart without calling [`pair_force`].
#[inline]
pub fn release<T: TangentialLaw>(
    c: &PairConstants,
    sp: Surface,
    sq: Surface,
    h: &mut ContactHistory<T>,
) -> f64 {
    if h.is_virgin() {
        return 0.0;
    }
    let (_, wt) = h.elastic_energy(c, sp, sq);
    *h = ContactHistory::default();
    if wt.is_finite() { wt } else { 0.0 }
}

/// `v` turned by the smallest rotation taking the unit vector `from` to the unit vector `to`
/// (Rodrigues' formula; identity when they coincide, a half turn when opposite).
#[inline]
pub fn rotate_to(v: Vec3, from: Vec3, to: Vec3) -> Vec3 {
    let axis = from.cross(to);
    let s = axis.length();
    let c = from.dot(to);
    if !(s > 1e-15) {
        return if c >= 0.0 { v } else { -v };
    }
    let k = axis * (1.0 / s);
    v * c + k.cross(v) * s + k * (k.dot(v) * (1.0 - c))
}

/// `v` turned by `angle` \[rad\] about the unit `axis` (Rodrigues).
#[inline]
pub fn rotate_about(v: Vec3, axis: Vec3, angle: f64) -> Vec3 {
    if angle == 0.0 {
        return v;
    }
    // DEM steps turn a contact by micro-radians: the Taylor series is exact to rounding below
    // 1e-3 rad (next terms a^5/120, a^6/720 < 1e-17) and saves the libm call.
    let (s, c) = if angle.abs() < 1e-3 {
        let a2 = angle * angle;
        (angle * (1.0 - a2 / 6.0), 1.0 - 0.5 * a2 * (1.0 - a2 / 12.0))
    } else {
        angle.sin_cos()
    };
    v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c))
}

#[cfg(test)]
mod tests;
