//! Non-linear Gauss-Seidel for the discrete tangential contact problem with Coulomb friction.
//!
//! Both the steady and the transient problems have, per element `I`, the slip (of body `q`
//! relative to body `p`, per step or per unit rolling distance)
//!
//! `S_I = w_I + sum_J M(I - J) t_J`,
//!
//! with `t_J` the traction on body `p` [Pa], `w_I` a known vector, and `M` a translation-invariant
//! 2x2-block kernel whose self term is `M(0) = -diag(D_x, D_y)` with `D_x, D_y > 0`. The friction
//! law (Coulomb, maximum dissipation, full non-linear direction) is, with the bound `g_I = mu p_I`:
//!
//! * stick: `S_I = 0`, `|t_I| <= g_I`;
//! * slip: `|t_I| = g_I`, `t_I = g_I S_I / |S_I|` (the traction on `p` follows the slip of `q`
//!   relative to `p`, so that the dissipation `t . S` is positive).
//!
//! One element at a time, with the others fixed, `S_I = r_I - D t_I` and the element's problem
//! has the exact solution: `t_I = D^-1 r_I` if that lies within the bound (stick), otherwise
//! `t_I = (D + lambda I)^-1 r_I` with `lambda > 0` such that `|t_I| = g_I` (slip, `S_I = lambda
//! t_I`). Sweeping these exact element solves is the non-linear block Gauss-Seidel that Kalker
//! (1990, *Three-dimensional elastic bodies in rolling contact*, ch. 5, algorithm TANG's inner
//! iteration) and Vollebregt (2014, "A Gauss-Seidel type solver for special convex programs, with
//! application to frictional contact mechanics", J. Optim. Theory Appl. 87) use. The sweep goes
//! against the material flow (leading edge first), which makes the dominant upwind coupling of
//! the rolling problem lower-triangular.

use super::SolverOptions;
use crate::error::RefError;
use crate::grid::Grid;
use crate::influence::Kernel;

/// Element solve: the `t` with `|t| <= g` and `S = r - D t` obeying Coulomb's law.
#[inline]
pub(crate) fn local_solve(rx: f64, ry: f64, dx: f64, dy: f64, g: f64) -> (f64, f64) {
    if !(g > 0.0) {
        return (0.0, 0.0);
    }
    let (sx, sy) = (rx / dx, ry / dy);
    let n2 = sx * sx + sy * sy;
    if n2 <= g * g {
        return (sx, sy);
    }
    if dx == dy {
        let s = g / n2.sqrt();
        return (sx * s, sy * s);
    }
    // Newton on phi(l) = 1/|t(l)| - 1/g, increasing and concave in l: from l = 0 (left of the
    // root) the iterates increase monotonically to the root.
    let mut l = 0.0f64;
    for _ in 0..60 {
        let (ax, ay) = (rx / (dx + l), ry / (dy + l));
        let n = (ax * ax + ay * ay).sqrt();
        let phi = 1.0 / n - 1.0 / g;
        let dphi = (ax * ax / (dx + l) + ay * ay / (dy + l)) / (n * n * n);
        let step = -phi / dphi;
        l += step;
        if step.abs() <= 1e-15 * (l + dx.max(dy)) {
            break;
        }
    }
    let (ax, ay) = (rx / (dx + l), ry / (dy + l));
    // Put the result exactly on the bound (Newton leaves a relative error ~1e-15).
    let s = g / (ax * ax + ay * ay).sqrt();
    (ax * s, ay * s)
}

/// The discrete operator `S = w + M t` on the elements of a grid.
pub(crate) struct Operator<'a> {
    pub grid: &'a Grid,
    pub kernel: &'a Kernel,
}

impl Operator<'_> {
    /// `D = -M(0)` (both components positive).
    pub fn diag(&self) -> (f64, f64) {
        let k = self.kernel.index(0, 0);
        (-self.kernel.xx[k], -self.kernel.yy[k])
    }

    /// Adds `M(. - J) (dx, dy)` to `(sx, sy)`: the effect of changing element `J`'s traction.
    #[inline]
    pub fn add_column(&self, j: usize, dtx: f64, dty: f64, sx: &mut [f64], sy: &mut [f64]) {
        let k = self.kernel;
        let (jx, jy) = (self.grid.ix[j], self.grid.iy[j]);
        for row in &self.grid.rows {
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

    /// `S = w + M t` from scratch.
    pub fn apply(&self, wx: &[f64], wy: &[f64], tx: &[f64], ty: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let mut sx = wx.to_vec();
        let mut sy = wy.to_vec();
        for j in 0..tx.len() {
            if tx[j] != 0.0 || ty[j] != 0.0 {
                self.add_column(j, tx[j], ty[j], &mut sx, &mut sy);
            }
        }
        (sx, sy)
    }
}

/// Sweep order: rows in turn, each from its leading edge (largest `x`) backwards.
pub(crate) fn leading_edge_first(grid: &Grid) -> Vec<usize> {
    let mut order = Vec::with_capacity(grid.len());
    for r in &grid.rows {
        order.extend((r.start..r.start + r.len).rev());
    }
    order
}

/// Solves the discrete problem by non-linear Gauss-Seidel sweeps, starting from (and
/// overwriting) `tx, ty`. Converged when a whole sweep changes no traction by more than
/// `opts.tolerance * max(bound)`. Returns the number of sweeps.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve(
    op: &Operator<'_>,
    wx: &[f64],
    wy: &[f64],
    bound: &[f64],
    order: &[usize],
    opts: &SolverOptions,
    tx: &mut [f64],
    ty: &mut [f64],
) -> Result<usize, RefError> {
    let (dx, dy) = op.diag();
    let (mut sx, mut sy) = op.apply(wx, wy, tx, ty);
    let scale = bound.iter().cloned().fold(0.0, f64::max);
    let tol = opts.tolerance * scale;
    let mut change = f64::INFINITY;
    for sweep in 1..=opts.max_sweeps {
        change = 0.0f64;
        for &e in order {
            let rx = sx[e] + dx * tx[e];
            let ry = sy[e] + dy * ty[e];
            let (nx, ny) = local_solve(rx, ry, dx, dy, bound[e]);
            let (ddx, ddy) = (nx - tx[e], ny - ty[e]);
            if ddx != 0.0 || ddy != 0.0 {
                change = change.max(ddx.abs().max(ddy.abs()));
                tx[e] = nx;
                ty[e] = ny;
                op.add_column(e, ddx, ddy, &mut sx, &mut sy);
            }
        }
        if change <= tol {
            return Ok(sweep);
        }
    }
    Err(RefError::NoConvergence {
        solver: "non-linear Gauss-Seidel",
        iterations: opts.max_sweeps,
        residual: change / scale.max(f64::MIN_POSITIVE),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_solve_obeys_coulomb() {
        // Stick inside the bound.
        assert_eq!(local_solve(1.0, 0.0, 2.0, 2.0, 1.0), (0.5, 0.0));
        // Isotropic slip: radial projection.
        let (x, y) = local_solve(3.0, 4.0, 1.0, 1.0, 1.0);
        assert!((x - 0.6).abs() < 1e-15 && (y - 0.8).abs() < 1e-15);
        // Anisotropic slip: on the bound and S = r - D t parallel to t with positive factor.
        let (rx, ry, dx, dy, g) = (3.0, -2.0, 1.0, 1.7, 0.9);
        let (x, y) = local_solve(rx, ry, dx, dy, g);
        assert!(((x * x + y * y).sqrt() - g).abs() < 1e-14);
        let (sx, sy) = (rx - dx * x, ry - dy * y);
        assert!((sx * y - sy * x).abs() < 1e-12, "slip not parallel");
        assert!(sx * x + sy * y > 0.0, "dissipation must be positive");
        // Zero bound.
        assert_eq!(local_solve(1.0, 1.0, 1.0, 1.0, 0.0), (0.0, 0.0));
    }
}
