//! Between the rows of the table (module documentation of [`super`], "Between nodes"): the
//! two-row blend (the previous round's law, and the reference of the tabulated one), the
//! blended spin terms, and the pure-spin parts the correction is built from.

use super::{
    Loads, NODE_LN_AB, NODE_NU, NODES, Node, ROW_SNAP, SpinRow, SpinTerms, Steady3d, bracket,
    node_at, saturation_of_ratio,
};
use crate::error::LawError;
use crate::kalker3d;

impl Steady3d {
    /// The law of the previous round between rows (module documentation, "Between nodes"):
    /// the loads of the two rows around `a/b` blended with convex weights, two translations
    /// per evaluation. At a row of the table it is [`Steady3d::new`]'s law. [`Steady3d::new`]
    /// fits its virtual row to this law; kept for that, for comparisons and for the bench.
    pub fn two_row_blend(ab: f64, nu: f64) -> Result<Self, LawError> {
        kalker3d::coefficients(ab, nu)?;
        let mut law = Self::with_node(ab, nu, node_at(ab, nu))?;
        let (i, wa) = bracket(&NODE_LN_AB, ab.ln());
        // Within a weight of ROW_SNAP of a row, that row (an a/b from f32 geometry misses a
        // row by ~1e-7; the loads differ from the blend's by less than ROW_SNAP of mu P).
        let wa = if wa < ROW_SNAP {
            0.0
        } else if wa > 1.0 - ROW_SNAP {
            1.0
        } else {
            wa
        };
        let (j, wn) = bracket(&NODE_NU, nu);
        for (k, (row, w)) in [(i, 1.0 - wa), (i + 1, wa)].into_iter().enumerate() {
            let (lo, hi) = (&NODES[row][j], &NODES[row][j + 1]);
            let mut n = [0.0; 18];
            for (o, (x, y)) in n.iter_mut().zip(lo.to_array().iter().zip(hi.to_array())) {
                *o = (1.0 - wn) * x + wn * y;
            }
            // At the column nu = 0.5 the shape of `hi` alone.
            let shapes = if wn == 1.0 {
                ((1.0, hi), (0.0, lo))
            } else {
                ((1.0 - wn, lo), (wn, hi))
            };
            law.rows[k] = SpinRow::new(w, Node::from_array(n), shapes.0, shapes.1);
        }
        if law.rows[0].w == 0.0 {
            // At a row (ab at or beyond the last row): evaluate that row only.
            law.rows.swap(0, 1);
        }
        Ok(law)
    }

    /// Between rows, `|phi_n|` outside the table's knots (rare): steps 3-5 on the blended
    /// terms from the two rows, with the correction's continuation.
    #[cold]
    #[inline(never)]
    pub(super) fn beyond_the_knots(
        &self,
        phi_n: f64,
        e: f64,
        tx0: f64,
        ty0: f64,
        ml: f64,
    ) -> Loads {
        let t = self.blended_terms_exact(phi_n, e, self.corr.g_beyond(phi_n));
        self.with_spin(phi_n, tx0, ty0, ml, &t)
    }

    /// [`Steady3d::two_row_blend`]'s evaluation between rows: the two rows' loads blended
    /// (the previous round's law: the reference, out of line).
    #[cold]
    #[inline(never)]
    pub(super) fn two_rows_blended(
        &self,
        phi_n: f64,
        e: f64,
        tx0: f64,
        ty0: f64,
        ml: f64,
    ) -> Loads {
        let [t0, t1] = self.spin_terms::<2>(phi_n, e);
        let a = self.with_spin(phi_n, tx0, ty0, ml, &t0);
        let b = self.with_spin(phi_n, tx0, ty0, ml, &t1);
        let (w0, w1) = (self.rows[0].w, self.rows[1].w);
        Loads {
            fx: w0 * a.fx + w1 * b.fx,
            fy: w0 * a.fy + w1 * b.fy,
            mz: w0 * a.mz + w1 * b.mz,
        }
    }

    /// The two rows' spin terms blended with the rows' weights (every term enters the loads
    /// linearly but the translation's `w` and `lam f_s`).
    #[inline(always)]
    pub(super) fn blended_terms(&self, t0: &SpinTerms, t1: &SpinTerms) -> SpinTerms {
        let (w0, w1) = (self.rows[0].w, self.rows[1].w);
        let b = |a: f64, b: f64| w0 * a + w1 * b;
        SpinTerms {
            w: b(t0.w, t1.w),
            cap_x: b(t0.cap_x, t1.cap_x),
            cap_y: b(t0.cap_y, t1.cap_y),
            f_sat: b(t0.f_sat, t1.f_sat),
            f_rest: b(t0.f_rest, t1.f_rest),
            ml_factor: b(t0.ml_factor, t1.ml_factor),
            spin_moment: b(t0.spin_moment, t1.spin_moment),
        }
    }

    /// Between rows: the two rows' spin terms at `phi_n` blended, with the correction `g`
    /// added to the unsaturated share (`e` the translation alone's utilisation).
    pub(super) fn blended_terms_exact(&self, phi_n: f64, e: f64, g: f64) -> SpinTerms {
        let [t0, t1] = self.spin_terms::<2>(phi_n, e);
        let mut t = self.blended_terms(&t0, &t1);
        t.f_rest += g;
        t
    }

    /// Pure spin `phi_n != 0` between rows, without the correction: the lateral force of the
    /// one-translation evaluation, the blend's, and `(1 - s_t)^(1/4)` of the one translation
    /// (what multiplies the correction).
    pub(super) fn pure_spin_parts(&self, phi_n: f64) -> (f64, f64, f64) {
        let [t0, t1] = self.spin_terms::<2>(phi_n, 0.0);
        let (one, blend, h, _) = self.pure_spin_of(phi_n, &t0, &t1);
        (one, blend, h)
    }

    /// [`Steady3d::pure_spin_parts`] from the two rows' spin terms `t0, t1` at `phi_n` (and
    /// `e = 0`), with each row's lateral force before the projection onto `|F| <= 1` (the
    /// blend's kinks are where one of them reaches 1).
    pub(super) fn pure_spin_of(
        &self,
        phi_n: f64,
        t0: &SpinTerms,
        t1: &SpinTerms,
    ) -> (f64, f64, f64, [f64; 2]) {
        let t = self.blended_terms(t0, t1);
        let one = self.with_spin(phi_n, 0.0, 0.0, 0.0, &t).fy;
        let a = self.with_spin(phi_n, 0.0, 0.0, 0.0, t0).fy;
        let b = self.with_spin(phi_n, 0.0, 0.0, 0.0, t1).fy;
        let blend = self.rows[0].w * a + self.rows[1].w * b;
        let ty = t.f_sat;
        let st = if ty != 0.0 {
            let q = self.n.ky * ty * ty;
            saturation_of_ratio(ty.abs() / (t.w * self.n.ky), q / (ty * ty))
        } else {
            0.0
        };
        let u = [
            self.force_unprojected(0.0, 0.0, t0).1,
            self.force_unprojected(0.0, 0.0, t1).1,
        ];
        (one, blend, (1.0 - st).sqrt().sqrt(), u)
    }
}
