//! Non-linear Gauss-Seidel for steady-state rolling in traction-difference variables (the idea of
//! Vollebregt's SteadyGS in CONTACT: Vollebregt 2014, "A Gauss-Seidel type solver for special
//! convex programs, with application to frictional contact mechanics", J. Optim. Theory Appl.;
//! written anew here).
//!
//! The steady slip per unit rolling distance (q relative to p) at element `I` is
//! `S_I = w_I + sum_J (A(I + e - J) - A(I - J))/h t_J` (upwind derivative, `e` the element one
//! step upstream, towards the leading edge). A plain element-wise Gauss-Seidel on this
//! non-symmetric operator diverges: its diagonal is no larger than the upstream coupling. With the
//! traction differences along each row, `dp_K = t_K - t_{K+e}` (and, one element downstream of
//! each row's trailing edge, `dp = -t_trailing`), the same slip reads
//!
//! `S_I = w_I - sum_K A(I - K)/h dp_K`,
//!
//! an operator that is symmetric positive definite (the Cerruti kernel), under the constraint
//! that the `dp` of each row sum to zero. The element update keeps that constraint: changing
//! `t_I` by `d` while the sticking elements just downstream of `I` move with it is
//! `dp_I += d, dp_J -= d`, with `J` the first element downstream of `I` that slips (or the
//! exterior element behind the trailing edge). Its effect on `S_I` is `-(A(0) - A(J - I))/h d`,
//! so the element problem of [`super::local`] applies with that diagonal.

use super::SolverOptions;
use super::local;
use crate::error::RefError;
use crate::grid::Grid;
use crate::influence::Kernel;

/// State of the steady solver in traction-difference variables.
pub(crate) struct SteadyGs<'a> {
    grid: &'a Grid,
    /// Cerruti kernel divided by `h` \[1/Pa\], offsets in `[-(N+1), N+1]`.
    ah: &'a Kernel,
    /// `dp` per element, then one exterior slot per row (behind its trailing edge).
    dpx: Vec<f64>,
    dpy: Vec<f64>,
}

impl<'a> SteadyGs<'a> {
    pub fn new(grid: &'a Grid, ah: &'a Kernel) -> Self {
        let m = grid.len() + grid.rows.len();
        SteadyGs {
            grid,
            ah,
            dpx: vec![0.0; m],
            dpy: vec![0.0; m],
        }
    }

    /// Sets `dp` from the tractions.
    fn set_dp(&mut self, tx: &[f64], ty: &[f64]) {
        let n = self.grid.len();
        for (r, row) in self.grid.rows.iter().enumerate() {
            for k in 0..row.len {
                let e = row.start + k;
                let (ux, uy) = if k + 1 < row.len {
                    (tx[e + 1], ty[e + 1])
                } else {
                    (0.0, 0.0)
                };
                self.dpx[e] = tx[e] - ux;
                self.dpy[e] = ty[e] - uy;
            }
            self.dpx[n + r] = -tx[row.start];
            self.dpy[n + r] = -ty[row.start];
        }
    }

    /// Slip `S_I = w_I - sum_K A(I-K)/h dp_K` at element `e` (using `A(d) = A(-d)`).
    fn slip(&self, e: usize, wx: f64, wy: f64) -> (f64, f64) {
        let g = self.grid;
        let k = self.ah;
        let n = g.len();
        let (ix, iy) = (g.ix[e], g.iy[e]);
        let (mut sx, mut sy) = (0.0, 0.0);
        for (r, row) in g.rows.iter().enumerate() {
            // Exterior slot at ix_lo - 1, then the contiguous row.
            let base = k.index(row.ix_lo - 1 - ix, row.iy - iy);
            let len = row.len + 1;
            let kxx = &k.xx[base..base + len];
            let kxy = &k.xy[base..base + len];
            let kyy = &k.yy[base..base + len];
            let (ex, ey) = (self.dpx[n + r], self.dpy[n + r]);
            sx += kxx[0] * ex + kxy[0] * ey;
            sy += kxy[0] * ex + kyy[0] * ey;
            let px = &self.dpx[row.start..row.start + row.len];
            let py = &self.dpy[row.start..row.start + row.len];
            let (mut ax, mut ay) = (0.0, 0.0);
            for i in 0..row.len {
                ax += kxx[i + 1] * px[i] + kxy[i + 1] * py[i];
                ay += kxy[i + 1] * px[i] + kyy[i + 1] * py[i];
            }
            sx += ax;
            sy += ay;
        }
        (wx - sx, wy - sy)
    }

    /// Solves the steady problem from (and overwriting) `tx, ty, stick`. Rows are swept from the
    /// trailing edge towards the leading edge. Converged when a sweep changes no traction by more
    /// than `opts.tolerance * max(bound)`; returns the number of sweeps.
    #[allow(clippy::too_many_arguments)]
    pub fn solve(
        &mut self,
        wx: &[f64],
        wy: &[f64],
        bound: &[f64],
        opts: &SolverOptions,
        tx: &mut [f64],
        ty: &mut [f64],
        stick: &mut [bool],
    ) -> Result<usize, RefError> {
        self.set_dp(tx, ty);
        let g = self.grid;
        let n = g.len();
        let k0 = self.ah.index(0, 0);
        let scale = bound.iter().cloned().fold(0.0, f64::max);
        let tol = opts.tolerance * scale;
        let mut change = f64::INFINITY;
        for sweep in 1..=opts.max_sweeps {
            change = 0.0f64;
            for (r, row) in g.rows.iter().enumerate() {
                for k in 0..row.len {
                    let e = row.start + k;
                    // First non-sticking element downstream (or the exterior slot).
                    let mut j = None;
                    for kk in (0..k).rev() {
                        if !stick[row.start + kk] {
                            j = Some(kk);
                            break;
                        }
                    }
                    let (jslot, jdx) = match j {
                        Some(kk) => (row.start + kk, kk as i64 - k as i64),
                        None => (n + r, -(k as i64) - 1),
                    };
                    let kj = self.ah.index(jdx, 0);
                    let cx = self.ah.xx[k0] - self.ah.xx[kj];
                    let cy = self.ah.yy[k0] - self.ah.yy[kj];
                    let (sx, sy) = self.slip(e, wx[e], wy[e]);
                    let l = local::solve(sx + cx * tx[e], sy + cy * ty[e], cx, cy, bound[e]);
                    stick[e] = l.stick;
                    let (dx, dy) = (l.tx - tx[e], l.ty - ty[e]);
                    if dx != 0.0 || dy != 0.0 {
                        change = change.max(dx.abs().max(dy.abs()));
                        self.dpx[e] += dx;
                        self.dpy[e] += dy;
                        self.dpx[jslot] -= dx;
                        self.dpy[jslot] -= dy;
                        let first = j.map_or(0, |kk| kk + 1);
                        for kk in first..=k {
                            tx[row.start + kk] += dx;
                            ty[row.start + kk] += dy;
                        }
                    }
                }
            }
            if change <= tol {
                return Ok(sweep);
            }
        }
        Err(RefError::NoConvergence {
            solver: "SteadyGS (steady rolling)",
            iterations: opts.max_sweeps,
            residual: change / scale.max(f64::MIN_POSITIVE),
        })
    }
}
