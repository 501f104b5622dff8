//! Half-space influence coefficients of a uniform traction on a rectangle (Boussinesq for the
//! normal, Cerruti for the tangential direction), for two quasi-identical bodies.
//!
//! The surface displacements of an elastic half-space under a point force on its surface are
//! Boussinesq's (normal force) and Cerruti's (tangential force) solutions (Johnson 1985, *Contact
//! Mechanics*, §3.2; Love 1929, "The stress produced in a semi-infinite solid by pressure on part
//! of the boundary", Phil. Trans. R. Soc. A 228). On the surface `z = 0` of one body of shear
//! modulus `G_i` and Poisson ratio `nu_i`, a tangential point force `Q_x` gives
//!
//! `u_x = Q_x / (2 pi G_i) [(1 - nu_i)/r + nu_i x^2/r^3]`, `u_y = Q_x / (2 pi G_i) nu_i x y / r^3`,
//!
//! and a normal point force `P` gives `u_z = P (1 - nu_i) / (2 pi G_i r)`. For two bodies pressed
//! together the contact traction acts on body `p` and its opposite on body `q`, and the quantity
//! that enters the contact conditions is the displacement *difference* `u_p - u_q`. With Kalker's
//! combined constants (Kalker 1990, *Three-dimensional elastic bodies in rolling contact*, §1.5:
//! `1/G = (1/G_p + 1/G_q)/2`, `nu = G/2 (nu_p/G_p + nu_q/G_q)`) the sum of the two bodies'
//! kernels is exactly
//!
//! `A_xx = 1/(pi G) [(1 - nu)/r + nu x^2/r^3]`, `A_xy = 1/(pi G) nu x y/r^3`,
//! `A_zz = (1 - nu)/(pi G r)`,
//!
//! when the coupling between normal and tangential directions is neglected, which is exact for
//! quasi-identical bodies (`(1-2 nu_p)/G_p = (1-2 nu_q)/G_q`, Kalker 1990 §1.5).
//!
//! Integrating over a rectangle with uniform traction uses the antiderivatives
//! `∫∫ 1/r = X ln(Y + r) + Y ln(X + r)`, `∫∫ X^2/r^3 = Y ln(X + r)`, `∫∫ Y^2/r^3 = X ln(Y + r)`
//! and `∫∫ X Y/r^3 = -r` (elementary; they are the closed forms Kalker 1990, ch. 5, uses for
//! piecewise-constant tractions), evaluated at the four corners.

/// Tangential influence coefficients of one rectangle: displacement difference `u_p - u_q` \[m\]
/// per unit uniform traction \[Pa\] on body `p` over the rectangle (so the unit is m/Pa).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    /// `u_x` per unit traction `t_x` \[m/Pa\].
    pub xx: f64,
    /// `u_x` per unit `t_y`, equal to `u_y` per unit `t_x` \[m/Pa\].
    pub xy: f64,
    /// `u_y` per unit traction `t_y` \[m/Pa\].
    pub yy: f64,
}

/// `a ln(b + sqrt(a^2 + b^2))`, with the limit 0 at `a = 0` and a cancellation-free form for
/// `b < 0` (`b + r = a^2/(r - b)`).
#[inline]
fn xlog(a: f64, b: f64) -> f64 {
    if a == 0.0 {
        return 0.0;
    }
    let r = a.hypot(b);
    if b >= 0.0 {
        a * (b + r).ln()
    } else {
        a * (a * a / (r - b)).ln()
    }
}

/// Sums `f` over the corners of the rectangle in relative coordinates: `X in [x1, x2]`,
/// `Y in [y1, y2]` with the signs of a double definite integral.
#[inline]
fn corners(x1: f64, x2: f64, y1: f64, y2: f64, f: impl Fn(f64, f64) -> f64) -> f64 {
    f(x2, y2) - f(x1, y2) - f(x2, y1) + f(x1, y1)
}

/// Cerruti influence coefficients (two quasi-identical bodies, combined `g` and `nu`) of a
/// uniform tangential traction on the rectangle `[-hx/2, hx/2] x [-hy/2, hy/2]`, at the surface
/// point `(x, y)` \[m\].
///
/// * `hx`, `hy` — rectangle sides \[m\], > 0;
/// * `g` — combined shear modulus \[Pa\], > 0; `nu` — combined Poisson ratio, in `[0, 0.5]`.
///
/// Source: Cerruti's point-force solution (Johnson 1985, §3.2) integrated in closed form (see the
/// module documentation). Inputs are not validated here (internal kernel; callers validate).
pub fn rectangle_tangential(x: f64, y: f64, hx: f64, hy: f64, g: f64, nu: f64) -> Tangential {
    // Relative coordinates X = x - x', Y = y - y' over the source rectangle.
    let (x1, x2) = (x - 0.5 * hx, x + 0.5 * hx);
    let (y1, y2) = (y - 0.5 * hy, y + 0.5 * hy);
    let ixx = corners(x1, x2, y1, y2, |a, b| xlog(b, a));
    let iyy = corners(x1, x2, y1, y2, xlog);
    let ixy = corners(x1, x2, y1, y2, |a, b| -a.hypot(b));
    let i1 = ixx + iyy;
    let c = 1.0 / (std::f64::consts::PI * g);
    Tangential {
        xx: c * ((1.0 - nu) * i1 + nu * ixx),
        xy: c * nu * ixy,
        yy: c * ((1.0 - nu) * i1 + nu * iyy),
    }
}

/// Boussinesq influence coefficient (two quasi-identical bodies, combined `g`, `nu`): the normal
/// displacement sum `u_zp + u_zq` \[m\] per unit uniform pressure \[Pa\] on the rectangle
/// `[-hx/2, hx/2] x [-hy/2, hy/2]`, at the surface point `(x, y)` \[m\]. Unit m/Pa.
///
/// Source: Boussinesq's point-force solution (Johnson 1985, §3.2) integrated in closed form
/// (Love 1929). Inputs are not validated here.
pub fn rectangle_normal(x: f64, y: f64, hx: f64, hy: f64, g: f64, nu: f64) -> f64 {
    let (x1, x2) = (x - 0.5 * hx, x + 0.5 * hx);
    let (y1, y2) = (y - 0.5 * hy, y + 0.5 * hy);
    let i1 = corners(x1, x2, y1, y2, |a, b| xlog(a, b) + xlog(b, a));
    (1.0 - nu) / (std::f64::consts::PI * g) * i1
}

/// Tangential influence kernel on a square grid of pitch `h`: coefficients of a unit traction on
/// the element at the origin, seen at the element centred at `(dx h + shift, dy h)` for integer
/// offsets `dx in [dx_min, dx_max]`, `dy in [-dy_max, dy_max]`. Translation invariance of the
/// half-space makes the full influence matrix a lookup in this table.
#[derive(Debug, Clone)]
pub(crate) struct Kernel {
    pub dx_min: i64,
    pub nx: usize,
    pub dy_max: i64,
    pub xx: Vec<f64>,
    pub xy: Vec<f64>,
    pub yy: Vec<f64>,
}

impl Kernel {
    /// Builds the table of [`rectangle_tangential`] for square elements of side `h` \[m\].
    pub fn new(h: f64, g: f64, nu: f64, dx_min: i64, dx_max: i64, dy_max: i64, shift: f64) -> Self {
        let nx = (dx_max - dx_min + 1) as usize;
        let ny = (2 * dy_max + 1) as usize;
        let mut xx = vec![0.0; nx * ny];
        let mut xy = vec![0.0; nx * ny];
        let mut yy = vec![0.0; nx * ny];
        for jy in 0..ny {
            let dy = jy as i64 - dy_max;
            for ix in 0..nx {
                let dx = ix as i64 + dx_min;
                let c = rectangle_tangential(dx as f64 * h + shift, dy as f64 * h, h, h, g, nu);
                let k = jy * nx + ix;
                xx[k] = c.xx;
                xy[k] = c.xy;
                yy[k] = c.yy;
            }
        }
        Kernel {
            dx_min,
            nx,
            dy_max,
            xx,
            xy,
            yy,
        }
    }

    /// Flat index of offset `(dx, dy)`; the caller keeps the offsets in range.
    #[inline]
    pub fn index(&self, dx: i64, dy: i64) -> usize {
        (dy + self.dy_max) as usize * self.nx + (dx - self.dx_min) as usize
    }

    /// The kernel multiplied by `factor`.
    pub fn scaled(mut self, factor: f64) -> Kernel {
        for v in self
            .xx
            .iter_mut()
            .chain(self.xy.iter_mut())
            .chain(self.yy.iter_mut())
        {
            *v *= factor;
        }
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Midpoint quadrature of the point-force kernels over a rectangle, for a field point well
    /// outside it (so the integrand is smooth).
    fn quadrature(x: f64, y: f64, hx: f64, hy: f64, g: f64, nu: f64) -> (Tangential, f64) {
        let m = 400;
        let (mut xx, mut xy, mut yy, mut zz) = (0.0, 0.0, 0.0, 0.0);
        let da = hx * hy / (m * m) as f64;
        for i in 0..m {
            for j in 0..m {
                let xs = -0.5 * hx + (i as f64 + 0.5) * hx / m as f64;
                let ys = -0.5 * hy + (j as f64 + 0.5) * hy / m as f64;
                let (dx, dy) = (x - xs, y - ys);
                let r = dx.hypot(dy);
                let c = da / (PI * g);
                xx += c * ((1.0 - nu) / r + nu * dx * dx / (r * r * r));
                yy += c * ((1.0 - nu) / r + nu * dy * dy / (r * r * r));
                xy += c * nu * dx * dy / (r * r * r);
                zz += c * (1.0 - nu) / r;
            }
        }
        (Tangential { xx, xy, yy }, zz)
    }

    #[test]
    fn closed_form_matches_quadrature_of_point_force_kernels() {
        // Far-ish field points, both signs of the offsets, a non-square rectangle.
        let (g, nu) = (30e9, 0.3);
        for &(x, y) in &[(2.0, 1.5), (-1.7, 2.2), (0.3, -2.5), (-2.4, -1.1)] {
            let c = rectangle_tangential(x, y, 1.0, 0.6, g, nu);
            let n = rectangle_normal(x, y, 1.0, 0.6, g, nu);
            let (q, qz) = quadrature(x, y, 1.0, 0.6, g, nu);
            for (a, b) in [(c.xx, q.xx), (c.xy, q.xy), (c.yy, q.yy), (n, qz)] {
                assert!((a - b).abs() < 1e-5 * q.xx.abs(), "({x},{y}): {a} vs {b}");
            }
        }
    }

    #[test]
    fn centre_of_square_matches_known_value() {
        // Uniform pressure on a square of side 2c: the centre's normal displacement (one body)
        // is (1-nu^2)/E * p * (4c/pi) * 2 ln(1+sqrt 2) = (1-nu)/(2 pi G) * p * 8 c ln(1 + sqrt 2)
        // (Love 1929; Johnson 1985 §3.2). Two bodies double it.
        let (g, nu, c) = (1.0, 0.25, 0.5);
        let expect = 2.0 * (1.0 - nu) / (2.0 * PI * g) * 8.0 * c * (1.0 + 2f64.sqrt()).ln();
        let got = rectangle_normal(0.0, 0.0, 2.0 * c, 2.0 * c, g, nu);
        assert!((got / expect - 1.0).abs() < 1e-14, "{got} vs {expect}");
        // At nu = 0 the tangential and normal kernels coincide.
        let t = rectangle_tangential(0.3, -0.2, 1.0, 1.0, g, 0.0);
        let z = rectangle_normal(0.3, -0.2, 1.0, 1.0, g, 0.0);
        assert!((t.xx - z).abs() < 1e-15 && (t.yy - z).abs() < 1e-15 && t.xy == 0.0);
    }

    #[test]
    fn symmetry_of_coefficients() {
        let (g, nu) = (1.0, 0.4);
        let a = rectangle_tangential(1.3, 0.7, 1.0, 1.0, g, nu);
        let b = rectangle_tangential(-1.3, 0.7, 1.0, 1.0, g, nu);
        let c = rectangle_tangential(0.7, 1.3, 1.0, 1.0, g, nu);
        assert!((a.xx - b.xx).abs() < 1e-15 && (a.xy + b.xy).abs() < 1e-15);
        assert!((a.xx - c.yy).abs() < 1e-14 && (a.xy - c.xy).abs() < 1e-14);
        // Self-influence: finite and positive, no xy coupling.
        let s = rectangle_tangential(0.0, 0.0, 1.0, 1.0, g, nu);
        assert!(s.xx > 0.0 && s.xx.is_finite() && s.xy.abs() < 1e-16);
        // Points on the element's edge extensions are finite (log terms vanish properly).
        let e = rectangle_tangential(-0.5, 0.5, 1.0, 1.0, g, nu);
        assert!(e.xx.is_finite() && e.xy.is_finite() && e.yy.is_finite());
    }

    #[test]
    fn hertz_type_tangential_traction_gives_johnsons_displacement() {
        // Traction t_x = q0 sqrt(1 - r^2/a^2) on one body gives, inside the circle,
        // u_x = pi q0 / (32 G a) [4(2-nu) a^2 - (4-3nu) x^2 - (4-nu) y^2] and
        // u_y = pi q0 / (32 G a) 2 nu x y (Johnson 1985, §7.1, the Hertz-type distribution used
        // for Cattaneo-Mindlin). Two bodies: twice that.
        let (g, nu, a, q0) = (1.0, 0.3, 1.0, 1.0);
        let n = 64;
        let h = 2.0 * a / n as f64;
        let c = |i: usize| -a + (i as f64 + 0.5) * h;
        for &(x, y) in &[(0.0, 0.0), (0.4, 0.1), (-0.3, 0.5)] {
            let mut ux = 0.0;
            let mut uy = 0.0;
            for i in 0..n {
                for j in 0..n {
                    let (xs, ys) = (c(i), c(j));
                    let r2 = (xs * xs + ys * ys) / (a * a);
                    if r2 >= 1.0 {
                        continue;
                    }
                    let t = q0 * (1.0 - r2).sqrt();
                    let k = rectangle_tangential(x - xs, y - ys, h, h, g, nu);
                    ux += k.xx * t;
                    uy += k.xy * t;
                }
            }
            let expect = 2.0 * PI * q0 / (32.0 * g * a)
                * (4.0 * (2.0 - nu) * a * a - (4.0 - 3.0 * nu) * x * x - (4.0 - nu) * y * y);
            // Piecewise-constant traction on a 64-grid: ~0.5 % quadrature error near the rim.
            assert!(
                (ux / expect - 1.0).abs() < 5e-3,
                "({x},{y}): {ux} vs {expect}"
            );
            let expect_y = 2.0 * PI * q0 / (32.0 * g * a) * 2.0 * nu * x * y;
            assert!(
                (uy - expect_y).abs() < 5e-3 * expect,
                "uy = {uy} vs {expect_y}"
            );
        }
    }
}
