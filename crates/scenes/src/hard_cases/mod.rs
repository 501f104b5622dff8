//! The hard-case matrix of the rigid regime: scenes where the feedback
//! Q -> creep slip -> Q is strong (long steps, soft material near the friction limit, a 1000:1
//! mass ratio, fast spin, a column of ten spheres), plus a sphere at rest. Each V-incline case
//! runs [`STEPS`] steps twice, once with creep-friction (`Fidelity::Creep`) and once with
//! `Fidelity::Coulomb` (the hook is called but leaves Rapier's friction alone), same scene and
//! settings, and checks ([`Verdict`]s, each a value against a limit):
//!
//! * no NaN (positions, velocities, the plugin's forces);
//! * no energy gain beyond plain Rapier's: the mechanical energy of the creep run never exceeds
//!   the Coulomb run's at the same step by more than 1e-6 of the initial energy (no scene has
//!   external work: gravity and the V-incline force below are conservative fields);
//! * `|Q| <= mu P` for the force the plugin used (each step, every contact) and for Rapier's own
//!   total impulses of the step;
//! * the measured quantity still converges (per case: the creep slip against Kalker's `F_ss`, the
//!   rolling state after the spin, the column coming to rest without drift).
//!
//! The test `crates/scenes/tests/hard_cases.rs` asserts every verdict of every case (the
//! engine limits as ignored tests), and `creep report` tabulates them with their margins: both
//! call [`HardCase::run`].
//!
//! How the creep and the energy are judged depends on the size of the creep against the
//! engine's own errors ([`Check`]): stiff materials (creepage ~3e-4, below the engine's own
//! rolling slip of 1e-3..4e-2 per rolled distance) step by step against a Coulomb twin from the
//! same state; soft rubber (creepage ~5e-2) run against run.
//!
//! The matrix ([`HardCase::ALL`]) and where each case runs:
//! * dt = 1/30 s, steel: passes.
//! * rubber-soft G (1 MPa) at Q/(mu P) = 0.8, creepage ~5e-2: passes at 1/240 s; at 1/60 s
//!   Rapier's own Coulomb run already slips 10 % of the rolled distance on this contact (an
//!   engine limit).
//! * mass ratio 1000: a light ball on a heavy slab passes; a heavy ball on a light slab is
//!   beyond Rapier's Gauss-Seidel (the light slab takes up the slip target; engine limit).
//! * 100 rad/s spin: passes (creep measured while the ball rolls to and fro, not at rest).
//! * a column of 10 spheres: passes (and stays at rest without drift).
//! * a sphere at rest on a plane for 10^4 steps: no creeping drift (< 1e-6 m).
//!
//! # The V-incline
//! An incline (tilted gravity on a flat fixed cuboid) accelerates for ever: at 1/30 s it would
//! run 10^5 m in 10^4 steps (and f32 positions would hide the slip). So the incline's
//! down-slope component of gravity, `m g sin(theta)`, is applied as a force field that points
//! towards `x = 0` from both sides (potential `m g sin(theta) |x|`), the normal component
//! `g cos(theta)` stays gravity: the ball rolls down one incline and up the other, for ever,
//! with the incline's constant `Q = (2/7) m g sin(theta)` and `P = m g cos(theta)` (Q flips sign
//! at `x = 0`). Energy is conserved but for the engine's own losses and creep.
//!
//! # The measured creep
//! Position-based: per step, the slip of the ball's contact point along x, `dx + R dtheta_z`
//! (relative to the support), signed by the incline force (creep slips along the force, Q being
//! opposite to it), summed over the run: `W`. For steady rolling, `W = F_ss(s) sum |dx|` with
//! `s = (2/7) tan(theta) / mu` (Kalker 2000; Kuhn 2011). The creep run's `W` minus the Coulomb
//! run's (the engine's own spurious slip) is compared with that.
//!
//! # Energy
//! `E = sum_b [ KE_b - m_b g . (x_b - x_b0) ] + m g sin(theta) |x| + (h/2) sum_b F_b . v_b`,
//! with `F_b` the conservative force on body b (gravity and the incline field) and `h` the
//! solver substep (`dt / num_solver_iterations`): Rapier integrates each substep with
//! symplectic Euler (`v += F/m h; x += v h`), whose exact invariant for a constant force is this
//! leap-frog corrected energy (the same half-step shift as Rapier's
//! `gravitational_potential_energy`; Hairer, Lubich & Wanner 2006, *Geometric Numerical
//! Integration*, §I.1.4). Without the correction the energy of a rolling ball oscillates by
//! `h F v`, far above 1e-6 of E.

mod cases;
mod energy;
pub mod fast_rolling;
mod run;
mod vee;
mod verdict;

/// Standard gravity [m/s^2].
const G: f64 = 9.81;

/// Steps per run of every case.
pub const STEPS: usize = 10_000;

/// Largest energy gain of the creep run over plain Rapier's, relative to the initial energy
/// (the tolerance; the f64 evaluation of f32 states is good to ~1e-7 of E).
pub const ENERGY_TOLERANCE: f64 = 1e-6;

/// Largest `|creep / Kalker - 1|` of a converging case (see [`HardCase::run`]).
pub const CREEP_TOLERANCE: f64 = 0.25;

pub use cases::*;
use energy::*;
pub use run::*;
use vee::*;
pub use verdict::*;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdict_margins() {
        let v = Verdict::new(
            "x",
            0.8,
            Bound::Within {
                centre: 1.0,
                half_width: 0.25,
            },
        );
        assert!(v.passed());
        assert!((v.margin() - 0.05).abs() < 1e-12);
        assert!((v.relative_margin() - 0.2).abs() < 1e-12);
        let v = Verdict::new("e", 2e-6, Bound::AtMost(1e-6));
        assert!(!v.passed() && v.margin() < 0.0);
        let v = Verdict::new("nan", f64::NAN, Bound::AtMost(1.0));
        assert!(!v.passed());
        let v = Verdict::new("n", 3.0, Bound::Above(0.0));
        assert!(v.passed() && v.margin() == 3.0);
        assert!(HardCase::run_steps(HardCase::AtRest, 0).is_err());
    }
}
