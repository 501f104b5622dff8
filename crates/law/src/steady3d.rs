//! A fast non-linear steady creep law for elliptic contacts with combined longitudinal, lateral
//! and spin creepage: `(xi, eta, phi) -> (Fx, Fy, Mz)`, saturating at `mu P`, and its inverse at
//! zero spin (`(Fx, Fy) -> (xi, eta)`).
//!
//! # Units and signs
//!
//! Kalker's normalisation with `c = sqrt(a b)` (`a` the semi-axis along the rolling direction):
//! `xi_n = xi G c^2/(mu P)`, `eta_n = eta G c^2/(mu P)`, `phi_n = phi G c^3/(mu P)`; forces over
//! `mu P`, moment over `mu P c`. [`Steady3d::loads`] uses the project's signs (creepage of body
//! q relative to body p, force on body p, DESIGN.md §2: a positive creepage gives a positive
//! force, the dissipation `Q . v_disp` is positive); [`Steady3d::loads_kalker`] the signs of
//! Kalker and CONTACT (a positive creepage gives a negative force: every output negated).
//!
//! # The law (a fit to the project's boundary elements)
//!
//! Linear part: Kalker's theory with the coefficients of [`crate::kalker3d`] (Kalker 1967/1990),
//! `Fx = C11 xi_n`, `Fy = C22 eta_n + C23 phi_n`, `Mz = -C23 eta_n + C33 phi_n` (normalised,
//! project signs). Non-linear part, with `g = min(a/b, b/a)`, `h = 1 - g`, and
//! `M_max = (3/8) a_M E(e)/c` the full-slip spin moment of the Hertz pressure about the centre
//! over `mu P c` (`integral mu p r dA`; `a_M` the major semi-axis, `E` the complete elliptic
//! integral of the second kind, [`crate::elliptic::complete_elliptic`]; `3 pi/16` for the circle):
//!
//! 1. translation: `t = (C11 xi_n, C22 eta_n)`, `s_t = S(|t|; k)` with the Kalker-type
//!    saturation `S(x; k) = 1 - (1 - u)^2 (1 + (2 - k) u)`, `u = min(x/k, 1)` (slope 1 at 0, full
//!    slip `S = 1` from `x = k` on with `1 - S ~ (k - x)^2`, the behaviour of the exact theory
//!    near full slip, see [`crate::steady_law`]; Kalker's closed form is `k = 3` with a cubic
//!    tail), `k = kx cos^2 + ky sin^2` of the direction of `t`, `kx = KX0 + KX_NU nu + KX_H h`,
//!    `ky = KY0 + KY_NU nu + KY_H h`, clamped to `[2, 3]`; the force `s_t t/|t|`;
//! 2. spin moment: `m = C33 phi_n/M_max`, `s_m = m/(1 + |m|^p)^(1/p)`,
//!    `p = P0 + P_H h + P_NU nu` (the spin moment saturates slowly: the contact centre always
//!    sticks);
//! 3. lateral force of spin: `f_s = C23 phi_n/(1 + z^q)^((1 + e)/q)`, `z = C23 |phi_n|/ks`, with
//!    `ks`, `q`, `e` each linear in `h` and `nu` (`KS*`, `Q*`, `E*` constants): linear at small
//!    spin, it peaks near `C23 phi_n ~ 0.9` and decays as `phi_n^-e` (in full slip of pure spin
//!    the traction field is symmetric and carries no force);
//! 4. combination (shared friction capacity): the translational force's components times
//!    `(1 - |s_m|^N_X)^(1/N_X)` and `(1 - |s_m|^N_Y)^(1/N_Y)`, plus `(0, f_s (1 - s_t)^R_F)`,
//!    projected onto `|F| <= 1`; the moment
//!    `Mz = M_max s_m (1 - s_t^N_M)^(1/N_M) - C23 eta_n (1 - s_t)^R_M
//!    - nu (T0 + T_H h) s_t^3 eta_n/(xi_n^2 + eta_n^2)`, the last term the moment that the
//!    normal-tangential coupling of the kernel (`nu > 0`) leaves at full lateral slip, decaying
//!    as `1/eta_n` (zero slope at the origin, so the linear theory is untouched).
//!
//! The pure cases reduce to one ingredient each, so their constants were fitted separately
//! (minimax over the boundary-element table of crate creep-reference, module `steady3d`:
//! `a/b = 1, 0.5, 0.2` x `nu = 0, 0.25, 0.5`, grid-extrapolated), then `N_X, N_Y, R_F, N_M` on
//! the combined cases and `R_M, T0, T_H` on the pure lateral ones. The error table against the boundary
//! elements is printed by `cargo run --release -p creep-reference --example steady3d_errors`;
//! it is **not** within the targets for spin and combined creepage (see the crate
//! creep-reference test `steady3d_vs_bem`, which asserts the measured errors). For `a/b > 1`
//! the constants are extrapolated (`h` from `g = b/a`); the table covers `a <= b` only.
//!
//! Cost: up to eleven `powf`, two square roots and a few divisions per evaluation (one `powf`
//! without spin). Measured with criterion (group `steady3d`, `cargo bench -p creep-law --bench
//! steady3d`, the same 64 inputs for each, side by side in one run; medians; 2-core machine
//! shared with other jobs, so only the ratios are meaningful): without spin 3.9-4.5 times
//! `F_ss` (Kalker's closed form with its cube root), with spin 14-15 times, the zero-spin
//! inverse 2.6-3.3 times. With `F_ss` at 27-32 ns in the quieter runs that is about 125 ns and
//! 490 ns: the 50 ns target is missed. (A hand-written `log2`/`exp2` power was tried
//! and was not faster than the library `powf`.)

use crate::elliptic::complete_elliptic;
use crate::error::LawError;
use crate::kalker3d::{self, KalkerCoefficients};

/// Saturation point of the longitudinal force: `kx = KX0 + KX_NU nu + KX_H h` (fitted).
pub const KX0: f64 = 2.3351;
/// See [`KX0`].
pub const KX_NU: f64 = -0.0954;
/// See [`KX0`].
pub const KX_H: f64 = -0.1353;
/// Saturation point of the lateral force: `ky = KY0 + KY_NU nu + KY_H h` (fitted).
pub const KY0: f64 = 2.401;
/// See [`KY0`].
pub const KY_NU: f64 = 0.1877;
/// See [`KY0`].
pub const KY_H: f64 = -0.2881;
/// Spin-moment shape `p = P0 + P_H h + P_NU nu` (fitted).
pub const P0: f64 = 1.3341;
/// See [`P0`].
pub const P_H: f64 = 0.2373;
/// See [`P0`].
pub const P_NU: f64 = -0.2325;
/// Spin lateral force: `ks = KS0 + KS_H h + KS_NU nu` (fitted).
pub const KS0: f64 = 1.0165;
/// See [`KS0`].
pub const KS_H: f64 = -0.47;
/// See [`KS0`].
pub const KS_NU: f64 = 0.036;
/// Spin lateral force: `q = Q0 + Q_H h + Q_NU nu` (fitted).
pub const Q0: f64 = 2.4398;
/// See [`Q0`].
pub const Q_H: f64 = -0.7846;
/// See [`Q0`].
pub const Q_NU: f64 = -0.0043;
/// Spin lateral force decay exponent `e = E0 + E_H h + E_NU nu` (fitted).
pub const E0: f64 = 0.9737;
/// See [`E0`].
pub const E_H: f64 = 0.032;
/// See [`E0`].
pub const E_NU: f64 = -0.0352;
/// Longitudinal force capacity left by the spin moment, exponent `N_X` (fitted, combined).
pub const N_X: f64 = 1.5069;
/// Lateral force capacity left by the spin moment, exponent `N_Y` (fitted, combined).
pub const N_Y: f64 = 2.728;
/// Fading of the spin's lateral force with the translational utilisation, `R_F` (fitted).
pub const R_F: f64 = 0.0574;
/// Moment capacity left by the translational force, exponent `N_M` (fitted, combined).
pub const N_M: f64 = 10.3016;
/// Fading of the lateral creepage's moment, `R_M` (fitted on pure lateral creepage).
pub const R_M: f64 = 1.0479;
/// Full-slip lateral moment of the coupling, `T0 + T_H h` (times `nu`; fitted, pure lateral).
pub const T0: f64 = 0.0346;
/// See [`T0`].
pub const T_H: f64 = 0.0852;

/// Normalised creepages are clamped to `[-CREEPAGE_CLAMP, CREEPAGE_CLAMP]` (deep in full slip).
pub const CREEPAGE_CLAMP: f64 = 1e6;

/// The law at one axis ratio and Poisson ratio (coefficients precomputed; build once per
/// contact shape and material pair).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steady3d {
    c: KalkerCoefficients,
    m_max: f64,
    /// Spin moment over `M_max` per `phi_n`: `C33/M_max`.
    m_per_phi: f64,
    kx: f64,
    ky: f64,
    p: f64,
    inv_p: f64,
    /// `C23/ks`.
    z_per_phi: f64,
    q: f64,
    /// `(1 + e)/q`.
    f_exp: f64,
    /// `nu (T0 + T_H h)`.
    tail: f64,
}

/// Normalised loads `(Fx/(mu P), Fy/(mu P), Mz/(mu P c))`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Loads {
    /// Longitudinal force over `mu P`.
    pub fx: f64,
    /// Lateral force over `mu P`.
    pub fy: f64,
    /// Spin moment over `mu P c`.
    pub mz: f64,
}

/// `S(x; k)` of the module documentation, for `x >= 0`, `k` in `[2, 3]`.
#[inline]
fn saturation(x: f64, k: f64) -> f64 {
    let u = (x / k).min(1.0);
    let v = 1.0 - u;
    1.0 - v * v * (1.0 + (2.0 - k) * u)
}

/// Inverse of [`saturation`] on `[0, 1)`: the `x` with `S(x; k) = s`, by Newton's method on the
/// cubic in `u` (monotone, `dS/du = (1 - u)(k + 3 (2 - k) u) > 0` for `k` in `[2, 3]`, `u < 1`).
fn saturation_inverse(s: f64, k: f64) -> f64 {
    let b = 2.0 - k;
    let mut u = s / k; // S ~ k u near 0
    for _ in 0..60 {
        let v = 1.0 - u;
        let f = 1.0 - v * v * (1.0 + b * u) - s;
        let d = v * (k + 3.0 * b * u);
        if !(d > 0.0) {
            break;
        }
        let step = f / d;
        u = (u - step).clamp(0.0, 1.0 - 1e-15);
        if step.abs() < 1e-15 {
            break;
        }
    }
    k * u
}

impl Steady3d {
    /// The law for the axis ratio `ab = a/b` in `[0.1, 10]` (`a` along the rolling direction)
    /// and Poisson ratio `nu` in `[0, 0.5]` (Kalker's table range).
    pub fn new(ab: f64, nu: f64) -> Result<Self, LawError> {
        let c = kalker3d::coefficients(ab, nu)?;
        let g = ab.min(1.0 / ab);
        let h = 1.0 - g;
        let (_, e, _) = complete_elliptic(1.0 - g * g)?;
        // a_M / c = sqrt(a_M / b_m) = 1/sqrt(g).
        let m_max = 0.375 * e / g.sqrt();
        let p = P0 + P_H * h + P_NU * nu;
        let q = Q0 + Q_H * h + Q_NU * nu;
        Ok(Steady3d {
            c,
            m_max,
            m_per_phi: c.c33 / m_max,
            kx: (KX0 + KX_NU * nu + KX_H * h).clamp(2.0, 3.0),
            ky: (KY0 + KY_NU * nu + KY_H * h).clamp(2.0, 3.0),
            p,
            inv_p: 1.0 / p,
            z_per_phi: c.c23 / (KS0 + KS_H * h + KS_NU * nu),
            q,
            f_exp: (1.0 + E0 + E_H * h + E_NU * nu) / q,
            tail: nu * (T0 + T_H * h),
        })
    }

    /// Kalker's coefficients in use.
    pub fn coefficients(&self) -> KalkerCoefficients {
        self.c
    }

    /// The full-slip spin moment `M_max` over `mu P c`.
    pub fn max_moment(&self) -> f64 {
        self.m_max
    }

    /// Saturation point for a translational linear force `(tx, ty)` of magnitude `tm > 0`.
    #[inline]
    fn k_of(&self, tx: f64, ty: f64, tm: f64) -> f64 {
        let (cx, cy) = (tx / tm, ty / tm);
        self.kx * cx * cx + self.ky * cy * cy
    }

    /// Loads for normalised creepages, project signs (module documentation). Non-finite
    /// creepages give zero loads (a sanitised no-contact answer, never NaN).
    #[inline]
    pub fn loads(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        if !(xi_n.is_finite() && eta_n.is_finite() && phi_n.is_finite()) {
            return Loads::default();
        }
        // Far in full slip the loads no longer change (to ~1e-6); clamping keeps the squares
        // and powers below finite overflow for any finite input.
        let xi_n = xi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let eta_n = eta_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let phi_n = phi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let c = &self.c;
        // Translation.
        let tx = c.c11 * xi_n;
        let ty = c.c22 * eta_n;
        let tm = (tx * tx + ty * ty).sqrt();
        let (mut fx, mut fy, st) = if tm > 0.0 {
            let st = saturation(tm, self.k_of(tx, ty, tm));
            (tx * st / tm, ty * st / tm, st)
        } else {
            (0.0, 0.0, 0.0)
        };
        // Spin.
        let (s_m, f_s) = if phi_n != 0.0 {
            let m = self.m_per_phi * phi_n;
            let s_m = m / (1.0 + m.abs().powf(self.p)).powf(self.inv_p);
            let z = self.z_per_phi * phi_n.abs();
            let f_s = c.c23 * phi_n / (1.0 + z.powf(self.q)).powf(self.f_exp);
            (s_m, f_s)
        } else {
            (0.0, 0.0)
        };
        // Shared capacity.
        if s_m != 0.0 {
            let am = s_m.abs();
            fx *= (1.0 - am.powf(N_X)).max(0.0).powf(1.0 / N_X);
            fy *= (1.0 - am.powf(N_Y)).max(0.0).powf(1.0 / N_Y);
        }
        fy += f_s * (1.0 - st).powf(R_F);
        let f = (fx * fx + fy * fy).sqrt();
        if f > 1.0 {
            fx /= f;
            fy /= f;
        }
        let mut mz = -c.c23 * eta_n * (1.0 - st).powf(R_M);
        if s_m != 0.0 {
            mz += self.m_max * s_m * (1.0 - st.powf(N_M)).max(0.0).powf(1.0 / N_M);
        }
        if tm > 0.0 {
            mz -= self.tail * st * st * st * eta_n / (xi_n * xi_n + eta_n * eta_n);
        }
        Loads { fx, fy, mz }
    }

    /// [`Steady3d::loads`] in Kalker's / CONTACT's signs (a positive creepage gives a negative
    /// force): every output negated.
    #[inline]
    pub fn loads_kalker(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        let l = self.loads(xi_n, eta_n, phi_n);
        Loads {
            fx: -l.fx,
            fy: -l.fy,
            mz: -l.mz,
        }
    }

    /// Inverse at zero spin, project signs: the normalised creepages `(xi_n, eta_n)` that give
    /// the force `(fx, fy)` (over `mu P`). `|F| < 1` is required (at full slip the creepage is
    /// not unique): otherwise [`LawError::OutOfRange`].
    pub fn creepages_for_force(&self, fx: f64, fy: f64) -> Result<(f64, f64), LawError> {
        let f = (fx * fx + fy * fy).sqrt();
        if !(f < 1.0) {
            return Err(LawError::OutOfRange {
                name: "force ratio |F|/(mu P)",
                value: f,
                range: "[0, 1) (full slip has no unique creepage)",
            });
        }
        if f == 0.0 {
            return Ok((0.0, 0.0));
        }
        // At zero spin t is parallel to F, |t| = S^-1(|F|; k) with k from the direction.
        let tm = saturation_inverse(f, self.k_of(fx, fy, f));
        Ok((tm * fx / f / self.c.c11, tm * fy / f / self.c.c22))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_limit_is_kalkers_theory() {
        for (ab, nu) in [(1.0, 0.25), (0.5, 0.0), (0.2, 0.5), (3.0, 0.3)] {
            let law = Steady3d::new(ab, nu).unwrap();
            let c = law.coefficients();
            let e = 1e-7;
            let l = law.loads(e, 0.0, 0.0);
            assert!((l.fx / e / c.c11 - 1.0).abs() < 1e-5, "{ab} {nu}");
            let l = law.loads(0.0, e, 0.0);
            assert!((l.fy / e / c.c22 - 1.0).abs() < 1e-5);
            assert!((l.mz / e / -c.c23 - 1.0).abs() < 1e-5);
            let l = law.loads(0.0, 0.0, e);
            assert!((l.fy / e / c.c23 - 1.0).abs() < 1e-4, "{}", l.fy / e);
            assert!((l.mz / e / c.c33 - 1.0).abs() < 1e-4, "{}", l.mz / e);
        }
    }

    #[test]
    fn saturates_at_mu_p_and_is_odd() {
        let law = Steady3d::new(0.5, 0.25).unwrap();
        for i in 0..200 {
            let t = i as f64 * 0.37;
            let (x, y, z) = (t.sin() * 3.0, (1.3 * t).cos() * 2.0, (0.7 * t).sin() * 4.0);
            let l = law.loads(x, y, z);
            assert!(l.fx.hypot(l.fy) <= 1.0 + 1e-12);
            assert!(l.mz.abs() <= law.max_moment() + 1e-12 + 1.0);
            let m = law.loads(-x, -y, -z);
            assert!((l.fx + m.fx).abs() < 1e-12 && (l.fy + m.fy).abs() < 1e-12);
            assert!((l.mz + m.mz).abs() < 1e-12);
            // Dissipation: the force does positive work on the translational creepage at zero spin.
            let p = law.loads(x, y, 0.0);
            assert!(p.fx * x + p.fy * y >= 0.0);
        }
        let l = law.loads(100.0, 0.0, 0.0);
        assert!((l.fx - 1.0).abs() < 1e-12);
        let k = law.loads_kalker(0.1, 0.0, 0.0);
        assert!(k.fx < 0.0);
        assert_eq!(law.loads(f64::NAN, 0.0, 0.0), Loads::default());
        // Huge finite creepages: the full-slip limits, never NaN.
        let l = law.loads(1e300, 0.0, 0.0);
        assert!((l.fx - 1.0).abs() < 1e-9 && l.fy == 0.0, "{l:?}");
        let l = law.loads(0.0, -1e300, 0.0);
        assert!((l.fy + 1.0).abs() < 1e-9 && l.mz.is_finite(), "{l:?}");
        let l = law.loads(0.0, 0.0, 1e300);
        assert!(
            (l.mz / law.max_moment() - 1.0).abs() < 1e-4 && l.fy.abs() < 1e-4,
            "{l:?}"
        );
        let l = law.loads(1e300, 1e300, -1e300);
        assert!(
            l.fx.is_finite() && l.fy.is_finite() && l.mz.is_finite(),
            "{l:?}"
        );
        // Circle: M_max = 3 pi/16.
        let c = Steady3d::new(1.0, 0.25).unwrap();
        assert!((c.max_moment() - 3.0 * std::f64::consts::PI / 16.0).abs() < 1e-12);
    }

    #[test]
    fn inverse_round_trips_at_zero_spin() {
        for (ab, nu) in [(1.0, 0.25), (0.2, 0.0), (2.0, 0.5)] {
            let law = Steady3d::new(ab, nu).unwrap();
            for i in 0..50 {
                let t = i as f64 * 0.41;
                let (x, y) = (0.3 * t.cos(), 0.25 * (1.7 * t).sin());
                let l = law.loads(x, y, 0.0);
                if l.fx.hypot(l.fy) > 0.999_999 {
                    continue;
                }
                let (bx, by) = law.creepages_for_force(l.fx, l.fy).unwrap();
                assert!(
                    (bx - x).abs() < 1e-9 && (by - y).abs() < 1e-9,
                    "{x} {y}: {bx} {by}"
                );
            }
            assert!(law.creepages_for_force(1.0, 0.0).is_err());
            assert!(law.creepages_for_force(f64::NAN, 0.0).is_err());
            assert_eq!(law.creepages_for_force(0.0, 0.0).unwrap(), (0.0, 0.0));
        }
        assert!(Steady3d::new(0.01, 0.25).is_err());
    }
}
