//! Scalar root finding for force-prescribed problems: the force is a continuous non-decreasing
//! function of the rigid creepage (or shift), so a bracket is found by stepping with an estimated
//! stiffness and the root by regula falsi with the Illinois modification (Dowell & Jarratt 1971,
//! "A modified regula falsi method for computing the root of an equation", BIT 11).

use crate::error::RefError;
use creep_law::root::{self, Illinois};

/// Finds `x` with `|f(x)| <= tol` for a non-decreasing `f`, starting at `x0` with the slope
/// estimate `slope > 0`. The last evaluation of `f` is at the returned root (callers rely on the
/// side effects of that evaluation). Returns the root and the last secant slope.
pub(crate) fn illinois(
    mut f: impl FnMut(f64) -> Result<f64, RefError>,
    x0: f64,
    slope: f64,
    tol: f64,
    what: &'static str,
) -> Result<(f64, f64), RefError> {
    let mut x0 = x0;
    let mut f0 = f(x0)?;
    if f0.abs() <= tol {
        return Ok((x0, slope));
    }
    let mut step = -f0 / slope;
    let (mut x1, mut f1);
    let mut expand = 0;
    loop {
        x1 = x0 + step;
        f1 = f(x1)?;
        if f1.abs() <= tol {
            let s = if x1 != x0 {
                (f1 - f0) / (x1 - x0)
            } else {
                slope
            };
            return Ok((x1, if s > 0.0 { s } else { slope }));
        }
        if f1.signum() != f0.signum() {
            break;
        }
        // Same sign: the function flattens (slip) faster than the slope predicts.
        x0 = x1;
        f0 = f1;
        step *= 2.0;
        expand += 1;
        if expand > 200 {
            return Err(RefError::NoConvergence {
                solver: what,
                iterations: expand,
                residual: f1,
            });
        }
    }
    // Illinois regula falsi (creep-law's `root::illinois`); an error of `f` stops it (as NaN).
    let mut failure = None;
    let result = root::illinois(
        |x| match f(x) {
            Ok(v) => v,
            Err(e) => {
                failure.get_or_insert(e);
                f64::NAN
            }
        },
        (x0, f0),
        (x1, f1),
        300,
        |_, fx, k| {
            fx.is_nan()
                || fx.abs() <= tol
                || (k.b - k.a).abs() <= 4.0 * f64::EPSILON * k.a.abs().max(k.b.abs())
        },
    );
    if let Some(e) = failure {
        return Err(e);
    }
    match result {
        Illinois::Root { x, bracket: k } if !x.is_nan() => {
            let s = (k.fb - k.fa) / (k.b - k.a);
            Ok((x, if s > 0.0 { s } else { slope }))
        }
        Illinois::Root { x, .. } => Err(RefError::NoConvergence {
            solver: what,
            iterations: 0,
            residual: x,
        }),
        Illinois::Exhausted(k) => Err(RefError::NoConvergence {
            solver: what,
            iterations: 300,
            residual: k.fa.abs().min(k.fb.abs()),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_of_saturating_functions() {
        // A force-like curve: linear then saturating, like Q(xi).
        let f = |x: f64| Ok(1.0 - (-3.0 * x).exp() - 0.9);
        let (x, _) = illinois(f, 0.0, 3.0, 1e-12, "test").unwrap();
        assert!((x - (10f64).ln() / 3.0).abs() < 1e-10);
        // Root below the start.
        let (x, _) = illinois(|x| Ok(x * x * x + x - 1.0), 5.0, 1.0, 1e-13, "test").unwrap();
        assert!((x * x * x + x - 1.0).abs() <= 1e-13);
        // No root: saturates below the target.
        assert!(illinois(|x: f64| Ok(x.tanh() - 2.0), 0.0, 1.0, 1e-9, "test").is_err());
    }
}
