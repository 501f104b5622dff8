//! The tabulated pure-spin correction of the one-translation evaluation between the rows of
//! the table (module documentation of [`super`], "Between rows").
//!
//! Between rows `loads` blends the two rows' spin terms (every term but the translation's
//! `w` and `lam f_s` enters the loads linearly, so the moment is the two rows' blend exactly)
//! and evaluates one translation on them. Its lateral force of pure spin then differs from the
//! blend of the two rows' (the translation's saturation is not linear); the difference is a
//! function of `phi_n` alone, `D(phi_n) = F_blend(phi_n) - F_one(phi_n)`, and is added to the
//! spin force's unsaturated share, `(1 - lam) f_s`, as `g(phi_n) = D/(1 - s_t)^(1/4)` with the
//! pure spin's translation utilisation `s_t` (so that pure spin is the blend to the table's
//! accuracy, and with translation the correction fades like that share does).
//!
//! `g` is tabulated once per contact at `|phi_n| = 2^(e + j/4)`, `e = -7 ... 12`,
//! `j = 0 ... 3` (81 knots, four per octave, `0.0078 ... 8192`), values and slopes (central
//! differences), and interpolated by cubic Hermite polynomials (Fritsch & Carlson 1980)
//! in the knot interval, indexed by the bits of `|phi_n|` (exponent and the two leading bits of
//! the mantissa: no logarithm, no search). Below the first knot `g` continues as
//! `g_0 (phi_n/phi_0)^2` (the difference of the two evaluations is of second order in the
//! spin); above the last it decays as `g_80 phi_80/phi_n` (the spin force fades in full
//! slip). Odd in `phi_n`.

use super::Steady3d;

/// Number of knots.
pub(crate) const KNOTS: usize = 81;
/// `log2` of the first knot.
const E0: i64 = -7;
/// First knot `2^E0`.
const PHI0: f64 = 1.0 / 128.0;
/// Last knot `2^(E0 + 20)`.
const PHI_LAST: f64 = 8192.0;
/// `(bits >> 50)` of the first knot: the biased exponent times four.
const BASE: i64 = (1023 + E0) * 4;
/// Width of a knot interval over its left knot, by the quarter `j` of the octave.
const W0: [f64; 4] = [0.25, 0.2, 0.25 / 1.5, 0.25 / 1.75];
/// Width of a knot interval over its right knot.
const W1: [f64; 4] = [0.2, 0.25 / 1.5, 0.25 / 1.75, 0.125];

/// The tabulated correction `g(|phi_n|)`: values and logarithmic slopes `phi dg/dphi` at the
/// knots (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpinCorrection {
    /// Whether the law evaluates one translation between rows (and this table applies).
    pub on: bool,
    g: [f64; KNOTS],
    d: [f64; KNOTS],
}

/// Knot `k`: `2^(E0 + k/4)` on the quarter-octave grid of the float bits (`2^e (1 + j/4)`).
fn knot(k: usize) -> f64 {
    let (e, j) = (E0 + (k / 4) as i64, (k % 4) as f64);
    2f64.powi(e as i32) * (1.0 + 0.25 * j)
}

impl SpinCorrection {
    /// No correction (at a row, and the two-row blend).
    pub const OFF: SpinCorrection = SpinCorrection {
        on: false,
        g: [0.0; KNOTS],
        d: [0.0; KNOTS],
    };

    /// The table for the two-row law `blend` (module documentation).
    pub fn build(blend: &Steady3d) -> SpinCorrection {
        let g_at = |phi: f64| {
            let (one, two, h) = blend.pure_spin_parts(phi);
            (two - one) / h
        };
        let mut out = SpinCorrection {
            on: true,
            g: [0.0; KNOTS],
            d: [0.0; KNOTS],
        };
        for k in 0..KNOTS {
            let phi = knot(k);
            let eps = 1e-4;
            out.g[k] = g_at(phi);
            out.d[k] = (g_at(phi * (1.0 + eps)) - g_at(phi * (1.0 - eps))) / (2.0 * eps);
        }
        out
    }

    /// `g(phi_n)` (odd in `phi_n`; zero when off).
    #[inline(always)]
    pub fn at(&self, phi_n: f64) -> f64 {
        let a = phi_n.abs();
        let bits = a.to_bits();
        let kq = (bits >> 50) as i64 - BASE;
        if kq >= KNOTS as i64 - 1 {
            return self.above(a) * 1f64.copysign(phi_n);
        }
        // Below the first knot: the first knot's value times (phi/phi_0)^2 (selects, no
        // branch: small spins are common).
        let below = kq < 0;
        let k = kq.max(0) as usize;
        let j = k & 3;
        // Position in the interval: the mantissa below its two leading bits.
        let frac = (bits & ((1u64 << 50) - 1)) as f64 * (1.0 / (1u64 << 50) as f64);
        let t = if below { 0.0 } else { frac };
        let r = a * (1.0 / PHI0);
        let scale = if below { r * r } else { 1.0 };
        let (g0, g1) = (self.g[k], self.g[k + 1]);
        let (m0, m1) = (self.d[k] * W0[j], self.d[k + 1] * W1[j]);
        let dg = g1 - g0;
        let c2 = 3.0 * dg - 2.0 * m0 - m1;
        let c3 = m0 + m1 - 2.0 * dg;
        (g0 + t * (m0 + t * (c2 + t * c3))) * (scale * 1f64.copysign(phi_n))
    }

    /// `g` above the last knot (rare; module documentation).
    #[cold]
    #[inline(never)]
    fn above(&self, a: f64) -> f64 {
        self.g[KNOTS - 1] * (PHI_LAST / a)
    }
}
