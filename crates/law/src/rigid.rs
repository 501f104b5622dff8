//! The rigid-contact creep kernel: creep-friction for impulse-based rigid-body engines
//! (Rapier, Avian, ...), one pure function per contact kind.
//!
//! An impulse-based engine keeps its own non-penetration and Coulomb friction constraints; what
//! it lets a contact hook write is a *target tangential velocity* of the friction row (Rapier's
//! `SolverContact::tangent_velocity`, Avian's `tangent_velocity`). This module computes that
//! target: the creep slip velocity of the contact, from what the engine has at the contact at
//! the start of a step (the normal, last step's normal and friction impulses, the two bodies'
//! motion, the shapes, the last target). The engine then enforces the slip below the Coulomb
//! limit and slides at it.
//!
//! | contact | function | law along the rolling direction | lateral | spin |
//! |---|---|---|---|---|
//! | ball on ball or on a flat surface | [`ball_creep`] | the pair's [`SteadyLaw`](crate::SteadyLaw) (Kalker's `F_ss` or the fitted law) | Kalker's `C22` | [`Steady3d`](crate::steady3d::Steady3d) |
//! | wheel, line contact | [`wheel_creep`] with [`WheelContact::Line`] | Carter's | `C11/C22 = 1/(1 - nu)` | none |
//! | wheel, crowned | [`wheel_creep`] with [`WheelContact::Crowned`] | `Steady3d` at the ellipse's `a/b` | Kalker's `C22(a/b)` | `Steady3d` |
//!
//! Each takes the per-pair constants ([`RigidPair`], built once per pair of materials and
//! friction coefficient, cached by [`RigidPairCache`]), the contact ([`RigidContact`]) and the
//! engine's inverse effective mass of the contact along a direction (a closure), and returns a
//! [`RigidCreep`]: the slip target, the friction force it was built for, the twisting moment,
//! the creep power booked and the loop gain, or the reason the contact is left to Coulomb
//! ([`CoulombReason`]). Units are SI throughout (m, s, N, kg, rad).
//!
//! # Use from an engine
//! Per contact and step: read last step's impulses, call the kernel, add
//! [`RigidCreep::target`] to the friction row's target velocity, store the target for the next
//! step ([`RigidContact::last_target`]: the kernel's only history besides the engine's own
//! impulses) and, after the step, apply [`RigidCreep::moment`] to body q (and its opposite to
//! body p) as an angular impulse `M dt` that does not reverse the relative spin. A contact whose
//! result is [`RigidCreep::coulomb`] gets no target (plain Coulomb friction), and its stored
//! target becomes zero.
//!
//! # Frame and creepages (Kalker 1967; Kalker 1990, *Three-dimensional elastic bodies in rolling
//! contact*, §1.2; signs of creep-reference's `bem` module)
//!
//! `z = n` (the unit normal from body p to body q); `x` is the direction in which the contact
//! moves over both surfaces, `x = -v_roll/|v_roll|` (Kuhn & Bagi's `v_roll` is the mean surface
//! velocity relative to the contact point, [`crate::kinematics`]); `y = z × x`
//! ([`RollFrame`]). With `V = |v_roll|`:
//!
//! `xi = v_disp . x / V`, `eta = v_disp . y / V` (creepage of q relative to p, \[-\]),
//! `phi = (w_q - w_p) . n / V` (spin creepage \[1/m\]).
//!
//! Linear theory (Kalker 1967, project signs: force on p, moment on p about `n`):
//! `Fx = G c^2 C11 xi`, `Fy = G c^2 C22 eta + G c^3 C23 phi`, `Mz = -G c^3 C23 eta + G c^4 C33 phi`,
//! `c = sqrt(a b)`.
//!
//! # The creep slip (Kuhn 2011, eq. 1, in its stiff-contact limit)
//!
//! Kuhn's rule with the elastic term gone (`c_CM -> 0`, rigid bodies) leaves the creep term:
//! the contact slips at `v_disp = F(|Q|) V Q/|Q|` for the friction force `Q`, with `F` the
//! steady creepage of the force and `P` the normal force (last step's impulses over `dt`), the
//! contact radius from Hertz (`a = (3 P R*/(4 E*))^(1/3)`, Johnson 1985, §4.2).
//!
//! * **Translation** (`Q_t`, the force less the spin's): at zero spin Kalker's simplified theory
//!   (Kalker 1982, "A fast algorithm for the simplified theory of rolling contact", Vehicle
//!   System Dynamics 11; FASTSIM) builds the traction from the flexibilities `L1 = 8a/(3 G C11)`,
//!   `L2 = 8a/(3 G C22)`, so the force is parallel to `(xi/L1, eta/L2)` and saturates in its
//!   magnitude alone. The creepage for a force `Q_t` is therefore
//!   `(xi, eta) = F(|Q_t|) (u_x, (C11/C22) u_y)`, `u = Q_t/|Q_t|`, with `F` the pair's steady law
//!   along the rolling direction (for a ball, `F_ss(s) = 3 mu P/(G a^2 C11) (1 - (1 - s)^(1/3))`,
//!   `s = |Q|/(mu P)`, Kalker 2000, or the fitted law; for a wheel, Carter's or the elliptic
//!   law, [`wheel`]). It is Kalker's linear theory at small force in every direction and the
//!   configured law exactly along `x`.
//! * **Spin**: the lateral force of pure spin `f_s(phi_n)` and the moment come from creep-law's
//!   fast 3-D law ([`Steady3d`](crate::steady3d::Steady3d), a fit to the boundary elements,
//!   Kalker's `C23`, `C33` at small spin); the spin's force takes its share of the friction
//!   capacity (`mu P - |Q_s|` is left to the translation), and the moment
//!   `Mz(xi_n, eta_n, phi_n)` is returned for the engine to apply after the step. A relative spin
//!   within [`SPIN_NOISE_ULPS`] f32 ulps of the bodies' angular speeds counts as none.
//!
//! # The implicit solve, and the loop gain
//!
//! The slip target depends on the force the solver then transmits. Explicitly (target from the
//! last force), one step maps a force error `e` to `-g e` with the loop gain
//! `g = m_t V dF/dQ / dt` (`m_t` the contact's effective mass along `Q`), unstable for `g > 1`
//! (soft materials, light bodies, long steps, fast rolling, `s -> 1`). The kernel solves the
//! local relation implicitly instead: had last step's target been `tau` instead of `tau_prev`,
//! the solver would have transmitted `Q* - (m_t/dt) tau` with
//! `Q* = Q_measured + (m_t/dt) tau_prev`. With `tau = V (xi, eta)` in the frame and
//! `K = m_t V/dt`, the translation force solves `Q_t + K F(|Q_t|) A u = Q*_t`, `A = diag(1, r)`,
//! `r = C11/C22`, `Q*_t = Q* - Q_s`. Written with `q = |Q_t|`: `u = (X/e_x, Y/e_y)/q`,
//! `e_x = 1 + K F(q)/q`, `e_y = 1 + r K F(q)/q`, and `|u| = 1` is the scalar equation
//! `q = sqrt((X/e_x)^2 + (Y/e_y)^2)`, whose right side falls as `q` grows (`F(q)/q` rises: the
//! creepage is convex in the force), so the root is unique ([`solve_translation`], capped at
//! the capacity); in steady state (`tau = tau_prev`) it returns the measured force, and for
//! `r = 1` it is the circular solve `q + K F(q) = |Q*|`. It holds for any `g`;
//! [`RigidCreep::loop_gain`] reports `g` at the solution.
//!
//! **A crowned wheel: the combined law.** The split above (the pure spin's lateral force, then
//! the translation in the capacity it leaves, with the 1-D law along `x` and the ratio `r`) is
//! not the 3-D law at the combined creepage `(xi, eta, phi)`. For a crowned wheel whose force
//! estimate is below `mu P` the kernel therefore solves the same relation, `Q + K (xi, eta) = Q*`
//! in the frame (`Q` the whole force, the spin's included), with `Q = mu P L(xi_n, eta_n, phi_n)`,
//! `L` the 3-D law's `(fx, fy)` ([`Steady3d::loads`](crate::steady3d::Steady3d::loads)):
//! normalised, `L(z) + kappa z = Q*/(mu P)`, `kappa = K/(G c^2)`, two unknowns
//! ([`solve_combined`]: damped Newton from the split answer, or from rest where the split
//! saturated). The force the kernel reports is then the law's at its target's creepages, and
//! its moment the law's `Mz` there. A ball keeps the split solve; a line contact has no spin.
//!
//! # Noise floors
//! An engine that solves in f32 resolves the relative surface velocity to about `eps_f32 u`
//! (`u` the contact's surface speed) and so transmits tangential impulses no load asked for; a
//! slip target built on them would turn rounding into slip that does work. The kernel leaves a
//! contact whose load is below [`solver_noise_force`] to Coulomb, and takes a relative spin
//! below [`SPIN_NOISE_ULPS`] ulps of the angular speeds as none.

mod ball;
mod consts;
mod frame;
pub mod wheel;

pub use ball::ball_creep;
pub use consts::{PAIR_CACHE_LEN, RigidPair, RigidPairCache};
pub(crate) use frame::ForceCreepage;
pub use frame::{
    COMBINED_ITERATIONS, COMBINED_TOLERANCE, CombinedSolve, LawCache, RollFrame, solve_combined,
    solve_translation,
};
pub use wheel::{WheelContact, WheelInput, wheel_creep};

use crate::kinematics::BodyMotion;
use crate::vector::Vec3;

/// What an impulse-based engine has at one contact at the start of a step (world frame, SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidContact {
    /// Unit contact normal, from body p to body q.
    pub normal: Vec3,
    /// The contact point \[m\] (a wheel's: the centre of its patch).
    pub point: Vec3,
    /// Body p's motion and surface (a fixed body or none: at rest, any position).
    pub p: BodyMotion,
    /// Body q's motion and surface.
    pub q: BodyMotion,
    /// Last step's total normal impulse of the contact \[N s\] (`P = impulse/dt`; zero for a
    /// new contact, which then does not creep).
    pub normal_impulse: f64,
    /// Last step's total friction impulse on body p \[N s\] (world vector; the part along the
    /// normal is dropped).
    pub tangent_impulse: Vec3,
    /// The slip target the kernel gave this contact last step \[m/s\] ([`RigidCreep::target`];
    /// zero for a new contact or one left to Coulomb).
    pub last_target: Vec3,
    /// Time step \[s\].
    pub dt: f64,
    /// `Some(tol)`: leave the contact to Coulomb when its largest creep slip (at full
    /// utilisation) is below `tol` \[m/s\] (an "auto" contact, whose creep no one would see);
    /// `None`: always creep.
    pub auto_tolerance: Option<f64>,
}

/// Why the kernel left a contact to Coulomb.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoulombReason {
    /// No normal load (a new contact, or one that separates) or no friction.
    NoLoad,
    /// The contact does not roll (`v_roll = 0`), or a wheel's heading is undefined.
    NotRolling,
    /// An auto contact whose creep slip is below its tolerance ([`RigidContact::auto_tolerance`]).
    BelowTolerance,
    /// The tangential load is within the solver's rounding ([`solver_noise_force`]).
    BelowNoise,
    /// The contact's shape is outside the 3-D law's table (a crowned wheel's `a/b`).
    OutsideTable,
}

/// The kernel's answer for one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidCreep {
    /// `None` when the contact creeps; else why it is left to Coulomb (every other field is
    /// then zero).
    pub coulomb: Option<CoulombReason>,
    /// The creep slip target \[m/s\]: the velocity of q's surface relative to p's at the contact
    /// that the friction row should enforce (tangent; add it to the engine's target).
    pub target: Vec3,
    /// The friction force on p the target was built for \[N\] (`Q_t + Q_s`).
    pub force: Vec3,
    /// The twisting moment of spin creep on body q \[N m\] (along the normal; `-moment` on
    /// body p), to be applied after the step.
    pub moment: Vec3,
    /// The creep power booked, `Q . target + Mz w_twist` floored at zero \[W\].
    pub power: f64,
    /// The loop gain `g = m_t V dF/dQ / dt` at the solution (module docs).
    pub loop_gain: f64,
}

impl RigidCreep {
    /// A contact left to Coulomb for `reason`.
    pub fn coulomb(reason: CoulombReason) -> Self {
        Self {
            coulomb: Some(reason),
            target: Vec3::ZERO,
            force: Vec3::ZERO,
            moment: Vec3::ZERO,
            power: 0.0,
            loop_gain: 0.0,
        }
    }
    /// The kernels' first answer ([`ball_creep`], [`wheel_creep`]): a contact without load
    /// (`p_force` \[N\] not above zero: new, or within the prediction distance but apart) or
    /// without friction (`mu` not above zero) is left to Coulomb; `None` for a loaded contact
    /// with friction. A host may ask before it builds the kernel's input.
    pub fn unloaded(p_force: f64, mu: f64) -> Option<Self> {
        (!(p_force > 0.0 && mu > 0.0)).then(|| Self::coulomb(CoulombReason::NoLoad))
    }
    /// Whether the contact creeps.
    pub fn creeps(&self) -> bool {
        self.coulomb.is_none()
    }
}

/// Rounding ulps of the bodies' angular speeds below which a relative spin about the normal is
/// taken as f32 noise (no spin creep): the solver resolves angular velocities to about
/// `eps_f32 |w|`; 16 as for the tangential load's floor ([`solver_noise_force`]). Without it the
/// noise spin of straight rolling drove the spin terms and a light ball on a heavy slab
/// exceeded its paired energy bound by 1.2 %.
pub const SPIN_NOISE_ULPS: f64 = 16.0;

/// Rounding ulps of the contact's surface speed that a solve may leave in its tangential
/// impulse (measured in Rapier: in free rolling of a 0.1 m steel or rubber ball at 20 m/s,
/// 1/30 and 1/120 s, the load inferred settles at a median of 1-2 and at most ~7 of these).
pub const NOISE_ULPS: f64 = 16.0;

/// The relative spin `w_twist` \[rad/s\], or 0 when it is within [`SPIN_NOISE_ULPS`] f32 ulps of
/// `w_scale` \[rad/s\] (the angular speeds it was computed from: noise, not spin).
#[inline]
pub fn spin_above_noise(w_twist: f64, w_scale: f64) -> f64 {
    if w_twist.abs() > SPIN_NOISE_ULPS * f64::from(f32::EPSILON) * w_scale {
        w_twist
    } else {
        0.0
    }
}

/// The tangential force \[N\] below which a contact's measured load is only the rounding of an
/// f32 solve: the solver enforces a relative surface velocity built from f32 velocities of size
/// `u = |v_p| + |w_p| |c - x_p| + |v_q| + |w_q| |c - x_q|` \[m/s\], so it resolves that velocity
/// to about `eps_f32 u` and transmits a tangential impulse of up to `m_t eps_f32 u` that no load
/// asked for (`m_t = 1/inv_m` the contact's effective mass along the force \[kg\]). The floor is
/// `NOISE_ULPS eps_f32 u m_t / dt`. (A 0.1 m rubber ball rolling freely at 20 m/s gained 1.5e-4
/// of its energy from slip targets built below it.) Zero without a dynamic body (`inv_m <= 0`).
pub fn solver_noise_force(p: &BodyMotion, q: &BodyMotion, c: Vec3, inv_m: f64, dt: f64) -> f64 {
    if !(inv_m > 0.0 && dt > 0.0) {
        return 0.0;
    }
    let speed = |b: &BodyMotion| {
        b.velocity.length() + b.angular_velocity.length() * (c - b.position).length()
    };
    NOISE_ULPS * f64::from(f32::EPSILON) * (speed(p) + speed(q)) / (inv_m * dt)
}

/// The force estimate of the implicit solve: `Q* = Q_measured + (m_t/dt) tau_prev` \[N\] and the
/// inverse effective mass `inv_m` \[1/kg\] along `Q_measured + tau_prev` (along `fallback` when
/// that is zero), from the contact's last impulses and target.
fn force_estimate(c: &RigidContact, fallback: Vec3, inv_mass: impl Fn(Vec3) -> f64) -> (Vec3, f64) {
    let (n, dt) = (c.normal, c.dt);
    let q_meas = c.tangent_impulse.reject(n) * (1.0 / dt);
    let tau_prev = c.last_target.reject(n);
    let probe = (q_meas + tau_prev).try_normalize().unwrap_or(fallback);
    let inv_m = inv_mass(probe);
    let q_star = if inv_m > 0.0 {
        q_meas + tau_prev * (1.0 / (inv_m * dt))
    } else {
        q_meas
    };
    (q_star, inv_m)
}

/// The translation's part of the answer: the force and target of the implicit solve.
struct Translation {
    /// Creepages along `x` and `y` \[-\].
    cx: f64,
    cy: f64,
    /// Friction force on p, spin's included \[N\].
    force: Vec3,
    /// Slip target \[m/s\].
    target: Vec3,
    /// Loop gain at the solution.
    gain: f64,
    /// Whether the force is capped at the capacity (the contact slides).
    capped: bool,
}

/// The implicit solve of the translation (module docs) in `frame`, for the force estimate
/// `q_star_t` less the spin's (world) \[N\], the spin's force `q_s` \[N\], `k = m_t V/dt` \[N\],
/// the lateral ratio `r`, the capacity `mu_t` \[N\], the rolling speed `roll` \[m/s\] and the
/// creepage law along `x` with its slope at zero.
#[allow(clippy::too_many_arguments)]
fn translate(
    frame: &RollFrame,
    q_star_t: Vec3,
    q_s: Vec3,
    k: f64,
    r: f64,
    mu_t: f64,
    roll: f64,
    slope0: f64,
    creepage: impl Fn(f64) -> f64,
) -> Translation {
    let s = frame::solve_translation_with_creepage(
        frame.split(q_star_t),
        k,
        r,
        mu_t,
        slope0,
        &creepage,
    );
    let (q_t, ux, uy) = (s.q, s.ux, s.uy);
    let dq = 1e-6 * mu_t;
    let gain = if dq > 0.0 {
        k * (creepage((q_t + dq).min(mu_t)) - creepage((q_t - dq).max(0.0))) / (2.0 * dq)
    } else {
        0.0
    };
    // The law at the answer, as the solve evaluated it there (the same bits).
    let f = s.creepage.unwrap_or_else(|| creepage(q_t));
    let (cx, cy) = (f * ux, f * r * uy);
    let force = frame.join(q_t * ux, q_t * uy) + q_s;
    let target = frame.join(cx, cy) * roll;
    Translation {
        cx,
        cy,
        force,
        target,
        gain,
        capped: !(q_t < mu_t),
    }
}

/// The answer of a contact that creeps: the translation, the twisting moment `mz` on p about
/// `n` \[N m\] and the relative spin `w_twist` \[rad/s\] (for the booked power).
fn creeping(t: &Translation, n: Vec3, mz: f64, w_twist: f64) -> RigidCreep {
    RigidCreep {
        coulomb: None,
        target: t.target,
        force: t.force,
        moment: n * (-mz),
        power: (t.force.dot(t.target) + mz * w_twist).max(0.0),
        loop_gain: t.gain,
    }
}

#[cfg(test)]
mod tests;
