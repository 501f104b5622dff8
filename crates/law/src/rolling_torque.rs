//! Contact-torque rolling resistance: the *velocity-preserving* category of the talk (a moment at
//! the contact resists relative rolling: gears, adhesion, visco- and elasto-plasticity), kept
//! for comparison with creep-friction. The three model types of Ai, Chen, Rotter & Ooi (2011,
//! "Assessment of rolling resistance models in discrete element simulations", Powder Technol.
//! 206, 269-282):
//!
//! * type A, constant directional torque: `M = -mu_r R* P w_r / |w_r|`;
//! * type B, viscous: `M = -beta R* P |v_w| w_r / |w_r|` with `v_w = R* |w_r|` the rolling speed,
//!   i.e. `M = -beta R*^2 P w_r` (`beta` [s/m]);
//! * type C, elastic-plastic spring-dashpot (EPSD; Iwashita & Oda 1998 in Ai's form): spring
//!   torque `M_k += -k_r w_r dt`, capped at `|M_k| <= M_m = mu_r R* P`, with
//!   `k_r = 2.25 k_n mu_r^2 R*^2`, plus a dashpot `M_d = -eta C_crit w_r`,
//!   `C_crit = 2 sqrt(I_r k_r)`, switched off once the spring is fully mobilised (Ai's f = 0).
//!
//! `w_r = (w_q - w_p)_t` is the relative rolling angular velocity [rad/s] (see
//! [`crate::kinematics::ContactRates::w_roll`]); the returned torque `M` acts on q and `-M` on p
//! [N m]. Torques are 3-D vectors in the tangent plane.

use crate::error::{LawError, finite_non_negative};
use crate::vector::Vec3;

/// A contact-torque rolling resistance model (Ai et al. 2011).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RollingModel {
    /// Type A: constant directional torque `mu_r R* P` against the rolling.
    ConstantTorque {
        /// Rolling friction coefficient mu_r [-].
        mu_r: f64,
    },
    /// Type B: viscous, `M = -beta R*^2 P w_r`.
    Viscous {
        /// Viscous rolling coefficient beta [s/m].
        beta: f64,
    },
    /// Type C: elastic-plastic spring-dashpot.
    Epsd {
        /// Rolling friction coefficient mu_r [-].
        mu_r: f64,
        /// Damping ratio eta [-] of the rolling dashpot (Ai et al. use 0.3).
        eta: f64,
    },
}

impl RollingModel {
    /// Type A with a validated `mu_r >= 0` [-].
    pub fn constant_torque(mu_r: f64) -> Result<Self, LawError> {
        Ok(Self::ConstantTorque {
            mu_r: finite_non_negative("rolling friction mu_r", mu_r, "-")?,
        })
    }
    /// Type B with a validated `beta >= 0` [s/m].
    pub fn viscous(beta: f64) -> Result<Self, LawError> {
        Ok(Self::Viscous {
            beta: finite_non_negative("viscous rolling coefficient beta", beta, "s/m")?,
        })
    }
    /// Type C with validated `mu_r >= 0` [-] and damping ratio `eta >= 0` [-].
    pub fn epsd(mu_r: f64, eta: f64) -> Result<Self, LawError> {
        Ok(Self::Epsd {
            mu_r: finite_non_negative("rolling friction mu_r", mu_r, "-")?,
            eta: finite_non_negative("rolling damping ratio eta", eta, "-")?,
        })
    }
}

/// Inputs of one rolling-torque evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingInput {
    /// Normal force P \[N\].
    pub p: f64,
    /// Effective rolling radius R* \[m\].
    pub r_star: f64,
    /// Normal contact stiffness k_n [N/m] (EPSD only; e.g. Hertz's `2 E* a`).
    pub k_n: f64,
    /// Relative rolling angular velocity `(w_q - w_p)_t` [rad/s].
    pub w_roll: Vec3,
    /// Unit contact normal (EPSD only: the stored spring torque is kept in the tangent plane).
    pub normal: Vec3,
    /// Time step \[s\] (EPSD only).
    pub dt: f64,
    /// Equivalent rolling inertia `I_r` [kg m^2] (EPSD damping only; see [`epsd_rolling_inertia`]).
    pub rolling_inertia: f64,
}

/// Output of one rolling-torque evaluation.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollingStep {
    /// Torque on body q [N m] (`-torque` on p).
    pub torque: Vec3,
    /// Energy dissipated in the step \[J\] (>= 0): `-M . w_r dt` for types A and B; dashpot work
    /// plus plastic rotation times `M_m` for EPSD.
    pub dissipation: f64,
    /// Whether the resistance is fully mobilised (type A always when rolling; EPSD at its cap).
    pub mobilised: bool,
}

/// History of one contact's EPSD spring (unused by types A and B).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollingState {
    /// Spring torque on q [N m].
    pub spring: Vec3,
}

/// `I_r = [1/(I_p + m_p r_p^2) + 1/(I_q + m_q r_q^2)]^-1` [kg m^2] (Ai et al. 2011, model C); a
/// body with infinite mass or inertia (a wall) contributes nothing to the sum.
pub fn epsd_rolling_inertia(m_p: f64, i_p: f64, r_p: f64, m_q: f64, i_q: f64, r_q: f64) -> f64 {
    let term = |m: f64, i: f64, r: f64| {
        let v = i + m * r * r;
        if v.is_finite() && v > 0.0 {
            1.0 / v
        } else {
            0.0
        }
    };
    let s = term(m_p, i_p, r_p) + term(m_q, i_q, r_q);
    if s > 0.0 { 1.0 / s } else { 0.0 }
}

impl RollingModel {
    /// Torque of the model for one step. Non-finite or non-positive `p` gives no torque (and
    /// resets the EPSD spring).
    pub fn torque(&self, state: &mut RollingState, input: &RollingInput) -> RollingStep {
        let RollingInput {
            p,
            r_star,
            k_n,
            w_roll,
            normal,
            dt,
            rolling_inertia,
        } = *input;
        if !(p > 0.0 && p.is_finite() && r_star.is_finite() && w_roll.is_finite()) {
            state.spring = Vec3::ZERO;
            return RollingStep::default();
        }
        let w = w_roll.length();
        let dt = if dt.is_finite() && dt > 0.0 { dt } else { 0.0 };
        match *self {
            RollingModel::ConstantTorque { mu_r } => {
                let Some(dir) = w_roll.try_normalize() else {
                    return RollingStep::default();
                };
                let m = mu_r * r_star * p;
                RollingStep {
                    torque: dir * -m,
                    dissipation: m * w * dt,
                    mobilised: true,
                }
            }
            RollingModel::Viscous { beta } => {
                let c = beta * r_star * r_star * p;
                RollingStep {
                    torque: w_roll * -c,
                    dissipation: c * w * w * dt,
                    mobilised: false,
                }
            }
            RollingModel::Epsd { mu_r, eta } => {
                let k_r = 2.25 * k_n * mu_r * mu_r * r_star * r_star;
                let m_max = mu_r * r_star * p;
                // Keep the stored torque in the current tangent plane, with its magnitude.
                let old = state.spring;
                let mut spring = old.reject(normal);
                let (lo, ln) = (old.length(), spring.length());
                if ln > 0.0 && lo > 0.0 {
                    spring = spring * (lo / ln);
                }
                let trial = spring - w_roll * (k_r * dt);
                let t = trial.length();
                let (spring, plastic, mobilised) = if t > m_max && t > 0.0 {
                    let kept = trial * (m_max / t);
                    let plastic = if k_r > 0.0 { (t - m_max) / k_r } else { w * dt };
                    (kept, plastic, true)
                } else {
                    (trial, 0.0, false)
                };
                state.spring = if spring.is_finite() {
                    spring
                } else {
                    Vec3::ZERO
                };
                let c = if mobilised || !(k_r > 0.0) || !(rolling_inertia > 0.0) {
                    0.0
                } else {
                    eta * 2.0 * (rolling_inertia * k_r).sqrt()
                };
                let damping = w_roll * -c;
                RollingStep {
                    torque: state.spring + damping,
                    dissipation: m_max * plastic + c * w * w * dt,
                    mobilised,
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn input(w: Vec3) -> RollingInput {
        RollingInput {
            p: 10.0,
            r_star: 0.01,
            k_n: 1e6,
            w_roll: w,
            normal: Vec3::Z,
            dt: 1e-4,
            rolling_inertia: 1e-6,
        }
    }

    #[test]
    fn constant_torque_opposes_rolling() {
        let m = RollingModel::constant_torque(0.05).unwrap();
        let mut s = RollingState::default();
        let out = m.torque(&mut s, &input(Vec3::new(0.0, 3.0, 0.0)));
        assert!((out.torque - Vec3::new(0.0, -0.05 * 0.01 * 10.0, 0.0)).length() < 1e-15);
        assert!((out.dissipation - 0.05 * 0.01 * 10.0 * 3.0 * 1e-4).abs() < 1e-18);
        assert_eq!(m.torque(&mut s, &input(Vec3::ZERO)).torque, Vec3::ZERO);
    }

    #[test]
    fn viscous_is_linear_in_rolling_rate() {
        let m = RollingModel::viscous(0.2).unwrap();
        let mut s = RollingState::default();
        let a = m.torque(&mut s, &input(Vec3::new(1.0, 0.0, 0.0))).torque;
        let b = m.torque(&mut s, &input(Vec3::new(2.0, 0.0, 0.0))).torque;
        assert!((b - a * 2.0).length() < 1e-18);
        assert!((a.x + 0.2 * 1e-4 * 10.0).abs() < 1e-15);
    }

    #[test]
    fn epsd_is_elastic_then_capped_and_dissipates_over_a_cycle() {
        let m = RollingModel::epsd(0.1, 0.0).unwrap();
        let inp = input(Vec3::new(5.0, 0.0, 0.0));
        let k_r = 2.25 * inp.k_n * 0.01 * inp.r_star * inp.r_star;
        let m_max = 0.1 * inp.r_star * inp.p;
        let mut s = RollingState::default();
        let mut theta = 0.0;
        let mut dissipated = 0.0;
        for _ in 0..400 {
            let out = m.torque(&mut s, &inp);
            theta += 5.0 * inp.dt;
            let expect = (k_r * theta).min(m_max);
            assert!(
                (out.torque.x + expect).abs() < 1e-12 * m_max,
                "theta={theta}"
            );
            dissipated += out.dissipation;
        }
        // Plastic rotation so far: theta - M_m / k_r.
        assert!((dissipated - m_max * (theta - m_max / k_r)).abs() < 1e-9 * m_max * theta);
        // Reverse: elastic unloading with stiffness k_r.
        let back = m.torque(&mut s, &input(Vec3::new(-5.0, 0.0, 0.0)));
        assert!((back.torque.x - (-m_max + k_r * 5.0 * 1e-4)).abs() < 1e-12 * m_max);
        assert!(!back.mobilised);
    }

    #[test]
    fn rejects_bad_parameters() {
        assert!(RollingModel::constant_torque(-0.1).is_err());
        assert!(RollingModel::viscous(f64::NAN).is_err());
        assert!(RollingModel::epsd(0.1, f64::INFINITY).is_err());
        let m = RollingModel::epsd(0.1, 0.3).unwrap();
        let mut s = RollingState { spring: Vec3::X };
        let mut inp = input(Vec3::X);
        inp.p = f64::NAN;
        assert_eq!(m.torque(&mut s, &inp).torque, Vec3::ZERO);
        assert_eq!(s.spring, Vec3::ZERO);
    }

    #[test]
    fn rolling_inertia_of_sphere_pair_and_wall() {
        let (m, r) = (2.0, 0.1);
        let i = 0.4 * m * r * r;
        let one = i + m * r * r;
        assert!((epsd_rolling_inertia(m, i, r, m, i, r) - one / 2.0).abs() < 1e-15);
        assert!(
            (epsd_rolling_inertia(m, i, r, f64::INFINITY, f64::INFINITY, 1.0) - one).abs() < 1e-15
        );
    }
}
