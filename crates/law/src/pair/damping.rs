//! Restitution-based normal damping of the Hertz contact.
//!
//! The damping force is Tsuji, Tanaka & Ishida's (1992, "Lagrangian numerical simulation of plug
//! flow of cohesionless particles in a horizontal pipe", Powder Technol. 71, 239-250) form
//!
//! `P = k_H delta^(3/2) + alpha sqrt(m* k_H) delta^(1/4) delta_dot`, `k_H = (4/3) E* sqrt(R*)`,
//!
//! with `m*` the pair's reduced mass. Scaling `delta` and `t` removes `k_H`, `m*` and the impact
//! speed from `m* delta'' + P = 0`: the coefficient of restitution depends on `alpha` alone
//! (Antypov & Elliott 2011, "On an analytical solution for the damped Hertzian spring", EPL). Without the no-tension cut-off, Antypov & Elliott's closed form (generalised to any
//! power law by Feng 2026, arXiv:2603.27764, eq. for p = 3/2) is
//! `alpha = sqrt(5) (-ln e) / sqrt(pi^2 + ln^2 e)` ([`alpha_without_cutoff`]).
//!
//! The pair kernel never lets the normal force pull (`P >= 0`); the cut-off changes `e(alpha)` (the
//! bodies leave with the speed they have when `P` reaches zero). [`damping_coefficient`]
//! therefore solves the scaled equation with the cut-off, `x'' = -max(x^(3/2) + alpha x^(1/4)
//! x', 0)`, `x(0) = 0`, `x'(0) = 1`, `e = -x'` at `x = 0` (still speed-independent: the cut-off
//! `P = 0` is invariant under the scaling), by classical Runge-Kutta, and inverts it by
//! regula falsi. The unit tests check the integrator against the closed form without cut-off.

use crate::error::LawError;
use crate::root::illinois;

/// The error of a restitution coefficient outside `[MIN_RESTITUTION, 1]`.
fn restitution_error(e: f64) -> LawError {
    LawError::OutOfRange {
        name: "restitution coefficient e",
        value: e,
        range: "[0.01, 1]",
    }
}

/// Smallest restitution coefficient accepted [-] (below it the damping diverges).
pub const MIN_RESTITUTION: f64 = 0.01;

/// `alpha(e)` of Antypov & Elliott (2011) for the damped Hertzian spring *without* the no-tension
/// cut-off: `sqrt(5) (-ln e) / sqrt(pi^2 + ln^2 e)` [-], for `0 < e <= 1`.
pub fn alpha_without_cutoff(e: f64) -> f64 {
    let l = e.ln();
    5f64.sqrt() * (-l) / (std::f64::consts::PI.powi(2) + l * l).sqrt()
}

/// Restitution coefficient of the scaled damped Hertzian impact with damping `alpha` [-];
/// `cutoff`: whether the normal force is kept >= 0 (the pair kernel's law).
pub fn restitution_for_damping(alpha: f64, cutoff: bool) -> f64 {
    if !(alpha > 0.0) {
        return 1.0;
    }
    let accel = |x: f64, v: f64| {
        let xp = x.max(0.0);
        let f = xp * xp.sqrt() + alpha * xp.sqrt().sqrt() * v;
        if cutoff { -f.max(0.0) } else { -f }
    };
    // Undamped contact lasts tau = 3.218 (Johnson 1985, §11.4 in scaled units); damping shortens
    // the rebound phase, never beyond a few times that.
    let h = 2.5e-4;
    let (mut x, mut v) = (0.0f64, 1.0f64);
    for _ in 0..200_000 {
        let (k1x, k1v) = (v, accel(x, v));
        let (k2x, k2v) = (
            v + 0.5 * h * k1v,
            accel(x + 0.5 * h * k1x, v + 0.5 * h * k1v),
        );
        let (k3x, k3v) = (
            v + 0.5 * h * k2v,
            accel(x + 0.5 * h * k2x, v + 0.5 * h * k2v),
        );
        let (k4x, k4v) = (v + h * k3v, accel(x + h * k3x, v + h * k3v));
        let xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if xn <= 0.0 && vn < 0.0 {
            // Crossing of x = 0 inside the step: interpolate the speed linearly in x.
            let s = x / (x - xn);
            return -(v + s * (vn - v));
        }
        if vn >= 0.0 && xn <= 0.0 {
            return 0.0; // stuck at the surface
        }
        x = xn;
        v = vn;
    }
    0.0
}

/// The damping coefficient `alpha` [-] whose impact, with the no-tension cut-off, rebounds with
/// restitution `e` [-] (`MIN_RESTITUTION <= e <= 1`; `e = 1` gives 0).
pub fn damping_coefficient(e: f64) -> Result<f64, LawError> {
    if !(MIN_RESTITUTION..=1.0).contains(&e) {
        return Err(restitution_error(e));
    }
    if e == 1.0 {
        return Ok(0.0);
    }
    let f = |a: f64| restitution_for_damping(a, true) - e;
    // Bracket: f(0) = 1 - e > 0; grow the upper end until the rebound is slower than e.
    let (mut lo, mut hi) = (0.0, alpha_without_cutoff(e).max(1e-3));
    let (mut flo, mut fhi) = (1.0 - e, f(hi));
    let mut guard = 0;
    while fhi > 0.0 {
        lo = hi;
        flo = fhi;
        hi *= 2.0;
        fhi = f(hi);
        guard += 1;
        if guard > 40 {
            return Err(restitution_error(e));
        }
    }
    // Illinois regula falsi (creep-law's `root::illinois`).
    Ok(illinois(f, (lo, flo), (hi, fhi), 60, |_, fc, k| {
        fc.abs() < 1e-10 || (k.b - k.a) < 1e-12 * k.b
    })
    .root_or_midpoint())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrator_reproduces_antypov_elliott_without_cutoff() {
        for e in [0.1, 0.3, 0.5, 0.7, 0.9] {
            let got = restitution_for_damping(alpha_without_cutoff(e), false);
            assert!((got / e - 1.0).abs() < 1e-4, "e = {e}: {got}");
        }
        assert_eq!(restitution_for_damping(0.0, true), 1.0);
    }

    #[test]
    fn inverse_with_cutoff() {
        for e in [0.1, 0.5, 0.9] {
            let a = damping_coefficient(e).unwrap();
            assert!((restitution_for_damping(a, true) / e - 1.0).abs() < 1e-6);
            // The cut-off lets the bodies leave faster: more damping is needed than without it.
            assert!(a > alpha_without_cutoff(e));
        }
        assert!(damping_coefficient(0.0).is_err());
        assert!(damping_coefficient(1.1).is_err());
        assert!(damping_coefficient(f64::NAN).is_err());
        assert_eq!(damping_coefficient(1.0), Ok(0.0));
    }
}
