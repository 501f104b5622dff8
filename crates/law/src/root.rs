//! Bracketed scalar root finding: regula falsi with the Illinois modification (Dowell &
//! Jarratt 1971, "A modified regula falsi method for computing the root of an equation", BIT 11,
//! 168-174). Superlinear (order ~1.44) and, unlike the plain secant, never leaves its bracket.
//!
//! One loop for every scalar solve of the workspace (the rigid regime's implicit creep force,
//! the compliant regime's damping coefficient, the boundary-element solver's force-prescribed
//! problems); each caller states its own stopping rule.

/// A bracket of [`illinois`]: `f(a) = fa` and `f(b) = fb` of opposite signs (after an Illinois
/// step, `fa` or `fb` is the halved value the method works with, not `f` itself).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bracket {
    /// One end.
    pub a: f64,
    /// Its (working) function value.
    pub fa: f64,
    /// The other end.
    pub b: f64,
    /// Its (working) function value.
    pub fb: f64,
}

/// What stops [`illinois`]: a root found, or the iteration budget spent.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Illinois {
    /// `converged` accepted `x`; `bracket` is the bracket `x` was drawn from.
    Root {
        /// The accepted abscissa.
        x: f64,
        /// The bracket it came from.
        bracket: Bracket,
    },
    /// The budget ran out; the last bracket.
    Exhausted(Bracket),
}

impl Illinois {
    /// The root, or the middle of the last bracket when the budget ran out.
    pub fn root_or_midpoint(self) -> f64 {
        match self {
            Illinois::Root { x, .. } => x,
            Illinois::Exhausted(k) => 0.5 * (k.a + k.b),
        }
    }
}

/// Illinois regula falsi on the bracket `[a, b]` with `f(a) = fa` and `f(b) = fb` of opposite
/// signs (either end may be the larger). Each iteration evaluates `f` at the secant point `x`
/// and stops when `converged(x, f(x), &bracket)` holds (the bracket before the update), else
/// replaces the end whose value has the sign of `f(x)` and halves the other end's value when the
/// same end moved twice in a row (the Illinois step, which keeps the order above 1).
pub fn illinois(
    mut f: impl FnMut(f64) -> f64,
    (a, fa): (f64, f64),
    (b, fb): (f64, f64),
    max_iter: usize,
    mut converged: impl FnMut(f64, f64, &Bracket) -> bool,
) -> Illinois {
    let mut k = Bracket { a, fa, b, fb };
    let mut side = 0i8;
    for _ in 0..max_iter {
        let x = (k.a * k.fb - k.b * k.fa) / (k.fb - k.fa);
        let fx = f(x);
        if converged(x, fx, &k) {
            return Illinois::Root { x, bracket: k };
        }
        if (fx > 0.0) == (k.fb > 0.0) {
            k.b = x;
            k.fb = fx;
            if side == 1 {
                k.fa *= 0.5;
            }
            side = 1;
        } else {
            k.a = x;
            k.fa = fx;
            if side == -1 {
                k.fb *= 0.5;
            }
            side = -1;
        }
    }
    Illinois::Exhausted(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root(r: Illinois) -> f64 {
        match r {
            Illinois::Root { x, .. } => x,
            e => panic!("no root: {e:?}"),
        }
    }

    #[test]
    fn increasing_and_decreasing_brackets() {
        // x^3 + x - 1 = 0 at 0.6823278038280193 (the real root of the depressed cubic).
        let f = |x: f64| x * x * x + x - 1.0;
        let x = root(illinois(f, (0.0, -1.0), (2.0, 9.0), 100, |_, fx, _| {
            fx.abs() < 1e-14
        }));
        assert!((x - 0.682_327_803_828_019_3).abs() < 1e-13);
        // The same root with the bracket given the other way round, and of -f.
        let g = |x: f64| -f(x);
        let y = root(illinois(g, (2.0, -9.0), (0.0, 1.0), 100, |_, fx, _| {
            fx.abs() < 1e-14
        }));
        assert!((y - x).abs() < 1e-13);
    }

    #[test]
    fn illinois_step_beats_plain_regula_falsi() {
        // A convex function where plain regula falsi keeps one end fixed and crawls:
        // e^x - 2 on [0, 4]; the Illinois step reaches 1e-14 in a few dozen evaluations.
        let mut n = 0;
        let x = root(illinois(
            |x: f64| {
                n += 1;
                x.exp() - 2.0
            },
            (0.0, -1.0),
            (4.0, 4f64.exp() - 2.0),
            60,
            |_, fx, _| fx.abs() < 1e-14,
        ));
        assert!((x - 2f64.ln()).abs() < 1e-14);
        assert!(n < 30, "{n} evaluations");
    }

    #[test]
    fn exhausted_reports_the_bracket() {
        let r = illinois(|x| x - 0.3, (0.0, -0.3), (1.0, 0.7), 2, |_, _, _| false);
        match r {
            Illinois::Exhausted(k) => {
                assert!(k.a.min(k.b) <= 0.3 && 0.3 <= k.a.max(k.b), "{k:?}");
                assert!(k.fa * k.fb <= 0.0, "{k:?}");
            }
            Illinois::Root { .. } => panic!("converged without accepting"),
        }
    }
}
