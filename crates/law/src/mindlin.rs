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
//! Pieces are merged when equal, and coalesced when both at the slip limit in nearly the same
//! direction (see "Coalescing"); a contact keeps at most [`MAX_PIECES`] (see `Merge`: two pieces
//! at the slip limit become one along their summed force, or else the narrowest pair whose
//! least-squares fit — or, when the fit's slope exceeds the limit's, the fit with its slope cut
//! to the limit's and the same force — stays within the limit and adds no energy becomes that
//! fit, or as a last resort an inner piece
//! is absorbed into its outer neighbour extended inwards; all keep `|u| <= L`, and any energy the
//! simplification removes is booked as dissipation, any it adds as `truncation_energy`).
//!
//! # Coalescing
//! Two neighbouring pieces that an update leaves at the slip limit, `u = kappa s e1` on annulus
//! 1 and `u = kappa s e2` on annulus 2 (springs that slipped in this step; `c = 0`), whose
//! directions differ by an angle `theta <= theta_tol` (`COALESCE` of [`MindlinMemory`], in
//! microradians; [`COALESCE_URAD`] = 0.3 rad for [`MindlinState`]) are made one piece at the
//! limit at once, `u = kappa s e` with `e` the direction of their summed force
//! `F1 + F2 = 8 G* kappa (w1 e1 + w2 e2)`, `w_i = integral_i s dx`. This is the capacity rule
//! the merge has always preferred (two annuli at the limit become one along their summed force),
//! applied eagerly, so that the memory stays below its capacity and later updates visit fewer
//! pieces (on creep-dem's 4,096 packing 6.0 instead of 7.3 pieces, 2.6 instead of 3.2 slipping
//! per update). What it changes, exactly:
//! - every spring stays at the limit, `|u| = kappa s`: Coulomb's bound holds and the stored
//!   energy `4 G* kappa^2 integral s^2 dx` is unchanged (no energy is added or booked; no work
//!   is done, since no displacement is imposed);
//! - the force keeps its direction and grows by
//!   `8 G* kappa ((w1 + w2) - |w1 e1 + w2 e2|) <= (1 - cos(theta / 2)) (|F1| + |F2|)`
//!   (from `|w1 e1 + w2 e2|^2 - (w1 + w2)^2 cos^2(theta / 2)
//!   = (1 - cos theta) (w1 - w2)^2 / 2 >= 0`): at most `theta^2 / 8` of the pair's force, 1.1 %
//!   at 0.3 rad; a chain of `k` coalescings in one update moves `Q` by at most
//!   `k (1 - cos(theta / 2)) mu P` (the errors of successive unions add, each at most
//!   `1 - cos(theta / 2)` times the union's force, itself at most `8 G* kappa integral_0^a s dx
//!   = mu P`);
//! - each spring's displacement turns by the angle between `e` and its own `e_i`, at most
//!   `theta`: it moves by at most `2 sin(theta / 2) kappa s <= theta kappa s`, i.e. by `theta`
//!   relative (the springs' later slip then starts from the common direction, as the springs of
//!   one slipping piece always do; see "The algorithm").
//!
//! On collinear paths all slipping springs share one direction, so coalescing changes nothing
//! (the Mindlin & Deresiewicz 1953 closed forms hold to rounding, as do the varying-`P` rules
//! of Popov & Heß 2015, ch. 5); it acts only where the path turns. `MindlinUncoalesced`
//! (`COALESCE = 0`) is the memory without it, bit for bit the memory before; the test
//! `coalescing_keeps_its_bound_against_the_uncoalesced_memory` checks the bound above on 2-D
//! paths, one update from the same state.
//!
//! # Energy under varying `P`
//! The balance `work = stored + slip_dissipation - truncation_energy` holds with the work
//! `sum Q_mid . du` to within the step size (first order; second order where no spring changes
//! between sticking and slipping), for any `mu` including `+inf`. Within a step `a^2` is taken
//! linear in time, like the displacement, and three rules follow from it. Springs entering the
//! contact always get a piece of their own, `u = (a^2 - x^2) du / d(a^2)` (when the memory is
//! full, the spare slot holds it until the merge makes room; extending the outermost piece
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

use crate::hertz;
use crate::material::PairMaterial;
use crate::pair::finite;
use crate::vector::Vec2;

/// The most pieces (annuli of distinct load history) one contact remembers: the capacity of
/// [`MindlinState`] and the largest capacity of a [`MindlinMemory`] (whose storage, and so
/// the flat layout, always has `MAX_PIECES + 1` slots).
pub const MAX_PIECES: usize = 8;

/// Largest displacement increment one update accepts \[m\]; longer ones are shortened to it (a
/// guard that keeps every output finite for any finite input, e.g. with `mu = +inf`).
pub const MAX_INCREMENT: f64 = 1e100;

/// Relative width (of the contact radius) below which a stick-slip cut is snapped to the end of
/// its piece (see `update_with_radius`).
const SLIVER: f64 = 1e-12;

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

/// [`int_s`] from the width `h = x2 - x1` and the depths `d1`, `d2` at the ends (shared by
/// neighbouring pieces): `h ((d1 + d2) / 2 + h^2 / 6)`, exact for the quadratic `s` (from
/// `a^2 - (x1^2 + x1 x2 + x2^2)/3` with `a^2 - x1 x2 = (d1 + d2)/2 + h^2/2`); every term is
/// positive, so thin annuli at the edge lose no digits either.
#[inline(always)]
fn int_s_ends(h: f64, d1: f64, d2: f64) -> f64 {
    h * (0.5 * (d1 + d2) + h * h * (1.0 / 6.0))
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
    /// Energy the springs gained when the memory was over its capacity and had to be
    /// simplified by the last-resort rule \[J\] (>= 0; zero in all but rare, long 2-D histories).
    /// The energy balance is `work = stored + slip_dissipation - truncation_energy`.
    pub truncation_energy: f64,
}

/// The angle within which two neighbouring annuli at the slip limit are coalesced into one as
/// soon as an update leaves them so, in microradians (`COALESCE` of [`MindlinMemory`]; see the
/// module docs, "Coalescing", for the error bound): 0.3 rad.
pub const COALESCE_URAD: u32 = 300_000;

/// Load-history state of one contact's Cattaneo-Mindlin tangential law, remembering at most
/// [`MAX_PIECES`] pieces and coalescing neighbours at the limit within [`COALESCE_URAD`]: the
/// memory every host uses.
pub type MindlinState = MindlinMemory<MAX_PIECES, COALESCE_URAD>;

/// [`MindlinState`] without eager coalescing (`COALESCE = 0`): neighbours at the slip limit
/// become one only when the memory is over its capacity (the memory before issue #15's
/// `coalesce` branch, bit for bit; the reference the coalesced memory is tested against).
pub type MindlinUncoalesced = MindlinMemory<MAX_PIECES, 0>;

/// Load-history state of one contact's Cattaneo-Mindlin tangential law, remembering at most `N`
/// pieces (`1 <= N <= MAX_PIECES`, checked at compile time): a smaller memory merges sooner
/// (see `Merge`), trading accuracy of long 2-D histories for speed. Two neighbouring pieces
/// that an update leaves at the slip limit in directions at most `COALESCE` microradians apart
/// are made one at once (module docs, "Coalescing"; 0: only when over the capacity). The
/// storage is the same for every `N` and `COALESCE` (`MAX_PIECES + 1` slots, the flat layout
/// of [`MindlinState::to_array`]). `Default` is a virgin, open contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MindlinMemory<const N: usize, const COALESCE: u32 = COALESCE_URAD> {
    /// Contact radius of the last update \[m\].
    a: f64,
    /// Number of pieces in use.
    n: usize,
    /// The pieces, inner to outer. Between updates `n <= N`; the spare slot holds the
    /// springs that enter the contact during an update until the merge has made room for them.
    pieces: [Piece; MAX_PIECES + 1],
    /// Tangential force after the last update \[N\].
    q: Vec2,
}

impl<const N: usize, const COALESCE: u32> MindlinMemory<N, COALESCE> {
    /// `1 <= N <= MAX_PIECES`, evaluated where a memory is created or updated.
    const CAPACITY_OK: () = assert!(N >= 1 && N <= MAX_PIECES, "capacity out of range");

    /// `|e1 - e2|^2 = 2 (1 - cos theta)` of two unit vectors `COALESCE` microradians apart
    /// (4 from `pi` on): the coalescing test's bound on the squared chord (0: none).
    const CHORD2: f64 = chord2(COALESCE);

    /// A virgin, open contact (no force, no memory).
    pub fn new() -> Self {
        let () = Self::CAPACITY_OK;
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
    ///
    /// Always inlined, so that a host's loop compiled for a wider instruction set (creep-dem's
    /// AVX2 copy of the force loops) compiles the update for it too (the same bits).
    #[inline(always)]
    pub fn update_with_radius(&mut self, pair: &PairMaterial, a: f64, du: Vec2) -> MindlinStep {
        let () = Self::CAPACITY_OK;
        let a = if finite(a) && a > 0.0 { a } else { 0.0 };
        let du = if !(finite(du.x) && finite(du.y)) {
            Vec2::ZERO
        } else if du.length_squared() > MAX_INCREMENT * MAX_INCREMENT {
            // `|du| > MAX_INCREMENT` without the square root (the two differ only within an
            // ulp of 1e100 m; an overflowing square is +inf, also > 1e200).
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
        //     (A pass of its own: folded into the cuts' pass below, the step ran 9 % slower.)
        let da2 = a2 - a2_old;
        let n_old = self.n;
        #[allow(clippy::needless_range_loop)]
        for i in 0..n_old {
            let p = &mut self.pieces[i];
            p.c += du - p.beta * da2;
        }
        // Springs entering during the step: the one at x entered when a(t)^2 = x^2 and, with the
        // displacement linear in a^2 over the step, took du (a^2 - x^2) / da2, i.e. beta = du / da2.
        // They always get a piece of their own (the spare slot when the memory is full; the merge
        // then makes room): giving them the outermost piece's field extended outwards instead
        // would let them enter with that piece's `c` (after a small `da2`, `c = du - beta da2`
        // with a huge `beta`), energy that no work paid for.
        if da2 > 0.0 {
            self.pieces[n_old] = Piece {
                x_hi: a,
                beta: du * (1.0 / da2),
                c: Vec2::ZERO,
            };
            self.n += 1;
        }

        // (iii)-(iv) Return-map every piece: it splits into a stuck inner part and a slipping
        // outer part. First the cuts, then one pass that writes the parts, inner to outer, and
        // merges them as they come ([`Merge`]).
        let mut cuts = [0.0f64; MAX_PIECES + 1];
        let mut splits = 0;
        let mut x_lo = 0.0;
        let k2 = kappa * kappa;
        let mut split_bits: u32 = 0;
        // The depth at the inner end of the piece: the last piece's outer one (`a^2` at 0).
        let mut s_lo = a2;
        let m_in = self.n;
        let mut stuck_bits: u32 = 0;
        // An index loop: the iterator forms (`zip` with the cuts, or `enumerate`) compiled
        // into a loop that ran the step 2-3 % slower on the peers' packing.
        #[allow(clippy::needless_range_loop)]
        for i in 0..m_in {
            let p = &self.pieces[i];
            // The pieces are non-empty and increasing (`x_lo < p.x_hi`): an update keeps
            // them so and `from_array` refuses other states.
            let hi = p.x_hi;
            let s_hi = depth(a, hi);
            let mut cut = stick_cut(p, kappa, k2, a2, (x_lo, hi), (s_lo, s_hi));
            if cut < hi {
                // A cut within rounding of an end of the piece is at that end: a sliver of
                // springs split off by rounding would take a slot of the memory (and change
                // which pieces the merge joins later) for a field it cannot resolve.
                if hi - cut <= SLIVER * a {
                    cut = hi;
                } else if cut - x_lo <= SLIVER * a {
                    cut = x_lo;
                }
                if cut > x_lo && cut < hi {
                    splits += 1;
                    split_bits |= 1 << i;
                }
            }
            // The leading wholly stuck pieces (other than the springs entering now) are
            // already the merged list's first pieces: [`Merge`] keeps an untouched piece after
            // an untouched one as it is, in its slot (no split before it), so the merge starts
            // after them.
            stuck_bits |= ((cut == hi) as u32) << i;
            cuts[i] = cut;
            x_lo = hi;
            s_lo = s_hi;
        }
        // The slip is booked at the force the springs had while they slipped (see `Onset`).
        let g_star = pair.g_star;
        let k = ((!stuck_bits).trailing_zeros() as usize).min(n_old);
        let k_lo = if k > 0 { self.pieces[k - 1].x_hi } else { 0.0 };
        let (n, d_u2) = if m_in + splits <= MAX_PIECES + 1 {
            // The parts fit in the storage: first move every piece to the slot of its first
            // part (from the outermost, so nothing unread is overwritten; a split piece's
            // slipping part takes the next slot), then write and merge in place (the merged
            // list never runs ahead of the pieces still to read).
            let mut off = splits;
            let mut i = m_in;
            while off > 0 {
                i -= 1;
                off -= (split_bits >> i & 1) as usize;
                self.pieces[i + off] = self.pieces[i];
            }
            let mut st = Merge::after(a, kappa, a2, k, k_lo);
            let mut pos = k;
            #[allow(clippy::needless_range_loop)]
            for i in k..m_in {
                let cut = cuts[i];
                let p = self.pieces[pos];
                let entering = i == n_old;
                pos += split_bits as usize >> i & 1;
                pos += 1;
                st.piece::<COALESCE>(
                    &mut self.pieces,
                    &p,
                    cut,
                    entering,
                    (a_old, da2, g_star),
                    &mut dissipated,
                );
            }
            merge_capacity::<N>(&mut self.pieces, st.n, a, kappa)
        } else {
            // Into a scratch list (a full memory with a split piece).
            let mut out = [Piece::default(); 2 * (MAX_PIECES + 1)];
            out[..k].copy_from_slice(&self.pieces[..k]);
            let mut st = Merge::after(a, kappa, a2, k, k_lo);
            #[allow(clippy::needless_range_loop)]
            for i in k..m_in {
                let cut = cuts[i];
                let p = self.pieces[i];
                st.piece::<COALESCE>(
                    &mut out,
                    &p,
                    cut,
                    i == n_old,
                    (a_old, da2, g_star),
                    &mut dissipated,
                );
            }
            let (n, d_u2) = merge_capacity::<N>(&mut out, st.n, a, kappa);
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

    /// `Q = 8 G* sum_pieces integral u(x) dx` (each boundary's depth evaluated once).
    #[inline(always)]
    fn integrate_force(&self, pair: &PairMaterial) -> Vec2 {
        let a = self.a;
        let mut x_lo = 0.0;
        let mut d_lo = a * a;
        let mut sum = Vec2::ZERO;
        #[allow(clippy::needless_range_loop)]
        for i in 0..self.n {
            let p = &self.pieces[i];
            let h = p.x_hi - x_lo;
            let d_hi = depth(a, p.x_hi);
            sum += p.c * h + p.beta * int_s_ends(h, d_lo, d_hi);
            (x_lo, d_lo) = (p.x_hi, d_hi);
        }
        sum * (8.0 * pair.g_star)
    }
}

/// Puts the springs of the trial piece `p` outside `cut` onto the slip limit (the piece's
/// slipping part, `u = kappa s e`) and adds its slip work to `dissipated` \[J\]; the slip is
/// booked at the force the springs had while they slipped (see [`Onset`]): contact radius `a`
/// \[m\] (`a_old` before the step), `da2 = a^2 - a_old^2` [m^2], shear modulus `g_star` \[Pa\].
/// Also returns `integral s dx` over the slipping part (`int_s(a, cut, p.x_hi)`, for
/// [`Merge::push`]). Always inlined into its uses in the update.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn slip_to_limit(
    p: &Piece,
    cut: f64,
    kappa: f64,
    a: f64,
    a_old: f64,
    da2: f64,
    g_star: f64,
    dissipated: &mut f64,
) -> (Piece, f64) {
    let onset = if da2 == 0.0 {
        Onset::Constant
    } else if p.x_hi > a_old {
        Onset::Entering
    } else {
        Onset::Shifted(da2)
    };
    let (e, work, is) = slip_piece(p, kappa, a, cut, p.x_hi, onset);
    *dissipated += 8.0 * g_star * work;
    let q = Piece {
        x_hi: p.x_hi,
        beta: e * kappa,
        c: Vec2::ZERO,
    };
    (q, is)
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

/// The radius `cut` in `[x_lo, hi]` that divides the stuck springs (`x <= cut`) of a trial piece
/// on `x_lo < x <= hi` from its slipping ones: the same cut as [`stick_radius`] clamped to the
/// piece, found with fewer square roots and divisions. For `|beta| <= kappa` the springs stick
/// where `q(s) = kappa^2 s^2 - |s beta + c|^2 >= 0`, and `q` has one root `s* >= 0` at most
/// (its roots' product `-|c|^2 / (kappa^2 - |beta|^2)` is not positive), so the stuck set is
/// `s >= s*` (Mindlin 1949: slip spreads inwards from the edge): the sign of `q` at the piece's
/// outer end (depth `s_hi`) and inner end (`s_lo`) settles the common cases (wholly stuck,
/// wholly slipping) exactly; only a piece that changes inside needs the root, the rationalised
/// `s* = |c|^2 / (sqrt(D) - beta.c)`, `D = (beta.c)^2 + (kappa^2 - |beta|^2) |c|^2`, and its
/// square root `x = sqrt(a^2 - s*)`. Springs entering the contact can bring `|beta| > kappa`,
/// and huge or non-finite values may overflow the squares: those go to [`stick_radius`].
/// `s_lo`, `s_hi` are the depths at `x_lo` and `hi` ([`depth`], shared by neighbours).
#[inline(always)]
fn stick_cut(
    p: &Piece,
    kappa: f64,
    k2: f64,
    a2: f64,
    (x_lo, hi): (f64, f64),
    (s_lo, s_hi): (f64, f64),
) -> f64 {
    let b2 = p.beta.length_squared();
    // Pieces at the limit have `|beta| = kappa` to rounding (`e kappa` with `|e| = 1 +- eps`).
    if b2 <= k2 * (1.0 + 1e-12) && k2 < f64::INFINITY {
        let u_hi = p.beta * s_hi + p.c;
        let q_hi = k2 * (s_hi * s_hi) - u_hi.length_squared();
        if q_hi >= 0.0 {
            return hi;
        }
        let u_lo = p.beta * s_lo + p.c;
        let q_lo = k2 * (s_lo * s_lo) - u_lo.length_squared();
        if q_lo < 0.0 && q_lo > f64::NEG_INFINITY {
            return x_lo;
        }
        let (c2, bc) = (p.c.length_squared(), p.beta.dot(p.c));
        let d = bc * bc + (k2 - b2).max(0.0) * c2;
        let den = d.sqrt() - bc;
        let s_star = c2 / den;
        if finite(q_hi) && finite(q_lo) && finite(s_star) && den > 0.0 {
            let r2 = a2 - s_star;
            return if r2 > 0.0 {
                r2.sqrt().clamp(x_lo, hi)
            } else {
                x_lo
            };
        }
    }
    stick_radius(p, kappa, a2).clamp(x_lo, hi)
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
#[inline(always)]
fn slip_piece(p: &Piece, kappa: f64, a: f64, x1: f64, x2: f64, onset: Onset) -> (Vec2, f64, f64) {
    let is = int_s(a, x1, x2);
    let is2 = int_s2(a, x1, x2);
    let trial = p.beta * is + p.c * (x2 - x1);
    let l = trial.length();
    let e = if l > 0.0 && finite(l) {
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
    (e, if work > 0.0 { work } else { 0.0 }, is)
}

/// `integral (F_on + kappa s) / 2 (b0 + (b1 - kappa) s) dx` [m^3] over `x1 < x <= x2` for
/// [`Onset::Shifted`]: `F_on = min(kappa (s - da2), b0 + b1 s)`, where `b0 + b1 s` is the trial
/// displacement along the slip direction; `is`, `is2` are `int_s`, `int_s2` over the annulus.
/// Inlined: in a DEM step the normal force changes every step, so this is the common case.
#[inline(always)]
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
    // The slip work over `y1 < x <= y2` (`js`, `js2`: int_s, int_s2 there).
    let part = |y1: f64, y2: f64, js: f64, js2: f64| {
        let sm = depth(a, 0.5 * (y1 + y2));
        let (m0, m1) = if kappa * (sm - da2) <= b0 + b1 * sm {
            (-kappa * da2, kappa)
        } else {
            (b0, b1)
        };
        // (F_on + kappa s) / 2 = g0 + g1 s; slip = h0 + h1 s.
        let (g0, g1) = (0.5 * m0, 0.5 * (m1 + kappa));
        let (h0, h1) = (b0, b1 - kappa);
        g0 * h0 * (y2 - y1) + (g0 * h1 + g1 * h0) * js + g1 * h1 * js2
    };
    let mut w = 0.0;
    if split > x1 && split < x2 {
        w += part(x1, split, int_s(a, x1, split), int_s2(a, x1, split));
        w += part(split, x2, int_s(a, split, x2), int_s2(a, split, x2));
    } else if x2 > x1 {
        // No crossing inside (`split` at an end): the whole annulus, whose integrals are known.
        w += part(x1, x2, is, is2);
    }
    w
}

/// The merge of an update's return-mapped pieces, written one part at a time into a list
/// (`out[..n]`, inner to outer) and merged as they come: equal neighbours are joined, and
/// neighbours at the slip limit whose directions differ by at most `COALESCE` microradians
/// are coalesced (see [`coalescible`]; 0: none); then [`merge_capacity`] enforces the capacity
/// `N`. `x_lo` is the outer radius of the last part, `prev_touched` whether the last kept
/// piece changed other than by the common `du` (two untouched neighbours were already distinct
/// after the last update and both moved by the same `du`, so only pairs with a touched piece
/// are compared).
///
/// Over the capacity, two neighbours are made one: preferably two pieces both at the slip
/// limit (`u = kappa s e1`, `kappa s e2`), which become one at the limit along their summed
/// force (the stored energy is unchanged and `|u| <= kappa s` still holds); otherwise the
/// narrowest pair whose least-squares merge stays within the limit (force kept, energy lost
/// booked as dissipation), the merge's slope cut to `kappa` with the force kept where the
/// fit's slope is over it (taken only if within the limit and not adding energy); as a last
/// resort the inner piece whose absorption by its outer neighbour (extended inwards) adds the
/// least energy.
struct Merge {
    a: f64,
    kappa: f64,
    a2: f64,
    n: usize,
    x_lo: f64,
    prev_touched: bool,
    /// `integral s dx` over the last piece's annulus where known (see [`Merge::push`]).
    last_is: Option<f64>,
}

impl Merge {
    #[inline(always)]
    fn new(a: f64, kappa: f64, a2: f64) -> Self {
        Self {
            a,
            kappa,
            a2,
            n: 0,
            x_lo: 0.0,
            prev_touched: false,
            last_is: None,
        }
    }

    /// A merge whose list already holds `n` untouched pieces, the last one ending at `x_lo`.
    #[inline(always)]
    fn after(a: f64, kappa: f64, a2: f64, n: usize, x_lo: f64) -> Self {
        Self {
            n,
            x_lo,
            ..Self::new(a, kappa, a2)
        }
    }

    /// The parts of the trial piece `p` (inner radius the last piece's outer one) cut at
    /// `cut`: the stuck part `x <= cut` as it is, the slipping part onto the limit
    /// ([`slip_to_limit`], its work added to `dissipated`); `entering`: the piece of springs
    /// that entered in this step (changed other than by the common `du`, as every slipping
    /// part); `(a_old, da2, g_star)` as for [`slip_to_limit`].
    #[inline(always)]
    fn piece<const COALESCE: u32>(
        &mut self,
        out: &mut [Piece],
        p: &Piece,
        cut: f64,
        entering: bool,
        (a_old, da2, g_star): (f64, f64, f64),
        dissipated: &mut f64,
    ) {
        let x_lo = self.x_lo;
        if cut > x_lo {
            self.push::<COALESCE>(out, Piece { x_hi: cut, ..*p }, entering, None);
        }
        if cut < p.x_hi {
            let (a, kappa) = (self.a, self.kappa);
            let (q, is) = slip_to_limit(p, cut, kappa, a, a_old, da2, g_star, dissipated);
            self.push::<COALESCE>(out, q, true, Some(is));
        }
        self.x_lo = p.x_hi;
    }

    /// Appends the part `p` (`t`: touched) to `out[..n]`, joined with the last piece where
    /// they are equal or coalescible. `is`: `integral s dx` over `p`'s annulus (from the end
    /// of `out[..n]` to `p.x_hi`) where already known (a slipping part's, from
    /// [`slip_to_limit`]): kept with the piece while it stands alone, so that a coalescing
    /// does not evaluate it again (the same function of the same radii: the same bits).
    #[inline(always)]
    fn push<const COALESCE: u32>(&mut self, out: &mut [Piece], p: Piece, t: bool, is: Option<f64>) {
        let chord2 = MindlinMemory::<MAX_PIECES, COALESCE>::CHORD2;
        let n = self.n;
        if n > 0 && (t || self.prev_touched) && same_form(&out[n - 1], &p, self.a2) {
            out[n - 1].x_hi = p.x_hi;
            self.prev_touched = true;
            self.last_is = None;
        } else if chord2 > 0.0
            && n > 0
            && (t || self.prev_touched)
            && coalescible(&out[n - 1], &p, self.kappa, chord2)
        {
            // Two neighbours at the limit in nearly the same direction: one along their summed
            // force (module docs, "Coalescing": energy and `|u| <= kappa s` kept, the force
            // changed by at most `1 - cos(theta / 2)` of theirs).
            let last = &out[n - 1];
            let i_last = match self.last_is {
                Some(v) => v,
                None => int_s(
                    self.a,
                    if n >= 2 { out[n - 2].x_hi } else { 0.0 },
                    last.x_hi,
                ),
            };
            let i_p = match is {
                Some(v) => v,
                None => int_s(self.a, last.x_hi, p.x_hi),
            };
            out[n - 1] = limit_union_of(last, &p, (i_last, i_p), self.kappa);
            self.prev_touched = true;
            self.last_is = None;
        } else {
            out[n] = p;
            self.n = n + 1;
            self.prev_touched = t;
            self.last_is = is;
        }
    }
}

/// The merge's capacity rule on a merged list of `n` pieces: [`enforce_capacity`] where
/// `n > N`; returns the number of pieces kept and the change of `integral |u|^2 dx` [m^3].
#[inline(always)]
fn merge_capacity<const N: usize>(out: &mut [Piece], n: usize, a: f64, kappa: f64) -> (usize, f64) {
    if n > N {
        enforce_capacity::<N>(out, n, a, kappa)
    } else {
        (n, 0.0)
    }
}

/// The capacity rule of the merge for `n > N` pieces (see [`Merge`]): returns the number kept
/// and the change of `integral |u|^2 dx` [m^3] it caused (<= 0 means energy was lost, which
/// the caller books as dissipation). Out of line: most updates do not need it.
#[inline(never)]
fn enforce_capacity<const N: usize>(
    out: &mut [Piece],
    mut n: usize,
    a: f64,
    kappa: f64,
) -> (usize, f64) {
    let a2 = a * a;
    let mut d_u2 = 0.0;
    while n > N {
        // The adjacent pair of limit pieces with the closest directions, if any.
        let mut best_pair = None;
        let mut best_cos = f64::NEG_INFINITY;
        let mut lim_p = at_limit(&out[0], kappa);
        for i in 0..n - 1 {
            let (p, q) = (&out[i], &out[i + 1]);
            let lim_q = at_limit(q, kappa);
            let both = lim_p && lim_q;
            lim_p = lim_q;
            if both {
                let cos = p.beta.dot(q.beta);
                if cos > best_cos {
                    best_cos = cos;
                    best_pair = Some(i);
                }
            }
        }
        if let Some(i) = best_pair {
            let lo = if i == 0 { 0.0 } else { out[i - 1].x_hi };
            out[i] = limit_union(&out[i], &out[i + 1], a, kappa, lo);
            remove_at(out, i + 1, n);
            n -= 1;
            continue;
        }
        // Otherwise the least-squares merge (force-preserving, energy-non-increasing) of the
        // narrowest neighbour pair whose merged field stays within the limit.
        // The pairs are tried narrowest first (ties: inner first), each found by a scan of the
        // widths: the first try nearly always succeeds, so sorting them all costs more.
        let mut width = [0.0f64; 2 * (MAX_PIECES + 1)];
        let mut lo = 0.0;
        for i in 0..n - 1 {
            width[i] = out[i + 1].x_hi - lo;
            lo = out[i].x_hi;
        }
        let mut merged = false;
        let mut tried: u32 = 0;
        for _ in 0..n - 1 {
            let mut i = usize::MAX;
            for j in 0..n - 1 {
                if tried >> j & 1 == 0 && (i == usize::MAX || width[j].total_cmp(&width[i]).is_lt())
                {
                    i = j;
                }
            }
            tried |= 1 << i;
            let lo = if i == 0 { 0.0 } else { out[i - 1].x_hi };
            let (p, q) = (out[i], out[i + 1]);
            // The integrals over the two annuli, shared by their energies and their fit.
            let ints = PairIntegrals::new(a, lo, p.x_hi, q.x_hi);
            let old = ints.piece_u2_p(&p) + ints.piece_u2_q(&q);
            let mut fit = least_squares_piece(&p, &q, &ints);
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
                remove_at(out, i + 1, n);
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
        remove_at(out, best, n);
        n -= 1;
        if best > 0 && same_form(&out[best - 1], &out[best], a2) {
            out[best - 1].x_hi = out[best].x_hi;
            remove_at(out, best, n);
            n -= 1;
        }
    }
    (n, d_u2)
}

/// Removes `out[k]` from the first `n` pieces (shifting the rest down by one): a plain loop,
/// since `copy_within` calls `memmove` for these few 40-byte pieces.
#[inline(always)]
fn remove_at(out: &mut [Piece], k: usize, n: usize) {
    for j in k..n - 1 {
        out[j] = out[j + 1];
    }
}

/// The integrals over two neighbouring annuli `lo < x <= x1` and `x1 < x <= x2` that the
/// capacity rule's least-squares merge needs for the pair's energy ([`piece_u2`]) and its fit
/// ([`least_squares_piece`]): each evaluated once, by the same functions of the same radii
/// (so the same bits as evaluating them where used).
struct PairIntegrals {
    lo: f64,
    x1: f64,
    x2: f64,
    /// `int_s` over the inner and the outer annulus.
    s1: (f64, f64),
    /// `int_s2` over the inner and the outer annulus.
    s2: (f64, f64),
}

impl PairIntegrals {
    #[inline]
    fn new(a: f64, lo: f64, x1: f64, x2: f64) -> Self {
        Self {
            lo,
            x1,
            x2,
            s1: (int_s(a, lo, x1), int_s(a, x1, x2)),
            s2: (int_s2(a, lo, x1), int_s2(a, x1, x2)),
        }
    }

    /// [`piece_u2`] of `p` over the inner annulus.
    #[inline]
    fn piece_u2_p(&self, p: &Piece) -> f64 {
        piece_u2_of(p, self.lo, self.x1, self.s1.0, self.s2.0)
    }

    /// [`piece_u2`] of `q` over the outer annulus.
    #[inline]
    fn piece_u2_q(&self, q: &Piece) -> f64 {
        piece_u2_of(q, self.x1, self.x2, self.s1.1, self.s2.1)
    }
}

/// [`piece_u2`] with `int_s`, `int_s2` over the annulus given (`is`, `is2`).
#[inline]
fn piece_u2_of(p: &Piece, x1: f64, x2: f64, is: f64, is2: f64) -> f64 {
    if x2 <= x1 {
        return 0.0;
    }
    let mut w = p.c.length_squared() * (x2 - x1);
    if p.beta != Vec2::ZERO {
        w += p.beta.length_squared() * is2 + 2.0 * p.beta.dot(p.c) * is;
    }
    w
}

/// The piece `s beta + c` on `lo < x <= q.x_hi` closest in `L2` to the two pieces `p`, `q`
/// (normal equations in the basis `{s, 1}`): it keeps `integral u dx` (the force) and
/// `integral s u dx`, and its `integral |u|^2 dx` is never larger (orthogonal projection).
fn least_squares_piece(p: &Piece, q: &Piece, ints: &PairIntegrals) -> Piece {
    let (lo, x1, x2) = (ints.lo, ints.x1, ints.x2);
    let (l1, l2) = (x1 - lo, x2 - x1);
    let (s1a, s1b) = ints.s1;
    let (s2a, s2b) = ints.s2;
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

/// Two neighbouring pieces at the slip limit, `p` on `lo < x <= p.x_hi` and `q` on
/// `p.x_hi < x <= q.x_hi`, made one at the limit along their summed force: `u = kappa s e`
/// with `e` the direction of `p.beta int_p s dx + q.beta int_q s dx` (the stored energy and
/// `|u| = kappa s` are unchanged; module docs, "Coalescing").
#[inline]
fn limit_union(p: &Piece, q: &Piece, a: f64, kappa: f64, lo: f64) -> Piece {
    limit_union_of(
        p,
        q,
        (int_s(a, lo, p.x_hi), int_s(a, p.x_hi, q.x_hi)),
        kappa,
    )
}

/// [`limit_union`] with `integral s dx` over the two annuli given, `(int_p, int_q)`.
#[inline]
fn limit_union_of(p: &Piece, q: &Piece, (int_p, int_q): (f64, f64), kappa: f64) -> Piece {
    let sum = p.beta * int_p + q.beta * int_q;
    let l = sum.length();
    let e = if l > 0.0 && finite(l) {
        sum * (1.0 / l)
    } else {
        Vec2::new(1.0, 0.0)
    };
    Piece {
        x_hi: q.x_hi,
        beta: e * kappa,
        c: Vec2::ZERO,
    }
}

/// Whether two neighbours are both at the slip limit ([`at_limit`]) with directions whose
/// squared chord `|e1 - e2|^2 = 2 (1 - cos theta)` is at most `chord2` (measured on
/// `|beta1 - beta2|^2 <= chord2 kappa^2`: `|beta| = kappa` to rounding at the limit).
#[inline]
fn coalescible(p: &Piece, q: &Piece, kappa: f64, chord2: f64) -> bool {
    p.c == Vec2::ZERO
        && q.c == Vec2::ZERO
        && (p.beta - q.beta).length_squared() <= chord2 * (kappa * kappa)
        && at_limit(p, kappa)
        && at_limit(q, kappa)
}

/// `2 (1 - cos theta)` for `theta = urad` microradians, by its Taylor series
/// `theta^2 - theta^4 / 12 + theta^6 / 360 - ...` (which, unlike `2 - 2 cos theta`, keeps its
/// digits at small angles; converged to rounding for `theta <= pi` in 30 terms, see the test
/// `coalescing_chord_is_two_minus_two_cos`), and 4 (every direction) from `pi` on. A `const fn`, so that a
/// memory's bound is a compile-time constant.
const fn chord2(urad: u32) -> f64 {
    let theta = urad as f64 * 1e-6;
    if theta >= std::f64::consts::PI {
        return 4.0;
    }
    // 2 (1 - cos theta) = 2 sum_{k >= 1} (-1)^(k+1) theta^(2k) / (2k)!.
    let t2 = theta * theta;
    let mut term = t2 / 2.0;
    let mut sum = 0.0;
    let mut k = 1.0;
    while k < 31.0 {
        sum += term;
        term *= -t2 / ((2.0 * k + 1.0) * (2.0 * k + 2.0));
        k += 1.0;
    }
    2.0 * sum
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

mod flat;
pub use flat::MINDLIN_FLAT_LEN;

#[cfg(test)]
mod reference;
#[cfg(test)]
mod tests;
