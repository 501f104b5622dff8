//! The creep law of one rigid ball contact, engine-free: what the hooks (crate::hooks) call once
//! per contact point. Everything Avian-specific (reading the manifold, the bodies, last step's
//! impulses) stays in the hooks; this module sees only vectors, forces and the pair's laws.
//!
//! # The law (Kalker 2000; Kuhn 2011)
//!
//! A loaded rolling contact creeps: the two surfaces slide relative to each other by the steady
//! creepage `xi = F(|Q|)` per unit rolled distance, with `F` the pair's steady law (Kalker's
//! `F_ss(s) = 3 mu P / (G a^2 C11) [1 - (1 - s)^(1/3)]`, `s = |Q|/(mu P)`, Kuhn 2011, eq. 1, or a
//! fitted law, creep-law's `SteadyLaw`), `a` Hertz's contact radius at the normal force `P`
//! (Johnson 1985, §4.2), `Q` the tangential force. The slip velocity the solver is asked for is
//! `tau = F(|Q|) |v_roll| Q/|Q|` (`v_roll`: Kuhn & Bagi 2004's rolling velocity).
//!
//! # The implicit solve
//!
//! The force a step transmits depends on the target it is given: with the contact's effective
//! mass `m_t` along the force, `Q = Q* - (m_t/dt) tau`, where `Q* = Q_meas + (m_t/dt) tau_prev`
//! is the force estimate with last step's target taken out. The target therefore solves
//! `q + K F(q) = |Q*|` along `Q*` with `K = m_t |v_roll| / dt` (unique root: `F` rises). Its
//! steady state is the measured force whatever `K`; `K` sets how fast it is reached
//! (the loop gain `K F'(q)` is reported).
//!
//! Spin creep (the lateral force and twisting moment of a relative spin about the normal) is
//! not modelled here: contacts are solved as circular and spin-free.

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::root::illinois;
use creep_law::{PairMaterial, SteadyLaw, Vec3, hertz, kalker};

/// Rounding ulps below which a tangential force is only the rounding of an f32 solve: the
/// solver resolves relative surface velocities of size `u` to about `eps_f32 u`, so it
/// transmits up to `m_t eps_f32 u / dt` that no load asked for; a target built on it would turn
/// rounding into slip that does work.
const NOISE_ULPS: f64 = 16.0;

/// The laws of one pair of materials and shapes, built once per contact pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PairLaw {
    /// The combined pair (moduli, `R*`, `C11`, friction).
    pub pair: PairMaterial,
    /// The steady creep law at the pair's `nu`, `C11`.
    pub law: SteadyLaw,
}

/// What one ball contact is at the start of a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BallContact {
    /// Unit normal from p to q.
    pub normal: Vec3,
    /// Last step's normal force \[N\].
    pub p_force: f64,
    /// Last step's tangential force on p \[N\].
    pub q_meas: Vec3,
    /// Last step's creep slip target (q's surface relative to p's) \[m/s\].
    pub tau_prev: Vec3,
    /// Body p's motion and surface.
    pub p: BodyMotion,
    /// Body q's motion and surface.
    pub q: BodyMotion,
    /// Contact point \[m\].
    pub point: Vec3,
    /// Inverse effective mass of the contact along the tangential force \[1/kg\].
    pub inv_mass: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Below this saturated slip \[m/s\] the contact is left to Coulomb (`None`: always creep).
    pub auto_tolerance: Option<f64>,
}

/// Why a contact was left to Coulomb friction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum CoulombReason {
    /// No load, no rolling or no friction.
    Unloaded,
    /// The saturated slip is below the auto tolerance.
    Auto,
    /// The tangential force is within the solver's rounding.
    Noise,
}

/// What the law asks of the solver for one contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum BallOutcome {
    /// Creep: the slip target and what goes with it.
    Creep {
        /// Creep slip target, q's surface relative to p's \[m/s\].
        target: Vec3,
        /// The tangential force the target was built from (on p) \[N\].
        q_used: Vec3,
        /// Creep power `Q . tau` \[W\].
        power: f64,
        /// Loop gain `K F'(q)` of the implicit solve \[-\].
        gain: f64,
    },
    /// Coulomb friction (no target).
    Coulomb(CoulombReason),
}

/// The creep slip target of one ball contact (module docs).
pub(crate) fn ball_contact(law: &PairLaw, c: &BallContact) -> BallOutcome {
    let pair = &law.pair;
    let mu = pair.mu;
    let p_force = c.p_force;
    if !(p_force > 0.0 && mu > 0.0 && c.dt > 0.0) {
        return BallOutcome::Coulomb(CoulombReason::Unloaded);
    }
    let n = c.normal;
    let rates = contact_rates(&c.p, &c.q, c.point, n);
    let roll = rates.v_roll.length();
    if !(roll > 0.0) {
        return BallOutcome::Coulomb(CoulombReason::Unloaded);
    }
    let a = hertz::contact_radius(pair, p_force);
    let mu_p = mu * p_force;
    if let Some(tol) = c.auto_tolerance {
        let bound = kalker::steady_creepage(1.0, mu_p, pair.g, a, pair.c11) * roll;
        if bound < tol {
            return BallOutcome::Coulomb(CoulombReason::Auto);
        }
    }
    let inv_m = c.inv_mass;
    let m_over_dt = if inv_m > 0.0 {
        1.0 / (inv_m * c.dt)
    } else {
        0.0
    };
    let q_star = (c.q_meas + c.tau_prev.reject(n) * m_over_dt).reject(n);
    let speed =
        |b: &BodyMotion| b.velocity.length() + b.angular_velocity.length() * (c.point - b.position).length();
    let noise = NOISE_ULPS * f64::from(f32::EPSILON) * (speed(&c.p) + speed(&c.q)) * m_over_dt;
    let q_star_abs = q_star.length();
    if !(q_star_abs > noise) {
        return BallOutcome::Coulomb(CoulombReason::Noise);
    }
    let u = q_star * (1.0 / q_star_abs);
    let k = roll * m_over_dt;
    let creepage = |q: f64| law.law.creepage_for_force(q, mu_p, pair.g, a);
    let hi = q_star_abs.min(mu_p);
    let h = |q: f64| q + k * creepage(q) - q_star_abs;
    let q = if k > 0.0 {
        let (fa, fb) = (h(0.0), h(hi));
        if fb <= 0.0 {
            hi
        } else {
            illinois(h, (0.0, fa), (hi, fb), 100, |_, fc, kb| {
                (kb.b - kb.a).abs() <= 1e-13 * hi || fc == 0.0
            })
            .root_or_midpoint()
        }
    } else {
        hi
    };
    let dq = 1e-6 * mu_p;
    let gain = k * (creepage((q + dq).min(mu_p)) - creepage((q - dq).max(0.0))) / (2.0 * dq);
    let f = creepage(q);
    let target = u * (f * roll);
    let q_used = u * q;
    BallOutcome::Creep {
        target,
        q_used,
        power: q_used.dot(target).max(0.0),
        gain,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use creep_law::{CreepModel, Material, Surface};

    fn steel_ball_on_plane(r: f64) -> PairLaw {
        let m = Material::steel();
        let pair = PairMaterial::new(&m, &m, Surface::Sphere(r), Surface::Plane)
            .and_then(|p| p.with_friction(0.5))
            .unwrap();
        PairLaw {
            pair,
            law: SteadyLaw::with_c11(CreepModel::Kuhn, pair.nu, pair.c11),
        }
    }

    /// A ball of radius `r` above a fixed plane, rolling along +x at `v` (p = ball, q = plane,
    /// n = -y).
    fn rolling(r: f64, v: f64, q_meas: Vec3, tau_prev: Vec3, inv_mass: f64) -> BallContact {
        BallContact {
            normal: Vec3::new(0.0, -1.0, 0.0),
            p_force: 100.0,
            q_meas,
            tau_prev,
            p: BodyMotion {
                position: Vec3::new(0.0, r, 0.0),
                velocity: Vec3::new(v, 0.0, 0.0),
                angular_velocity: Vec3::new(0.0, 0.0, -v / r),
                surface: Surface::Sphere(r),
            },
            q: BodyMotion {
                position: Vec3::new(0.0, -1.0, 0.0),
                velocity: Vec3::ZERO,
                angular_velocity: Vec3::ZERO,
                surface: Surface::Plane,
            },
            point: Vec3::ZERO,
            inv_mass,
            dt: 1.0 / 60.0,
            auto_tolerance: None,
        }
    }

    #[test]
    fn steady_state_returns_the_measured_force_and_kalkers_creepage() {
        let law = steel_ball_on_plane(0.1);
        let (v, q) = (2.0, Vec3::new(12.0, 0.0, 0.0));
        let a = hertz::contact_radius(&law.pair, 100.0);
        let f = law.law.creepage_for_force(12.0, 50.0, law.pair.g, a);
        // Fed its own steady target, the solve gives the same force and target back.
        let c = rolling(0.1, v, q, Vec3::new(f * v, 0.0, 0.0), 0.2);
        let BallOutcome::Creep { target, q_used, gain, .. } = ball_contact(&law, &c) else {
            panic!("no creep");
        };
        assert!((q_used - q).length() < 1e-9 * 12.0, "{q_used:?}");
        assert!((target.x - f * v).abs() < 1e-9 * f * v && target.y == 0.0, "{target:?}");
        assert!(gain > 0.0 && gain.is_finite());
    }

    #[test]
    fn solve_satisfies_its_equation_and_saturates_at_mu_p() {
        let law = steel_ball_on_plane(0.1);
        let v = 3.0;
        let c = rolling(0.1, v, Vec3::new(0.0, 0.0, 20.0), Vec3::ZERO, 0.5);
        let BallOutcome::Creep { target, q_used, .. } = ball_contact(&law, &c) else {
            panic!("no creep");
        };
        let k = v / (0.5 * c.dt);
        let q = q_used.length();
        let a = hertz::contact_radius(&law.pair, 100.0);
        let f = law.law.creepage_for_force(q, 50.0, law.pair.g, a);
        assert!((q + k * f - 20.0).abs() < 1e-9 * 20.0, "{q}");
        assert!((target.z - f * v).abs() < 1e-12);
        // A force estimate far beyond mu P: the contact slides at mu P.
        let c = rolling(0.1, v, Vec3::new(1.0e6, 0.0, 0.0), Vec3::ZERO, 0.0);
        let BallOutcome::Creep { q_used, .. } = ball_contact(&law, &c) else {
            panic!("no creep");
        };
        assert_eq!(q_used.length(), 50.0);
    }

    #[test]
    fn unloaded_still_noise_and_auto_contacts_are_coulomb() {
        let law = steel_ball_on_plane(0.1);
        let mut c = rolling(0.1, 1.0, Vec3::new(5.0, 0.0, 0.0), Vec3::ZERO, 0.2);
        c.p_force = 0.0;
        assert_eq!(ball_contact(&law, &c), BallOutcome::Coulomb(CoulombReason::Unloaded));
        let c = rolling(0.1, 0.0, Vec3::new(5.0, 0.0, 0.0), Vec3::ZERO, 0.2);
        assert_eq!(ball_contact(&law, &c), BallOutcome::Coulomb(CoulombReason::Unloaded));
        let c = rolling(0.1, 1.0, Vec3::new(1e-9, 0.0, 0.0), Vec3::ZERO, 0.2);
        assert_eq!(ball_contact(&law, &c), BallOutcome::Coulomb(CoulombReason::Noise));
        let mut c = rolling(0.1, 1.0, Vec3::new(5.0, 0.0, 0.0), Vec3::ZERO, 0.2);
        c.auto_tolerance = Some(1.0);
        assert_eq!(ball_contact(&law, &c), BallOutcome::Coulomb(CoulombReason::Auto));
    }
}
