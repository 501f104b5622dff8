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
    // [`cbrt`] instead of libm's. Kept as `1 - c`, not the cancellation-free
    // `s/(1 + c + c^2)`: that form gives a small nonzero creep where `1 - c` rounds to 0
    // (`s` below ~1e-16), which changed creep-dem's parallel-versus-serial agreement over a
    // settling run from 4e-14 to 4e-7 m (test `parallel_force_loop_is_deterministic`).
    let c = cbrt(1.0 - s);
    3.0 / c11 * (1.0 - c)
}

// Evans' constants (FreeBSD's and musl's s_cbrt.c): B1 = (1023 - 1023/3 - 0.03306235651) 2^20,
// B2 the same for subnormals (scaled by 2^54 first); P0..P4 the polynomial of `(t^3/x)` that
// corrects the estimate, bit for bit (his hex comments).
const B1: u32 = 715_094_163;
const B2: u32 = 696_219_795;
const P0: f64 = f64::from_bits(0x3ffe_03e6_0f61_e692); // 1.87595182427177009643
const P1: f64 = f64::from_bits(0xbffe_28e0_92f0_2420); // -1.88497979543377169875
const P2: f64 = f64::from_bits(0x3ff9_f160_4a49_d6c2); // 1.621429720105354466140
const P3: f64 = f64::from_bits(0xbfe8_44cb_bee7_51d9); // -0.758397934778766047437
const P4: f64 = f64::from_bits(0x3fc2_b000_d4e4_edd7); // 0.145996192886612446982

/// Evans' polynomial correction of the bit estimate `t` of a cube root to 23 bits, given
/// `r = t^3/x`, then rounded to 21 bits (away from zero) so that `t*t` is exact.
#[inline(always)]
fn evans_correct(t: f64, r: f64) -> f64 {
    let t = t * ((P0 + r * (P1 + r * P2)) + ((r * r) * r) * (P3 + r * P4));
    f64::from_bits((t.to_bits().wrapping_add(0x8000_0000)) & 0xffff_ffff_c000_0000)
}

/// [`cbrt`] of `x` in `[2^-60, 1]`, left as the fraction of its last (Halley) step:
/// `(t, n, d)` with `cbrt(x) = t n / d` (`n = t^3 + 2x`, `d = 2 t^3 + x`, all > 0; the step
/// `t + t (x - t^3)/(2 t^3 + x)` of [`cbrt`] over one denominator), so that a caller that
/// divides anyway folds this division into its own. `inv_x` is `1/x` to a few ulps (e.g.
/// computed beside `x` from the quantities `x` is made of, so that it does not wait for `x`):
/// it enters only the polynomial's argument `r = t^3/x`, whose 2^-23.5 error bound (Evans)
/// leaves the 21-bit estimate, and hence the Halley step's cubic convergence to 53 bits,
/// unchanged by a relative perturbation of 1e-15. The same bit estimate, polynomial and
/// rounding as [`cbrt`] (test `cbrt_fraction_equals_cbrt`: within 2 ulps of it).
#[inline(always)]
pub(crate) fn cbrt_fraction(x: f64, inv_x: f64) -> (f64, f64, f64) {
    // x normal and positive: the exponent divided by 3 (Evans), sign bit 0.
    let hx = ((x.to_bits() >> 32) as u32) & 0x7fff_ffff;
    let t = f64::from_bits(u64::from(hx / 3 + B1) << 32);
    let t = evans_correct(t, (t * t) * (t * inv_x));
    let t3 = (t * t) * t;
    (t, t3 + x + x, t3 + t3 + x)
}

/// Cube root of `x` \[any unit^3 -> unit\], within 1 ulp of the correctly rounded result for
/// every finite `x` (including negative, zero and subnormal; `NaN` and `±inf` are returned
/// as they are): Bruce Evans' algorithm of FreeBSD's and musl's `cbrt` (s_cbrt.c, 2009): an
/// exponent-divided-by-3 bit estimate (5 bits), a degree-4 polynomial correction to 23 bits
/// (its error bound `|t^3/x - 1| < 2^-23.5`, Evans' comment), rounding to 21 bits so that
/// `t*t` is exact, then one Halley step (order 3, `t += t (x - t^3)/(2 t^3 + x)`, one division
/// for `1e-290 < |x| < 1e290`, Evans' two-division form beyond) to within an ulp (tested
/// against libm). It replaces the system libm's `cbrt` in Kalker's `F_ss` ([`steady_creepage_n`]), the
/// creep term's hot path in every host: that one costs more than twice
/// as much (measured side by side, `cargo bench -p creep-law --bench cbrt`: 8.1 against 19.0
/// ns per call). Always inlined: the cheap tier calls it once per creeping contact, and as a
/// call it made the caller spill and reload every live vector register around it (the SysV
/// ABI saves none), seen in the LAMMPS plugin's profile.
#[inline(always)]
pub fn cbrt(x: f64) -> f64 {
    let mut ui = x.to_bits();
    let mut hx = ((ui >> 32) as u32) & 0x7fff_ffff;
    if hx >= 0x7ff0_0000 {
        // NaN or infinity.
        return x + x;
    }
    if hx < 0x0010_0000 {
        // Zero or subnormal: scale into the normal range.
        ui = (x * f64::from_bits(0x4350_0000_0000_0000)).to_bits(); // 2^54
        hx = ((ui >> 32) as u32) & 0x7fff_ffff;
        if hx == 0 {
            return x;
        }
        hx = hx / 3 + B2;
    } else {
        hx = hx / 3 + B1;
    }
    ui &= 1 << 63;
    ui |= u64::from(hx) << 32;
    let t = f64::from_bits(ui);
    let t = evans_correct(t, (t * t) * (t / x));
    // One Halley step (order 3) to 53 bits: Evans' `r = x/t^2; t += t (r - t)/(2t + r)`.
    // Where neither `t^3` underflows nor `2 t^3 + x` overflows, the same step is
    // `t += t (x - t^3)/(2 t^3 + x)`: one division instead of two (the division chain is the
    // latency of the creep term); `t*t` is exact (21 bits), `t^3` rounds once, and the
    // correction is 2^-23 of `t`, so its rounding stays far below an ulp.
    let ax = x.abs();
    if ax > 1e-290 && ax < 1e290 {
        let t3 = (t * t) * t;
        return t + t * ((x - t3) / (t3 + t3 + x));
    }
    let s = t * t;
    let r = x / s;
    let w = t + t;
    let r = (r - t) / (w + r);
    t + t * r
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

    /// Distance in ulps between two finite f64 of the same sign.
    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    #[test]
    fn cbrt_fraction_equals_cbrt() {
        // Over [2^-60, 1] (the creep term's `1 - s`), with `inv_x` exact and 3 ulps off: the
        // fraction's value `t n/d` against libm's root. Its rounding: `t^3`, `n`, `d`, `t n` and
        // the division, half an ulp each (the Halley step itself is exact to 2^-60, Evans),
        // hence at most 3 ulps; `cbrt` (the step as a correction, whose rounding is scaled by
        // 2^-23) is within 1.
        let mut seed = 0x853c_49e6_748f_ea9bu64;
        let mut worst = 0u64;
        for i in 0..200_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let u = (seed >> 11) as f64 / (1u64 << 53) as f64;
            let x = if i % 2 == 0 {
                2f64.powf(-60.0 * u)
            } else {
                u.max(1e-18)
            };
            let x = x.min(1.0);
            for inv_x in [
                1.0 / x,
                (1.0 / x) * (1.0 + 6.7e-16),
                (1.0 / x) * (1.0 - 6.7e-16),
            ] {
                let (t, n, d) = cbrt_fraction(x, inv_x);
                let got = t * n / d;
                let want = x.cbrt();
                let ulps = got.to_bits().abs_diff(want.to_bits());
                worst = worst.max(ulps);
                assert!(ulps <= 3, "x {x:e}: {got:e} against {want:e}");
            }
        }
        // Exact cubes stay exact to the same bound.
        for (x, c) in [(1.0, 1.0), (0.125, 0.5), (0.001, 0.1)] {
            let (t, n, d) = cbrt_fraction(x, 1.0 / x);
            assert!((t * n / d - c).abs() <= 3.0 * f64::EPSILON * c, "cbrt({x})");
        }
        eprintln!("cbrt_fraction: worst {worst} ulps from libm");
    }

    #[test]
    fn cbrt_is_within_one_ulp_of_libm() {
        // A deterministic sweep of [2^-1074, 2^1023] (every binade, many mantissas), both signs,
        // and the creep law's range (1 - s for s in [0, 1]) densely.
        let mut worst = 0;
        let mut check = |x: f64| {
            let (a, b) = (cbrt(x), x.cbrt());
            assert!(
                a.is_finite() && (a == b || ulps(a, b) <= 1),
                "x={x:e}: {a:e} vs {b:e}"
            );
            worst = worst.max(ulps(a, b));
        };
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        for _ in 0..200_000 {
            // xorshift64*: random bit patterns of finite doubles.
            state ^= state >> 12;
            state ^= state << 25;
            state ^= state >> 27;
            let bits = state.wrapping_mul(0x2545_f491_4f6c_dd1d);
            let x = f64::from_bits(bits);
            if x.is_finite() {
                check(x);
            }
        }
        for i in 0..=100_000 {
            let s = i as f64 / 100_000.0;
            check(1.0 - s);
            check(-(1.0 - s));
        }
        for x in [
            f64::MIN_POSITIVE,
            5e-324,
            1e-310,
            f64::MAX,
            1.0,
            8.0,
            27.0,
            0.125,
        ] {
            check(x);
            check(-x);
        }
        assert!(worst <= 1, "worst {worst} ulp");
        // Exact cubes come out exact; specials as libm.
        assert_eq!(cbrt(8.0), 2.0);
        assert_eq!(cbrt(-27.0), -3.0);
        assert_eq!(cbrt(0.0).to_bits(), 0.0_f64.to_bits());
        assert_eq!(cbrt(-0.0).to_bits(), (-0.0_f64).to_bits());
        assert_eq!(cbrt(f64::INFINITY), f64::INFINITY);
        assert_eq!(cbrt(f64::NEG_INFINITY), f64::NEG_INFINITY);
        assert!(cbrt(f64::NAN).is_nan());
    }

    #[test]
    fn creepage_matches_the_closed_form() {
        // Against Kalker's form `3/C11 [1 - (1 - s)^(1/3)]` evaluated with libm's cube root:
        // the cube roots differ by at most an ulp (<= 1.2e-16 below 1), so the creepages by at
        // most 3/C11 * 2.5e-16 absolute (with the roundings of `1 - c` and the product); and against the series `1 - (1 - s)^(1/3) = s/3 +
        // s^2/9 + 5 s^3/81 + ...` where `1 - c` still has 11 digits (s >= 1e-4).
        for nu in [0.0, 0.2, 0.5] {
            let c = c11(nu);
            for i in 0..=10_000 {
                let s = i as f64 / 10_000.0;
                let exact = 3.0 / c * (1.0 - (1.0 - s).cbrt());
                let got = creepage_n(s, c);
                assert!(
                    (got - exact).abs() <= 3.0 / c * 2.5e-16,
                    "nu={nu} s={s}: {got:e} vs {exact:e}"
                );
            }
            for s in [1e-4_f64, 1e-3, 1e-2] {
                let series = 3.0 / c
                    * (s / 3.0
                        + s * s / 9.0
                        + 5.0 * s.powi(3) / 81.0
                        + 10.0 * s.powi(4) / 243.0
                        + 22.0 * s.powi(5) / 729.0);
                let got = creepage_n(s, c);
                assert!(
                    (got / series - 1.0).abs() < 1e-10,
                    "nu={nu} s={s}: {got:e} vs {series:e}"
                );
            }
        }
    }
}
