//! Hertz's elliptic contact: the semi-axes, peak pressure and approach of two bodies whose
//! relative curvatures differ in the two principal directions (a crowned wheel on a plane, a
//! ball in a groove), with the complete elliptic integrals `K(e)` and `E(e)`.
//!
//! Source: Hertz (1882); Johnson 1985, *Contact Mechanics*, §4.2, eqs. (4.36)-(4.39). With the
//! relative principal curvature sums `kx = 1/R1x + 1/R2x` (in the `x`-`z` plane, `x` the rolling
//! direction) and `ky = 1/R1y + 1/R2y`, Johnson's `A = kx/2`, `B = ky/2`. For the major semi-axis
//! `a_M`, the minor `b_m`, `k = b_m/a_M`, `e^2 = 1 - k^2` and `p0 = 3 P/(2 pi a_M b_m)`:
//!
//! `A_M = p0/E* * b_m/(e^2 a_M^2) (K - E)`, `A_m = p0/E* * b_m/(e^2 a_M^2) (E/k^2 - K)`,
//! `delta = p0 b_m K / E*`,
//!
//! where `A_M` is the curvature half-sum along the major axis (the smaller of `A`, `B`). The
//! ratio `A_m/A_M = (E/k^2 - K)/(K - E)` fixes `k` (found here by bisection on `ln k`, the ratio
//! being monotone), then `a_M^3 = 3 P (K - E)/(2 pi E* e^2 A_M)`.
//!
//! `K` and `E` come from the arithmetic-geometric mean (Abramowitz & Stegun 1964, §17.6), which
//! also gives `K - E = K sum_n 2^(n-1) c_n^2` without cancellation (so the circular limit
//! `e -> 0` is exact).

use crate::error::{LawError, positive};
use std::f64::consts::PI;

/// The complete elliptic integrals `(K(m), E(m), K(m) - E(m))` of parameter `m = e^2` in
/// `[0, 1)`, by the arithmetic-geometric mean (Abramowitz & Stegun 1964, §17.6.3-17.6.4):
/// `a0 = 1`, `b0 = sqrt(1 - m)`, `c0^2 = m`; `K = pi/(2 a_N)`, `K - E = K sum 2^(n-1) c_n^2`.
pub fn complete_elliptic(m: f64) -> Result<(f64, f64, f64), LawError> {
    if !(0.0..1.0).contains(&m) {
        return Err(LawError::OutOfRange {
            name: "elliptic parameter m",
            value: m,
            range: "[0, 1)",
        });
    }
    let (mut a, mut b) = (1.0f64, (1.0 - m).sqrt());
    let mut c2 = m;
    let mut sum = 0.5 * c2;
    let mut pow = 0.5;
    for _ in 0..40 {
        let an = 0.5 * (a + b);
        let bn = (a * b).sqrt();
        // c_{n+1} = (a_n - b_n)/2 = c_n^2/(4 a_{n+1}).
        let cn = c2 / (4.0 * an);
        a = an;
        b = bn;
        c2 = cn * cn;
        pow *= 2.0;
        sum += pow * c2;
        if c2 <= 1e-34 * a * a {
            break;
        }
    }
    let k = PI / (2.0 * a);
    let k_minus_e = k * sum;
    Ok((k, k - k_minus_e, k_minus_e))
}

/// A solved elliptic Hertz contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EllipticHertz {
    /// Semi-axis along the rolling direction `x` \[m\].
    pub a: f64,
    /// Semi-axis along `y` \[m\].
    pub b: f64,
    /// Peak pressure `p0 = 3 P/(2 pi a b)` \[Pa\].
    pub p0: f64,
    /// Approach of distant points `delta` \[m\].
    pub delta: f64,
}

impl EllipticHertz {
    /// `c = sqrt(a b)` \[m\], the length of Kalker's normalisation.
    pub fn c(&self) -> f64 {
        (self.a * self.b).sqrt()
    }
    /// The axis ratio `a/b`.
    pub fn ab(&self) -> f64 {
        self.a / self.b
    }
}

/// `(E/k^2 - K)/(K - E)` for `k = b_m/a_M` in `(0, 1)`: the ratio `A_m/A_M` of the curvature
/// half-sums (Johnson 1985, eq. 4.39), increasing as `k` decreases.
fn curvature_ratio(k: f64) -> Result<f64, LawError> {
    let (kk, ee, k_minus_e) = complete_elliptic(1.0 - k * k)?;
    Ok((ee / (k * k) - kk) / k_minus_e)
}

/// Solves Hertz's elliptic contact for the relative principal curvature sums `kx` (in the
/// rolling plane `x`-`z`) and `ky` \[1/m\] (both finite and > 0), the normal force `p` \[N\] (> 0)
/// and the contact modulus `e_star` \[Pa\] (> 0, Johnson's `1/E* = (1 - nu1^2)/E1 + (1 -
/// nu2^2)/E2`). The principal directions of both bodies are taken aligned with `x`, `y`.
///
/// A zero curvature sum (a cylinder on a plane) is a line contact, not an ellipse:
/// [`LawError::NotPositive`]. Curvature ratios beyond `10^6` are refused
/// ([`LawError::OutOfRange`]).
pub fn elliptic_hertz(kx: f64, ky: f64, p: f64, e_star: f64) -> Result<EllipticHertz, LawError> {
    let kx = positive("curvature sum kx", kx, "1/m")?;
    let ky = positive("curvature sum ky", ky, "1/m")?;
    let p = positive("normal force P", p, "N")?;
    let e_star = positive("contact modulus E*", e_star, "Pa")?;
    let (a_major_curv, ratio) = if kx <= ky {
        (0.5 * kx, ky / kx)
    } else {
        (0.5 * ky, kx / ky)
    };
    if ratio > 1e6 {
        return Err(LawError::OutOfRange {
            name: "curvature ratio",
            value: ratio,
            range: "[1e-6, 1e6]",
        });
    }
    // k = b_m/a_M; ratio 1 is the circle.
    let k = if ratio - 1.0 < 1e-14 {
        1.0
    } else {
        // Bisection on ln k in [ln 1e-5, 0]: curvature_ratio decreases from huge to 1.
        let (mut lo, mut hi) = ((1e-5f64).ln(), 0.0f64);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if hi - lo < 1e-15 {
                break;
            }
            if curvature_ratio(mid.exp())? > ratio {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        (0.5 * (lo + hi)).exp()
    };
    let m = 1.0 - k * k;
    let (kk, _, k_minus_e) = complete_elliptic(m)?;
    // (K - E)/e^2 -> pi/4 as e -> 0; the AGM series gives it without cancellation for e > 0.
    let k_e_over_m = if m > 0.0 { k_minus_e / m } else { PI / 4.0 };
    let a_major = (3.0 * p * k_e_over_m / (2.0 * PI * e_star * a_major_curv)).cbrt();
    let b_minor = k * a_major;
    let p0 = 1.5 * p / (PI * a_major * b_minor);
    let delta = p0 * b_minor * kk / e_star;
    let (a, b) = if kx <= ky {
        (a_major, b_minor)
    } else {
        (b_minor, a_major)
    };
    Ok(EllipticHertz { a, b, p0, delta })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elliptic_integrals_known_values() {
        // K(0) = E(0) = pi/2; K(1/2) = 1.854074677301372, E(1/2) = 1.350643881047675
        // (Abramowitz & Stegun 1964, Table 17.1).
        let (k, e, d) = complete_elliptic(0.0).unwrap();
        assert!((k - PI / 2.0).abs() < 1e-15 && (e - PI / 2.0).abs() < 1e-15 && d == 0.0);
        let (k, e, d) = complete_elliptic(0.5).unwrap();
        assert!((k - 1.854_074_677_301_372).abs() < 1e-14);
        assert!((e - 1.350_643_881_047_675).abs() < 1e-14);
        assert!((d - (k - e)).abs() < 1e-15);
        // Small m: K - E = pi m/4 (1 + 3m/8 + ...), no cancellation.
        let (_, _, d) = complete_elliptic(1e-10).unwrap();
        assert!((d / (PI * 1e-10 / 4.0) - 1.0).abs() < 1e-9);
        assert!(complete_elliptic(1.0).is_err() && complete_elliptic(-0.1).is_err());
    }

    #[test]
    fn circular_limit_is_hertz_sphere() {
        // Ball of radius R on a plane: kx = ky = 1/R, a^3 = 3 P R/(4 E*), delta = a^2/R
        // (Johnson 1985, §4.2).
        let (r, p, e) = (0.01, 100.0, 115e9);
        let h = elliptic_hertz(1.0 / r, 1.0 / r, p, e).unwrap();
        let a = (0.75 * p * r / e).cbrt();
        assert!((h.a / a - 1.0).abs() < 1e-12 && (h.b / a - 1.0).abs() < 1e-12);
        assert!((h.delta / (a * a / r) - 1.0).abs() < 1e-12);
        // Nearly circular: continuous.
        let h2 = elliptic_hertz(1.0 / r, 1.0 / r * (1.0 + 1e-9), p, e).unwrap();
        assert!((h2.a / a - 1.0).abs() < 1e-8 && (h2.b / a - 1.0).abs() < 1e-8);
    }

    #[test]
    fn satisfies_johnsons_equations_and_the_published_approximation() {
        // Crowned wheel on a plane: rolling radius 0.05 m, crown radius 0.5 m.
        let (kx, ky, p, e) = (1.0 / 0.05, 1.0 / 0.5, 200.0, 115e9);
        let h = elliptic_hertz(kx, ky, p, e).unwrap();
        // Major axis along y (smaller curvature); re-evaluate Johnson's (4.39) forward.
        let (a_m, b_m) = (h.b, h.a);
        let k = b_m / a_m;
        let m = 1.0 - k * k;
        let (kk, ee, _) = complete_elliptic(m).unwrap();
        let pre = h.p0 / e * b_m / (m * a_m * a_m);
        assert!((pre * (kk - ee) / (0.5 * ky) - 1.0).abs() < 1e-10);
        assert!((pre * (ee / (k * k) - kk) / (0.5 * kx) - 1.0).abs() < 1e-10);
        // Hamrock & Brewe (1983, "Simplified solution for stresses and deformations", J. Lubr.
        // Technol. 105, 171-177): ellipticity a_M/b_m ~ 1.0339 (R_y/R_x)^0.6360 with
        // R_y/R_x = kx/ky, stated within about 1 % of the exact value.
        let approx = 1.0339 * (kx / ky).powf(0.6360);
        assert!(
            ((a_m / b_m) / approx - 1.0).abs() < 0.02,
            "{} vs {approx}",
            a_m / b_m
        );
        // Swapping the curvatures swaps the axes.
        let s = elliptic_hertz(ky, kx, p, e).unwrap();
        assert!((s.a / h.b - 1.0).abs() < 1e-12 && (s.b / h.a - 1.0).abs() < 1e-12);
        // Bad input.
        assert!(elliptic_hertz(0.0, ky, p, e).is_err());
        assert!(elliptic_hertz(kx, ky, -1.0, e).is_err());
        assert!(elliptic_hertz(kx, f64::NAN, p, e).is_err());
    }
}
