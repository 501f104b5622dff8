//! Wheels: a cylinder rolling on its round face on a flat surface, with one contact (at the
//! centre of its patch) for the whole wheel.
//!
//! The rolling frame is the wheel's own: `x` along the heading `n × e` (`e` the axle), oriented
//! with the rolling, `y = n × x`; the rolling speed is `V = |v_roll . x|` (Kuhn & Bagi's
//! `v_roll` at the patch centre), so a wheel at slip angle `alpha` has `eta = tan(alpha)`.
//!
//! * **Crowned wheel** (crown radius `R_c`, [`WheelContact::crowned`]): Hertz's elliptic contact
//!   with the curvature sums `kx = 1/R`, `ky = 1/R_c` (Hertz 1882; Johnson 1985, §4.2;
//!   [`crate::elliptic`]), semi-axes `a` (rolling direction) and `b`, both `~ P^(1/3)`; the law
//!   along `x` is the fast 3-D law at zero spin ([`crate::steady3d::Steady3d`], fitted to the
//!   boundary elements of Kalker's exact theory, Kalker 1967/1990), normalised with
//!   `c = sqrt(a b)`; the lateral ratio is Kalker's `C11/C22` at `a/b` (Kalker 1990, Table E.3);
//!   spin creep as a ball's (parent module docs); the force is then solved again with the 3-D
//!   law at the combined creepage, so that it is the law's at the target's creepages (parent
//!   module docs, "A crowned wheel: the combined law").
//! * **Line contact** (no crown): Carter's two-dimensional solution (Carter 1926; Johnson
//!   1985, §8.2): half-width `a = sqrt(4 (P/L) R/(pi E*))` (Johnson 1985, eq. 4.43,
//!   [`line_half_width`]) and `xi = (mu a/R)(1 - sqrt(1 - Q/(mu P)))` ([`carter_creepage`]);
//!   laterally the same law scaled by `C11/C22 = 1/(1 - nu)`: the ratio of the plane-strain to
//!   the antiplane shear compliance of the strip (an assumption for the slender limit, not a
//!   quoted solution); Kalker's table tends to it as `a/b -> 0` (Kalker 1990, Table E.3:
//!   `C11/C22` = 1.31 and 1.92 at `a/b = 0.1`, `nu = 0.25, 0.5`, against 1.33 and 2). No spin
//!   creep.
//!
//! **Spin of a wheel on a joint.** A wheel's relative spin is best read from its axle turning
//! between two steps (the `axle_turn` argument of [`wheel_creep`]) rather than from its angular velocity: the
//! angular velocity holds the twisting impulse applied to the wheel alone after the last step,
//! which a joint shares with the carrier only in the next solve.

use super::{
    CoulombReason, LawCache, RigidContact, RigidCreep, RollFrame, creeping, force_estimate,
    solve_combined, solver_noise_force, spin_above_noise, translate,
};
use crate::elliptic::elliptic_hertz;
use crate::error::LawError;
use crate::kinematics::contact_rates;
use crate::material::PairMaterial;
use crate::vector::Vec3;

/// The shape of a wheel's contact law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum WheelContact {
    /// Crowned wheel: elliptic semi-axes at unit load, `a = a1 P^(1/3)`, `b = b1 P^(1/3)` \[m\]
    /// (`a` along the rolling direction).
    Crowned {
        /// `a` at 1 N \[m\].
        a1: f64,
        /// `b` at 1 N \[m\].
        b1: f64,
    },
    /// Line contact of width `width` \[m\] (Carter's law).
    Line {
        /// Contact length along the axle \[m\].
        width: f64,
    },
}

impl WheelContact {
    /// The crowned contact of a wheel of radius `radius` \[m\] with crown radius `crown` \[m\]
    /// on a flat surface, contact modulus `e_star` \[Pa\] (Hertz's ellipse at 1 N:
    /// [`elliptic_hertz`] with the curvatures `1/radius`, `1/crown`).
    pub fn crowned(radius: f64, crown: f64, e_star: f64) -> Result<Self, LawError> {
        let h = elliptic_hertz(1.0 / radius, 1.0 / crown, 1.0, e_star)?;
        Ok(Self::Crowned { a1: h.a, b1: h.b })
    }
}

/// What the wheel kernel needs of the wheel beyond [`RigidContact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelInput {
    /// The axle's unit direction (world).
    pub axle: Vec3,
    /// Rolling radius \[m\].
    pub radius: f64,
    /// Its contact law's shape.
    pub contact: WheelContact,
    /// Whether the wheel is body p of the contact (else body q).
    pub wheel_is_p: bool,
    /// Whether the contact may creep in spin: a crowned wheel's single patch contact (a wheel
    /// left on several contact points, whose friction points resist a twist as Coulomb does,
    /// has none).
    pub spin: bool,
}

/// The creep slip target of a wheel's patch contact (module docs; parent module docs for the
/// solve).
///
/// * `pair`: the pair of the wheel (as a sphere of its radius) and the flat surface
///   ([`super::RigidPair::pair_for`]; its `mu` is the contact's friction coefficient, its
///   `E*`, `G` and `nu` are used);
/// * `wheel`: the wheel ([`WheelInput`]);
/// * `contact`: what the engine has at the patch ([`RigidContact`]: the point is the patch
///   centre, the impulses the whole wheel's);
/// * `laws`: the elliptic laws by shape (a crowned wheel's, built on first use);
/// * `axle_turn()`: the angle \[rad\] the wheel turned about the normal over the last step
///   (from the wheel's poses at the last two steps), or `None` to read the spin from the
///   angular velocities; called once, only for a contact that gets past the load, rolling and
///   shape checks (an engine that tracks the axle per step updates its track there);
/// * `inv_mass(d)`: the contact's inverse effective mass along the unit tangent `d` \[1/kg\]
///   (as for [`super::ball_creep`]).
pub fn wheel_creep(
    pair: &PairMaterial,
    wheel: &WheelInput,
    contact: &RigidContact,
    laws: &mut LawCache,
    axle_turn: impl FnOnce() -> Option<f64>,
    inv_mass: impl Fn(Vec3) -> f64,
) -> RigidCreep {
    let mu = pair.mu;
    let dt = contact.dt;
    let n = contact.normal;
    let (p, q) = (&contact.p, &contact.q);
    let p_force = contact.normal_impulse / dt;
    let rates = contact_rates(p, q, contact.point, n);
    // The wheel's frame: x along the heading n x axle, with the rolling.
    let heading = n.cross(wheel.axle).try_normalize();
    let frame =
        heading.map(|h| RollFrame::along(if h.dot(rates.v_roll) > 0.0 { -h } else { h }, n));
    let roll = frame.map_or(0.0, |f| rates.v_roll.dot(f.x).abs());
    if let Some(out) = RigidCreep::unloaded(p_force, mu) {
        return out;
    }
    let Some(frame) = frame.filter(|_| roll > 0.0) else {
        return RigidCreep::coulomb(CoulombReason::NotRolling);
    };
    let mu_p = mu * p_force;
    let g = pair.g;
    // The law along x: the elliptic law with c^2 = a b, or Carter's half-width.
    let (law3, line) = match wheel.contact {
        WheelContact::Crowned { a1, b1 } => {
            let s = p_force.cbrt();
            let (a, b) = (a1 * s, b1 * s);
            let Some(law3) = laws.get(a / b, pair.nu.clamp(0.0, 0.5)) else {
                return RigidCreep::coulomb(CoulombReason::OutsideTable);
            };
            (Some((law3, a * b)), None)
        }
        WheelContact::Line { width } => (
            None,
            Some(line_half_width(p_force, width, wheel.radius, pair.e_star)),
        ),
    };
    let turn = axle_turn();
    let w_twist_read = match turn {
        Some(turn) if wheel.wheel_is_p => q.angular_velocity.dot(n) - turn / dt,
        Some(turn) => turn / dt - p.angular_velocity.dot(n),
        None => rates.w_twist,
    };
    // Noise of the angular velocities, and for a turn read from the poses, of the axle's
    // direction per step.
    let w_scale = p.angular_velocity.length()
        + q.angular_velocity.length()
        + if turn.is_some() { 1.0 / dt } else { 0.0 };
    let w_twist = if wheel.spin {
        spin_above_noise(w_twist_read, w_scale)
    } else {
        0.0
    };
    let (phi_n, spin_fy) = match law3 {
        Some((law3, c2)) if w_twist != 0.0 => {
            let phi_n = w_twist / roll * g * c2 * c2.sqrt() / mu_p;
            (phi_n, law3.loads(0.0, 0.0, phi_n).fy)
        }
        _ => (0.0, 0.0),
    };
    let q_s = frame.y * (spin_fy * mu_p);
    // The capacity left to the translation.
    let mu_t = (mu_p - spin_fy.abs() * mu_p).max(0.0);
    let radius = wheel.radius;
    let creepage = |q: f64| -> f64 {
        match (law3, line) {
            (Some((law3, c2)), _) => {
                let f = (q / mu_t).clamp(0.0, 1.0 - 1e-9);
                law3.creepages_for_force(f, 0.0).map_or(0.0, |(x, _)| x) * mu_t / (g * c2)
            }
            (None, Some(a)) => carter_creepage(q, mu_p, p_force, a, radius),
            _ => 0.0,
        }
    };
    let (slope0, r) = match (law3, line) {
        (Some((law3, c2)), _) => {
            let k = law3.coefficients();
            (1.0 / (g * c2 * k.c11), k.c11 / k.c22)
        }
        (None, Some(a)) => (a / (2.0 * radius * p_force), 1.0 / (1.0 - pair.nu)),
        _ => (0.0, 1.0),
    };
    if let Some(tolerance) = contact.auto_tolerance
        && creepage(mu_p) * roll < tolerance
    {
        return RigidCreep::coulomb(CoulombReason::BelowTolerance);
    }
    let (q_star, inv_m) = force_estimate(contact, frame.x, inv_mass);
    let noise = solver_noise_force(p, q, contact.point, inv_m, dt);
    if !(q_star.length() > noise) {
        return RigidCreep::coulomb(CoulombReason::BelowNoise);
    }
    let k = if inv_m > 0.0 {
        roll / (inv_m * dt)
    } else {
        0.0
    };
    let t = translate(
        &frame,
        q_star - q_s,
        q_s,
        k,
        r,
        mu_t,
        roll,
        slope0,
        creepage,
    );
    let Some((law3, c2)) = law3 else {
        return creeping(&t, n, 0.0, w_twist);
    };
    // The combined law: the split solve above (the spin's force, then the translation within
    // what it leaves) is the guess of the 2-D solve with the 3-D law itself, so that the force
    // is the law's at the creepages of the target (module docs). An estimate beyond the
    // capacity `mu P` keeps the split answer (the contact slides).
    let scale = g * c2 / mu_p;
    let (mut t, mut l) = (t, None);
    if k > 0.0 && q_star.length() < mu_p {
        let (xs, ys) = frame.split(q_star);
        // Where the split solve saturated (the spin left too little), start from rest.
        let guess = if t.capped {
            (0.0, 0.0)
        } else {
            (t.cx * scale, t.cy * scale)
        };
        let c = solve_combined(law3, (xs / mu_p, ys / mu_p), k / (g * c2), phi_n, guess);
        let (cx, cy) = (c.creepage.0 / scale, c.creepage.1 / scale);
        t.cx = cx;
        t.cy = cy;
        t.force = frame.join(c.loads.fx * mu_p, c.loads.fy * mu_p);
        t.target = frame.join(cx, cy) * roll;
        l = Some(c.loads);
    }
    // Kalker's twisting moment on p about n.
    let mz = if phi_n != 0.0 {
        l.unwrap_or_else(|| law3.loads(t.cx * scale, t.cy * scale, phi_n))
            .mz
            * mu_p
            * c2.sqrt()
    } else {
        0.0
    };
    creeping(&t, n, mz, w_twist)
}

/// Carter's creepage \[-\] at force `q` \[N\] below `mu_p` \[N\] for a line contact of
/// half-width `a` \[m\] and rolling radius `r` \[m\] under the load `p` \[N\]:
/// `(mu a/R)(1 - sqrt(1 - q/(mu P)))` (Carter 1926; Johnson 1985, eq. 8.38), written without
/// cancellation as `(a/R) (q/P) / (1 + sqrt(1 - q/(mu P)))`, `q` clamped to `[0, mu P]`.
pub fn carter_creepage(q: f64, mu_p: f64, p: f64, a: f64, r: f64) -> f64 {
    if !(mu_p > 0.0 && p > 0.0) {
        return 0.0;
    }
    let q = q.clamp(0.0, mu_p);
    (a / r) * (q / p) / (1.0 + (1.0 - q / mu_p).sqrt())
}

/// Hertz's half-width \[m\] of a line contact: `a = sqrt(4 (P/L) R/(pi E*))` (Johnson 1985,
/// eq. 4.43) for the load `p` \[N\] over the length `width` \[m\], radius `r` \[m\], contact
/// modulus `e_star` \[Pa\].
pub fn line_half_width(p: f64, width: f64, r: f64, e_star: f64) -> f64 {
    (4.0 * (p / width) * r / (std::f64::consts::PI * e_star)).sqrt()
}
