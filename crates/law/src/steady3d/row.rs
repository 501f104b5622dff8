//! One row of the table at the contact's `nu` (module documentation of [`super`], steps 1-2)
//! and the spin terms the translation and the moment use (steps 3-5).

use super::Node;

/// The spin constants of one row `a/b = NODE_AB[i]` of the table at the contact's `nu` (module
/// documentation, "Between nodes"), with the row's weight, prepared once per contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct SpinRow {
    /// Weight of the row's spin terms in the blend (`0`: not evaluated).
    pub(super) w: f64,
    /// Constants of the row interpolated in `nu` (only the spin constants `ma .. am` are used).
    pub(super) n: Node,
    /// The spin force's shape as one rational function of `u = phi_n^2`, `N(u)/D(u)` with
    /// `N = sum num[k] u^k`, `D = sum den[k] u^k`: at a column of the table the node's own
    /// `(1 + p1 u + p2 u^2)/(1 + q1 u + q2 u^2 + q3 u^3)`; between columns the blend of the
    /// two nodes' shapes by their outputs, `w0 n0/d0 + w1 n1/d1 = (w0 n0 d1 + w1 n1 d0)/(d0 d1)`,
    /// multiplied out here once (every coefficient is `>= 0`: no cancellation).
    pub(super) num: [f64; 6],
    pub(super) den: [f64; 7],
}

/// Product of two polynomials (coefficients in increasing powers) into `out` (zeroed first).
fn poly_mul(a: &[f64], b: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|o| *o = 0.0);
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            if x * y != 0.0 {
                out[i + j] += x * y;
            }
        }
    }
}

impl SpinRow {
    /// The row from its weight, its constants interpolated in `nu`, and the spin shapes of the
    /// row's two `nu` nodes with their weights `(w0, lo), (w1, hi)` (`w1 = 0`: `lo` alone).
    pub(super) fn new(w: f64, n: Node, (w0, lo): (f64, &Node), (w1, hi): (f64, &Node)) -> Self {
        let n0 = [1.0, lo.p1, lo.p2];
        let d0 = [1.0, lo.q1, lo.q2, lo.q3];
        let mut num = [0.0; 6];
        let mut den = [0.0; 7];
        if w1 == 0.0 {
            num[..3].copy_from_slice(&n0);
            den[..4].copy_from_slice(&d0);
        } else {
            let n1 = [1.0, hi.p1, hi.p2];
            let d1 = [1.0, hi.q1, hi.q2, hi.q3];
            let (mut a, mut b) = ([0.0; 6], [0.0; 6]);
            poly_mul(&n0, &d1, &mut a);
            poly_mul(&n1, &d0, &mut b);
            for k in 0..6 {
                num[k] = w0 * a[k] + w1 * b[k];
            }
            poly_mul(&d0, &d1, &mut den);
        }
        SpinRow { w, n, num, den }
    }

    /// `(N(u), D(u))` of the spin force's shape (Estrin's scheme: short dependency chains).
    #[inline(always)]
    pub(super) fn shape_parts(&self, u: f64, u2: f64, u4: f64) -> (f64, f64) {
        let (a, b) = (&self.num, &self.den);
        let num = (a[0] + a[1] * u) + u2 * (a[2] + a[3] * u) + u4 * (a[4] + a[5] * u);
        let den = (b[0] + b[1] * u) + u2 * (b[2] + b[3] * u) + u4 * (b[4] + b[5] * u + b[6] * u2);
        (num, den)
    }
}

/// The spin's terms of one row (or their blend over two rows) that the translation and the
/// moment use (module documentation, steps 1-5): `w`, the capacities `w (1 - ax s^2)`,
/// `w (1 - ay s^4)` (floored at 0), `lam f_s`, `(1 - lam) f_s`, the moment-of-lateral-creepage
/// factor `1 - am s^2` and the spin moment `M_max s max(0, 1 - b2 e^2 - b8 e^8)` over `M_max`.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct SpinTerms {
    pub(super) w: f64,
    pub(super) cap_x: f64,
    pub(super) cap_y: f64,
    pub(super) f_sat: f64,
    pub(super) f_rest: f64,
    pub(super) ml_factor: f64,
    pub(super) spin_moment: f64,
}

impl SpinTerms {
    /// The terms of `row` given its spin utilisation `s`, the lateral force of pure spin `f_s`,
    /// and `(e^2, e^8)` of the translation alone.
    #[inline(always)]
    pub(super) fn of_row(row: &SpinRow, s: f64, f_s: f64, e2: f64, e8: f64) -> Self {
        let n = &row.n;
        let s2 = s * s;
        let w = 1.0 + n.gam * s2;
        SpinTerms {
            w,
            cap_x: w * (1.0 - n.ax * s2).max(0.0),
            cap_y: w * (1.0 - n.ay * s2 * s2).max(0.0),
            f_sat: n.lam * f_s,
            f_rest: (1.0 - n.lam) * f_s,
            ml_factor: 1.0 - n.am * s2,
            spin_moment: s * (1.0 - n.b2 * e2 - n.b8 * e8).max(0.0),
        }
    }
}
