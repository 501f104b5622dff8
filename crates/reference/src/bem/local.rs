//! The element problem of the Gauss-Seidel solvers: Coulomb's law at one element with the others
//! held fixed.
//!
//! With the other elements fixed, the slip of the element is `S = r - D t` with a known `r` and a
//! positive diagonal `D = diag(dx, dy)`. The solution with the bound `g = mu p` is
//!
//! * stick: `t = D^-1 r` if `|D^-1 r| <= g` (then `S = 0`);
//! * slip: `t = (D + l I)^-1 r` with `l > 0` such that `|t| = g` (then `S = l t`: the traction on
//!   body p is parallel to the slip of q relative to p, Coulomb's law with maximum dissipation).
//!
//! This is the element solver of Kalker's and Vollebregt's Gauss-Seidel methods (Kalker 1990,
//! *Three-dimensional elastic bodies in rolling contact*, ch. 5; Vollebregt 2014, "A Gauss-Seidel
//! type solver for special convex programs, with application to frictional contact mechanics",
//! J. Optim. Theory Appl.), written here with a Newton iteration on `1/|t(l)| - 1/g`.

/// Solution of the element problem: the traction and whether the element sticks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Local {
    pub tx: f64,
    pub ty: f64,
    pub stick: bool,
}

/// Element solve: the `t` with `|t| <= g` and `S = r - D t` obeying Coulomb's law.
#[inline]
pub(crate) fn solve(rx: f64, ry: f64, dx: f64, dy: f64, g: f64) -> Local {
    if g.is_nan() || g <= 0.0 {
        return Local {
            tx: 0.0,
            ty: 0.0,
            stick: false,
        };
    }
    let (sx, sy) = (rx / dx, ry / dy);
    let n2 = sx * sx + sy * sy;
    if n2 <= g * g {
        return Local {
            tx: sx,
            ty: sy,
            stick: true,
        };
    }
    if dx == dy {
        let s = g / n2.sqrt();
        return Local {
            tx: sx * s,
            ty: sy * s,
            stick: false,
        };
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
    Local {
        tx: ax * s,
        ty: ay * s,
        stick: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn element_solve_obeys_coulomb() {
        // Stick inside the bound.
        let s = solve(1.0, 0.0, 2.0, 2.0, 1.0);
        assert_eq!((s.tx, s.ty, s.stick), (0.5, 0.0, true));
        // Isotropic slip: radial projection.
        let s = solve(3.0, 4.0, 1.0, 1.0, 1.0);
        assert!((s.tx - 0.6).abs() < 1e-15 && (s.ty - 0.8).abs() < 1e-15 && !s.stick);
        // Anisotropic slip: on the bound and S = r - D t parallel to t with positive factor.
        let (rx, ry, dx, dy, g) = (3.0, -2.0, 1.0, 1.7, 0.9);
        let s = solve(rx, ry, dx, dy, g);
        assert!((s.tx.hypot(s.ty) - g).abs() < 1e-14);
        let (sx, sy) = (rx - dx * s.tx, ry - dy * s.ty);
        assert!((sx * s.ty - sy * s.tx).abs() < 1e-12, "slip not parallel");
        assert!(sx * s.tx + sy * s.ty > 0.0, "dissipation must be positive");
        // Zero bound.
        let s = solve(1.0, 1.0, 1.0, 1.0, 0.0);
        assert_eq!((s.tx, s.ty), (0.0, 0.0));
    }
}
