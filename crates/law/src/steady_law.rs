//! Steady creep laws of circular contact, selectable by [`CreepModel`]: Kalker's closed form
//! `F_ss` (Kuhn's rule, [`crate::kalker`]) and a law fitted to the project's boundary-element
//! solution of Kalker's exact theory (the "fitted" tiers).
//!
//! Notation as in [`crate::kalker`]: force ratio `s = |Q|/(mu P)`, normalised creepage
//! `xi_n = xi G a^2/(mu P)`.
//!
//! # The fitted law
//!
//! `xi_n(s) = (1 - r) Q(r)`, `r = sqrt(1 - s)`, `Q(r) = sum_k q_k(nu) r^k` (degree 4), with
//!
//! * `Q(1) = 2 / C11`: since `1 - r = s/2 + O(s^2)`, the small-creepage slope is Kalker's linear
//!   theory `Q = G a^2 C11 xi` with the boundary-element `C11` (Kalker 1967's table to 0.2 %);
//! * `Q(0) = x_sat`: the law reaches full slip (`s = 1`) at the boundary-element saturation
//!   creepage, the smallest creepage at which the whole contact slips. In the uncoupled theory
//!   this is `x_sat = 3 (4 - 3 nu)/16`: at full slip the traction is `mu p` along `x`, whose
//!   surface displacement difference (Johnson 1985, *Contact Mechanics*, §7.2, tangential
//!   traction of Hertzian form, doubled for two bodies with Kalker's combined `G`) has
//!   `du_x/dx = -3 (4 - 3 nu) x/(16 a) mu P/(G a^2)`, so the slip `xi + du_x/dx` keeps its sign
//!   on the whole contact from that creepage on;
//! * the remaining coefficients fitted by least squares to the relative creepage error of the
//!   boundary-element curve (grid-extrapolated) at 5 Poisson ratios `nu = 0, 0.125, ..., 0.5`,
//!   and interpolated in `nu` by the quartic through them (see [`crate::steady_table`] for the
//!   provenance and the generator, `creep ref fit steady`).
//!
//! The square root makes `1 - s ~ (x_sat - xi_n)^2` near full slip, the behaviour of the
//! boundary-element curve (Kalker's closed form has `1 - s ~ (3/C11 - xi_n)^3`). Against the
//! grid-extrapolated boundary elements (8 Poisson ratios in `[0, 0.5]`) the fitted law is within
//! 0.45 % in creepage for `s <= 0.98` and 0.42 % of `mu P` in force at any creepage; `F_ss` errs
//! by up to 10.2 % and 2.7 % (tests `tiers_vs_bem` of crate `creep-reference`; tables in its
//! README). Cost: a square root and a few multiply-adds, cheaper than `F_ss`'s cube root.
//!
//! The fitted law is defined for `nu` in `[0, 0.5]`, the range of the boundary-element tables;
//! other `nu` are clamped to it.

use crate::kalker;
use crate::steady_table::{NODES, Q_NU, TERMS};

/// Which creep law a contact uses. `Default` is [`CreepModel::Kuhn`], the talk's model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum CreepModel {
    /// Kuhn's rule (Kuhn 2011, the talk, eq. 1): Kalker's closed-form steady creepage `F_ss`,
    /// applied at once.
    #[default]
    Kuhn,
    /// The fitted steady law ([`SteadyLaw`]), applied at once (Kuhn's rule with a better `F_ss`).
    Fitted,
    /// The fitted steady law with the transient extension of [`crate::transient_law`]: the
    /// creep rate relaxes to the steady one over a rolling length of order `a`.
    FittedTransient,
}

impl CreepModel {
    /// Every model, in tier order.
    pub const ALL: [CreepModel; 3] = [
        CreepModel::Kuhn,
        CreepModel::Fitted,
        CreepModel::FittedTransient,
    ];

    /// Lower-case name (`kuhn`, `fitted`, `fitted-transient`), as the CLI spells it.
    pub fn name(self) -> &'static str {
        match self {
            CreepModel::Kuhn => "kuhn",
            CreepModel::Fitted => "fitted",
            CreepModel::FittedTransient => "fitted-transient",
        }
    }

    /// Whether the steady law is the fitted one (both fitted tiers).
    #[inline]
    pub fn is_fitted(self) -> bool {
        !matches!(self, CreepModel::Kuhn)
    }
}

impl std::fmt::Display for CreepModel {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for CreepModel {
    type Err = crate::LawError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        CreepModel::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or(crate::LawError::OutOfRange {
                name: "creep model",
                value: f64::NAN,
                range: "one of kuhn, fitted, fitted-transient",
            })
    }
}

/// A steady creep law evaluated at one Poisson ratio (coefficients precomputed: build it once
/// per material pair where the hot path allows).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SteadyLaw {
    /// Kalker's closed form with the given `C11`.
    Kuhn {
        /// `C11` (Kalker's table, [`kalker::c11`]).
        c11: f64,
    },
    /// The fitted law with its coefficients `q_k` at the pair's `nu`.
    Fitted {
        /// `q_0 .. q_4` of `Q(r)`.
        q: [f64; TERMS],
    },
}

/// Coefficients `q_k(nu)` of the fitted law, `nu` clamped to `[0, 0.5]` (Horner in `nu`).
#[inline]
fn fitted_coefficients(nu: f64) -> [f64; TERMS] {
    let nu = if nu.is_nan() { 0.0 } else { nu.clamp(0.0, 0.5) };
    let mut q = [0.0; TERMS];
    for (k, c) in Q_NU.iter().enumerate() {
        let mut acc = c[NODES - 1];
        for j in (0..NODES - 1).rev() {
            acc = acc * nu + c[j];
        }
        q[k] = acc;
    }
    q
}

/// `Q(r)` by Horner.
#[inline]
fn poly(q: &[f64; TERMS], r: f64) -> f64 {
    // Plain multiply-adds: `f64::mul_add` is a library call without a hardware FMA target.
    (((q[4] * r + q[3]) * r + q[2]) * r + q[1]) * r + q[0]
}

/// `dQ/dr` by Horner.
#[inline]
fn poly_derivative(q: &[f64; TERMS], r: f64) -> f64 {
    ((4.0 * q[4] * r + 3.0 * q[3]) * r + 2.0 * q[2]) * r + q[1]
}

/// The fitted law's normalised creepage at force ratio `s` (clamped to `[0, 1]`, NaN as 0) and
/// coefficients `q`.
#[inline]
fn fitted_creepage(q: &[f64; TERMS], s: f64) -> f64 {
    let s = if s.is_nan() { 0.0 } else { s.clamp(0.0, 1.0) };
    let r = (1.0 - s).sqrt();
    (1.0 - r) * poly(q, r)
}

/// Inverse of [`fitted_creepage`] for `0 <= x`: Newton's method on `u = 1 - r` in
/// `x = u Q(1 - u)`, from the root of the law with `Q` replaced by its chord, safeguarded to
/// the bracket `[0, 1]`, to rounding. Returns `s = u (2 - u)`.
fn fitted_force_ratio(q: &[f64; TERMS], x: f64) -> f64 {
    let x_sat = q[0];
    if x >= x_sat {
        return 1.0;
    }
    if !(x > 0.0) {
        return 0.0;
    }
    // Chord: Q(r) ~ x_sat + d r with d = Q(1) - x_sat, so x = u (x_sat + d (1 - u)).
    let q1: f64 = q.iter().sum();
    let d = q1 - x_sat;
    let (b, c) = (x_sat + d, x);
    // d u^2 - b u + c = 0, smaller root (stable form).
    let disc = (b * b - 4.0 * d * c).max(0.0);
    let mut u = 2.0 * c / (b + disc.sqrt());
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    for _ in 0..50 {
        let r = 1.0 - u;
        let f = u * poly(q, r) - x;
        if f > 0.0 {
            hi = hi.min(u);
        } else {
            lo = lo.max(u);
        }
        let df = poly(q, r) - u * poly_derivative(q, r);
        let mut next = u - f / df;
        if !(next > lo && next < hi) {
            next = 0.5 * (lo + hi);
        }
        if (next - u).abs() <= 4.0 * f64::EPSILON * u {
            u = next;
            break;
        }
        u = next;
    }
    (u * (2.0 - u)).min(1.0)
}

impl SteadyLaw {
    /// The law of `model` at Poisson ratio `nu` (Kuhn: `C11` from [`kalker::c11`]; fitted: `nu`
    /// clamped to `[0, 0.5]`). Both transient and steady fitted tiers share the fitted law.
    #[inline]
    pub fn new(model: CreepModel, nu: f64) -> Self {
        match model {
            CreepModel::Kuhn => SteadyLaw::Kuhn {
                c11: kalker::c11(nu),
            },
            CreepModel::Fitted | CreepModel::FittedTransient => SteadyLaw::Fitted {
                q: fitted_coefficients(nu),
            },
        }
    }

    /// The law of `model` for a pair whose Kalker `C11` is already known (`c11`, used by Kuhn's
    /// rule) and whose Poisson ratio is `nu` (used by the fitted law).
    #[inline]
    pub fn with_c11(model: CreepModel, nu: f64, c11: f64) -> Self {
        match model {
            CreepModel::Kuhn => SteadyLaw::Kuhn { c11 },
            _ => SteadyLaw::new(model, nu),
        }
    }

    /// Normalised steady creepage `xi_n` at force ratio `s = |Q|/(mu P)`, `s` clamped to
    /// `[0, 1]` (NaN counts as 0). Monotone increasing; `xi_n(1)` is
    /// [`SteadyLaw::saturation_creepage_n`].
    #[inline]
    pub fn creepage_n(&self, s: f64) -> f64 {
        match self {
            SteadyLaw::Kuhn { c11 } => kalker::creepage_n(s, *c11),
            SteadyLaw::Fitted { q } => fitted_creepage(q, s),
        }
    }

    /// Inverse of [`SteadyLaw::creepage_n`]: the force ratio at normalised creepage `xi_n`
    /// (odd in `xi_n`; `±1` from the saturation creepage on; NaN gives 0). Exact to rounding:
    /// Kalker's closed form inverts in closed form, the fitted law by safeguarded Newton.
    #[inline]
    pub fn force_ratio(&self, creepage_n: f64) -> f64 {
        match self {
            SteadyLaw::Kuhn { c11 } => kalker::force_ratio(creepage_n, *c11),
            SteadyLaw::Fitted { q } => {
                if creepage_n.is_nan() {
                    return 0.0;
                }
                creepage_n.signum() * fitted_force_ratio(q, creepage_n.abs())
            }
        }
    }

    /// Normalised creepage at which the law reaches full slip (`s = 1`): `3/C11` for Kalker's
    /// closed form, the boundary-element saturation creepage for the fitted law.
    #[inline]
    pub fn saturation_creepage_n(&self) -> f64 {
        match self {
            SteadyLaw::Kuhn { c11 } => 3.0 / c11,
            SteadyLaw::Fitted { q } => q[0],
        }
    }

    /// The law's linear creep coefficient: `Q = G a^2 C11 xi` as `s -> 0` (Kalker's table for
    /// Kuhn's rule; the boundary-element value for the fitted law, `2 / Q(1)`).
    #[inline]
    pub fn c11(&self) -> f64 {
        match self {
            SteadyLaw::Kuhn { c11 } => *c11,
            SteadyLaw::Fitted { q } => 2.0 / q.iter().sum::<f64>(),
        }
    }

    /// Steady creepage [-] of a Hertz contact of `pair` under normal force `pn` \[N\] carrying a
    /// tangential force of magnitude `q_abs` \[N\] with friction coefficient `mu` [-]:
    /// [`Self::creepage_for_force`] at Hertz's contact radius `a(pn)` ([`crate::hertz`],
    /// Johnson 1985, §4.2) and the Coulomb limit `mu pn`. The closed form every rolling scene
    /// (incline, friction drive) is graded against, in any engine.
    pub fn contact_creepage(
        &self,
        pair: &crate::PairMaterial,
        mu: f64,
        pn: f64,
        q_abs: f64,
    ) -> f64 {
        let a = crate::hertz::contact_radius(pair, pn);
        self.creepage_for_force(q_abs, mu * pn, pair.g, a)
    }

    /// Dimensional steady creepage [-] for a tangential force of magnitude `q_abs` \[N\], Coulomb
    /// limit `mu_p` \[N\] (`+inf`: no slip, Kalker's linear theory `|Q|/(G a^2 C11)`), combined
    /// shear modulus `g` \[Pa\] and contact radius `a` \[m\]: `mu P/(G a^2) xi_n(|Q|/(mu P))`.
    /// Returns 0 when there is no contact (`a`, `g` or `mu P` not positive).
    #[inline]
    pub fn creepage_for_force(&self, q_abs: f64, mu_p: f64, g: f64, a: f64) -> f64 {
        let denom = g * a * a;
        if !(denom > 0.0) || !denom.is_finite() {
            return 0.0;
        }
        if mu_p == f64::INFINITY {
            return if q_abs.is_finite() {
                q_abs / (denom * self.c11())
            } else {
                0.0
            };
        }
        if !(mu_p > 0.0) {
            return 0.0;
        }
        if let SteadyLaw::Kuhn { c11 } = self {
            return kuhn_creepage_for_force(q_abs, mu_p, 3.0 * mu_p, denom * *c11);
        }
        mu_p / denom * self.creepage_n(q_abs / mu_p)
    }
}

/// [`SteadyLaw::creepage_for_force`] of [`SteadyLaw::Kuhn`] for a finite `mu_p > 0` \[N\], with
/// `three_mu_p = 3 mu P` and `denom_c11 = G a^2 C11` (finite, > 0) given, so that a caller
/// evaluating one contact's law many times (the rigid kernel's implicit solve) computes them
/// once: Kalker's closed form (Kalker 2000) `mu P/(G a^2) 3/C11 (1 - c)`, `c = (1 - s)^(1/3)`,
/// `s = |Q|/(mu P)` clamped to `[0, 1]` (`kalker::creepage_n`'s form) as `3 mu P (1 - c)/(G
/// a^2 C11)`: two divisions, not four.
#[inline(always)]
pub(crate) fn kuhn_creepage_for_force(
    q_abs: f64,
    mu_p: f64,
    three_mu_p: f64,
    denom_c11: f64,
) -> f64 {
    let q = if q_abs.is_nan() {
        0.0
    } else {
        q_abs.clamp(0.0, mu_p)
    };
    let c = kalker::cbrt(1.0 - q / mu_p);
    three_mu_p * (1.0 - c) / denom_c11
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::steady_table::{C11_NODES, NU_NODES, Q_NODES, X_SAT_NODES};

    #[test]
    fn interpolation_in_nu_hits_the_nodes() {
        for i in 0..NODES {
            let q = fitted_coefficients(NU_NODES[i]);
            for k in 0..TERMS {
                assert!((q[k] - Q_NODES[i][k]).abs() < 1e-9, "node {i} k {k}");
            }
            let law = SteadyLaw::new(CreepModel::Fitted, NU_NODES[i]);
            assert!((law.c11() / C11_NODES[i] - 1.0).abs() < 1e-9);
            assert!((law.saturation_creepage_n() - X_SAT_NODES[i]).abs() < 1e-9);
        }
    }

    #[test]
    fn endpoints_slope_and_saturation() {
        for nu in [0.0, 0.1, 0.25, 0.3, 0.45, 0.5] {
            let law = SteadyLaw::new(CreepModel::Fitted, nu);
            let s = 1e-7;
            let slope = law.creepage_n(s) / s * law.c11();
            assert!((slope - 1.0).abs() < 1e-6, "nu={nu}: {slope}");
            assert_eq!(law.creepage_n(1.0), law.saturation_creepage_n());
            assert_eq!(law.creepage_n(0.0), 0.0);
            assert_eq!(law.creepage_n(f64::NAN), 0.0);
            assert_eq!(law.creepage_n(2.0), law.saturation_creepage_n());
            // Close to Kalker's table (the boundary elements reproduce it to 0.2 %).
            assert!((law.c11() / kalker::c11(nu) - 1.0).abs() < 0.01, "nu={nu}");
            // Saturation close to the uncoupled closed form 3 (4 - 3 nu)/16.
            let closed = 3.0 * (4.0 - 3.0 * nu) / 16.0;
            assert!((law.saturation_creepage_n() / closed - 1.0).abs() < 0.03);
        }
    }

    #[test]
    fn monotone_and_inverse_exact_for_every_model() {
        for model in CreepModel::ALL {
            for i in 0..=50 {
                let nu = 0.5 * i as f64 / 50.0;
                let law = SteadyLaw::new(model, nu);
                let mut prev = -1.0;
                for j in 0..=2000 {
                    let s = j as f64 / 2000.0;
                    let x = law.creepage_n(s);
                    assert!(x > prev, "{model} nu={nu} s={s}");
                    prev = x;
                    let back = law.force_ratio(x);
                    assert!((back - s).abs() < 1e-12, "{model} nu={nu} s={s}: {back}");
                    assert_eq!(law.force_ratio(-x), -back);
                    // Kuhn's tier is Kalker's closed form (crate::kalker).
                    if model == CreepModel::Kuhn {
                        assert_eq!(kalker::steady_creepage_n(s, nu), x);
                        assert_eq!(kalker::steady_force_ratio(x, nu), back);
                    }
                }
                assert_eq!(law.force_ratio(10.0), 1.0);
                assert_eq!(law.force_ratio(f64::NAN), 0.0);
            }
        }
    }

    #[test]
    fn dimensional_form_and_linear_limit() {
        let law = SteadyLaw::new(CreepModel::Fitted, 0.3);
        let (mu_p, g, a) = (30.0, 80e9, 1e-4);
        let f = law.creepage_for_force(15.0, mu_p, g, a);
        assert!((f / (law.creepage_n(0.5) * mu_p / (g * a * a)) - 1.0).abs() < 1e-14);
        let lin = law.creepage_for_force(1.0, f64::INFINITY, g, a);
        assert!((lin * g * a * a * law.c11() - 1.0).abs() < 1e-14);
        let big = law.creepage_for_force(1.0, 1e8, g, a);
        assert!((big / lin - 1.0).abs() < 1e-6, "{big} {lin}");
        assert_eq!(law.creepage_for_force(1.0, mu_p, g, 0.0), 0.0);
        assert_eq!(law.creepage_for_force(1.0, 0.0, g, a), 0.0);
    }

    #[test]
    fn contact_creepage_is_kalkers_at_hertzs_radius() {
        // A steel ball of 0.1 m on a steel plane: Kalker's F_ss (kalker::steady_creepage) at
        // Hertz's radius, for the Kuhn model; zero without load.
        let steel = crate::Material::steel();
        let pair = crate::PairMaterial::new(
            &steel,
            &steel,
            crate::Surface::Plane,
            crate::Surface::Sphere(0.1),
        )
        .unwrap();
        let law = SteadyLaw::with_c11(CreepModel::Kuhn, pair.nu, pair.c11);
        let (mu, pn) = (0.5, 300.0);
        for s in [0.05, 0.3, 0.7, 0.95] {
            let q = s * mu * pn;
            let a = crate::hertz::contact_radius(&pair, pn);
            let kalker = crate::kalker::steady_creepage(s, mu * pn, pair.g, a, pair.c11);
            let got = law.contact_creepage(&pair, mu, pn, q);
            assert!(
                (got / kalker - 1.0).abs() < 1e-12,
                "s {s}: {got} vs {kalker}"
            );
        }
        assert_eq!(law.contact_creepage(&pair, mu, 0.0, 1.0), 0.0);
    }

    #[test]
    fn model_names_round_trip() {
        for m in CreepModel::ALL {
            assert_eq!(m.name().parse::<CreepModel>().unwrap(), m);
        }
        assert!("nope".parse::<CreepModel>().is_err());
        assert_eq!(CreepModel::default(), CreepModel::Kuhn);
    }
}
