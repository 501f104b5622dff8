//! Kalker's creep theory for circular contact: the linear creep coefficient `C11(nu)` and the
//! closed-form steady creepage `F_ss` used by Kuhn's creep-friction rule.
//!
//! Notation: `s = |Q| / (mu P)` is the force ratio, `xi` the creepage (slip speed over rolling
//! speed, dimensionless), `a` the contact radius \[m\], `G` and `nu` the pair's combined shear modulus
//! \[Pa\] and Poisson ratio in Kalker's sense (see [`crate::material::PairMaterial`]). The normalised
//! creepage is `xi_n = xi G a^2 / (mu P)` (dimensionless).

/// Kalker's linear creep coefficient `C11` for circular contact (`a/b = 1`), from Kalker's table of
/// creep coefficients (Kalker 1967, "On the rolling contact of two elastic bodies in the presence of
/// dry friction", thesis, Delft; reproduced in Johnson 1985, *Contact Mechanics*, Table 8.1):
/// `C11 = 3.40, 4.12, 5.20` at `nu = 0, 0.25, 0.5`.
pub const C11_TABLE: [(f64, f64); 3] = [(0.0, 3.40), (0.25, 4.12), (0.5, 5.20)];

/// `C11(nu)` for circular contact, interpolated in `nu` through Kalker's three tabulated values
/// ([`C11_TABLE`]) by the quadratic Lagrange polynomial (Lagrange interpolation through equally
/// spaced nodes, e.g. Press et al., *Numerical Recipes*, 3rd ed., §3.2, Neville's form):
/// `C11(nu) = 3.40 + 2.16 nu + 2.88 nu^2`. It is exact at the three tabulated ratios; between them
/// the project's boundary-element solver (crate `creep-reference`) is the check.
///
/// `nu` is dimensionless; outside `[0, 0.5]` the polynomial is extrapolated (for `nu < 0` it stays
/// positive down to `nu = -1`, where it gives 4.12).
#[inline]
pub fn c11(nu: f64) -> f64 {
    // Lagrange quadratic through (0, 3.40), (0.25, 4.12), (0.5, 5.20).
    3.40 + nu * (2.16 + 2.88 * nu)
}

/// Kalker's (2000, "Rolling contact phenomena: linear elasticity", in *Rolling Contact Phenomena*,
/// Jacobson & Kalker eds., pp. 1-84) closed-form steady creepage for circular contact, normalised: `xi_n = xi G a^2 / (mu P)` as a function of the force
/// ratio `s = |Q| / (mu P)`:
///
/// `xi_n(s) = 3 / C11(nu) * [1 - (1 - s)^(1/3)]`
///
/// i.e. `F_ss = 3 mu P / (G a^2 C11) [1 - (1 - |Q|/(mu P))^(1/3)]` of Kuhn (2011, the talk, eq. 1).
/// Small-`s` limit: `xi_n = s / C11` (Kalker's linear theory, `Q = G a^2 C11 xi`). `s` is clamped to
/// `[0, 1]`; at `s = 1` (full slip) the creepage is `3 / C11`.
/// With `C11` known (a pair's cached [`crate::PairMaterial::c11`]) use
/// [`crate::SteadyLaw::Kuhn`], which evaluates this closed form.
#[inline]
pub fn steady_creepage_n(s: f64, nu: f64) -> f64 {
    creepage_n(s, c11(nu))
}

/// [`steady_creepage_n`] with `C11` given: the closed form behind [`crate::SteadyLaw::Kuhn`].
#[inline]
pub(crate) fn creepage_n(s: f64, c11: f64) -> f64 {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    3.0 / c11 * (1.0 - (1.0 - s).cbrt())
}

/// Inverse of [`steady_creepage_n`]: the force ratio `s = |Q| / (mu P)` that Kalker's closed form
/// gives for a normalised creepage `xi_n >= 0`:
///
/// `s = 1 - (1 - C11 xi_n / 3)^3` for `xi_n < 3 / C11`, and `s = 1` (full slip) beyond.
/// Negative `xi_n` gives the odd extension `s(-xi_n) = -s(xi_n)`.
#[inline]
pub fn steady_force_ratio(creepage_n: f64, nu: f64) -> f64 {
    force_ratio(creepage_n, c11(nu))
}

/// [`steady_force_ratio`] with `C11` given: the inverse behind [`crate::SteadyLaw::Kuhn`].
#[inline]
pub(crate) fn force_ratio(creepage_n: f64, c11: f64) -> f64 {
    if creepage_n.is_nan() {
        return 0.0;
    }
    let sign = creepage_n.signum();
    let t = 1.0 - (c11 * creepage_n.abs() / 3.0).min(1.0);
    sign * (1.0 - t * t * t)
}

/// Dimensional steady creepage `F_ss(|Q|/(mu P))` [dimensionless slip per unit rolling distance]
/// (Kalker 2000; Kuhn 2011, the talk, eq. 1): `F_ss = 3 mu P / (G a^2 C11) [1 - (1 - s)^(1/3)]`.
///
/// * `s` — force ratio `|Q|/(mu P)`, clamped to `[0, 1]`;
/// * `mu_p` — Coulomb limit `mu P` \[N\];
/// * `g` — combined shear modulus \[Pa\]; `a` — contact radius \[m\]; `c11` — from [`c11`].
///
/// Returns 0 when `a = 0` or `mu P = 0` (no contact, no creep).
#[inline]
pub fn steady_creepage(s: f64, mu_p: f64, g: f64, a: f64, c11: f64) -> f64 {
    let denom = g * a * a;
    if !(denom > 0.0) || !(mu_p > 0.0) || !mu_p.is_finite() {
        return 0.0;
    }
    mu_p / denom * creepage_n(s, c11)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c11_reproduces_kalkers_table() {
        for (nu, c) in C11_TABLE {
            assert!((c11(nu) - c).abs() < 1e-12, "nu={nu}");
        }
    }

    #[test]
    fn linear_limit_is_kalkers_linear_theory() {
        // xi_n -> s / C11 as s -> 0, i.e. Q = G a^2 C11 xi.
        for nu in [0.0, 0.25, 0.3, 0.5] {
            let s = 1e-7;
            let rel = steady_creepage_n(s, nu) * c11(nu) / s - 1.0;
            assert!(rel.abs() < 1e-6, "nu={nu} rel={rel}");
        }
    }

    #[test]
    fn inverse_round_trips() {
        for nu in [0.0, 0.25, 0.5] {
            for i in 0..=100 {
                let s = i as f64 / 100.0;
                let back = steady_force_ratio(steady_creepage_n(s, nu), nu);
                assert!((back - s).abs() < 1e-12, "nu={nu} s={s} back={back}");
            }
            assert_eq!(steady_force_ratio(10.0, nu), 1.0);
            assert_eq!(steady_force_ratio(-10.0, nu), -1.0);
        }
    }

    #[test]
    fn full_slip_creepage_and_monotonicity() {
        let nu = 0.3;
        assert!((steady_creepage_n(1.0, nu) - 3.0 / c11(nu)).abs() < 1e-15);
        let mut prev = -1.0;
        for i in 0..=1000 {
            let x = steady_creepage_n(i as f64 / 1000.0, nu);
            assert!(x > prev);
            prev = x;
        }
        assert_eq!(steady_creepage_n(2.0, nu), steady_creepage_n(1.0, nu));
        assert_eq!(steady_creepage_n(f64::NAN, nu), 0.0);
    }

    #[test]
    fn dimensional_form_matches_normalised() {
        let (mu_p, g, a, nu) = (0.3 * 100.0, 80e9, 1e-4, 0.3);
        let f = steady_creepage(0.5, mu_p, g, a, c11(nu));
        let expect = steady_creepage_n(0.5, nu) * mu_p / (g * a * a);
        assert!((f / expect - 1.0).abs() < 1e-14);
        assert_eq!(steady_creepage(0.5, mu_p, g, 0.0, c11(nu)), 0.0);
        // From the force, through the steady law of Kuhn's rule (SteadyLaw::Kuhn).
        let law = crate::SteadyLaw::Kuhn { c11: c11(nu) };
        let by_force = law.creepage_for_force(0.5 * mu_p, mu_p, g, a);
        assert!((by_force / f - 1.0).abs() < 1e-14);
        // mu -> inf: linear theory, and the finite-mu law approaches it.
        let lin = law.creepage_for_force(1.0, f64::INFINITY, g, a);
        assert!((lin * g * a * a * c11(nu) - 1.0).abs() < 1e-14);
        let big = law.creepage_for_force(1.0, 1e8, g, a);
        assert!((big / lin - 1.0).abs() < 1e-7);
    }
}
