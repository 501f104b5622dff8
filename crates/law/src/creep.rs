//! Kuhn's creep-friction update for transient rolling and sliding of spheres (Kuhn 2011, the
//! talk, eq. 1; after Dahlberg & Alfredsson 2009 for cylinders):
//!
//! `dQ = c_CM^-1 ( du_disp - F_ss(|Q|/(mu P)) Q/|Q| |du_roll| )`
//!
//! The Cattaneo-Mindlin compliance `c_CM` with its load history is [`MindlinState`]; `F_ss` is
//! Kalker's steady creepage ([`crate::kalker::steady_creepage`]). Each step feeds the Cattaneo-Mindlin
//! algorithm the *effective* displacement `du_eff = du_disp - du_creep`, with the creep
//! displacement `du_creep = F_ss Q/|Q| |du_roll|` evaluated explicitly from the force at the start
//! of the step and the new normal force.
//!
//! Energy: the work `Q . du_disp` splits into the creep part `Q . du_creep = |Q| F_ss |du_roll|`
//! (dissipated: the slip of the rolling contact's trailing slip zone) and `Q . du_eff`, which the
//! Cattaneo-Mindlin springs store or dissipate by micro-slip.
//!
//! Stability guard (ours): an explicit creep step larger than the elastic displacement that would
//! unload `|Q|` to zero would flip the force (creep can relax a force, never reverse it). The creep
//! displacement of one step is therefore capped at that unloading displacement,
//! `2 delta_CM(|Q|/2)` (Mindlin & Deresiewicz 1953 unloading; `delta_CM` Mindlin's loading curve),
//! which is inactive whenever `F_ss |du_roll| <= |Q| / (8 G* a)` — all ordinary DEM steps.
//!
//! One entry point: [`CreepState::update`] takes the pair's law, [`CreepLaw`] (the pair's
//! material, its [`CreepModel`] and that model's [`SteadyLaw`], built once per pair), and one
//! step, [`CreepInput`] (`P`, optionally `a`, `du_disp`, `du_roll`). Tiers ([`CreepModel`]):
//! `Kuhn` is Kuhn's rule as above (the talk's model, Kalker's `F_ss`), `Fitted` the same rule
//! with the boundary-element-fitted steady law of [`crate::steady_law`] in place of `F_ss`, and
//! `FittedTransient` the fitted law with the relaxed creep rate of [`crate::transient_law`],
//! whose lag state lives in [`CreepState`]. Every tier's steady creep rate comes from
//! [`SteadyLaw`].

use crate::hertz;
use crate::material::PairMaterial;
use crate::mindlin::{MindlinState, MindlinStep};
use crate::pair::finite;
use crate::steady_law::{CreepModel, SteadyLaw};
use crate::transient_law;
use crate::vector::Vec2;

/// The creep-friction law of one contact pair: its combined material, its creep model and that
/// model's steady law ([`SteadyLaw::with_c11`] at the pair's `nu` and cached `C11`). Build it
/// once per pair (it holds the fitted law's coefficients) and pass it to every
/// [`CreepState::update`] of the pair's contacts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepLaw {
    pair: PairMaterial,
    model: CreepModel,
    steady: SteadyLaw,
}

impl CreepLaw {
    /// The law of `model` for `pair`.
    pub fn new(pair: PairMaterial, model: CreepModel) -> Self {
        Self {
            pair,
            model,
            steady: SteadyLaw::with_c11(model, pair.nu, pair.c11),
        }
    }

    /// The law of `model` for `pair` with its steady law given, for a host that builds the
    /// steady law once per pair of materials and meets contacts of other radii (the DEM pair
    /// kernel, creep-law `pair`): `steady` must be `SteadyLaw::with_c11(model, pair.nu,
    /// pair.c11)` (checked in debug builds).
    #[inline]
    pub fn from_parts(pair: PairMaterial, model: CreepModel, steady: SteadyLaw) -> Self {
        debug_assert_eq!(steady, SteadyLaw::with_c11(model, pair.nu, pair.c11));
        Self {
            pair,
            model,
            steady,
        }
    }

    /// Kuhn's rule ([`CreepModel::Kuhn`], the talk's model) for `pair`.
    pub fn kuhn(pair: PairMaterial) -> Self {
        Self::new(pair, CreepModel::Kuhn)
    }

    /// The pair's combined material.
    #[inline]
    pub fn pair(&self) -> &PairMaterial {
        &self.pair
    }

    /// The creep model (tier).
    #[inline]
    pub fn model(&self) -> CreepModel {
        self.model
    }

    /// The steady creep law of the model at the pair's Poisson ratio.
    #[inline]
    pub fn steady(&self) -> &SteadyLaw {
        &self.steady
    }
}

/// One step's input to [`CreepState::update`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepInput {
    /// Normal force at the end of the step \[N\] (not positive or not finite: open contact).
    pub p: f64,
    /// Contact radius at the end of the step \[m\]; `None`: Hertz's, [`hertz::contact_radius`]
    /// of `p` (give it when the host knows it better, e.g. `sqrt(R* delta)` from a DEM overlap).
    pub a: Option<f64>,
    /// Relative displacement of the step `du_disp = du_q - du_p` in the tangent plane \[m\].
    pub du_disp: Vec2,
    /// Rolling displacement of the step in the tangent plane \[m\] (Kuhn & Bagi 2004; only its
    /// length enters the law).
    pub du_roll: Vec2,
}

impl CreepInput {
    /// A step at normal force `p` \[N\] (Hertz's contact radius) with displacements `du_disp` and
    /// `du_roll` \[m\].
    #[inline]
    pub fn new(p: f64, du_disp: Vec2, du_roll: Vec2) -> Self {
        Self {
            p,
            a: None,
            du_disp,
            du_roll,
        }
    }

    /// This step with the contact radius `a` \[m\] given.
    #[inline]
    pub fn with_radius(self, a: f64) -> Self {
        Self { a: Some(a), ..self }
    }
}

/// What one creep-friction update did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepStep {
    /// Tangential force on p from q after the step \[N\].
    pub q: Vec2,
    /// Contact radius used \[m\].
    pub a: f64,
    /// Creep displacement of the step, `F_ss Q/|Q| |du_roll|` (after the guard) \[m\].
    pub creep_displacement: Vec2,
    /// Energy dissipated by Cattaneo-Mindlin micro-slip and gross slip \[J\] (>= 0).
    pub slip_dissipation: f64,
    /// Energy dissipated by creep, `Q . du_creep` \[J\]: `|Q| F_ss |du_roll|` >= 0 for Kuhn's rule
    /// and the fitted tier; for the transient tier it can be slightly negative for a step in
    /// which the force turns faster than the lagged creep rate follows.
    pub creep_dissipation: f64,
    /// Energy added by simplifying an over-full load memory \[J\] (>= 0, see
    /// [`MindlinStep::truncation_energy`]).
    pub truncation_energy: f64,
}

impl CreepStep {
    /// Total energy dissipated in the step \[J\].
    #[inline]
    pub fn dissipation(&self) -> f64 {
        self.slip_dissipation + self.creep_dissipation
    }
}

/// State of one creep-friction contact: its Cattaneo-Mindlin load history and, for
/// [`CreepModel::FittedTransient`], the lagged creep rate. `Default` is a virgin, open contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CreepState {
    mindlin: MindlinState,
    /// Lag state `[phi_1, phi_2]` of [`crate::transient_law`] [-] (zero unless the transient
    /// tier is used).
    lag: [Vec2; 2],
}

impl CreepState {
    /// A virgin, open contact.
    pub fn new() -> Self {
        Self::default()
    }

    /// Tangential force on p from q after the last update \[N\].
    #[inline]
    pub fn force(&self) -> Vec2 {
        self.mindlin.force()
    }

    /// A state from its parts: a Cattaneo-Mindlin memory and the transient tier's lag state
    /// (`[Vec2::ZERO; 2]` unless [`CreepModel::FittedTransient`] is used), e.g. read back from
    /// a flat history array.
    pub fn from_parts(mindlin: MindlinState, lag: [Vec2; 2]) -> Self {
        Self { mindlin, lag }
    }

    /// The underlying Cattaneo-Mindlin state (load history).
    #[inline]
    pub fn mindlin(&self) -> &MindlinState {
        &self.mindlin
    }

    /// Mutable access to the Cattaneo-Mindlin state (e.g. to rotate it with the tangent basis).
    /// Prefer [`CreepState::transform`], which also rotates the transient tier's lagged rate.
    #[inline]
    pub fn mindlin_mut(&mut self) -> &mut MindlinState {
        &mut self.mindlin
    }

    /// Lag state `[phi_1, phi_2]` of the transient tier [-] (slip per unit rolling distance;
    /// `phi_2` is the lagged creep rate, see [`crate::transient_law`]).
    #[inline]
    pub fn lag(&self) -> [Vec2; 2] {
        self.lag
    }

    /// Applies the linear map `m` (row-major, e.g. a rotation of the tangent basis) to every
    /// vector of the state: the Cattaneo-Mindlin memory ([`MindlinState::transform`]) and the
    /// lagged creep rate.
    pub fn transform(&mut self, m: [[f64; 2]; 2]) {
        self.mindlin.transform(m);
        for v in &mut self.lag {
            *v = Vec2::new(m[0][0] * v.x + m[0][1] * v.y, m[1][0] * v.x + m[1][1] * v.y);
        }
    }

    /// One step of the creep-friction rule of `law` (Kuhn 2011, the talk, eq. 1, with the steady
    /// law of [`CreepLaw::steady`] in place of `F_ss`; see the module doc): the normal force
    /// becomes `step.p` \[N\] with contact radius `step.a` \[m\] (Hertz's
    /// [`hertz::contact_radius`] when `None`, e.g. given from a DEM overlap), and the surfaces
    /// move by the relative displacement `du_disp = du_q - du_p` \[m\] while rolling by `du_roll`
    /// \[m\] (Kuhn & Bagi 2004; only its length enters), both in the tangent plane.
    /// [`CreepModel::FittedTransient`] also advances the lagged creep rate of
    /// [`crate::transient_law`]. Non-finite inputs count as zero motion / open contact.
    /// Switching the model of a live contact is allowed (the lag state starts from its last
    /// value, zero if never used).
    ///
    /// Always inlined (with the Cattaneo-Mindlin update), so that a host's loop compiled for a
    /// wider instruction set compiles the update for it too (the same bits).
    #[inline(always)]
    pub fn update(&mut self, law: &CreepLaw, step: CreepInput) -> CreepStep {
        let CreepLaw {
            pair,
            model,
            steady,
        } = law;
        let (pair, model) = (pair, *model);
        let CreepInput {
            p,
            a,
            du_disp,
            du_roll,
        } = step;
        let a = match a {
            Some(a) => a,
            None => hertz::contact_radius(pair, p),
        };
        let roll = du_roll.length();
        let q = self.mindlin.force();
        let q_abs = q.length();
        let open = !(p > 0.0 && finite(p) && a > 0.0);
        let rolling = roll > 0.0 && finite(roll);
        let mut creep_vec = Vec2::ZERO;
        let mut creep_dissipation = 0.0;
        if model == CreepModel::FittedTransient && (open || !self.lag.iter().all(|v| v.is_finite()))
        {
            self.lag = [Vec2::ZERO; 2];
        }
        if rolling && !open {
            let mu_p = pair.mu * p;
            // Steady creep rate of the current force (Kuhn: Kalker's F_ss).
            // (Kuhn's closed form inlined, the same bits: `pair::kuhn_creepage`.)
            let f = if q_abs > 0.0 {
                crate::pair::kuhn_creepage(steady, q_abs, mu_p, pair.g, a)
            } else {
                0.0
            };
            if model == CreepModel::FittedTransient {
                let target = if q_abs > 0.0 && f.is_finite() {
                    q * (f / q_abs)
                } else {
                    Vec2::ZERO
                };
                let s = if mu_p > 0.0 { q_abs / mu_p } else { 0.0 };
                let (rate, lag) = transient_law::step(
                    target,
                    self.lag,
                    roll,
                    transient_law::relaxation_length(s, a),
                );
                self.lag = lag;
                let mut c = rate * roll;
                let creep = c.length();
                if creep > 0.0 && q_abs > 0.0 {
                    let k_t = pair.tangential_stiffness(a);
                    if creep * k_t > q_abs {
                        c = c * (creep.min(unload_to_zero(q_abs, mu_p, k_t)) / creep);
                    }
                }
                if c.is_finite() {
                    creep_vec = c;
                    // Work of Q on the creep displacement: the lagged rate may point away from
                    // Q for a moment when Q turns, so this can be slightly negative.
                    creep_dissipation = q.dot(c);
                }
            } else if q_abs > 0.0 {
                // Kuhn's rule (Kalker's F_ss, or the fitted steady law), as in the module doc.
                let mut creep = f * roll;
                let k_t = pair.tangential_stiffness(a);
                if creep * k_t > q_abs {
                    creep = creep.min(unload_to_zero(q_abs, mu_p, k_t));
                }
                if finite(creep) && creep > 0.0 {
                    creep_vec = q * (creep / q_abs);
                    creep_dissipation = q_abs * creep;
                }
            }
        }
        let du_eff = if creep_vec != Vec2::ZERO {
            du_disp - creep_vec
        } else {
            du_disp
        };
        let MindlinStep {
            q: q_new,
            a,
            slip_dissipation,
            truncation_energy,
        } = self.mindlin.update_with_radius(pair, a, du_eff);
        CreepStep {
            q: q_new,
            a,
            creep_displacement: creep_vec,
            slip_dissipation,
            creep_dissipation,
            truncation_energy,
        }
    }
}

/// Displacement that unloads a force `q` \[N\] to zero along the Mindlin & Deresiewicz (1953)
/// unloading branch from a virgin loading: `2 delta_CM(q/2)`, with Mindlin's loading curve
/// `delta_CM(Q) = 3 mu P / (16 G* a) [1 - (1 - Q/(mu P))^(2/3)]` (`3 mu P/(16 G* a) = 3 mu P /
/// (2 k_t)`); `q / k_t` when `mu P` is infinite.
fn unload_to_zero(q: f64, mu_p: f64, k_t: f64) -> f64 {
    if !mu_p.is_finite() {
        return q / k_t;
    }
    let s = (0.5 * q / mu_p).min(1.0);
    let t = (1.0 - s).cbrt();
    2.0 * 3.0 * mu_p / (2.0 * k_t) * (1.0 - t * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kalker;

    fn pair() -> PairMaterial {
        crate::material::steel_ball_on_plane()
    }

    #[test]
    fn no_rolling_is_plain_cattaneo_mindlin() {
        let pair = pair();
        let mut c = CreepState::new();
        let mut m = MindlinState::new();
        for i in 0..100 {
            let du = Vec2::new((i as f64).sin(), (0.3 * i as f64).cos()) * 2e-7;
            let p = 100.0 + 50.0 * (0.1 * i as f64).sin();
            let a = c.update(&CreepLaw::kuhn(pair), CreepInput::new(p, du, Vec2::ZERO));
            let b = m.update(&pair, p, du);
            assert_eq!(a.q, b.q);
            assert_eq!(a.slip_dissipation, b.slip_dissipation);
            assert_eq!(a.creep_dissipation, 0.0);
            assert_eq!(c.mindlin(), &m);
        }
    }

    #[test]
    fn unload_to_zero_matches_masing() {
        // At q = 0.5 mu P the Masing unloading 2 delta(q/2) is exactly the closed form.
        let (mu_p, k_t) = (30.0, 1e7);
        let d = unload_to_zero(15.0, mu_p, k_t);
        let ds = 3.0 * mu_p / (2.0 * k_t);
        assert!((d - 2.0 * ds * (1.0 - 0.75f64.powf(2.0 / 3.0))).abs() < 1e-18);
        // Small q: q / k_t.
        assert!((unload_to_zero(1e-6, mu_p, k_t) * k_t / 1e-6 - 1.0).abs() < 1e-6);
    }

    #[test]
    fn steady_rolling_creepage_is_kalkers() {
        // Roll at held displacement rate ratio xi: Q converges to Kalker's steady force.
        let pair = pair();
        let p = 100.0;
        let a = hertz::contact_radius(&pair, p);
        let mu_p = pair.mu * p;
        for s_target in [0.2, 0.6, 0.9] {
            let xi = kalker::steady_creepage(s_target, mu_p, pair.g, a, pair.c11);
            let mut st = CreepState::new();
            st.update(
                &CreepLaw::kuhn(pair),
                CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
            );
            let dr = a / 50.0;
            for _ in 0..5000 {
                st.update(
                    &CreepLaw::kuhn(pair),
                    CreepInput::new(p, Vec2::new(xi * dr, 0.0), Vec2::new(dr, 0.0)),
                );
            }
            let s = st.force().x / mu_p;
            assert!((s - s_target).abs() < 1e-6, "target {s_target}: {s}");
        }
    }

    #[test]
    fn huge_rolling_step_relaxes_but_never_reverses() {
        let pair = pair();
        let p = 100.0;
        let a = hertz::contact_radius(&pair, p);
        let mut st = CreepState::new();
        st.update(
            &CreepLaw::kuhn(pair),
            CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
        );
        st.update(
            &CreepLaw::kuhn(pair),
            CreepInput::new(p, Vec2::new(1e-6, 0.0), Vec2::ZERO),
        );
        let q0 = st.force().x;
        assert!(q0 > 0.0);
        let step = st.update(
            &CreepLaw::kuhn(pair),
            CreepInput::new(p, Vec2::ZERO, Vec2::new(100.0 * a, 0.0)),
        );
        assert!(step.q.x >= -1e-12 * q0 && step.q.x < q0, "{:?}", step.q);
        assert!(step.creep_dissipation >= 0.0);
    }
}
