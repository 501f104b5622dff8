//! Transient extension of the steady creep law ([`crate::CreepModel::FittedTransient`]): the creep
//! rate does not jump to the steady one when rolling starts, it relaxes to it over a rolling
//! length of order `a`, in the manner of the relaxation length of tyre models (e.g. Pacejka,
//! *Tyre and Vehicle Dynamics*, 2nd ed. 2006, ch. 7, first-order lag of the slip over the
//! distance rolled; here the lag acts on the creep term of Kuhn's rule, not on the force).
//!
//! With `F(s) Q/|Q|` the steady creep rate of the current force (vector, [`crate::SteadyLaw`]),
//! the creep displacement of a step rolling `|du_roll|` is
//!
//! `du_creep = [beta F(s) Q/|Q| + (1 - beta) phi_2] |du_roll|`,
//!
//! where the lagged rate `phi_2` follows the steady rate through two equal first-order lags in
//! series over the rolled distance (per-contact state `phi_1`, `phi_2`, zero on a virgin contact):
//! `d phi_1/dx = (F Q/|Q| - phi_1)/L`, `d phi_2/dx = (phi_1 - phi_2)/L`, `L = l a sqrt(1 - s)`,
//! integrated exactly over each step with the target held (`t = |du_roll|/L`):
//! `phi_1 <- T + (phi_1 - T) e^-t`, `phi_2 <- T + [(phi_2 - T) + (phi_1 - T) t] e^-t`.
//!
//! Held force from a virgin contact (the force applied by a shift, then rolling): the creep rate
//! starts at `beta F(s)`, and the lag, S-shaped, brings it to `F(s)` after a few `L`; held
//! creepage: the force builds up faster than with Kuhn's rule while the lag fills. Limits:
//! without rolling the term is zero (the Cattaneo-Mindlin law, as in Kuhn's rule); in steady
//! rolling `phi_1 = phi_2 = F(s) Q/|Q|` and the steady law is recovered exactly. The lag length
//! shrinks with the stick zone (`sqrt(1 - s)`, the fitted law's variable, is the stick zone's
//! size in Johnson's picture) and vanishes at full slip.
//!
//! `beta` and `l` minimise the largest ratio of this tier's error to Kuhn's rule's over the
//! project's boundary-element transients (`crates/reference/data/transient_bem.csv`, from
//! `creep ref fit transient`: held force and held creepage at `Q/(mu P) = 0.3, 0.6, 0.9`,
//! `nu = 0, 0.25, 0.5`, grid N = 32), by a grid search in steps of 0.025 (`beta`) and 0.05 (`l`)
//! (`cargo run --release -p creep-reference --example tier_errors -- tune 2 rel`), rounded. The
//! boundary elements start at 57-62 % of the steady rate, reach it after 0.5 a (at 0.9 mu P) to
//! 1.4 a (at 0.3 mu P) and overshoot it by up to 14 % before settling; a lag cannot follow the
//! overshoot, which bounds the held-force error near 15 % (Kuhn's rule: 45 %). One lag does
//! slightly worse (worst case 2.5 times better than Kuhn's rule instead of 2.7).

use crate::vector::Vec2;

/// Fraction `beta` of the steady creep rate that acts at once when rolling starts [-].
pub const INITIAL_FRACTION: f64 = 0.5;

/// `l` of the relaxation length `L = l a sqrt(1 - s)` of each lag [-].
pub const RELAXATION_LENGTH: f64 = 0.3;

/// Relaxation length `L` \[m\] at force ratio `s` (clamped to `[0, 1]`) and contact radius `a`
/// \[m\]: `l a sqrt(1 - s)` ([`RELAXATION_LENGTH`]); zero at full slip.
#[inline]
pub fn relaxation_length(s: f64, a: f64) -> f64 {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    RELAXATION_LENGTH * a * (1.0 - s).sqrt()
}

/// One step of the transient creep rate: returns `(rate, lag_new)` for the steady rate vector
/// `target` = `F(s) Q/|Q|` [-], the lag state `lag = [phi_1, phi_2]` [-] at the start of the
/// step, the rolled distance `roll` \[m\] (>= 0) and the relaxation length `length` \[m\] (> 0;
/// otherwise the lag is skipped and the steady rate acts at once). The creep displacement of the
/// step is `rate * roll`.
#[inline]
pub fn step(target: Vec2, lag: [Vec2; 2], roll: f64, length: f64) -> (Vec2, [Vec2; 2]) {
    if !(length > 0.0) || !(roll >= 0.0) {
        return (target, [target; 2]);
    }
    let rate = target * INITIAL_FRACTION + lag[1] * (1.0 - INITIAL_FRACTION);
    let t = roll / length;
    let e = (-t).exp();
    let d1 = lag[0] - target;
    let d2 = lag[1] - target;
    (rate, [target + d1 * e, target + (d2 + d1 * t) * e])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_target_relaxes_step_size_free() {
        let target = Vec2::new(0.01, 0.0);
        let l = 0.5;
        let (mut a, mut b) = ([Vec2::ZERO; 2], [Vec2::ZERO; 2]);
        for _ in 0..100 {
            a = step(target, a, 0.01, l).1;
        }
        for _ in 0..10 {
            b = step(target, b, 0.1, l).1;
        }
        // Two lags in series from zero: 1 - (1 + t) e^-t at t = 1/l.
        let t = 1.0 / l;
        let exact = 0.01 * (1.0 - (1.0 + t) * (-t).exp());
        assert!((a[1].x - exact).abs() < 1e-15 && (b[1].x - exact).abs() < 1e-15);
        let (rate, _) = step(target, [Vec2::ZERO; 2], 0.01, l);
        assert!((rate.x - INITIAL_FRACTION * 0.01).abs() < 1e-18);
        // Steady: the target is a fixed point with rate = target.
        let (rate, lag) = step(target, [target; 2], 0.3, l);
        assert_eq!((rate, lag), (target, [target; 2]));
        // No length: at once.
        assert_eq!(step(target, [Vec2::ZERO; 2], 0.1, 0.0).0, target);
        assert!(relaxation_length(0.5, 2.0) > 0.0);
        assert_eq!(relaxation_length(1.0, 2.0), 0.0);
        assert_eq!(
            relaxation_length(f64::NAN, 1.0),
            relaxation_length(0.0, 1.0)
        );
    }
}
