//! The Cattaneo-Mindlin memory in its plain, unoptimised form (a frozen copy of an earlier
//! `crates/law/src/mindlin.rs`, unchanged but for this header): the oracle
//! that the faster [`super::MindlinState`] must reproduce bit for bit (`mindlin/tests.rs`,
//! `reference_*` tests) and the baseline of `crates/law/benches/mindlin.rs`. Not used by the
//! library itself. Its module documentation follows.
//!
//! Cattaneo-Mindlin tangential contact with load-history memory, for arbitrary 2-D tangential
//! displacement paths and varying normal force.
//!
//! # The model
//! The algorithm is the *method of dimensionality reduction* (MDR) of Popov & Heß (2015, *Method of
//! Dimensionality Reduction in Contact Mechanics and Friction*, Springer, ch. 5 "Tangential
//! contact"), which maps the Hertz contact with Mindlin's tangential compliance onto a 1-D row of
//! independent springs: at distance `x` from the centre (`0 <= x <= a`, two symmetric halves)
//! a spring has normal stiffness `E*` and tangential stiffness `4 G*` per unit length, carries the
//! normal force density `E* (a^2 - x^2) / R*` and slips by Coulomb's law, so its tangential
//! displacement `u(x)` obeys `|u(x)| <= L(x) = kappa (a^2 - x^2)` with
//! `kappa = mu E* / (4 G* R*)`. The tangential force is `Q = 2 * 4 G* * integral_0^a u(x) dx`.
//! Popov & Heß (2015, ch. 5) show that this mapping reproduces the Cattaneo-Mindlin problem of
//! axisymmetric profiles under histories of normal and (collinear) tangential load; the unit
//! tests confirm it here to rounding: at constant `P` it reproduces Mindlin & Deresiewicz (1953)
//! loading, unloading and reloading with their memory, and under varying `P` it is the rule we
//! follow and test (new springs enter with zero displacement, leaving springs release theirs;
//! e.g. proportional loading `Q/P = const < mu` is slip-free with `dQ = 8 G* a d delta`, as
//! Mindlin & Deresiewicz 1953 found).
//!
//! # The algorithm
//! The spring field `u(x)` is held exactly, as a short list of *pieces* (annuli of the 3-D
//! contact), each of the form `u(x) = s(x) beta + c` with the depth `s = a^2 - x^2` (so the
//! limit is `kappa s`; a piece at the slip limit has `c = 0`, `|beta| = kappa`; a stuck piece
//! `beta = 0`; springs that entered while `a` grew carry `beta = du / d(a^2)`). Each update
//! (i) rewrites the pieces for the new contact radius (`s` shifts uniformly with `a^2`),
//! (ii) adds the displacement increment to every spring, (iii) finds in closed form, per piece,
//! the radius that divides sticking from slipping springs (the depth decreases outwards, so the
//! slipping part is always the outer end of a piece), and (iv) sets the slipping springs onto the
//! limit. Every step is
//! integrated along the exact branch, so at constant `P` the closed forms are reproduced to
//! rounding whatever the step size. For collinear paths the slip direction of a piece is exact;
//! when the path turns, the springs of one slipping piece are given one common direction (that of
//! their summed trial force) — the one approximation, which vanishes as steps get small.
//! Pieces are merged when equal; a contact keeps at most [`MAX_PIECES`] (see `merge`: two pieces
//! at the slip limit become one along their summed force, or else the narrowest pair whose
//! least-squares fit — or, when the fit's slope exceeds the limit's, the fit with its slope cut
//! to the limit's and the same force — stays within the limit and adds no energy becomes that
//! fit, or as a last resort an inner piece
//! is absorbed into its outer neighbour extended inwards; all keep `|u| <= L`, and any energy the
//! simplification removes is booked as dissipation, any it adds as `truncation_energy`).
//!
//! # Energy under varying `P`
//! The balance `work = stored + slip_dissipation - truncation_energy` holds with the work
//! `sum Q_mid . du` to within the step size (first order; second order where no spring changes
//! between sticking and slipping), for any `mu` including `+inf`. Within a step `a^2` is taken
//! linear in time, like the displacement, and three rules follow from it. Springs entering the
//! contact always get a piece of their own, `u = (a^2 - x^2) du / d(a^2)` (when the memory is
//! full, the spare slot holds it until `merge` makes room; extending the outermost piece
//! outwards instead gave them that piece's `c`, which after a small `d(a^2)` is huge: energy no
//! work paid for, orders of magnitude more than the work at large `mu`). Springs leaving the
//! contact release the energy they had when they left, not at the start of the step. And the
//! slip of a step is booked at the force the springs had while slipping, `(F_on + kappa s) / 2`
//! (see `Onset`), not at the end-of-step limit, which misses the fall of the limit as `a`
//! shrinks. At constant `P` all three reduce to the exact Mindlin-Deresiewicz bookkeeping.
//!
//! Conventions: `Q` is the tangential force on body p from body q \[N\]; the displacement increment
//! `du` is `du_disp = du_q - du_p` \[m\] in the tangent plane, so a stuck contact has `dQ = k_t du`
//! with `k_t = 8 G* a` (Mindlin 1949).

#![allow(
    dead_code,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::wrong_self_convention
)]

use crate::hertz;
use crate::material::PairMaterial;
use crate::vector::Vec2;

/// The most pieces (annuli of distinct load history) one contact remembers.
pub const MAX_PIECES: usize = 8;

/// Largest displacement increment one update accepts \[m\]; longer ones are shortened to it (a
/// guard that keeps every output finite for any finite input, e.g. with `mu = +inf`).
pub const MAX_INCREMENT: f64 = 1e100;

/// One annulus `x_lo < x <= x_hi` of the spring row, where `u(x) = s(x) beta + c` with the depth
/// `s(x) = a^2 - x^2` [m^2] (the slip limit is `kappa s(x)`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Piece {
    /// Outer radius of the annulus \[m\] (inner radius: the previous piece's, or 0).
    x_hi: f64,
    /// Displacement per unit depth [1/m]; `|beta| <= kappa`, `= kappa` on springs at the limit.
    beta: Vec2,
    /// Uniform displacement \[m\].
    c: Vec2,
}

/// Depth `s(x) = a^2 - x^2 = (a - x)(a + x)` [m^2], in the factored form that keeps its relative
/// accuracy near the edge `x -> a`.
#[inline]
fn depth(a: f64, x: f64) -> f64 {
    (a - x) * (a + x)
}

/// `integral_{x1}^{x2} s dx` [m^3] by Simpson's rule (exact for the quadratic `s`), evaluated
/// with [`depth`] so that thin annuli at the edge lose no digits.
#[inline]
fn int_s(a: f64, x1: f64, x2: f64) -> f64 {
    let h = x2 - x1;
    h / 6.0 * (depth(a, x1) + 4.0 * depth(a, 0.5 * (x1 + x2)) + depth(a, x2))
}

/// `integral_{x1}^{x2} s^2 dx` [m^5] by 3-point Gauss-Legendre quadrature (exact for the quartic
/// `s^2`; Abramowitz & Stegun 1964, §25.4), free of cancellation like [`int_s`].
#[inline]
fn int_s2(a: f64, x1: f64, x2: f64) -> f64 {
    const R: f64 = 0.774_596_669_241_483_4; // sqrt(3/5)
    let h = 0.5 * (x2 - x1);
    let m = 0.5 * (x1 + x2);
    let (s0, sm, sp) = (depth(a, m), depth(a, m - R * h), depth(a, m + R * h));
    h * (8.0 * s0 * s0 + 5.0 * (sm * sm + sp * sp)) / 9.0
}

/// What one Cattaneo-Mindlin update did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MindlinStep {
    /// Tangential force on p from q after the step \[N\].
    pub q: Vec2,
    /// Contact radius used \[m\].
    pub a: f64,
    /// Energy dissipated by micro-slip and gross slip in the step \[J\] (>= 0): slip of each spring
    /// times its force while it slipped (at constant `P` the force at the end of the step), plus
    /// the energy springs had when they left the contact, plus any energy a merge of the memory
    /// removed.
    pub slip_dissipation: f64,
    /// Energy the springs gained when the memory was over [`MAX_PIECES`] and had to be
    /// simplified by the last-resort rule \[J\] (>= 0; zero in all but rare, long 2-D histories).
    /// The energy balance is `work = stored + slip_dissipation - truncation_energy`.
    pub truncation_energy: f64,
}

/// Load-history state of one contact's Cattaneo-Mindlin tangential law. `Default` is a virgin,
/// open contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MindlinState {
    /// Contact radius of the last update \[m\].
    a: f64,
    /// Number of pieces in use.
    n: usize,
    /// The pieces, inner to outer. Between updates `n <= MAX_PIECES`; the spare slot holds the
    /// springs that enter the contact during an update until `merge` has made room for them.
    pieces: [Piece; MAX_PIECES + 1],
    /// Tangential force after the last update \[N\].
    q: Vec2,
}

impl MindlinState {
    /// A virgin, open contact (no force, no memory).
    pub fn new() -> Self {
        Self::default()
    }

    /// Tangential force on p from q after the last update \[N\].
    #[inline]
    pub fn force(&self) -> Vec2 {
        self.q
    }

    /// Contact radius of the last update \[m\].
    #[inline]
    pub fn contact_radius(&self) -> f64 {
        self.a
    }

    /// Number of remembered pieces (annuli of distinct history); 0 for an open contact.
    #[inline]
    pub fn memory_depth(&self) -> usize {
        self.n
    }

    /// Forgets everything (the contact opened).
    pub fn reset(&mut self) {
        *self = Self::default();
    }

    /// Applies the 2x2 matrix `m` (rows) to the stored tangential state, e.g. a rotation when the
    /// engine's tangent basis turns with the contact normal.
    pub fn transform(&mut self, m: [[f64; 2]; 2]) {
        let apply =
            |v: Vec2| Vec2::new(m[0][0] * v.x + m[0][1] * v.y, m[1][0] * v.x + m[1][1] * v.y);
        for p in &mut self.pieces[..self.n] {
            p.c = apply(p.c);
            p.beta = apply(p.beta);
        }
        self.q = apply(self.q);
    }

    /// Elastic energy stored in the tangential springs \[J\]:
    /// `W = 4 G* integral_0^a |u(x)|^2 dx` (two halves, `(1/2) 4 G* |u|^2` per unit length).
    pub fn elastic_energy(&self, pair: &PairMaterial) -> f64 {
        let mut x_lo = 0.0;
        let mut w = 0.0;
        for p in &self.pieces[..self.n] {
            w += piece_u2(p, self.a, x_lo, p.x_hi);
            x_lo = p.x_hi;
        }
        4.0 * pair.g_star * w
    }

    /// Advances the contact by one step: the normal force becomes `p` \[N\] (Hertz gives the contact
    /// radius) and the surfaces move by `du` \[m\] (`du_q - du_p`, tangent plane). Non-finite or
    /// negative `p` is treated as an open contact, a non-finite `du` as no motion.
    pub fn update(&mut self, pair: &PairMaterial, p: f64, du: Vec2) -> MindlinStep {
        let a = hertz::contact_radius(pair, p);
        self.update_with_radius(pair, a, du)
    }

    /// [`MindlinState::update`] with the contact radius `a` \[m\] given directly (e.g. from the
    /// overlap in a DEM code: `a = sqrt(R* delta)`).
    pub fn update_with_radius(&mut self, pair: &PairMaterial, a: f64, du: Vec2) -> MindlinStep {
        let a = if a.is_finite() && a > 0.0 { a } else { 0.0 };
        let du = if !du.is_finite() {
            Vec2::ZERO
        } else if du.length() > MAX_INCREMENT {
            du * (MAX_INCREMENT / du.length())
        } else {
            du
        };
        let kappa = kappa(pair);
        let mut dissipated = 0.0;
        if a == 0.0 {
            if self.n > 0 {
                dissipated = self.elastic_energy(pair);
            }
            *self = Self::default();
            return MindlinStep {
                q: Vec2::ZERO,
                a: 0.0,
                slip_dissipation: dissipated,
                truncation_energy: 0.0,
            };
        }
        let a_old = self.a;
        let a2_old = a_old * a_old;
        let a2 = a * a;

        // (i) Springs that left the contact release their energy, with the displacement they had
        //     when they left: the one at x left when a(t)^2 = x^2, i.e. (with a^2 linear over the
        //     step, as for entering springs below) after the fraction s_old / (a_old^2 - a^2) of
        //     the step, so it had moved by du s_old / (a_old^2 - a^2) more: beta + du / (-da2).
        //     Booking the displacement at the start of the step instead leaves the work that the
        //     mid-step force did on them unaccounted, an energy error of first order in the step.
        if a < a_old {
            let extra = du * (1.0 / (a2_old - a2));
            let mut x_lo = 0.0;
            let mut keep = 0;
            for i in 0..self.n {
                let p = self.pieces[i];
                if p.x_hi > a {
                    let from = if x_lo > a { x_lo } else { a };
                    let mut leaving = p;
                    if (p.beta + extra).is_finite() {
                        leaving.beta += extra;
                    }
                    dissipated += 4.0 * pair.g_star * piece_u2(&leaving, a_old, from, p.x_hi);
                }
                if x_lo < a {
                    keep = i + 1;
                }
                x_lo = p.x_hi;
            }
            self.n = keep;
            if keep > 0 {
                self.pieces[keep - 1].x_hi = a;
            }
        }
        // (i) The depth shifts uniformly: s_new(x) = s_old(x) + (a^2 - a_old^2), so
        //     u = s_old beta + c = s_new beta + (c - da2 beta); (ii) every spring moves by du.
        let da2 = a2 - a2_old;
        for p in &mut self.pieces[..self.n] {
            p.c += du - p.beta * da2;
        }
        // Springs entering during the step: the one at x entered when a(t)^2 = x^2 and, with the
        // displacement linear in a^2 over the step, took du (a^2 - x^2) / da2, i.e. beta = du / da2.
        // They always get a piece of their own (the spare slot when the memory is full; `merge`
        // then makes room): giving them the outermost piece's field extended outwards instead
        // would let them enter with that piece's `c` (after a small `da2`, `c = du - beta da2`
        // with a huge `beta`), energy that no work paid for.
        if da2 > 0.0 {
            self.pieces[self.n] = Piece {
                x_hi: a,
                beta: du * (1.0 / da2),
                c: Vec2::ZERO,
            };
            self.n += 1;
        }

        // (iii)-(iv) Return-map every piece: it splits into a stuck inner part and a slipping
        // outer part. Pieces that only stick or only slip are updated in place; a split needs
        // a scratch list.
        let mut cuts = [0.0f64; MAX_PIECES + 1];
        let mut splits = 0;
        let mut x_lo = 0.0;
        for (p, cut_out) in self.pieces[..self.n].iter().zip(cuts.iter_mut()) {
            let cut = stick_radius(p, kappa, a2).clamp(x_lo, p.x_hi.max(x_lo));
            splits += usize::from(cut > x_lo && cut < p.x_hi);
            *cut_out = cut;
            x_lo = p.x_hi.max(x_lo);
        }
        // The slip is booked at the force the springs had while they slipped (see `Onset`).
        let slip = |p: &Piece, cut: f64, dissipated: &mut f64| {
            let onset = if da2 == 0.0 {
                Onset::Constant
            } else if p.x_hi > a_old {
                Onset::Entering
            } else {
                Onset::Shifted(da2)
            };
            let (e, work) = slip_piece(p, kappa, a, cut, p.x_hi, onset);
            *dissipated += 8.0 * pair.g_star * work;
            Piece {
                x_hi: p.x_hi,
                beta: e * kappa,
                c: Vec2::ZERO,
            }
        };
        let (n, d_u2) = if splits == 0 {
            let mut x_lo = 0.0;
            for (p, &cut) in self.pieces[..self.n].iter_mut().zip(cuts.iter()) {
                let x_hi = p.x_hi;
                if cut < x_hi && x_hi > x_lo {
                    *p = slip(p, cut, &mut dissipated);
                }
                x_lo = x_hi.max(x_lo);
            }
            merge(&mut self.pieces, self.n, a, kappa)
        } else {
            let mut out = [Piece::default(); 2 * (MAX_PIECES + 1)];
            let mut m = 0;
            let mut x_lo = 0.0;
            for (p, &cut) in self.pieces[..self.n].iter().zip(cuts.iter()) {
                if p.x_hi <= x_lo {
                    continue;
                }
                if cut > x_lo {
                    out[m] = Piece { x_hi: cut, ..*p };
                    m += 1;
                }
                if cut < p.x_hi {
                    out[m] = slip(p, cut, &mut dissipated);
                    m += 1;
                }
                x_lo = p.x_hi;
            }
            let (n, d_u2) = merge(&mut out, m, a, kappa);
            self.pieces[..n].copy_from_slice(&out[..n]);
            (n, d_u2)
        };
        self.a = a;
        self.n = n;
        let d_energy = 4.0 * pair.g_star * d_u2;
        let truncation_energy = if d_energy > 0.0 { d_energy } else { 0.0 };
        if d_energy < 0.0 {
            dissipated -= d_energy;
        }
        self.q = self.integrate_force(pair);
        // Saturate instead of overflowing on absurd (but finite) displacements.
        let slip_dissipation = if dissipated > 0.0 {
            dissipated.min(f64::MAX)
        } else {
            0.0
        };
        MindlinStep {
            q: self.q,
            a,
            slip_dissipation,
            truncation_energy,
        }
    }

    /// `Q = 8 G* sum_pieces integral u(x) dx`.
    fn integrate_force(&self, pair: &PairMaterial) -> Vec2 {
        let mut x_lo = 0.0;
        let mut sum = Vec2::ZERO;
        for p in &self.pieces[..self.n] {
            sum += p.c * (p.x_hi - x_lo) + p.beta * int_s(self.a, x_lo, p.x_hi);
            x_lo = p.x_hi;
        }
        sum * (8.0 * pair.g_star)
    }
}

/// `kappa = mu E* / (4 G* R*)` [1/m]: the slip limit is `L(x) = kappa (a^2 - x^2)`; `+inf` for
/// `mu = +inf`.
#[inline]
fn kappa(pair: &PairMaterial) -> f64 {
    pair.mu * pair.e_star / (4.0 * pair.g_star * pair.r_star)
}

/// `integral_{x1}^{x2} |u(x)|^2 dx` over a piece [m^3].
fn piece_u2(p: &Piece, a: f64, x1: f64, x2: f64) -> f64 {
    if x2 <= x1 {
        return 0.0;
    }
    let mut w = p.c.length_squared() * (x2 - x1);
    if p.beta != Vec2::ZERO {
        w += p.beta.length_squared() * int_s2(a, x1, x2) + 2.0 * p.beta.dot(p.c) * int_s(a, x1, x2);
    }
    w
}

/// The radius inside which the springs of a (trial) piece satisfy `|s beta + c| <= kappa s`.
/// That holds for `s >= s*`, the larger root of `(kappa^2 - |beta|^2) s^2 - 2 (beta.c) s - |c|^2`,
/// `s* = |c|^2 / (sqrt(D) - beta.c)` with `D = (beta.c)^2 + (kappa^2 - |beta|^2) |c|^2` (the
/// rationalised root, free of cancellation); the
/// depth decreases outwards, so the stuck set is `x <= sqrt(a^2 - s*)`.
#[inline]
fn stick_radius(p: &Piece, kappa: f64, a2: f64) -> f64 {
    // Written with the unit vector of c, so that huge displacements cannot overflow:
    // s* = |c| / (sqrt(D') - beta.c_hat), D' = (beta.c_hat)^2 + kappa^2 - |beta|^2.
    let cl = p.c.length();
    if cl == 0.0 {
        // u = s beta: within the limit everywhere or nowhere (springs entering the contact can
        // bring |beta| > kappa).
        return if p.beta.length() <= kappa {
            f64::INFINITY
        } else {
            0.0
        };
    }
    let bc = p.beta.dot(p.c * (1.0 / cl));
    let d = bc * bc + (kappa * kappa - p.beta.length_squared()).max(0.0);
    let den = d.sqrt() - bc;
    if !(den > 0.0) {
        return 0.0; // everything slips
    }
    let s_star = cl / den;
    if !(s_star > 0.0) {
        return f64::INFINITY; // kappa = +inf: nothing ever slips
    }
    let r2 = a2 - s_star;
    if r2 > 0.0 { r2.sqrt() } else { 0.0 }
}

/// The force at which `slip_piece` books the slip of a spring over one step.
///
/// A spring that slips during a step first reaches its limit (at the force `F_on`) and then
/// slides along it to the end-of-step limit `kappa s`; with the limit linear in time over the
/// step (`a^2` linear, as for entering and leaving springs) and a steady displacement rate, its
/// slip rate is constant, so the slip work is `(F_on + kappa s) / 2` times the slip (the
/// trapezoidal rule, exact for the linear force). `F_on` is the start-of-step limit
/// `kappa s_old` for a spring that was at the limit, or the displacement where a stuck spring
/// met the limit; we take `min(kappa s_old, e . u_trial)`: exact for the first case; for the
/// second the true value lies between the displacements at the start and the end of the step,
/// so the error is one step's displacement on the springs that change from sticking to slipping
/// (a band one step wide while the slip zone is wide: second order overall; the whole slip band
/// when it is thinner than a step, at large `mu`: first order). Booking at the end-of-step limit
/// alone is first order wrong whenever the limit moves and wrong by the whole slip work when the
/// slip band is thinner than a step (a spring stuck at `u` and met by the falling limit slides
/// from `u` down to `kappa s`); booking at `kappa s_old` instead overshoots as much.
#[derive(Debug, Clone, Copy)]
enum Onset {
    /// Constant limit (`da2 = 0`, constant P): `F_on = kappa s`, the end-of-step limit, which is
    /// the exact Mindlin-Deresiewicz booking.
    Constant,
    /// Springs that entered during the step: their limit rose from 0 (`F_on = 0`).
    Entering,
    /// Springs in contact before the step, whose depth changed by `da2` [m^2]:
    /// `F_on = min(kappa (s - da2), e . u_trial)`.
    Shifted(f64),
}

/// Puts the springs `x1 < x <= x2` of a trial piece onto the slip limit `u = kappa s e`. Returns
/// their common slip direction `e` (that of their summed trial displacement) and
/// `integral (F_on + kappa s) / 2 (e . u_trial - kappa s) dx` [m^3] (see [`Onset`] for `F_on`):
/// the slip work divided by `8 G*` (the force density is `4 G*` times the displacement-valued
/// `F`, and there are two halves).
fn slip_piece(p: &Piece, kappa: f64, a: f64, x1: f64, x2: f64, onset: Onset) -> (Vec2, f64) {
    let is = int_s(a, x1, x2);
    let is2 = int_s2(a, x1, x2);
    let trial = p.beta * is + p.c * (x2 - x1);
    let l = trial.length();
    let e = if l > 0.0 && l.is_finite() {
        trial * (1.0 / l)
    } else {
        Vec2::new(1.0, 0.0)
    };
    // Along e the trial displacement is b0 + b1 s, the slip (b0 + (b1 - kappa) s).
    let (b0, b1) = (e.dot(p.c), e.dot(p.beta));
    let work = match onset {
        Onset::Constant => kappa * (b1 * is2 + b0 * is - kappa * is2),
        Onset::Entering => 0.5 * kappa * (b1 * is2 + b0 * is - kappa * is2),
        Onset::Shifted(da2) => shifted_slip_work(kappa, a, (x1, x2), (b0, b1), da2, (is, is2)),
    };
    (e, if work > 0.0 { work } else { 0.0 })
}

/// `integral (F_on + kappa s) / 2 (b0 + (b1 - kappa) s) dx` [m^3] over `x1 < x <= x2` for
/// [`Onset::Shifted`]: `F_on = min(kappa (s - da2), b0 + b1 s)`, where `b0 + b1 s` is the trial
/// displacement along the slip direction; `is`, `is2` are `int_s`, `int_s2` over the annulus.
/// Kept out of line so that the constant-`P` path stays small.
#[inline(never)]
fn shifted_slip_work(
    kappa: f64,
    a: f64,
    (x1, x2): (f64, f64),
    (b0, b1): (f64, f64),
    da2: f64,
    (is, is2): (f64, f64),
) -> f64 {
    // F_on = min(kappa (s - da2), b0 + b1 s): two lines crossing at
    // s_x = (b0 + kappa da2) / (kappa - b1); split there if inside the annulus.
    let s_x = (b0 + kappa * da2) / (kappa - b1);
    let r2 = a * a - s_x;
    let split = if r2 > x1 * x1 && r2 < x2 * x2 {
        r2.sqrt().clamp(x1, x2)
    } else {
        x2
    };
    let mut w = 0.0;
    for (y1, y2) in [(x1, split), (split, x2)] {
        if y2 <= y1 {
            continue;
        }
        let sm = depth(a, 0.5 * (y1 + y2));
        let (m0, m1) = if kappa * (sm - da2) <= b0 + b1 * sm {
            (-kappa * da2, kappa)
        } else {
            (b0, b1)
        };
        // (F_on + kappa s) / 2 = g0 + g1 s; slip = h0 + h1 s.
        let (g0, g1) = (0.5 * m0, 0.5 * (m1 + kappa));
        let (h0, h1) = (b0, b1 - kappa);
        let (js, js2) = if y1 == x1 && y2 == x2 {
            (is, is2)
        } else {
            (int_s(a, y1, y2), int_s2(a, y1, y2))
        };
        w += g0 * h0 * (y2 - y1) + (g0 * h1 + g1 * h0) * js + g1 * h1 * js2;
    }
    w
}

/// Merges equal neighbours and drops empty pieces in place, then enforces [`MAX_PIECES`].
/// Returns the number of pieces kept and the change of `integral |u|^2 dx` [m^3] that the
/// enforcement caused (<= 0 means energy was lost, which the caller books as dissipation).
///
/// Over the limit, two neighbours are made one: preferably two pieces both at the slip limit
/// (`u = kappa s e1`, `kappa s e2`), which become one at the limit along their summed force
/// (the stored energy is unchanged and `|u| <= kappa s` still holds); otherwise the narrowest
/// pair whose least-squares merge stays within the limit (force kept, energy lost booked as
/// dissipation), the merge's slope cut to `kappa` with the force kept where the fit's slope is
/// over it (taken only if within the limit and not adding energy); as a last resort the inner
/// piece whose absorption by its outer neighbour
/// (extended inwards) adds the least energy.
fn merge(out: &mut [Piece], m: usize, a: f64, kappa: f64) -> (usize, f64) {
    let a2 = a * a;
    let mut n = 0;
    let mut x_lo = 0.0;
    for i in 0..m {
        let p = out[i];
        if p.x_hi <= x_lo {
            continue;
        }
        if n > 0 && same_form(&out[n - 1], &p, a2) {
            out[n - 1].x_hi = p.x_hi;
        } else {
            out[n] = p;
            n += 1;
        }
        x_lo = p.x_hi;
    }
    let mut d_u2 = 0.0;
    while n > MAX_PIECES {
        // The adjacent pair of limit pieces with the closest directions, if any.
        let mut best_pair = None;
        let mut best_cos = f64::NEG_INFINITY;
        for i in 0..n - 1 {
            let (p, q) = (&out[i], &out[i + 1]);
            if at_limit(p, kappa) && at_limit(q, kappa) {
                let cos = p.beta.dot(q.beta);
                if cos > best_cos {
                    best_cos = cos;
                    best_pair = Some(i);
                }
            }
        }
        if let Some(i) = best_pair {
            let lo = if i == 0 { 0.0 } else { out[i - 1].x_hi };
            let (p, q) = (out[i], out[i + 1]);
            let sum = p.beta * int_s(a, lo, p.x_hi) + q.beta * int_s(a, p.x_hi, q.x_hi);
            let l = sum.length();
            let e = if l > 0.0 && l.is_finite() {
                sum * (1.0 / l)
            } else {
                Vec2::new(1.0, 0.0)
            };
            out[i] = Piece {
                x_hi: q.x_hi,
                beta: e * kappa,
                c: Vec2::ZERO,
            };
            out.copy_within(i + 2..n, i + 1);
            n -= 1;
            continue;
        }
        // Otherwise the least-squares merge (force-preserving, energy-non-increasing) of the
        // narrowest neighbour pair whose merged field stays within the limit.
        let mut order = [(0.0f64, 0usize); 2 * (MAX_PIECES + 1)];
        let mut lo = 0.0;
        for i in 0..n - 1 {
            order[i] = (out[i + 1].x_hi - lo, i);
            lo = out[i].x_hi;
        }
        order[..n - 1].sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let mut merged = false;
        for &(_, i) in &order[..n - 1] {
            let lo = if i == 0 { 0.0 } else { out[i - 1].x_hi };
            let (p, q) = (out[i], out[i + 1]);
            let old = piece_u2(&p, a, lo, p.x_hi) + piece_u2(&q, a, p.x_hi, q.x_hi);
            let mut fit = least_squares_piece(&p, &q, a, lo);
            let mut ok = fit.beta.length() <= kappa && stick_radius(&fit, kappa, a2) >= fit.x_hi;
            if !ok && fit.beta.length() > kappa {
                // The fit's slope over the limit's (two annuli near the limit in different
                // directions, as a turning path under a rising load leaves them): the slope
                // cut to `kappa`, the uniform part re-solved to keep the force. Taken only if
                // within the limit and not adding energy.
                let len = fit.x_hi - lo;
                let force = fit.beta * int_s(a, lo, fit.x_hi) + fit.c * len;
                let beta = fit.beta * (kappa / fit.beta.length());
                let cut = Piece {
                    x_hi: fit.x_hi,
                    beta,
                    c: (force - beta * int_s(a, lo, fit.x_hi)) * (1.0 / len),
                };
                ok = len > 0.0
                    && cut.c.is_finite()
                    && stick_radius(&cut, kappa, a2) >= cut.x_hi
                    && piece_u2(&cut, a, lo, cut.x_hi) <= old;
                fit = cut;
            }
            if ok {
                d_u2 += piece_u2(&fit, a, lo, fit.x_hi) - old;
                out[i] = fit;
                out.copy_within(i + 2..n, i + 1);
                n -= 1;
                merged = true;
                break;
            }
        }
        if merged {
            continue;
        }
        // Last resort: absorb an inner piece into its outer neighbour extended inwards (its field
        // stays within the limit where the depth is larger): the one that adds the least energy.
        let mut best = 0;
        let mut best_gain = f64::INFINITY;
        let mut lo = 0.0;
        let mut best_lo = 0.0;
        for i in 0..n - 1 {
            let (gone, outer) = (&out[i], &out[i + 1]);
            let gain = piece_u2(outer, a, lo, gone.x_hi) - piece_u2(gone, a, lo, gone.x_hi);
            if gain < best_gain {
                best_gain = gain;
                best = i;
                best_lo = lo;
            }
            lo = gone.x_hi;
        }
        let (gone, outer) = (out[best], out[best + 1]);
        d_u2 += piece_u2(&outer, a, best_lo, gone.x_hi) - piece_u2(&gone, a, best_lo, gone.x_hi);
        out.copy_within(best + 1..n, best);
        n -= 1;
        if best > 0 && same_form(&out[best - 1], &out[best], a2) {
            out[best - 1].x_hi = out[best].x_hi;
            out.copy_within(best + 1..n, best);
            n -= 1;
        }
    }
    (n, d_u2)
}

/// The piece `s beta + c` on `lo < x <= q.x_hi` closest in `L2` to the two pieces `p`, `q`
/// (normal equations in the basis `{s, 1}`): it keeps `integral u dx` (the force) and
/// `integral s u dx`, and its `integral |u|^2 dx` is never larger (orthogonal projection).
fn least_squares_piece(p: &Piece, q: &Piece, a: f64, lo: f64) -> Piece {
    let (x1, x2) = (p.x_hi, q.x_hi);
    let (l1, l2) = (x1 - lo, x2 - x1);
    let (s1a, s1b) = (int_s(a, lo, x1), int_s(a, x1, x2));
    let (s2a, s2b) = (int_s2(a, lo, x1), int_s2(a, x1, x2));
    let (s0, s1, s2) = (l1 + l2, s1a + s1b, s2a + s2b);
    let m0 = p.beta * s1a + p.c * l1 + q.beta * s1b + q.c * l2;
    let m1 = p.beta * s2a + p.c * s1a + q.beta * s2b + q.c * s1b;
    let det = s2 * s0 - s1 * s1;
    if det > 1e-12 * s2 * s0 {
        Piece {
            x_hi: x2,
            beta: (m1 * s0 - m0 * s1) * (1.0 / det),
            c: (m0 * s2 - m1 * s1) * (1.0 / det),
        }
    } else {
        Piece {
            x_hi: x2,
            beta: Vec2::ZERO,
            c: m0 * (1.0 / s0),
        }
    }
}

/// Whether a piece is at the slip limit, `u = kappa s e` (`c = 0`, `|beta| = kappa`, as
/// `slip_piece` leaves it). `c = 0` alone does not say so: springs that have just entered the
/// contact also have `c = 0`, with any `|beta| < kappa`, and setting them onto the limit would
/// give them energy that no work paid for.
#[inline]
fn at_limit(p: &Piece, kappa: f64) -> bool {
    p.c == Vec2::ZERO && p.beta.length_squared() >= kappa * kappa * (1.0 - 1e-9)
}

/// Whether two pieces hold the same field to rounding (so they can be one).
#[inline]
fn same_form(p: &Piece, q: &Piece, a2: f64) -> bool {
    const TOL2: f64 = 1e-24; // (1e-12)^2, compared on squares to save square roots
    let scale2 = p.c.length_squared().max(q.c.length_squared())
        + a2 * a2 * p.beta.length_squared().max(q.beta.length_squared());
    (p.c - q.c).length_squared() <= TOL2 * scale2
        && a2 * a2 * (p.beta - q.beta).length_squared() <= TOL2 * scale2
}

/// Number of `f64` in the flat form of a [`MindlinState`] ([`MindlinState::to_array`]): the
/// contact radius, the piece count, the force (2) and `MAX_PIECES + 1` pieces of 5 numbers.
pub const MINDLIN_FLAT_LEN: usize = 4 + 5 * (MAX_PIECES + 1);

impl MindlinState {
    /// The state as a flat array of `f64` (for hosts that pass contact history through a C
    /// ABI, e.g. a LAMMPS pair style): `[a, n, q.x, q.y, (x_hi, beta.x, beta.y, c.x, c.y) x 9]`.
    pub fn to_array(&self) -> [f64; MINDLIN_FLAT_LEN] {
        let mut out = [0.0; MINDLIN_FLAT_LEN];
        out[0] = self.a;
        out[1] = self.n as f64;
        out[2] = self.q.x;
        out[3] = self.q.y;
        for (i, p) in self.pieces.iter().enumerate() {
            let o = 4 + 5 * i;
            out[o..o + 5].copy_from_slice(&[p.x_hi, p.beta.x, p.beta.y, p.c.x, p.c.y]);
        }
        out
    }

    /// The inverse of [`MindlinState::to_array`]. A non-finite entry, a negative radius or a
    /// piece count that is not an integer in `[0, MAX_PIECES]` is an error.
    pub fn from_array(v: &[f64; MINDLIN_FLAT_LEN]) -> Result<Self, crate::LawError> {
        if let Some(&bad) = v.iter().find(|x| !x.is_finite()) {
            return Err(crate::LawError::OutOfRange {
                name: "Mindlin history entry",
                value: bad,
                range: "finite",
            });
        }
        let n = v[1];
        if !(n >= 0.0 && n <= MAX_PIECES as f64 && n.fract() == 0.0) || v[0] < 0.0 {
            return Err(crate::LawError::OutOfRange {
                name: "Mindlin history piece count",
                value: n,
                range: "an integer in [0, 8] with a >= 0",
            });
        }
        let mut pieces = [Piece::default(); MAX_PIECES + 1];
        for (i, p) in pieces.iter_mut().enumerate() {
            let o = 4 + 5 * i;
            *p = Piece {
                x_hi: v[o],
                beta: Vec2::new(v[o + 1], v[o + 2]),
                c: Vec2::new(v[o + 3], v[o + 4]),
            };
        }
        Ok(Self {
            a: v[0],
            n: n as usize,
            pieces,
            q: Vec2::new(v[2], v[3]),
        })
    }
}
