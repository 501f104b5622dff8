//! Between the rows of the table (module documentation of [`super`], "Between nodes"): the
//! two rows' spin terms blended, with the pure-spin correction, **tabulated** once per contact
//! in `|phi_n|`, so that `loads` runs one table lookup and one translation.
//!
//! The law between rows blends the two rows' spin terms (every term but the translation's
//! `w` and `lam f_s` enters the loads linearly, so the moment is the blend of the two rows'
//! loads exactly) and evaluates one translation on them. Its lateral force of pure spin then
//! differs from the blend of the two rows' (the translation's saturation is not linear); the
//! difference is a function of `phi_n` alone, `D(phi_n) = F_blend(phi_n) - F_one(phi_n)`, and is
//! added to the spin force's unsaturated share, `(1 - lam) f_s`, as `g(phi_n) = D/(1 - s_t)^(1/4)`
//! with the pure spin's translation utilisation `s_t` (so that pure spin is the blend, and with
//! translation the correction fades like that share does).
//!
//! Four functions of `|phi_n|` are tabulated: the two rows' spin utilisations `s_0, s_1`
//! (step 1) and the blended shares of the spin force, `sum w_r lam_r f_s,r` and `sum w_r (1 -
//! lam_r) f_s,r + g` (step 2 and the correction), at the knots `|phi_n| = 2^e (1 + j/8)`,
//! `e = -7 ... 5`, `j = 0 ... 7` (105 knots, eight per octave, `0.0078 ... 64`), as `f32`
//! (1.7 KB), interpolated linearly in `|phi_n|` in the knot interval, which the bits of
//! `|phi_n|` index (the exponent and the three leading bits of the mantissa: no logarithm, no
//! search). The terms that depend on the utilisations (`w`, the capacities with their floors,
//! `1 - am s^2`, the spin moment) are computed from the interpolated `s_r` with each row's
//! constants, as at a row (so the floors' kinks are where they belong). Outside the knots'
//! range the terms are evaluated from the rows (exact; the correction continues as `g_0
//! (phi_n/phi_0)^2` below the first knot, where the difference of the two evaluations is of
//! second order in the spin, and as `g_104 phi_104/phi_n` above the last, where the spin
//! force fades).

use super::{SpinRow, SpinTerms, Steady3d};

/// Knots per octave, `2^PER_OCTAVE_BITS` (the leading mantissa bits index them).
const PER_OCTAVE_BITS: u32 = 3;
/// Octaves tabulated.
const OCTAVES: usize = 13;
/// Number of knots.
pub(crate) const KNOTS: usize = OCTAVES * (1 << PER_OCTAVE_BITS) + 1;
/// `log2` of the first knot.
const E0: i64 = -7;
/// First knot `2^E0`.
const PHI0: f64 = 1.0 / 128.0;
/// Last knot `2^(E0 + OCTAVES)`.
const PHI_LAST: f64 = 64.0;
/// Bits below the exponent and the knot-indexing mantissa bits.
const SHIFT: u32 = 52 - PER_OCTAVE_BITS;
/// `(bits >> SHIFT)` of the first knot.
const BASE: i64 = (1023 + E0) << PER_OCTAVE_BITS;

/// The tabulated spin terms between rows (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpinCorrection {
    /// Whether the law evaluates one translation between rows (and this table applies).
    pub on: bool,
    /// The correction `g` at the first and the last knot (for the spins outside the knots).
    g_ends: (f64, f64),
    /// At each knot: `s_0, s_1, sum w_r lam_r f_s,r, sum w_r (1 - lam_r) f_s,r + g`.
    v: [[f32; 4]; KNOTS],
}

/// Knot `k` on the float bits' grid, `2^e (1 + j/8)`.
pub(crate) fn knot(k: usize) -> f64 {
    let n = 1usize << PER_OCTAVE_BITS;
    let (e, j) = (E0 + (k / n) as i64, (k % n) as f64);
    2f64.powi(e as i32) * (1.0 + j / n as f64)
}

impl SpinCorrection {
    /// No table (at a row, and the two-row blend).
    pub const OFF: SpinCorrection = SpinCorrection {
        on: false,
        g_ends: (0.0, 0.0),
        v: [[0.0; 4]; KNOTS],
    };

    /// The correction `g(phi_n) > 0` for `phi_n > 0`, from the two rows (exact).
    pub fn g_exact(law: &Steady3d, phi_n: f64) -> f64 {
        let (one, two, h) = law.pure_spin_parts(phi_n);
        (two - one) / h
    }

    /// The table for the two-row law `blend` (module documentation).
    pub fn build(blend: &Steady3d) -> SpinCorrection {
        let mut out = SpinCorrection {
            on: true,
            g_ends: (Self::g_exact(blend, PHI0), Self::g_exact(blend, PHI_LAST)),
            v: [[0.0; 4]; KNOTS],
        };
        for (k, v) in out.v.iter_mut().enumerate() {
            let phi = knot(k);
            let [t0, t1] = blend.spin_terms::<2>(phi, 0.0);
            let t = blend.blended_terms_exact(phi, 0.0, Self::g_exact(blend, phi));
            // At e = 0 a row's spin moment term is its utilisation s.
            let row = [t0.spin_moment, t1.spin_moment, t.f_sat, t.f_rest];
            for (o, x) in v.iter_mut().zip(row) {
                *o = x as f32;
            }
        }
        out
    }

    /// The correction `g(phi_n)` outside the knots' range (odd in `phi_n`; module
    /// documentation); inside it, the value at the nearer end (not used there).
    pub fn g_beyond(&self, phi_n: f64) -> f64 {
        let a = phi_n.abs();
        let g = if a < PHI0 {
            let r = a / PHI0;
            self.g_ends.0 * r * r
        } else {
            self.g_ends.1 * (PHI_LAST / a).min(1.0)
        };
        g * 1f64.copysign(phi_n)
    }

    /// The spin terms at `phi_n` from the table and the rows' constants (`e^2, e^8` of the
    /// translation alone), or `None` outside the knots' range.
    #[inline(always)]
    pub fn terms(&self, rows: &[SpinRow; 2], phi_n: f64, e2: f64, e8: f64) -> Option<SpinTerms> {
        let a = phi_n.abs();
        let bits = a.to_bits();
        let kq = (bits >> SHIFT) as i64 - BASE;
        if !(0..KNOTS as i64 - 1).contains(&kq) {
            return None;
        }
        let k = kq as usize;
        // Position in the interval: the mantissa below its leading bits.
        let t = (bits & ((1u64 << SHIFT) - 1)) as f64 * (1.0 / (1u64 << SHIFT) as f64);
        let (p, q) = (&self.v[k], &self.v[k + 1]);
        let at = |i: usize| {
            let (x, y) = (p[i] as f64, q[i] as f64);
            x + t * (y - x)
        };
        let sign = 1f64.copysign(phi_n);
        let (s0, s1) = (at(0), at(1));
        let (r0, r1) = (&rows[0], &rows[1]);
        let (n0, n1) = (&r0.n, &r1.n);
        let (q0, q1) = (s0 * s0, s1 * s1);
        let (g0, g1) = (r0.w * (1.0 + n0.gam * q0), r1.w * (1.0 + n1.gam * q1));
        Some(SpinTerms {
            w: g0 + g1,
            cap_x: g0 * (1.0 - n0.ax * q0).max(0.0) + g1 * (1.0 - n1.ax * q1).max(0.0),
            cap_y: g0 * (1.0 - n0.ay * q0 * q0).max(0.0) + g1 * (1.0 - n1.ay * q1 * q1).max(0.0),
            f_sat: at(2) * sign,
            f_rest: at(3) * sign,
            ml_factor: 1.0 - (r0.w * n0.am * q0 + r1.w * n1.am * q1),
            spin_moment: r0.w * s0 * (1.0 - n0.b2 * e2 - n0.b8 * e8).max(0.0)
                + r1.w * s1 * (1.0 - n1.b2 * e2 - n1.b8 * e8).max(0.0),
        })
    }
}
