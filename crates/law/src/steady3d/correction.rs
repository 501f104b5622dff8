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
//! What depends on `|phi_n|` alone is tabulated, ten columns per knot:
//!
//! * the two rows' spin utilisations `s_0, s_1` (step 1); the terms that are not linear in
//!   them (`w = sum w_r (1 + gam_r s_r^2)` and the capacities, `w_r (1 + gam_r s_r^2)` times
//!   `max(0, 1 - ax_r s_r^2)` resp. `max(0, 1 - ay_r s_r^4)`) are computed from the
//!   interpolated `s_r` with each row's constants, so the floors' kinks are where they belong;
//! * the two blended shares of the spin force, `sum w_r lam_r f_s,r` and `sum w_r (1 - lam_r)
//!   f_s,r + g` (step 2 and the correction; the latter less its kinks, below);
//! * the factor of the lateral creepage's moment `1 - sum w_r am_r s_r^2`;
//! * the spin moment's coefficients `A = sum w_r s_r`, `B = sum w_r b2_r s_r`, `C = sum w_r
//!   b8_r s_r` (linear in the `s_r`: their interpolation is that of the `s_r`): the spin
//!   moment is `A - B e^2 - C e^8`, no row's floor `max(0, 1 - b2 e^2 - b8 e^8)` being active
//!   anywhere (test `spin_moment_capacity_is_positive_at_every_node`);
//! * the kinks of the correction: the blend's pure spin force `sum w_r min(1, U_r)` (each
//!   row's force `U_r` projected onto `mu P`) has a kink where a row's force reaches `mu P`,
//!   which linear interpolation rounds off (1.6 % of `mu P` at `a/b = 3` near `phi_n =
//!   0.72`); with `Q_r = w_r (1 - U_r)/(1 - s_t)^(1/4)` the correction is `g = g_s + min(0,
//!   Q_0) + min(0, Q_1)`, so `g_s` (in the unsaturated share's column) and `Q_0, Q_1` are
//!   tabulated and the minima taken after the interpolation (the one translation's own pure
//!   spin force stays below `0.86 mu P` over the table's range: no such kink).
//!
//! The knots are `|phi_n| = 2^e (1 + j/8)`, `e = -7 ... 5`, `j = 0 ... 7` (105 knots, eight per
//! octave, `0.0078 ... 64`); each stores its values and the differences to the next knot
//! (`f64`, 16.8 KB in all), so a column is `v + t d`: one load, one multiplication, one
//! addition. The knot interval and `t` come from the bits of `|phi_n|` (the exponent and the
//! three leading bits of the mantissa index it, the mantissa below them is `t`: no logarithm,
//! no search, no division, no conversion). At the knots the table is the exact blended terms
//! to rounding. Outside the knots' range the terms are evaluated from the rows (exact; the
//! correction continues as `g_0 (phi_n/phi_0)^2` below the first knot, where the difference
//! of the two evaluations is of second order in the spin, and as `g_104 phi_104/phi_n` above
//! the last, where the spin force fades).

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
/// Columns of the table (module documentation).
pub(crate) const COLS: usize = 10;
/// The rows' utilisations `s_0, s_1`.
const S: usize = 0;
/// The two shares of the spin force.
const F_SAT: usize = 2;
const F_REST: usize = 3;
/// The factor of the lateral creepage's moment.
const ML: usize = 4;
/// The spin moment's `A, B, C`.
const SM: usize = 5;
/// The correction's kink terms `Q_0, Q_1`.
const KINK: usize = 8;

/// One knot: each column's value there and its difference to the next knot.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Knot {
    v: [f64; COLS],
    d: [f64; COLS],
}

/// The tabulated spin terms between rows (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SpinCorrection {
    /// Whether the law evaluates one translation between rows (and this table applies).
    pub on: bool,
    /// The correction `g` at the first and the last knot (for the spins outside the knots).
    g_ends: (f64, f64),
    /// The knots (module documentation).
    k: [Knot; KNOTS],
}

/// Knot `k` on the float bits' grid, `2^e (1 + j/8)`.
pub(crate) fn knot(k: usize) -> f64 {
    let n = 1usize << PER_OCTAVE_BITS;
    let (e, j) = (E0 + (k / n) as i64, (k % n) as f64);
    2f64.powi(e as i32) * (1.0 + j / n as f64)
}

/// The knot interval of `a = |phi_n|` and the position `t` in it, in `[0, 1)`, from the bits
/// of `a`; `None` outside the knots.
#[inline(always)]
fn interval(a: f64) -> Option<(usize, f64)> {
    let bits = a.to_bits();
    let kq = (bits >> SHIFT) as i64 - BASE;
    if !(0..KNOTS as i64 - 1).contains(&kq) {
        return None;
    }
    // The mantissa below the indexing bits as the mantissa of a float in [1, 2), minus one
    // (exact).
    const MANTISSA: u64 = (1 << 52) - 1;
    let t = f64::from_bits(((bits << PER_OCTAVE_BITS) & MANTISSA) | 1f64.to_bits()) - 1.0;
    Some((kq as usize, t))
}

/// `max(0, x)` (one instruction on x86: `maxsd`).
#[inline(always)]
fn floor0(x: f64) -> f64 {
    x.max(0.0)
}

/// `min(0, x)` (one instruction on x86: `minsd`).
#[inline(always)]
fn ceil0(x: f64) -> f64 {
    x.min(0.0)
}

impl SpinCorrection {
    /// No table (at a row, and the two-row blend).
    pub const OFF: SpinCorrection = SpinCorrection {
        on: false,
        g_ends: (0.0, 0.0),
        k: [Knot {
            v: [0.0; COLS],
            d: [0.0; COLS],
        }; KNOTS],
    };

    /// The correction `g(phi_n) > 0` for `phi_n > 0`, from the two rows (exact).
    pub fn g_exact(law: &Steady3d, phi_n: f64) -> f64 {
        let (one, two, h) = law.pure_spin_parts(phi_n);
        (two - one) / h
    }

    /// The table's columns at `phi_n > 0` from the two rows (exact; module documentation).
    pub fn columns_exact(blend: &Steady3d, phi_n: f64) -> [f64; COLS] {
        let [t0, t1] = blend.spin_terms::<2>(phi_n, 0.0);
        let (one, two, h, u) = blend.pure_spin_of(phi_n, &t0, &t1);
        let mut t = blend.blended_terms(&t0, &t1);
        t.f_rest += (two - one) / h;
        let mut out = [0.0; COLS];
        out[F_SAT] = t.f_sat;
        out[F_REST] = t.f_rest;
        out[ML] = t.ml_factor;
        for (r, tr) in [t0, t1].iter().enumerate() {
            let (w, n) = (blend.rows[r].w, &blend.rows[r].n);
            // At e = 0 a row's spin moment term is its utilisation s.
            let s = tr.spin_moment;
            out[S + r] = s;
            out[SM] += w * s;
            out[SM + 1] += w * n.b2 * s;
            out[SM + 2] += w * n.b8 * s;
            let q = w * (1.0 - u[r]) / h;
            out[KINK + r] = q;
            out[F_REST] -= ceil0(q);
        }
        out
    }

    /// The table for the two-row law `blend` (module documentation).
    pub fn build(blend: &Steady3d) -> SpinCorrection {
        let mut out = SpinCorrection {
            on: true,
            g_ends: (Self::g_exact(blend, PHI0), Self::g_exact(blend, PHI_LAST)),
            ..Self::OFF
        };
        let mut next = Self::columns_exact(blend, knot(0));
        for k in 0..KNOTS {
            let v = next;
            if k + 1 < KNOTS {
                next = Self::columns_exact(blend, knot(k + 1));
            }
            out.k[k].v = v;
            // The last knot is never an interval's start: no difference.
            out.k[k].d = std::array::from_fn(|i| if k + 1 < KNOTS { next[i] - v[i] } else { 0.0 });
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

    /// The spin terms at `phi_n` from the table (`e^2, e^8` of the translation alone), or
    /// `None` outside the knots' range.
    #[inline(always)]
    pub fn terms(&self, rows: &[SpinRow; 2], phi_n: f64, e2: f64, e8: f64) -> Option<SpinTerms> {
        let (k, t) = interval(phi_n.abs())?;
        let kn = &self.k[k];
        let c = |i: usize| kn.v[i] + t * kn.d[i];
        let sign = 1f64.copysign(phi_n);
        let (s0, s1) = (c(S), c(S + 1));
        let (r0, r1) = (&rows[0], &rows[1]);
        let (n0, n1) = (&r0.n, &r1.n);
        let (q0, q1) = (s0 * s0, s1 * s1);
        let (g0, g1) = (r0.w * (1.0 + n0.gam * q0), r1.w * (1.0 + n1.gam * q1));
        Some(SpinTerms {
            w: g0 + g1,
            cap_x: g0 * floor0(1.0 - n0.ax * q0) + g1 * floor0(1.0 - n1.ax * q1),
            cap_y: g0 * floor0(1.0 - n0.ay * q0 * q0) + g1 * floor0(1.0 - n1.ay * q1 * q1),
            f_sat: c(F_SAT) * sign,
            f_rest: (c(F_REST) + ceil0(c(KINK)) + ceil0(c(KINK + 1))) * sign,
            ml_factor: c(ML),
            spin_moment: c(SM) - c(SM + 1) * e2 - c(SM + 2) * e8,
        })
    }
}
