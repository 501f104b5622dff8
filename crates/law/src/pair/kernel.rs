//! The kernel: [`pair_force`], its outputs, [`release`] and the rotations of the carried basis.

use super::{ContactGeometry, ContactHistory, PairBody, PairConstants, TangentialLaw};
use crate::hertz;
use crate::kinematics::{BodyMotion, ContactRates, contact_rates_and_approach};
use crate::material::{PairMaterial, Surface};
use crate::rolling_torque::{RollingInput, epsd_rolling_inertia};
use crate::vector::{Vec2, Vec3};

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
    let (m_star, pm) = reduced_mass_and_material(c, p, q);
    if !(delta > 0.0 && m_star > 0.0 && finite(pm.r_star)) {
        let released = release(c, p.surface, q.surface, h);
        return PairForces {
            dissipation: PairDissipation {
                slip: released,
                ..PairDissipation::default()
            },
            ..PairForces::default()
        };
    }
    let n = g.normal;
    let cp = g.point;
    // Two spheres: the arms from the centres to the contact point lie along the normal (the
    // point of a sphere's surface nearest the other body is on its normal through the centre),
    // `c - x_p = rho_p n`, `c - x_q = -rho_q n`; the rates and the torques then take the
    // shorter forms below (the same values to rounding; test `sphere_forms_equal_the_general_ones`).
    // The contact point being the middle of the overlap along the normal ([`ContactGeometry`]'s
    // contract, as [`ContactGeometry::sphere_sphere`] places it), the arms' lengths are the radii
    // less half the overlap, `rho = r - delta/2`: the projections `(c - x_p) . n` and
    // `(x_q - c) . n` to rounding, without their two dot products.
    let (spheres, rho_p, rho_q) = match (p.surface, q.surface) {
        (Surface::Sphere(rp), Surface::Sphere(rq)) => (true, rp - 0.5 * delta, rq - 0.5 * delta),
        _ => (false, 0.0, 0.0),
    };
    let (rates, delta_dot) = if spheres {
        sphere_rates_and_approach(p, q, rho_p, rho_q, n)
    } else {
        rates_and_approach(p, q, cp, n)
    };

    // The tangent basis carried with the contact: turned about the normal by the pair's mean
    // spin, then carried onto the new tangent plane by projection, or, when the normal turned
    // far in one step, by the smallest rotation taking the last normal to the new one.
    if h.is_virgin() {
        h.t1 = n.tangent_basis().0;
        h.normal = n;
    }
    let spin = 0.5 * (p.angular_velocity + q.angular_velocity).dot(n);
    let Some(t1) = carry_tangent(h.t1, h.normal, n, spin * dt) else {
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
            Surface::Sphere(r) if b.mass > 0.0 && finite(b.mass) => {
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
    let (torque_p, torque_q) = if spheres {
        // `(c - x_p) x f_p = rho_p n x f_p` and `(c - x_q) x (-f_p) = rho_q n x f_p`, with
        // `n x f_p = n x Q = Q_1 t2 - Q_2 t1` (`n x n = 0`, `n x t1 = t2`, `n x t2 = -t1`).
        let nf = t2 * step.q.x - t1 * step.q.y;
        (nf * rho_p - torque_roll, nf * rho_q + torque_roll)
    } else {
        (
            (cp - p.position).cross(f_p) + (-torque_roll),
            (cp - q.position).cross(-f_p) + torque_roll,
        )
    };
    PairForces {
        touching: true,
        force_p: f_p,
        torque_p,
        torque_q,
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

/// Whether `x` is finite (not NaN, not infinite), as [`f64::is_finite`], in the floating-point
/// domain: `x - x` is 0 for every finite `x` and NaN otherwise (IEEE 754: `inf - inf` and
/// `NaN - x` are NaN). The kernel's hot path tests this a dozen times per contact; LLVM turns
/// `is_finite` (and `x > 0 && x < inf`) into a test of the bit pattern in an integer register,
/// a move out of the vector register and four to a dozen integer operations per test (seen in
/// the LAMMPS plugin's profile), where this is one subtraction and one compare.
#[inline(always)]
#[allow(clippy::eq_op)] // `x - x` is the point: 0 or NaN
pub(crate) fn finite(x: f64) -> bool {
    x - x == 0.0
}

/// The reduced mass `m*` \[kg\] (NaN when neither body can move) and the pair material (with
/// `R*`) of a contact: [`PairBody::reduced_mass`] and [`PairConstants::pair_material`], except
/// that for two movable spheres `m* = m_p m_q/(m_p + m_q)` and `R* = r_p r_q/(r_p + r_q)` share
/// one reciprocal, `1/((m_p + m_q)(r_p + r_q))` (one division instead of two; a few ulps apart).
#[inline(always)]
fn reduced_mass_and_material(c: &PairConstants, p: &PairBody, q: &PairBody) -> (f64, PairMaterial) {
    if let (Surface::Sphere(rp), Surface::Sphere(rq)) = (p.surface, q.surface)
        && p.mass > 0.0
        && q.mass > 0.0
    {
        let (sr, sm) = (rp + rq, p.mass + q.mass);
        let inv = 1.0 / (sr * sm);
        if inv > 0.0 && finite(inv) && finite(sm) {
            let pm = PairMaterial {
                r_star: rp * rq * sm * inv,
                surface_p: p.surface,
                surface_q: q.surface,
                ..c.material
            };
            return (p.mass * q.mass * sr * inv, pm);
        }
    }
    (
        PairBody::reduced_mass(p, q).unwrap_or(f64::NAN),
        c.pair_material(p.surface, q.surface),
    )
}

/// Kuhn & Bagi's (2004) contact rates of `p` and `q` at `cp` with normal `n`, and the approach
/// rate `delta_dot` \[m/s\]: creep-law's [`crate::kinematics::contact_rates_and_approach`].
#[inline(always)]
pub(super) fn rates_and_approach(
    p: &PairBody,
    q: &PairBody,
    cp: Vec3,
    n: Vec3,
) -> (ContactRates, f64) {
    let motion = |b: &PairBody| BodyMotion {
        position: b.position,
        velocity: b.velocity,
        angular_velocity: b.angular_velocity,
        surface: b.surface,
    };
    contact_rates_and_approach(&motion(p), &motion(q), cp, n)
}

/// [`rates_and_approach`] for two spheres whose arms to the contact point lie along the normal
/// `n`: `c - x_p = rho_p n`, `c - x_q = -rho_q n` (`rho_p`, `rho_q` \[m\] the centres'
/// distances to the contact point along `n`). With `A = w_p x n`, `B = w_q x n` (tangential)
/// and `dv = v_q - v_p`, Kuhn & Bagi's (2004) rates (DESIGN §2, as
/// [`crate::kinematics::contact_rates`]) are `v_disp = dv_t - rho_p A - rho_q B`, `v_roll =
/// dv_t (rho_q - rho_p)/(2 d) + (rho_p A - rho_q B)/2` (`d = rho_p + rho_q`: the contact
/// point's velocity `c' = v_p + dv rho_p/d`; `v_roll = 0` where `d` is not finite and > 0, as
/// there), the approach rate `-dv . n`: two cross products where the general form takes four,
/// and no projections of the rates onto the tangent plane but one (`dv_t`). The same values to
/// rounding (test `sphere_forms_equal_the_general_ones`).
#[inline(always)]
pub(super) fn sphere_rates_and_approach(
    p: &PairBody,
    q: &PairBody,
    rho_p: f64,
    rho_q: f64,
    n: Vec3,
) -> (ContactRates, f64) {
    let a = p.angular_velocity.cross(n);
    let b = q.angular_velocity.cross(n);
    let dv = q.velocity - p.velocity;
    let dvn = dv.dot(n);
    let dv_t = dv - n * dvn;
    let d = rho_p + rho_q;
    let v_roll = if d > 0.0 && finite(d) {
        dv_t * ((rho_q - rho_p) / (2.0 * d)) + (a * rho_p - b * rho_q) * 0.5
    } else {
        Vec3::ZERO
    };
    let w_rel = q.angular_velocity - p.angular_velocity;
    let rates = ContactRates {
        v_disp: dv_t - a * rho_p - b * rho_q,
        v_roll,
        w_roll: w_rel.reject(n),
        w_twist: w_rel.dot(n),
    };
    (rates, -dvn)
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

/// The carried first tangent `t1` (unit, normal to the last normal `from`) on the tangent plane
/// of the new normal `to`, turned about `to` by `spin_angle` \[rad\] (the pair's mean spin times
/// the step), unit; `None` where it degenerates (a reset contact).
///
/// For the turns of a DEM step (the normal turns by `theta` ~ the relative tangential speed
/// times the step over the distance of the centres, micro-radians) the tangent is carried by
/// projection, `t1 - to (to . t1)`, renormalised (as LAMMPS' granular styles carry their
/// history, `rotate_rescale_vec`), instead of by the smallest rotation taking `from` to `to`
/// ([`rotate_to`], Rodrigues). The two agree exactly for a tangent in the plane of the turn
/// (the projection of a unit vector of that plane, normalised, is its rotation) and for one
/// along the turn's axis (unchanged by both); in between, at angle `phi` from the axis, the
/// projection is the rotated tangent turned about `to` by `atan(tan(phi) cos(theta)) - phi =
/// -(theta^2/4) sin(2 phi) + O(theta^4)`: the two carries differ at second order in the turn
/// per step (1e-12 rad per step at `theta` = 2e-6), a twist of the basis only (the stored
/// force keeps its size, and the contact's spin rotation, `rotate_about`, is unchanged), and
/// it stays below `(theta_max/4)` times the total turning of the contact over a run. The
/// projection takes no cross product, no division and no branch on the turn; it saved 54 of
/// ~1,063 instructions per contact of the LAMMPS plugin (issue #16). Where the normal turns
/// far in one step (beyond 45 degrees) the rotation is kept as before (e.g. a half turn of the
/// normal reverses the tangent, the convention of [`rotate_to`]).
#[inline(always)]
pub(super) fn carry_tangent(t1: Vec3, from: Vec3, to: Vec3, spin_angle: f64) -> Option<Vec3> {
    if from.dot(to) > std::f64::consts::FRAC_1_SQRT_2 {
        // A turn of the normal below 45 degrees: the projection's length is at least
        // cos(45 deg), no degeneracy. The spin about `to` without its part along `to`
        // (Rodrigues' `to (to . t1)(1 - c)`), which the projection removes anyway.
        return renormalize(spin_without_axial(t1, to, spin_angle).reject(to));
    }
    let rotated = rotate_about(rotate_to(t1, from, to), to, spin_angle);
    renormalize(rotated.reject(to))
}

/// `v` turned by the smallest rotation taking the unit vector `from` to the unit vector `to`
/// (Rodrigues' formula; identity when they coincide, a half turn when opposite).
///
/// Always inlined: the kernel calls it once per contact and step (a call kept its operands in
/// memory, 9 % of the LAMMPS plugin's spring-tier run).
#[inline(always)]
pub fn rotate_to(v: Vec3, from: Vec3, to: Vec3) -> Vec3 {
    let axis = from.cross(to);
    let s2 = axis.dot(axis);
    let c = from.dot(to);
    if !(s2 > 1e-30) {
        return if c >= 0.0 { v } else { -v };
    }
    // Rodrigues with the unit axis `k = axis/s`, `s = sin(angle)`: `v c + (k x v) s + k (k.v)
    // (1 - c)`. For turns below a quarter (`c > 0`, every DEM step) the same is
    // `v c + axis x v + axis (axis.v) / (1 + c)` (`s^2 = (1 - c)(1 + c)`): no square root and
    // one division; beyond, where `1 + c` may round to 0, the unit-axis form.
    if c > 0.0 {
        return v * c + axis.cross(v) + axis * (axis.dot(v) * inv_one_plus_cos(s2, c));
    }
    let s = s2.sqrt();
    let k = axis * (1.0 / s);
    v * c + k.cross(v) * s + k * (k.dot(v) * (1.0 - c))
}

/// `1/(1 + c)` for `c = cos(angle) > 0`, `s2 = sin^2(angle)`. Below `s2 = 1e-4` (turns under
/// 0.01 rad, every DEM step) the series `1/(1 + sqrt(1 - x)) = (1 - sqrt(1 - x))/x = 1/2 + x/8
/// + x^2/16 + 5 x^3/128 + ...` (binomial series of `sqrt(1 - x)`) to the `x^2` term, without the
/// division: the coefficient multiplies `axis (axis . v)`, of size `s2 |v|`, so the truncation
/// `5 x^3/128` changes the rotated vector by `0.04 s2^4 |v| < 4e-18 |v|`, below its rounding.
#[inline(always)]
fn inv_one_plus_cos(s2: f64, c: f64) -> f64 {
    if s2 < 1e-4 {
        0.5 + s2 * (0.125 + s2 * 0.0625)
    } else {
        1.0 / (1.0 + c)
    }
}

/// `t / |t|` for a vector `t` of length close to 1, `None` for a zero, tiny or non-finite one.
/// The carried tangent comes out of exact rotations and the projection onto the tangent plane
/// with `|t|^2 = 1 + eps`, `eps` a few ulps: there one Newton step of `1/sqrt` from 1,
/// `t (3 - |t|^2)/2`, is within `3 eps^2/8` of `1/|t|` (Taylor series of `(1 + eps)^(-1/2)`),
/// below the rounding for `|eps| < 1e-8`, with no square root and no division; otherwise
/// `Vec3::try_normalize`.
#[inline(always)]
fn renormalize(t: Vec3) -> Option<Vec3> {
    let l2 = t.dot(t);
    if (l2 - 1.0).abs() < 1e-8 {
        Some(t * (1.5 - 0.5 * l2))
    } else {
        t.try_normalize()
    }
}

/// `v` turned by `angle` \[rad\] about the unit `axis` (Rodrigues).
#[inline(always)]
pub fn rotate_about(v: Vec3, axis: Vec3, angle: f64) -> Vec3 {
    if angle == 0.0 {
        return v;
    }
    let (s, c) = small_sin_cos(angle);
    v * c + axis.cross(v) * s + axis * (axis.dot(v) * (1.0 - c))
}

/// [`rotate_about`] without Rodrigues' term along the unit `axis`, `axis (axis . v)(1 - c)`:
/// `v c + (axis x v) s`. For a caller that projects the result onto the plane
/// normal to `axis` (the carried tangent), the projection of this equals the projection of the
/// rotation (to rounding), with one dot product and two vector products fewer.
#[inline(always)]
fn spin_without_axial(v: Vec3, axis: Vec3, angle: f64) -> Vec3 {
    if angle == 0.0 {
        return v;
    }
    let (s, c) = small_sin_cos(angle);
    v * c + axis.cross(v) * s
}

/// `(sin a, cos a)` of an angle \[rad\]: below 1e-3 rad the Taylor series (exact to rounding
/// there), otherwise libm's.
#[inline(always)]
fn small_sin_cos(angle: f64) -> (f64, f64) {
    // DEM steps turn a contact by micro-radians: the Taylor series is exact to rounding below
    // 1e-3 rad (next terms a^5/120, a^6/720 < 1e-17) and saves the libm call; the constant
    // divisions as products with the rounded reciprocals (a relative change of 1e-16 in terms of
    // size a^2 < 1e-6, far below the rounding of the result).
    if angle.abs() < 1e-3 {
        let a2 = angle * angle;
        (
            angle * (1.0 - a2 * (1.0 / 6.0)),
            1.0 - 0.5 * a2 * (1.0 - a2 * (1.0 / 12.0)),
        )
    } else {
        angle.sin_cos()
    }
}
