//! The rolling frame of a contact and the anisotropic implicit solve of its translation
//! (the equations are in the parent module's docs, "The implicit solve"), and the cache of
//! the 3-D laws of elliptic contacts by shape.

use crate::root::illinois;
use crate::steady_law::{SteadyLaw, kuhn_creepage_for_force};
use crate::steady3d::{Loads, Steady3d};
use crate::vector::Vec3;

/// The rolling frame of a contact: `x` (the contact's travel over the surfaces) and `y = n × x`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollFrame {
    /// Unit vector along the rolling direction.
    pub x: Vec3,
    /// Unit vector across it, `n × x`.
    pub y: Vec3,
}

impl RollFrame {
    /// The frame from Kuhn & Bagi's rolling velocity (non-zero, tangent) and the normal.
    pub fn new(v_roll: Vec3, n: Vec3) -> Option<Self> {
        let x = (-v_roll).try_normalize()?;
        Some(Self { x, y: n.cross(x) })
    }
    /// The frame with the unit rolling direction `x` given (a wheel's heading), `y = n × x`.
    pub fn along(x: Vec3, n: Vec3) -> Self {
        Self { x, y: n.cross(x) }
    }
    /// Components of a tangent vector in the frame.
    #[inline]
    pub fn split(&self, v: Vec3) -> (f64, f64) {
        (v.dot(self.x), v.dot(self.y))
    }
    /// The world vector of frame components.
    #[inline]
    pub fn join(&self, x: f64, y: f64) -> Vec3 {
        self.x * x + self.y * y
    }
}

/// The translation force of the implicit solve (parent module docs, "The implicit solve"):
/// returns `(q, u_x, u_y)`, the
/// magnitude `q` in `[0, q_max]` and the unit direction in the frame, for the force estimate
/// `(x_star, y_star)` \[N\], `k = m_t V/dt` \[N\], the creepage law `creepage(q)` \[-\] along
/// the rolling direction with initial slope `slope0 = dF/dq(0)` \[1/N\], the lateral ratio
/// `r = C11/C22` (in `(0, 1]` for `nu >= 0`) and the capacity `q_max` \[N\] (beyond it the
/// contact slides at `q_max`).
pub fn solve_translation(
    q_star: (f64, f64),
    k: f64,
    r: f64,
    q_max: f64,
    slope0: f64,
    creepage: &dyn Fn(f64) -> f64,
) -> (f64, f64, f64) {
    let s = solve_translation_with_creepage(q_star, k, r, q_max, slope0, creepage);
    (s.q, s.ux, s.uy)
}

/// The answer of [`solve_translation_with_creepage`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TranslationSolve {
    /// The force's magnitude \[N\].
    pub q: f64,
    /// Its unit direction in the frame.
    pub ux: f64,
    pub uy: f64,
    /// `creepage(q)` when the solve evaluated it at `q` (`None`: not evaluated there).
    pub creepage: Option<f64>,
}

/// [`solve_translation`] with the creepage law's value at the answer, when the solve
/// evaluated it there (its last evaluation is at the root it returns), so that the caller
/// need not evaluate the law again; generic in the law, so that it inlines into the
/// solve's loop. The same operations as [`solve_translation`], so the same bits.
#[inline]
pub(crate) fn solve_translation_with_creepage(
    (x_star, y_star): (f64, f64),
    k: f64,
    r: f64,
    q_max: f64,
    slope0: f64,
    creepage: impl Fn(f64) -> f64,
) -> TranslationSolve {
    let q_star = x_star.hypot(y_star);
    if !(q_star > 0.0) {
        return TranslationSolve {
            q: 0.0,
            ux: 1.0,
            uy: 0.0,
            creepage: None,
        };
    }
    let hi0 = q_star.min(q_max);
    if !(k > 0.0) || !(hi0 > 0.0) {
        return TranslationSolve {
            q: hi0.max(0.0),
            ux: x_star / q_star,
            uy: y_star / q_star,
            creepage: None,
        };
    }
    // The last evaluation of `dir`: `(q, creepage(q) or NaN at q = 0, ux, uy)`. The answer
    // is the point evaluated last (the root, or `hi0` when the force saturates), so its
    // direction and creepage are read here rather than evaluated again.
    let last = std::cell::Cell::new((f64::NAN, f64::NAN, 0.0, 0.0));
    // F(q)/q, continuous at 0 with the law's slope.
    let dir = |q: f64| {
        let (ratio, fq) = if q > 0.0 {
            let fq = creepage(q);
            (fq / q, fq)
        } else {
            (slope0, f64::NAN)
        };
        let f = k * ratio;
        let d = (x_star / (1.0 + f), y_star / (1.0 + r * f));
        last.set((q, fq, d.0, d.1));
        d
    };
    let h = |q: f64| {
        let (ux, uy) = dir(q);
        q - ux.hypot(uy)
    };
    let (fa, fb) = (h(0.0), h(hi0));
    let q = if fb <= 0.0 {
        hi0
    } else {
        // `h` rises at least as fast as `q` (`|dir(q)|` falls with `q`, as `F(q)/q` never
        // falls for any creep model: test `creepage_over_force_never_falls`), so a residual
        // `|h| <= tol` puts `q` within `tol` of the root, as a bracket of width `tol` does,
        // and it comes several evaluations sooner.
        let tol = 1e-13 * hi0;
        illinois(h, (0.0, fa), (hi0, fb), 100, |_, fc, kb| {
            (kb.b - kb.a).abs() <= tol || fc.abs() <= tol
        })
        .root_or_midpoint()
    };
    let (q_last, f_last, ux_last, uy_last) = last.get();
    let ((ux, uy), fq) = if q_last.to_bits() == q.to_bits() {
        ((ux_last, uy_last), f_last)
    } else {
        let d = dir(q);
        (d, last.get().1)
    };
    let creepage = (q > 0.0).then_some(fq);
    let norm = ux.hypot(uy);
    if norm > 0.0 {
        TranslationSolve {
            q,
            ux: ux / norm,
            uy: uy / norm,
            creepage,
        }
    } else {
        TranslationSolve {
            q,
            ux: x_star / q_star,
            uy: y_star / q_star,
            creepage,
        }
    }
}

/// The steady creepage of a force along the rolling direction at one contact:
/// [`SteadyLaw::creepage_for_force`] at fixed `mu P`, `G` and `a`, with what does not depend
/// on the force computed once (the implicit solve evaluates the law a dozen times per
/// contact). For Kalker's closed form (Kalker 2000, `F_ss(s) = 3 mu P/(G a^2 C11)
/// (1 - (1 - s)^(1/3))`, `s = |Q|/(mu P)`) the function [`SteadyLaw::creepage_for_force`]
/// calls (`kuhn_creepage_for_force`) with `3 mu P` and `G a^2 C11` kept, so the same bits; any
/// other case is that function.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ForceCreepage {
    law: SteadyLaw,
    mu_p: f64,
    g: f64,
    a: f64,
    /// `(3 mu P, G a^2 C11)` for Kalker's closed form with a finite positive `G a^2` and
    /// `mu P` (`None`: every other case).
    kalker: Option<(f64, f64)>,
}

impl ForceCreepage {
    /// The law `law` at capacity `mu_p` \[N\], combined shear modulus `g` \[Pa\] and contact
    /// radius `a` \[m\].
    #[inline]
    pub(crate) fn new(law: SteadyLaw, mu_p: f64, g: f64, a: f64) -> Self {
        let denom = g * a * a;
        let kalker = match law {
            SteadyLaw::Kuhn { c11 }
                if denom > 0.0 && denom.is_finite() && mu_p > 0.0 && mu_p.is_finite() =>
            {
                Some((3.0 * mu_p, denom * c11))
            }
            _ => None,
        };
        Self {
            law,
            mu_p,
            g,
            a,
            kalker,
        }
    }

    /// The creepage \[-\] of a force of magnitude `q_abs` \[N\].
    #[inline(always)]
    pub(crate) fn at(&self, q_abs: f64) -> f64 {
        match self.kalker {
            Some((three_mu_p, denom_c11)) => {
                kuhn_creepage_for_force(q_abs, self.mu_p, three_mu_p, denom_c11)
            }
            None => self
                .law
                .creepage_for_force(q_abs, self.mu_p, self.g, self.a),
        }
    }
}

/// Largest number of Newton steps of [`solve_combined`].
pub const COMBINED_ITERATIONS: usize = 8;

/// Relative residual at which [`solve_combined`] stops (of `1 + |q*|`, in units of `mu P`).
pub const COMBINED_TOLERANCE: f64 = 1e-10;

/// The answer of [`solve_combined`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CombinedSolve {
    /// The normalised creepages `(xi_n, eta_n)` \[-\].
    pub creepage: (f64, f64),
    /// The law's loads there (at the given spin).
    pub loads: Loads,
    /// The largest component of the residual `L(z) + kappa z - q*` left \[-\] (units of `mu P`).
    pub residual: f64,
}

/// The implicit solve with the combined 3-D law (parent module docs, "The implicit solve"):
/// the normalised creepages `z = (xi_n, eta_n)` with
/// `L(z, phi_n) + kappa z = q*`, `L` the law's `(fx, fy)` ([`Steady3d::loads`], over `mu P`),
/// for the force estimate `q*` over `mu P` (frame components, the spin's force included),
/// `kappa = K/(G c^2)` (`K = m_t V/dt` \[N\]) and the spin creepage `phi_n`. The force over
/// `mu P` is then the law's at the creepages it returns, exactly.
///
/// Damped Newton from `guess` with a forward-difference Jacobian (the law is piecewise
/// trilinear where tabulated, so a step that does not lower the residual's largest component
/// is halved, up to six times); stops at [`COMBINED_TOLERANCE`] or after
/// [`COMBINED_ITERATIONS`] steps with the best point found (never worse than `guess`).
pub fn solve_combined(
    law: &Steady3d,
    q_star: (f64, f64),
    kappa: f64,
    phi_n: f64,
    guess: (f64, f64),
) -> CombinedSolve {
    let res = |z: (f64, f64)| {
        let l = law.loads(z.0, z.1, phi_n);
        (
            l,
            (l.fx + kappa * z.0 - q_star.0, l.fy + kappa * z.1 - q_star.1),
        )
    };
    let size = |r: (f64, f64)| r.0.abs().max(r.1.abs());
    let tol = COMBINED_TOLERANCE * (1.0 + size(q_star));
    let mut z = guess;
    let (mut l, mut r) = res(z);
    let mut norm = size(r);
    for _ in 0..COMBINED_ITERATIONS {
        if !(norm > tol) {
            break;
        }
        let h = 1e-7 * size(z).max(1e-4);
        let (_, rx) = res((z.0 + h, z.1));
        let (_, ry) = res((z.0, z.1 + h));
        let (j00, j01) = ((rx.0 - r.0) / h, (ry.0 - r.0) / h);
        let (j10, j11) = ((rx.1 - r.1) / h, (ry.1 - r.1) / h);
        let det = j00 * j11 - j01 * j10;
        if !(det.abs() > 0.0 && det.is_finite()) {
            break;
        }
        let dz = ((j01 * r.1 - j11 * r.0) / det, (j10 * r.0 - j00 * r.1) / det);
        let mut step = 1.0;
        let mut better = false;
        for _ in 0..7 {
            let zn = (z.0 + step * dz.0, z.1 + step * dz.1);
            let (ln, rn) = res(zn);
            let nn = size(rn);
            if nn < norm {
                (z, l, r, norm, better) = (zn, ln, rn, nn, true);
                break;
            }
            step *= 0.5;
        }
        if !better {
            break;
        }
    }
    CombinedSolve {
        creepage: z,
        loads: l,
        residual: norm,
    }
}

/// The 3-D laws of elliptic contacts by shape, looked up by `(a/b, nu)` in a short list (no hashing, no
/// allocation once every shape has been seen): building a [`Steady3d`] interpolates Kalker's
/// table and the fitted constants and costs far more than one evaluation.
#[derive(Debug, Clone, Default)]
pub struct LawCache {
    entries: Vec<(f64, f64, Steady3d)>,
    next: usize,
}

/// Largest number of distinct `(a/b, nu)` laws kept (replaced round-robin beyond).
const LAW_CACHE_LEN: usize = 32;

impl LawCache {
    /// The law at `(ab, nu)` (`a/b` and Poisson's ratio), built on first use; `None` outside
    /// Kalker's table.
    pub fn get(&mut self, ab: f64, nu: f64) -> Option<&Steady3d> {
        let found = self
            .entries
            .iter()
            .position(|(a, n, _)| *a == ab && *n == nu);
        let i = match found {
            Some(i) => i,
            None => {
                let law = Steady3d::new(ab, nu).ok()?;
                if self.entries.len() < LAW_CACHE_LEN {
                    self.entries.push((ab, nu, law));
                    self.entries.len() - 1
                } else {
                    let i = self.next;
                    self.next = (self.next + 1) % LAW_CACHE_LEN;
                    self.entries[i] = (ab, nu, law);
                    i
                }
            }
        };
        Some(&self.entries[i].2)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kalker(q: f64) -> f64 {
        // F_ss of a circle with mu P = 1, G a^2 C11 = 1: 3 (1 - (1 - q)^(1/3)).
        3.0 * (1.0 - (1.0 - q.min(1.0)).cbrt())
    }

    #[test]
    fn frame_is_right_handed_with_x_against_v_roll() {
        let n = Vec3::new(0.0, -1.0, 0.0);
        let f = RollFrame::new(Vec3::new(-2.0, 0.0, 0.0), n).unwrap();
        assert_eq!(f.x, Vec3::new(1.0, 0.0, 0.0));
        assert!((f.x.cross(f.y) - n).length() < 1e-15);
        let v = Vec3::new(0.3, 0.0, -0.7);
        let (a, b) = f.split(v);
        assert!((f.join(a, b) - v).length() < 1e-15);
        assert!(RollFrame::new(Vec3::ZERO, n).is_none());
    }

    #[test]
    fn isotropic_solve_is_the_circular_one() {
        // r = 1: q + k F(q) = |Q*| along Q*.
        let (k, qs) = (2.0, (0.3, -0.4));
        let (q, ux, uy) = solve_translation(qs, k, 1.0, 1.0, 1.0, &kalker);
        assert!((q + k * kalker(q) - 0.5).abs() < 1e-12, "{q}");
        assert!((ux - 0.6).abs() < 1e-12 && (uy + 0.8).abs() < 1e-12);
    }

    #[test]
    fn anisotropic_solve_satisfies_its_equation_and_its_fixed_point() {
        let (k, r) = (3.0, 3.40 / 3.98);
        for qs in [(0.2, 0.1), (-0.05, 0.3), (0.0, 0.6), (0.9, 0.9)] {
            let (q, ux, uy) = solve_translation(qs, k, r, 1.0, 1.0, &kalker);
            assert!((ux.hypot(uy) - 1.0).abs() < 1e-12);
            if q < 1.0 {
                // Q + K F A u = Q*.
                let f = kalker(q);
                let ex = q * ux + k * f * ux - qs.0;
                let ey = q * uy + k * f * r * uy - qs.1;
                assert!(ex.abs() < 1e-10 && ey.abs() < 1e-10, "{qs:?}: {ex} {ey}");
            } else {
                assert_eq!(q, 1.0);
            }
        }
        // Fixed point: a force Q with its own target gives Q back.
        let (q0, u0) = (0.4, (0.6, 0.8));
        let f = kalker(q0);
        let qs = (q0 * u0.0 + k * f * u0.0, q0 * u0.1 + k * f * r * u0.1);
        let (q, ux, uy) = solve_translation(qs, k, r, 1.0, 1.0, &kalker);
        assert!((q - q0).abs() < 1e-10 && (ux - 0.6).abs() < 1e-9 && (uy - 0.8).abs() < 1e-9);
        // The lateral direction creeps less per force (r < 1): the force turns towards y.
        let (_, ux, uy) = solve_translation((0.3, 0.3), k, r, 1.0, 1.0, &kalker);
        assert!(uy > ux, "{ux} {uy}");
    }

    #[test]
    fn force_creepage_is_the_laws_bit_for_bit() {
        use crate::steady_law::CreepModel;
        for model in CreepModel::ALL {
            let law = SteadyLaw::new(model, 0.28);
            for (mu_p, g, a) in [
                (120.0, 8.1e10, 2.3e-4),
                (3.5e-3, 4.0e5, 1e-3),
                (0.0, 8.1e10, 2.3e-4),
                (f64::INFINITY, 8.1e10, 2.3e-4),
                (f64::NAN, 8.1e10, 2.3e-4),
                (10.0, 0.0, 1e-3),
                (10.0, 8.1e10, 0.0),
                (10.0, f64::INFINITY, 1e-3),
            ] {
                let f = ForceCreepage::new(law, mu_p, g, a);
                let scale = if mu_p.is_finite() { mu_p } else { 50.0 };
                for i in -2..=42 {
                    let q = scale * f64::from(i) / 40.0;
                    for q in [q, -q, f64::NAN, f64::INFINITY, 1e-300] {
                        let (got, want) = (f.at(q), law.creepage_for_force(q, mu_p, g, a));
                        assert!(
                            got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()),
                            "{model:?} {mu_p} {g} {a} {q}: {got} {want}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn law_cache_reuses_and_refuses() {
        let mut c = LawCache::default();
        let a = *c.get(1.0, 0.25).unwrap();
        let b = *c.get(1.0, 0.25).unwrap();
        assert_eq!(a, b);
        assert_eq!(c.entries.len(), 1);
        assert!(c.get(20.0, 0.25).is_none());
        for i in 0..40 {
            c.get(0.2 + 0.01 * f64::from(i), 0.3).unwrap();
        }
        assert_eq!(c.entries.len(), LAW_CACHE_LEN);
    }
}
