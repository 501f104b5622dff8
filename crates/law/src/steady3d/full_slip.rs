//! The loads of full slip: where the whole elliptic patch slips, the traction is `mu p` along
//! the rigid slip `w(x, y) = (xi - phi y, eta + phi x)` at every point (Coulomb's law on
//! Hertz's pressure; Kalker 1990, sec. 2.2, the rigid-slip limit of the exact theory), so the
//! loads depend on the contact's axis ratio and on the creepage's direction only, not on its
//! size nor on `nu`:
//!
//! ```text
//! (Fx, Fy)/(mu P) = int (3/(2 pi a b)) sqrt(1 - (x/a)^2 - (y/b)^2) w/|w| dA
//! Mz/(mu P c)     = int (3/(2 pi a b)) sqrt(1 - (x/a)^2 - (y/b)^2) (x w_y - y w_x)/|w| dA
//! ```
//!
//! in units of `c = sqrt(a b)` (`a = sqrt(a/b)`, `b = 1/sqrt(a/b)`), the project's signs.
//! [`rigid_slip_loads`] evaluates the integral by quadrature (the reference);
//! [`FullSlip`] interpolates a table of it (`full_slip_data.rs`, written by `cargo run --release
//! -p creep-law --example full_slip_table`): per row `a/b` ([`row_ab`]), a grid over the
//! creepage's direction folded into `xi, eta >= 0` (the exact symmetries, module
//! documentation of [`super`]): `u = eta/(xi + eta)` in `[0, 1]` and `v = phi/(xi + eta +
//! |phi|)` in `[-1, 1]`, bilinear in `(u, v)` and linear in `ln(a/b)` between rows.

use super::Loads;

/// Rows of the table: `a/b = 10^((k - 12)/12)`, `k = 0 ... 24` (`0.1 ... 10`, Kalker's range).
pub const ROWS: usize = 25;
/// Nodes over `u = eta/(xi + eta)`.
pub const NU: usize = 25;
/// Nodes over `v = phi/(xi + eta + |phi|)` (odd: a node at `v = 0`, where `v` has a kink).
pub const NV: usize = 49;
/// One row: at `(u_i, v_j)` (index `i NV + j`), the force along and across the translation
/// over `mu P` and `Mz/(mu P c)` ([`rigid_slip_frame`]).
pub type Row = [[f32; 3]; NU * NV];

/// `a/b` of row `k`.
pub fn row_ab(k: usize) -> f64 {
    10f64.powf((k as f64 - 12.0) / 12.0)
}

/// The direction `(xi, eta, phi)` (`xi, eta >= 0`) of node `(u, v)` of the grid.
pub fn node_direction(i: usize, j: usize) -> [f64; 3] {
    let u = i as f64 / (NU - 1) as f64;
    let v = -1.0 + 2.0 * j as f64 / (NV - 1) as f64;
    // xi + eta = 1 - |v|, phi = v: then v = phi/(xi + eta + |phi|).
    let t = 1.0 - v.abs();
    [t * (1.0 - u), t * u, v]
}

/// The loads of full slip in the direction `(xi, eta, phi)` (any size, not all zero) by
/// midpoint quadrature in the patch's polar coordinates `x = a sin(al) cos(th)`, `y = b
/// sin(al) sin(th)` with `n` steps in `al` over `[0, pi/2]` and `4 n` in `th` (the Hertz
/// weight `sqrt(1 - rho^2) rho d rho = cos^2(al) sin(al) d al` is smooth in `al`; the
/// integrand is bounded, discontinuous only at the pole of the slip), divided by the
/// quadrature of the weight alone (so that a pure translation gives `|F| = mu P` to rounding).
/// `n = 200` is within about 1e-4.
pub fn rigid_slip_loads(ab: f64, dir: [f64; 3], n: usize) -> [f64; 3] {
    let (a, b) = (ab.sqrt(), 1.0 / ab.sqrt());
    let [xi, eta, phi] = dir;
    let (da, dt) = (
        std::f64::consts::FRAC_PI_2 / n as f64,
        std::f64::consts::TAU / (4 * n) as f64,
    );
    let mut out = [0.0; 3];
    let mut total = 0.0;
    for i in 0..n {
        let al = (i as f64 + 0.5) * da;
        let (s, c) = al.sin_cos();
        // mu p dA / (mu P) = 3/(2 pi) cos(al) * sin(al) cos(al) dal dth (a b = 1).
        let wgt = 1.5 / std::f64::consts::PI * c * c * s * da * dt;
        for j in 0..4 * n {
            let th = (j as f64 + 0.5) * dt;
            let (st, ct) = th.sin_cos();
            let (x, y) = (a * s * ct, b * s * st);
            let (wx, wy) = (xi - phi * y, eta + phi * x);
            let m = wx.hypot(wy);
            total += wgt;
            if m > 0.0 {
                let (ux, uy) = (wx / m, wy / m);
                out[0] += wgt * ux;
                out[1] += wgt * uy;
                out[2] += wgt * (x * uy - y * ux);
            }
        }
    }
    out.map(|v| v / total)
}

/// The full-slip moment of a pure spin over `mu P c`: `M_max = (3/8) E(e) a_M/c` with `a_M`
/// the longer semi-axis, `E` the complete elliptic integral of the second kind at `e^2 = 1 -
/// g^2`, `g` the axis ratio's smaller side (Kalker 1990, sec. 2.2; `3 pi/16 mu P a` on a
/// circle, Johnson 1985, sec. 8.4).
pub fn max_moment(ab: f64) -> f64 {
    let g = ab.min(1.0 / ab);
    let e = crate::elliptic::complete_elliptic(1.0 - g * g).map_or(f64::NAN, |(_, e, _)| e);
    0.375 * e / g.sqrt()
}

/// The loads of full slip in the frame of the translation `(xi, eta)`, the table's entries:
/// the force along `(xi, eta)/|(xi, eta)|` and across it (turned +90 degrees) over `mu P`
/// (along `(1, 0)` for a pure spin), and `Mz` over the pure spin's [`max_moment`]. A pure
/// translation is `(1, 0, 0)` and a pure spin `(0, 0, +-1)`, exactly at every `a/b`; the force
/// turns with the translation without the chord error of interpolating its components, and
/// the moment's scale with `a/b` is the closed form's, not the interpolation's.
pub fn rigid_slip_frame(ab: f64, dir: [f64; 3], n: usize) -> [f64; 3] {
    let l = rigid_slip_loads(ab, dir, n);
    let t = dir[0].hypot(dir[1]);
    if t == 0.0 {
        return [0.0, 0.0, dir[2].signum()];
    }
    let (cx, cy) = (dir[0] / t, dir[1] / t);
    [
        l[0] * cx + l[1] * cy,
        l[1] * cx - l[0] * cy,
        l[2] / max_moment(ab),
    ]
}

/// The interpolated loads of full slip at one axis ratio: the two rows around it and their
/// weights (`a/b` outside `[0.1, 10]` takes the end row), and the two rows blended once into
/// one for this axis ratio (`None` beyond [`BLENDED_MAX`] axis ratios in a process).
#[derive(Clone, Copy)]
pub struct FullSlip {
    rows: [&'static Row; 2],
    w: f64,
    one: Option<&'static Row>,
    /// [`max_moment`] at this `a/b`.
    m_max: f64,
}

/// Most full-slip rows blended for an axis ratio and kept (14.7 KB each, 3.8 MB in all); beyond
/// them a contact blends the two rows at each evaluation (the same bits).
pub const BLENDED_MAX: usize = 256;

/// The row of full slip at the weight `w` between the rows `r`, entry by entry in `f32` as
/// [`FullSlip::loads`] blends them (so the same bits), made at the first request of `key` (the
/// axis ratio's bits) and kept; `None` once [`BLENDED_MAX`] are kept.
fn blended(key: u64, r: [&'static Row; 2], w: f64) -> Option<&'static Row> {
    static KEPT: std::sync::Mutex<Vec<(u64, &'static Row)>> = std::sync::Mutex::new(Vec::new());
    super::lut::kept(&KEPT, key, BLENDED_MAX, || blend_rows(r, w))
}

/// The rows `r` blended at the weight `w`, entry by entry in `f32`.
fn blend_rows(r: [&Row; 2], w: f64) -> Box<Row> {
    let w = w as f32;
    Box::new(std::array::from_fn(|k| {
        let (a, b) = (r[0][k], r[1][k]);
        [
            a[0] + (b[0] - a[0]) * w,
            a[1] + (b[1] - a[1]) * w,
            a[2] + (b[2] - a[2]) * w,
        ]
    }))
}

impl std::fmt::Debug for FullSlip {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FullSlip").field("w", &self.w).finish()
    }
}

impl PartialEq for FullSlip {
    fn eq(&self, o: &Self) -> bool {
        // (`one` is these two rows blended: the same loads whether kept or not.)
        self.w == o.w
            && self.m_max == o.m_max
            && std::ptr::eq(self.rows[0], o.rows[0])
            && std::ptr::eq(self.rows[1], o.rows[1])
    }
}

impl FullSlip {
    /// The cell's four entries at `base`, blended between the two rows (beyond
    /// [`BLENDED_MAX`] axis ratios).
    #[cold]
    #[inline(never)]
    fn corners(&self, base: usize) -> ([f32; 3], [f32; 3], [f32; 3], [f32; 3]) {
        let (r0, r1) = (
            &self.rows[0][base..base + NV + 2],
            &self.rows[1][base..base + NV + 2],
        );
        let w = self.w as f32;
        let corner = |k: usize| {
            let (a, b) = (r0[k], r1[k]);
            [
                a[0] + (b[0] - a[0]) * w,
                a[1] + (b[1] - a[1]) * w,
                a[2] + (b[2] - a[2]) * w,
            ]
        };
        (corner(0), corner(1), corner(NV), corner(NV + 1))
    }

    /// The table at the axis ratio `ab` (finite, > 0).
    pub fn at(ab: f64) -> FullSlip {
        let k = (12.0 * ab.log10() + 12.0).clamp(0.0, (ROWS - 1) as f64);
        let lo = (k as usize).min(ROWS - 2);
        let w = k - lo as f64;
        let t = &super::full_slip_data::ROWS;
        let rows = [&t[lo], &t[lo + 1]];
        FullSlip {
            rows,
            w,
            one: blended(ab.to_bits(), rows, w),
            m_max: max_moment(ab.clamp(0.1, 10.0)),
        }
    }

    /// The loads of full slip (project signs) in the direction of the normalised creepages
    /// `(xi_n, eta_n, phi_n)` (finite, not all zero; their size does not matter).
    #[inline]
    pub fn loads(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        let sx = 1.0f64.copysign(xi_n);
        let sy = 1.0f64.copysign(eta_n);
        let (x, y, p) = (xi_n.abs(), eta_n.abs(), phi_n * sy);
        let t = x + y;
        let u = if t > 0.0 { y / t } else { 0.0 };
        let v = p / (t + p.abs());
        let fu = u * (NU - 1) as f64;
        let fv = (v + 1.0) * 0.5 * (NV - 1) as f64;
        // (Through i64: `fu`, `fv` are finite and not negative, and x86-64 converts an f64 to
        // an i64 in one instruction, to a usize in several.)
        let i = (fu as i64 as usize).min(NU - 2);
        let j = (fv as i64 as usize).min(NV - 2);
        let (wu, wv) = (fu - i as f64, fv - j as f64);
        let base = i * NV + j;
        // The cell's four entries of each row (one bounds check per row), blended in `a/b`
        // and bilinearly in f32, the entries' own precision (within 1e-7 of the f64 blend:
        // test `f32_blend_is_the_f64_blend`).
        let (wu, wv) = (wu as f32, wv as f32);
        let (c00, c01, c10, c11) = match self.one {
            Some(row) => {
                let r = &row[base..base + NV + 2];
                (r[0], r[1], r[NV], r[NV + 1])
            }
            None => self.corners(base),
        };
        let mut out = [0.0f64; 3];
        for m in 0..3 {
            let lo = c00[m] + (c01[m] - c00[m]) * wv;
            let hi = c10[m] + (c11[m] - c10[m]) * wv;
            out[m] = f64::from(lo + (hi - lo) * wu);
        }
        // Back from the translation's frame (the creepages are clamped, so the squares are
        // finite).
        let h2 = x * x + y * y;
        let (cx, cy) = if h2 > 0.0 {
            let r = 1.0 / h2.sqrt();
            (x * r, y * r)
        } else {
            (1.0, 0.0)
        };
        Loads {
            fx: sx * (out[0] * cx - out[1] * cy),
            fy: sy * (out[0] * cy + out[1] * cx),
            mz: sy * out[2] * self.m_max,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small deterministic generator (xorshift) for the sample directions.
    fn rng(state: &mut u64) -> f64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The table against the quadrature off its nodes: random axis ratios over Kalker's range
    /// and random directions of every sign (size irrelevant): within 0.7 % of `mu P` in each
    /// force and 1.7 % of `mu P c` in the moment (the largest where the pole of the slip
    /// crosses the edge of a long patch, `a/b` near 0.1 or 10).
    #[test]
    fn table_matches_quadrature_off_its_nodes() {
        let mut st = 0x9e37_79b9_7f4a_7c15u64;
        let mut worst = [0.0f64; 3];
        for _ in 0..300 {
            let ab = 10f64.powf(2.0 * rng(&mut st) - 1.0);
            let d = [
                4.0 * rng(&mut st) - 2.0,
                4.0 * rng(&mut st) - 2.0,
                (8.0 * rng(&mut st) - 4.0) * rng(&mut st),
            ];
            let q = rigid_slip_loads(ab, d, 100);
            let l = FullSlip::at(ab).loads(d[0] * 7.0, d[1] * 7.0, d[2] * 7.0);
            for (w, e) in worst
                .iter_mut()
                .zip([l.fx - q[0], l.fy - q[1], l.mz - q[2]])
            {
                *w = w.max(e.abs());
            }
        }
        assert!(worst[0] < 7e-3 && worst[1] < 7e-3, "{worst:?}");
        assert!(worst[2] < 1.7e-2, "{worst:?}");
    }

    /// The row blended once for an axis ratio (`blend_rows`) reads the same bits as the two rows
    /// blended at each evaluation (beyond `BLENDED_MAX` axis ratios), at random axis ratios
    /// and directions of every sign.
    #[test]
    fn blended_row_reads_as_the_two_rows() {
        let mut st = 0x51a7_c0de_1234_5678u64;
        for _ in 0..200 {
            let ab = 10f64.powf(2.0 * rng(&mut st) - 1.0);
            let at = FullSlip::at(ab);
            let kept = FullSlip {
                one: Some(Box::leak(blend_rows(at.rows, at.w))),
                ..at
            };
            let two = FullSlip { one: None, ..at };
            for _ in 0..20 {
                let d = [
                    4.0 * rng(&mut st) - 2.0,
                    4.0 * rng(&mut st) - 2.0,
                    8.0 * rng(&mut st) - 4.0,
                ];
                let (a, b) = (kept.loads(d[0], d[1], d[2]), two.loads(d[0], d[1], d[2]));
                assert_eq!(
                    [a.fx.to_bits(), a.fy.to_bits(), a.mz.to_bits()],
                    [b.fx.to_bits(), b.fy.to_bits(), b.mz.to_bits()],
                    "a/b {ab}, {d:?}"
                );
            }
        }
    }

    /// The cell read in f32 (`loads`) against the same entries blended in f64: within 1e-6 of
    /// `mu P` (and of `M_max`) at random axis ratios and directions, so the f32 arithmetic adds
    /// nothing beyond the entries' own rounding.
    #[test]
    fn f32_blend_is_the_f64_blend() {
        let mut st = 0x2545_f491_4f6c_dd1du64;
        let mut worst = 0.0f64;
        for _ in 0..2000 {
            let ab = 10f64.powf(2.0 * rng(&mut st) - 1.0);
            let (x, y, p) = (
                2.0 * rng(&mut st) - 1.0,
                2.0 * rng(&mut st) - 1.0,
                4.0 * rng(&mut st) - 2.0,
            );
            let t = FullSlip::at(ab);
            let l = t.loads(x, y, p);
            // The f64 reference: the same cell, weights and frame.
            let (ax, ay, pp) = (x.abs(), y.abs(), p * 1.0f64.copysign(y));
            let tt = ax + ay;
            let u = if tt > 0.0 { ay / tt } else { 0.0 };
            let v = pp / (tt + pp.abs());
            let (fu, fv) = (u * (NU - 1) as f64, (v + 1.0) * 0.5 * (NV - 1) as f64);
            let (i, j) = ((fu as usize).min(NU - 2), (fv as usize).min(NV - 2));
            let (wu, wv) = (fu - i as f64, fv - j as f64);
            let base = i * NV + j;
            let mut out = [0.0f64; 3];
            for (r, wr) in [(t.rows[0], 1.0 - t.w), (t.rows[1], t.w)] {
                for (k, w) in [
                    (base, (1.0 - wu) * (1.0 - wv)),
                    (base + 1, (1.0 - wu) * wv),
                    (base + NV, wu * (1.0 - wv)),
                    (base + NV + 1, wu * wv),
                ] {
                    for m in 0..3 {
                        out[m] += wr * w * f64::from(r[k][m]);
                    }
                }
            }
            let h = ax.hypot(ay);
            let (cx, cy) = if h > 0.0 {
                (ax / h, ay / h)
            } else {
                (1.0, 0.0)
            };
            let (sx, sy) = (1.0f64.copysign(x), 1.0f64.copysign(y));
            let e = [
                l.fx - sx * (out[0] * cx - out[1] * cy),
                l.fy - sy * (out[0] * cy + out[1] * cx),
                (l.mz - sy * out[2] * t.m_max) / t.m_max,
            ];
            worst = e.iter().fold(worst, |w, d| w.max(d.abs()));
        }
        assert!(worst < 1e-6, "{worst:e}");
        eprintln!("f32 blend against f64: worst {worst:.2e}");
    }

    /// The checked-in table is its generator's (`examples/full_slip_table.rs`): a few entries
    /// recomputed, to the six printed decimals.
    #[test]
    fn table_is_its_generator_output() {
        let t = &crate::steady3d::full_slip_data::ROWS;
        for (k, i, j) in [
            (0, 3, 11),
            (7, 12, 24),
            (12, 24, 40),
            (19, 0, 30),
            (24, 17, 2),
        ] {
            let q = rigid_slip_frame(row_ab(k), node_direction(i, j), 240);
            let e = t[k][i * NV + j];
            for c in 0..3 {
                assert!(
                    (f64::from(e[c]) - q[c]).abs() < 1e-6,
                    "{k} {i} {j}: {e:?} {q:?}"
                );
            }
        }
    }

    /// Closed forms: a pure translation slips everywhere along itself (`|F| = mu P`, no
    /// moment); a pure spin on a circle gives no force and `Mz = 3 pi/16 mu P a` (Johnson
    /// 1985, sec. 8.4: the torque of full slip on Hertz's pressure).
    #[test]
    fn closed_forms_of_full_slip() {
        for ab in [0.1, 0.37, 1.0, 2.9, 10.0] {
            let t = FullSlip::at(ab);
            let l = t.loads(0.6, -0.8, 0.0);
            assert!(
                (l.fx - 0.6).abs() < 1e-12 && (l.fy + 0.8).abs() < 1e-12,
                "{l:?}"
            );
            assert!(l.mz.abs() < 1e-12, "{l:?}");
        }
        let l = FullSlip::at(1.0).loads(0.0, 0.0, -3.0);
        let m = 3.0 * std::f64::consts::PI / 16.0;
        assert!(l.fx == 0.0 && l.fy == 0.0, "{l:?}");
        assert!((l.mz + m).abs() < 1e-12, "{} vs {}", l.mz, -m);
        // The closed form of the pure spin's moment is the quadrature's at every a/b.
        for ab in [0.1, 0.2, 0.5, 1.0, 1.7, 4.0, 10.0] {
            let q = rigid_slip_loads(ab, [0.0, 0.0, 1.0], 200)[2];
            assert!(
                (q / max_moment(ab) - 1.0).abs() < 1e-4,
                "{ab}: {q} {}",
                max_moment(ab)
            );
        }
    }
}
