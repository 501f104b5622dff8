//! Non-linear Gauss-Seidel for the transient (shift) problem, whose operator is symmetric
//! positive definite (Vollebregt's ConvexGS, see [`super::local`] for the element problem).
//!
//! Per element `I` the slip distance of the step (q relative to p) is
//!
//! `S_I = w_I - sum_J A(I - J) t_J`,
//!
//! with `t_J` the traction on body p \[Pa\], `A` the Cerruti influence kernel \[m/Pa\] and `w_I`
//! known \[m\] (the rigid shift plus the previous displacement at the material point). With the
//! others fixed, `S_I = r_I - A(0) t_I` and the element problem of [`super::local`] applies with
//! `D = diag(A_xx(0), A_yy(0))`. Sweeps of exact element solves minimise the convex energy
//! `t.A.t/2 - w.t` over the Coulomb discs `|t_I| <= mu p_I`, so they converge (block coordinate
//! descent on a strictly convex quadratic with separable convex constraints).

use super::SolverOptions;
use super::local;
use crate::error::RefError;
use crate::grid::Grid;
use crate::influence::Kernel;

/// Adds `sign * K(. - J) (dtx, dty)` to `(sx, sy)` over all grid elements.
#[inline]
#[allow(clippy::too_many_arguments)]
pub(crate) fn add_column(
    grid: &Grid,
    k: &Kernel,
    j: usize,
    sign: f64,
    dtx: f64,
    dty: f64,
    sx: &mut [f64],
    sy: &mut [f64],
) {
    let (jx, jy) = (grid.ix[j], grid.iy[j]);
    let (dtx, dty) = (sign * dtx, sign * dty);
    for row in &grid.rows {
        let base = k.index(row.ix_lo - jx, row.iy - jy);
        let kxx = &k.xx[base..base + row.len];
        let kxy = &k.xy[base..base + row.len];
        let kyy = &k.yy[base..base + row.len];
        let ox = &mut sx[row.start..row.start + row.len];
        let oy = &mut sy[row.start..row.start + row.len];
        for i in 0..row.len {
            ox[i] += kxx[i] * dtx + kxy[i] * dty;
            oy[i] += kxy[i] * dtx + kyy[i] * dty;
        }
    }
}

/// Solves `S = w - A t` with Coulomb's law by sweeps of element solves, starting from (and
/// overwriting) `tx, ty`. Converged when a whole sweep changes no traction by more than
/// `opts.tolerance * max(bound)`. Returns the number of sweeps.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve(
    grid: &Grid,
    a: &Kernel,
    wx: &[f64],
    wy: &[f64],
    bound: &[f64],
    opts: &SolverOptions,
    tx: &mut [f64],
    ty: &mut [f64],
) -> Result<usize, RefError> {
    let k0 = a.index(0, 0);
    let (dx, dy) = (a.xx[k0], a.yy[k0]);
    let mut sx = wx.to_vec();
    let mut sy = wy.to_vec();
    for j in 0..grid.len() {
        if tx[j] != 0.0 || ty[j] != 0.0 {
            add_column(grid, a, j, -1.0, tx[j], ty[j], &mut sx, &mut sy);
        }
    }
    let scale = bound.iter().cloned().fold(0.0, f64::max);
    let tol = opts.tolerance * scale;
    let mut change = f64::INFINITY;
    for sweep in 1..=opts.max_sweeps {
        change = 0.0f64;
        for e in 0..grid.len() {
            let rx = sx[e] + dx * tx[e];
            let ry = sy[e] + dy * ty[e];
            let l = local::solve(rx, ry, dx, dy, bound[e]);
            let (ddx, ddy) = (l.tx - tx[e], l.ty - ty[e]);
            if ddx != 0.0 || ddy != 0.0 {
                change = change.max(ddx.abs().max(ddy.abs()));
                tx[e] = l.tx;
                ty[e] = l.ty;
                add_column(grid, a, e, -1.0, ddx, ddy, &mut sx, &mut sy);
            }
        }
        if change <= tol {
            return Ok(sweep);
        }
    }
    Err(RefError::NoConvergence {
        solver: "ConvexGS (transient)",
        iterations: opts.max_sweeps,
        residual: change / scale.max(f64::MIN_POSITIVE),
    })
}
