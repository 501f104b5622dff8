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
//! # The table (where the boundary elements are computed)
//!
//! Where creep-reference's boundary elements are computed for the contact's `(a/b, nu)`
//! ([`lut::nodes`]; [`Steady3d::tabulated`] says whether a contact is covered), [`Steady3d::loads`]
//! interpolates them ([`lut`]): per node, the loads `(Fx/(mu P), Fy/(mu P), Mz/(mu P c))` of
//! Kalker's exact theory (boundary elements on grids `N/2` and `N`, extrapolated `2 f(N) -
//! f(N/2)`) on the quarter `xi_n, eta_n >= 0` of a grid [`lut::LUT_XI`] x [`lut::LUT_XI`] x
//! [`lut::LUT_PHI`] (`0 ... 2` and `-4 ... 4`; geometric below `0.1`, so that the slope at
//! small creepage is Kalker's linear theory's within about 0.5 %; dense where the loads curve:
//! the onset of full slip, and a lateral creepage against the spin), `f32`. The other signs by
//! the exact symmetries of the theory (quasi-identical bodies, a contact symmetric about the
//! rolling direction): `xi -> -xi` negates `Fx`; `(eta, phi) -> -(eta, phi)` negates `Fy` and
//! `Mz`. Each table is refined once, at its first use, onto a read grid ([`lut::refine`]): along
//! the spin the midpoint of each cell added, the thirds of `|phi_n| = 0.2 ... 0.26`
//! ([`lut::FINE_PHI`]; the cubic through the cell's two computed spins and one on each side),
//! which follows the loads where they bend faster than the computed spins resolve (the pure
//! spin's lateral force of `a > b` peaks between `phi_n = 0.2` and `0.26`); along `xi_n` and `eta_n` points added in the widest cells,
//! `0.86 ... 2`, and in `0.14 ... 0.2` ([`lut::FINE_XI`]; the cubic through the four computed
//! creepages around, the quadratic through the last three in the end cell), where full slip of
//! translation sets in and the loads bend faster than a straight line across the computed cells
//! follows. Within
//! the grid the loads are trilinear in `(xi_n, eta_n, phi_n)`
//! on the read grid (a convex combination of the eight corners: `|F| <= mu P` holds since it
//! holds at every point of the read grid, where the extrapolation's and the cubic's excess is
//! scaled onto it); beyond it see "Beyond the box". Between two
//! computed `nu` of one `a/b` the two tables' loads are blended linearly in `nu` (one cell for
//! both, the tables read at the contact's creepages); between
//! two computed `a/b`, the rows of those two and, beyond each, of the nearest computed `a/b` at
//! least half the interval's width away (three rows in the end intervals) are blended by
//! Lagrange's cubic in `ln(a/b)`, the moment in units of each row's
//! full-slip spin moment `M_max` ([`full_slip::max_moment`]; docs/CREEP3D.md)
//! ([`Coverage::BetweenRatios`], looser bounds). A blend is made once per `(a/b, nu)` into a
//! read table of its own (`lut::baked`, at its first use), so every contact reads one table; a `nu`
//! outside the computed ones is extrapolated ("Beyond the computed nu"). Near zero creepage
//! (`|xi_n| + |eta_n| + |phi_n| <` [`lut::LINEAR_REACH`]) the difference between Kalker's linear
//! theory and the tables' own slopes (the secants of their first cells, a few per cent off
//! Kalker's between computed `nu` or `a/b`) is added, faded out by [`lut::linear_fade`]: the
//! slopes at zero are Kalker's, as the fitted law's are. Elsewhere (an `a/b` below the lowest
//! computed one, `0.2`, or above the highest, `5`) the fitted law below ([`Steady3d::coverage`]
//! says which).
//! The computed nodes are listed by [`lut::nodes`] and in docs/CREEP3D.md. The inverse at zero spin,
//! [`Steady3d::creepages_for_force`], is the fitted law's everywhere.
//!
//! # Beyond the computed nu
//!
//! A `nu` outside the range that the rows serving the contact's `a/b` compute takes the tables at
//! the nearest computed `nu_r` with the creepages scaled by Kalker's coefficients ([`kalker3d`]),
//! `xi_n C11(nu)/C11(nu_r)`, `eta_n C22(nu)/C22(nu_r)`, `phi_n C23(nu)/C23(nu_r)`: the slopes at
//! small creepage are the contact's own, and the onsets of full slip move with them (Kalker's
//! simplified theory makes a pure creepage's curve a function of `C x`; Kalker 1990, sec.
//! 1.5). [`Coverage::ExtrapolatedNu`]; looser bounds (docs/CREEP3D.md, "Beyond the computed
//! nu"). Every computed `a/b` from `0.5` to `5` has `nu = 0` and `0.5`, so a contact there is
//! never extrapolated; a node added without them would be.
//!
//! # Beyond the box
//!
//! Beyond the box `|xi_n|, |eta_n| <= 2`, `|phi_n| <= 4` (the table's, and the fitted law's as
//! well), with `s > 1` the largest of `|xi_n|/2, |eta_n|/2, |phi_n|/4`, the loads are
//! `L = L_fs + (L_edge - L_fs)/s`: `L_edge` the loads where the ray of the creepage leaves the
//! box, `L_fs` the loads of full slip in its direction ([`full_slip`]: the traction `mu p` along
//! the rigid slip everywhere, Kalker 1990, sec. 2.2). A spin keeps a sticking patch around its
//! pole that shrinks as `1/s` (the boundary elements along rays, creep-reference's example
//! `steady3d_far`); a translation is in full slip at the edge already. docs/CREEP3D.md,
//! "Beyond the box", grades it.
//!
//! Regenerate a node with `cargo run --release -p creep-reference --example steady3d_lut --
//! solve AB NU [N]` (resumable; the CSV in `crates/reference/data/steady3d_lut/`) and the data
//! module with `... -- emit` (`steady3d/lut_data.rs`). The accuracy and the coverage:
//! docs/CREEP3D.md ("The table").
//!
//! # The fitted law (where the table does not cover the contact)
//!
//! Linear part: Kalker's theory with the coefficients of [`crate::kalker3d`] (Kalker 1967/1990),
//! `Fx = C11 xi_n`, `Fy = C22 eta_n + C23 phi_n`, `Mz = -C23 eta_n + C33 phi_n` (normalised,
//! project signs); every non-linear ingredient below has slope 1 (or 0) at zero creepage, so
//! the law is Kalker's linear theory exactly at small creepage. `M_max = (3/8) a_M E(e)/c` is
//! the full-slip spin moment of the Hertz pressure about the centre over `mu P c`
//! (`integral mu p r dA`; `a_M` the major semi-axis, `E` the complete elliptic integral of the
//! second kind, [`crate::elliptic::complete_elliptic`]; `3 pi/16` for the circle). With the
//! shape constants of a [`Node`] (`kx, ky, t, ma, mb, p1, q1, q2, p2, q3, lam, ax, ay, gam,
//! b2, b8, am, beta`):
//!
//! 1. spin-moment utilisation: `m = C33 |phi_n|/M_max`,
//!    `s = m (1 + ma m)/(1 + mb m + ma m^2)` (in `[0, 1)` for `ma >= 0`, `mb >= 1`);
//! 2. lateral force of pure spin: `f_s = C23 phi_n (1 + p1 u + p2 u^2)/(1 + q1 u + q2 u^2 +
//!    q3 u^3)`, `u = phi_n^2` (linear at small spin, a peak, then a decay as `1/phi_n`: in full
//!    slip of pure spin the traction field carries no force);
//! 3. translation: the linear force `t = (C11 xi_n, C22 eta_n + lam f_s)/w`, `w = 1 + gam s^2`
//!    (the spin softens the translational response), its utilisation `s_t = S(|t|; k)` with
//!    Kalker-type saturation `S(x; k) = 1 - (1 - v)^2 (1 + (2 - k) v)`, `v = min(x/k, 1)`
//!    (slope 1 at 0, full slip from `x = k` on with `1 - S ~ (k - x)^2`, the behaviour of the
//!    exact theory near full slip, see [`crate::steady_law`]), `k = kx cos^2 + ky sin^2` of the
//!    direction of `t`; the force `s_t d/|d|` with `d = (t_x (1 - b + b C22/C11), t_y)`,
//!    `b = beta s_t^4` in partial slip and `1 - (1 - beta) (k/|t|)^2` in full slip (with `nu > 0`
//!    the force turns from the linear direction `t` towards the creepage direction as the
//!    contact slips, and wholly as the creepage grows in full slip),
//!    times the capacities left by the spin,
//!    `w (1 - ax s^2)` along x and `w (1 - ay s^4)` along y (floored at zero);
//! 4. plus the rest of the spin's lateral force, `(1 - lam) f_s (1 - s_t)^(1/4)`, and the
//!    projection onto `|F| <= 1`;
//! 5. moment: `Mz = M_l (1 - am s^2) + M_max s sign(phi_n) max(0, 1 - b2 e^2 - b8 e^8)` with
//!    `e = S(|t_0|; k)` the utilisation of the translation alone (`t_0 = (C11 xi_n, C22
//!    eta_n)`) and `M_l = -C23 eta_n (1 - e) - nu t e^3 eta_n^3/(xi_n^2 + eta_n^2)^2` the
//!    moment of lateral creepage (the last term the moment the normal-tangential coupling of
//!    the kernel, `nu > 0`, leaves at full lateral slip: zero slope at the origin).
//!
//! The constants are fitted per node of the boundary-element table of crate creep-reference
//! (module `steady3d`: rows `a/b = 0.2, 0.5, 1, 2, 5` x columns `nu = 0, 0.25, 0.5`,
//! grid-extrapolated), minimax in stages (`kx` on pure longitudinal, `ky, t` on pure lateral
//! creepage, `beta` on combined translation, `ma, mb` on the pure spin moment, then the rest
//! jointly on pure spin and combined creepage), by
//! `cargo run --release -p creep-reference --example steady3d_fit`, which prints [`NODES`].
//!
//! **`a > b` has its own rows.** The law is not symmetric under `a/b -> b/a` with the axes
//! swapped (rolling along the long axis is not rolling along the short one): Kalker's own
//! table says so (`C11 = 4.37` at `a/b = 2` against `C22 = 2.88` at `a/b = 0.5`, `nu = 0`) and
//! the boundary elements agree (pure `xi_n = 0.1` at `a/b = 2` gives `0.381 mu P`, pure
//! `eta_n = 0.1` at `a/b = 0.5` gives `0.264 mu P`), so `a/b = 2, 5` are fitted as nodes.
//!
//! # Between nodes
//!
//! Interpolation in `ln(a/b)` between rows and in `nu` between columns, both piecewise linear
//! with convex weights, clamped beyond the end rows (`a/b < 0.2`: the `0.2` row; `a/b > 5`: the
//! `5` row). The per-node fits are not smooth in their constants (the spin's shape
//! constants trade off against `lam, ay, gam` differently at every node), so interpolating the
//! constants across rows put the lateral force of pure spin 11-16 % off between rows. Instead:
//!
//! * the translation's constants `kx, ky, t, beta` (and the inverse) are interpolated in both
//!   directions (pure translation stays within 0.8 % between nodes);
//! * within a row, the spin constants are interpolated in `nu` and the spin force's shape is
//!   blended by its outputs at the row's two columns;
//! * across rows (**between rows**), the spin terms of the two rows around `a/b` (steps 1-2
//!   and the factors of steps 3-5, each row with the contact's own Kalker coefficients and
//!   `M_max`: `w`, the capacities, `lam f_s`, `(1 - lam) f_s`, `1 - am s^2` and the spin
//!   moment) are blended with the row weights, and **one** translation (steps 3-5) is
//!   evaluated on them, plus a correction `g(phi_n)` added to the unsaturated share
//!   `(1 - lam) f_s`: `g = D/(1 - s_t)^(1/4)` where `D` is the difference between the lateral
//!   force of pure spin of the two rows' blended loads and of the one translation, and `s_t`
//!   the one translation's utilisation in pure spin. What depends on `|phi_n|` alone is
//!   **tabulated** once per contact at 105 knots (`|phi_n| = 2^-7 ... 2^6`, eight per octave,
//!   `f64` values and differences, interpolated linearly, indexed by the float's bits): the
//!   rows' utilisations `s_0, s_1` (`w` and the capacities with their floors are computed
//!   from them with each row's constants), the two blended shares of the spin force (with
//!   `g`, whose kinks, where a row's pure spin force reaches `mu P`, are two columns of
//!   their own, clamped after the interpolation), the lateral moment's factor and the spin
//!   moment as `A - B e^2 - C e^8` (module `correction`). Outside the knots the terms come
//!   from the rows (exact) and `g` continues as `phi_n^2` below, `1/phi_n` above. Within a
//!   blend weight of [`ROW_SNAP`] of a row, that row.
//!
//! What that law is, against the two rows' blended loads ([`Steady3d::two_row_blend`], the
//! previous round's law between rows, two translations per evaluation): zero spin is the same
//! law bit for bit; the lateral force of pure spin is the blend's up to the table's
//! interpolation (measured at most 0.49 % of `mu P` on `phi_n = 1e-4 ... 1e4`; 1.59 % at the
//! kink near `phi_n = 0.72` at `a/b = 3`, where one row's pure spin force reaches `mu P`,
//! before the kinks were tabulated apart; exact at the knots to rounding), the moment within
//! 0.074 % of `mu P c` for every creepage (it
//! is linear in the blended terms); with translation and spin combined the force differs from
//! the blend's (creep-reference's example `steady3d_virtual`: up to 10-23 % of `mu P` at the
//! corners of full slip, `|eta_n| = 0.6` with spin), and against the boundary elements off
//! the nodes it is closer than the blend at five of six validation cases (below). Saturation
//! `|F| <= 1` (the projection), oddness, dissipation at zero spin and Kalker's linear theory
//! at small creepage (below the first knot the terms are the rows', the correction
//! `O(phi_n^2)`) carry over; tests `between_rows_*`.
//!
//! [`Steady3d::new`] does this interpolation once per contact (build it once per contact shape
//! and material pair; between rows it builds the table: 105 knots, both rows' spin terms and
//! three pure-spin evaluations each, about 16 us; at a row about 3 us, the struct being 17.5
//! KB with the table); [`Steady3d::loads`] evaluates one row's spin terms and one
//! translation at a row of the table, the table and one translation between rows.
//!
//! # Accuracy of the fitted law
//!
//! See the error tables of crate creep-reference (`cargo run --release -p creep-reference
//! --example steady3d_errors`, and with `-- --table crates/reference/data/steady3d_bem_validation.csv`
//! off the nodes), pinned by its test `steady3d_vs_bem`. Largest errors, forces over `mu P`, moments over
//! `mu P c`:
//!
//! * rows `a/b = 0.2, 0.5, 1` (the nodes): pure cases within 1.7 % / 0.8 %, combined creepage
//!   within 5.0 % / 3.7 %;
//! * between them (`a/b = 0.27, 0.35, 0.7, 0.85` at `nu = 0.125, 0.375`): translation within
//!   0.8 %, the lateral force of pure spin within 4.7 %, the spin moment 1.7 %, combined
//!   creepage within 4.7 % / 3.7 %: pure spin is not within 2 % between rows (blending two rows whose spin force peaks at different spins leaves a few per
//!   cent; more rows would reduce it);
//! * rows `a/b = 2, 5` (`a > b`): translation within 0.5 %, but the law's form fits the spin
//!   there poorly: pure spin force 1.7-2.8 % at a/b = 2 and 5.0-8.9 % at a/b = 5, combined
//!   force 5.8-9.1 % and 18-24 %, moments up to 15 %; between them (`a/b = 1.4, 3`) spin force
//!   up to 19 %, combined 18 % (14.8 % at `a/b = 1.4`, 17.7 % at `a/b = 3`); below the table
//!   (`phi_n = 0.025-0.075`) the spin force within 3.1 %. The constants of `a/b = 2, 5` are
//!   fitted with boundary-element points below the table and from the previous `nu` node.
//!
//! **Over the whole creepage space the fitted law is far off.** Graded on creep-reference's error map
//! (module `steady3d_map`: every sign combination of the three creepages from full slip to
//! full slip, `a/b = 0.2 ... 5`, `nu = 0 ... 0.5`; `cargo run --release -p creep-reference
//! --example steady3d_map -- grade`), it is within 2 % of `mu P` and 3 % of `mu P c` at 13 % of
//! the points only, and off by up to 73 % of `mu P` in `Fx`, 100 % in `Fy` and 102 % of `mu P c`
//! in `Mz` where spin meets a translation beyond the onset of slip: the spin's capacities
//! (step 3) reach their floor of zero and take the whole translational force, and the spin
//! moment (step 5) survives full translational slip. At zero spin it is within 2.6 % of `mu P`
//! and 3.0 % of `mu P c` on the whole map; with spin only pure creepages (the tables above)
//! are graded well. docs/CREEP3D.md ("The error map") has the tables.
//!
//! # Accuracy and cost of the table
//!
//! The table serves every case of the error map (`a/b = 0.2 ... 5`): at a computed `a/b` up to
//! 3 every signed point is within 2 % of `mu P` in each force and 3 % of `mu P a` in the
//! moment, at `a/b = 5` within 2.26 % and 0.61 %, between two computed `a/b` within 3.98 % and
//! 4.24 % (`cargo run --release -p creep-reference --example steady3d_map -- grade`;
//! creep-reference's test `table_meets_the_bounds_where_it_covers_the_map`, docs/CREEP3D.md). An
//! evaluation costs the fitted law's or less: 287 instructions at a node, 372 blending two
//! (`valgrind --tool=callgrind` on the bench's `--count` mode; the fitted law 320-328), 21.5 /
//! 28.3 ns (the bench's `--time` mode, a quiet machine; the fitted law 31.9 ns on a loaded one).
//!
//! # Cost of the fitted law
//!
//! No `powf`, no logarithm. Without spin one translation (two square roots, two divisions);
//! with spin at a row one division for the row's spin utilisation and spin-force shape (a
//! row's two `nu` shapes are multiplied out into one rational function of `phi_n^2` in
//! [`Steady3d::new`]), and one translation: one division for its utilisation, a square root
//! and a division in parallel for its direction, two square roots for `(1 - s_t)^(1/4)`;
//! between rows one table lookup instead of the spin division (ten columns, `v + t d` each:
//! a load, a multiplication and an addition); the projection onto `|F| <= 1`, the rare
//! inputs (not finite, beyond the clamp, all tiny) and spins outside the table are
//! out-of-line branches. Measured (`cargo bench -p creep-law --bench steady3d --
//! --rounds-only`: the thread's CPU time, variants interleaved, medians; the previous law
//! [`Steady3d::two_row_blend`] timed in the same rounds; docs/CREEP3D.md has the tables):
//! with spin 38-42 ns between rows (medians of three runs; main's evaluation, alternated with
//! this one in one script, 54-56 ns; the two rows' translations 85-89 ns), 43-48 ns at a node
//! or a row (as before, the same law), without spin about 15 ns; `F_ss` 8.8 ns: **issue
//! #17's 50 ns with spin met for every a/b**. Load-free, `valgrind --tool=callgrind` counts
//! per evaluation of `loads` (the bench's `--count` mode) 281-283 instructions between rows
//! (main: 346-347) and 288 at a node or a row (main: 296). What made the difference between
//! rows: the table holds the terms that need no per-call arithmetic on the rows' constants
//! (the spin moment's `A, B, C` instead of two rows' `s (1 - b2 e^2 - b8 e^8)`, the lateral
//! moment's factor), in `f64` with the differences stored (`v + t d`: no `f32` conversions,
//! no subtraction), and `t` from the mantissa bits by one `or` and one subtraction; the
//! spins outside the knots in a cold function (no merge of two paths' terms, whose spills
//! cost a dozen instructions). Earlier: the projection a cold branch, `s_t/|d|` as `(s_t/|d|^2)
//! |d|`, a row's `nu` shapes multiplied out. Tried and not adopted (docs/CREEP3D.md): one row
//! fitted per contact to the two rows' blend (Levenberg-Marquardt on the 20 spin constants of
//! one row): the cost of a row, but it did not follow the blend and the errors against the
//! boundary elements off the nodes rose.

use crate::elliptic::complete_elliptic;
use crate::error::LawError;
use crate::kalker3d::{self, KalkerCoefficients};

/// Fitted shape constants of the law at one node `(a/b, nu)` (module documentation, steps 1-5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    /// Saturation point of the longitudinal force (`S(x; kx)`), in `[2, 3]`.
    pub kx: f64,
    /// Saturation point of the lateral force, in `[2, 3]`.
    pub ky: f64,
    /// Full-slip moment of lateral creepage from the coupling, per `nu`.
    pub t: f64,
    /// Spin-moment shape `ma >= 0`.
    pub ma: f64,
    /// Spin-moment shape `mb >= 1`.
    pub mb: f64,
    /// Spin lateral force numerator `p1 >= 0` (of `u`).
    pub p1: f64,
    /// Spin lateral force denominator `q1 >= 0` (of `u`).
    pub q1: f64,
    /// Spin lateral force denominator `q2 >= 0` (of `u^2`).
    pub q2: f64,
    /// Spin lateral force numerator `p2 >= 0` (of `u^2`).
    pub p2: f64,
    /// Spin lateral force denominator `q3 >= 0` (of `u^3`).
    pub q3: f64,
    /// Share of the spin's lateral force that saturates with the translation, in `[0, 1]`.
    pub lam: f64,
    /// Longitudinal capacity taken by the spin, `1 - ax s^2`.
    pub ax: f64,
    /// Lateral capacity taken by the spin, `1 - ay s^4`.
    pub ay: f64,
    /// Softening of the translation by the spin, `w = 1 + gam s^2`, `gam >= 0`.
    pub gam: f64,
    /// Spin-moment capacity taken by the translation, `e^2` term.
    pub b2: f64,
    /// Spin-moment capacity taken by the translation, `e^8` term.
    pub b8: f64,
    /// Fading of the lateral creepage's moment with the spin, `1 - am s^2`.
    pub am: f64,
    /// Turning of the force towards the creepage direction, `b = beta s_t^4` (partial slip),
    /// in `[0, 1]`.
    pub beta: f64,
}

impl Node {
    /// The constants as an array, in declaration order.
    pub fn to_array(&self) -> [f64; 18] {
        [
            self.kx, self.ky, self.t, self.ma, self.mb, self.p1, self.q1, self.q2, self.p2,
            self.q3, self.lam, self.ax, self.ay, self.gam, self.b2, self.b8, self.am, self.beta,
        ]
    }

    /// The constants from an array, in declaration order.
    pub fn from_array(a: [f64; 18]) -> Self {
        Node {
            kx: a[0],
            ky: a[1],
            t: a[2],
            ma: a[3],
            mb: a[4],
            p1: a[5],
            q1: a[6],
            q2: a[7],
            p2: a[8],
            q3: a[9],
            lam: a[10],
            ax: a[11],
            ay: a[12],
            gam: a[13],
            b2: a[14],
            b8: a[15],
            am: a[16],
            beta: a[17],
        }
    }

    /// Whether the sign constraints of the module documentation hold (`kx, ky` in `[2, 3]`,
    /// `ma, p1, q1, q2, p2, q3, gam >= 0`, `mb >= 1`, `lam, beta` in `[0, 1]`, all finite).
    pub fn is_admissible(&self) -> bool {
        let a = self.to_array();
        a.iter().all(|v| v.is_finite())
            && (2.0..=3.0).contains(&self.kx)
            && (2.0..=3.0).contains(&self.ky)
            && self.ma >= 0.0
            && self.mb >= 1.0
            && [self.p1, self.q1, self.q2, self.p2, self.q3, self.gam]
                .iter()
                .all(|&v| v >= 0.0)
            && (0.0..=1.0).contains(&self.lam)
            && (0.0..=1.0).contains(&self.beta)
    }
}

/// Axis ratios `a/b` of the nodes (rows of [`NODES`]).
pub const NODE_AB: [f64; 5] = [0.2, 0.5, 1.0, 2.0, 5.0];
/// `ln` of [`NODE_AB`] (the interpolation variable in the axis ratio).
const NODE_LN_AB: [f64; 5] = [
    -1.6094379124341003,
    -std::f64::consts::LN_2,
    0.0,
    std::f64::consts::LN_2,
    1.6094379124341003,
];
/// Poisson ratios of the nodes (columns of [`NODES`]).
pub const NODE_NU: [f64; 3] = [0.0, 0.25, 0.5];

/// The fitted constants, `NODES[i][j]` at `a/b = NODE_AB[i]`, `nu = NODE_NU[j]` (printed by
/// `cargo run --release -p creep-reference --example steady3d_fit`).
#[rustfmt::skip]
pub const NODES: [[Node; 3]; 5] = [
    [
        Node { kx: 2.183006e0, ky: 2.183007e0, t: 5.233908e-2, ma: 7.549813e-1, mb: 1.000000e0, p1: 3.419525e-9, q1: 8.224952e-1, q2: 6.321319e-1, p2: 8.892918e-1, q3: 6.325372e-1, lam: 2.078143e-1, ax: 8.362818e-1, ay: 7.546003e-1, gam: 4.067646e0, b2: 1.708930e-1, b8: -4.850984e-1, am: 4.310111e-1, beta: 0.000000e0 },
        Node { kx: 2.176671e0, ky: 2.196326e0, t: 9.365365e-2, ma: 8.684146e-1, mb: 1.086008e0, p1: 2.709103e1, q1: 2.964627e1, q2: 2.952589e1, p2: 1.509563e1, q3: 9.998030e0, lam: 5.040586e-1, ax: 8.913102e-1, ay: 7.051092e-1, gam: 1.346023e1, b2: 1.517921e-1, b8: -1.581933e-1, am: 6.834821e-1, beta: 5.697619e-1 },
        Node { kx: 2.178337e0, ky: 2.257334e0, t: 1.028920e-1, ma: 1.140880e0, mb: 1.261601e0, p1: 8.167323e0, q1: 1.557496e1, q2: 1.065547e1, p2: 2.870062e-3, q3: 4.054388e-4, lam: 2.954135e-12, ax: 9.414686e-1, ay: 6.439298e-1, gam: 1.513840e1, b2: 1.315587e-1, b8: -6.243262e-2, am: 9.031405e-1, beta: 4.709985e-1 },
    ],
    [
        Node { kx: 2.290039e0, ky: 2.290043e0, t: 4.072012e-2, ma: 8.519359e-1, mb: 1.212643e0, p1: 7.652335e-1, q1: 4.597228e-2, q2: 1.056653e0, p2: 7.840016e-1, q3: 6.723970e-2, lam: 8.018379e-1, ax: 9.016905e-1, ay: 1.191056e0, gam: 2.325133e0, b2: 1.883079e-1, b8: -2.902856e-1, am: 4.188568e-1, beta: 0.000000e0 },
        Node { kx: 2.265537e0, ky: 2.323151e0, t: 6.147980e-2, ma: 9.929077e-1, mb: 1.374525e0, p1: 6.570222e-1, q1: 1.783607e-2, q2: 1.190381e0, p2: 8.358778e-1, q3: 5.598184e-2, lam: 8.452506e-1, ax: 9.766199e-1, ay: 1.183695e0, gam: 2.649411e0, b2: 1.924245e-1, b8: -1.516822e-1, am: 5.095434e-1, beta: 4.525367e-1 },
        Node { kx: 2.217111e0, ky: 2.401860e0, t: 6.477306e-2, ma: 1.327769e0, mb: 1.697142e0, p1: 1.571938e0, q1: 9.445481e-1, q2: 1.053889e0, p2: 4.279667e-1, q3: 8.481045e-3, lam: 9.436719e-1, ax: 1.045429e0, ay: 1.079216e0, gam: 2.789865e0, b2: 1.946274e-1, b8: -4.484981e-2, am: 7.452743e-1, beta: 3.857866e-1 },
    ],
    [
        Node { kx: 2.367506e0, ky: 2.368022e0, t: 5.909518e-2, ma: 4.415028e-1, mb: 1.032776e0, p1: 5.298757e0, q1: 4.162475e0, q2: 3.923019e0, p2: 3.662827e-2, q3: 6.812520e-2, lam: 5.055788e-1, ax: 1.027908e0, ay: 2.131422e0, gam: 1.981400e0, b2: -1.322297e-3, b8: 3.371595e-1, am: 3.252422e-1, beta: 0.000000e0 },
        Node { kx: 2.346358e0, ky: 2.401336e0, t: 3.912171e-2, ma: 3.728167e-1, mb: 1.000000e0, p1: 1.397696e1, q1: 1.203315e1, q2: 1.070630e1, p2: 8.034773e-1, q3: 9.741677e-1, lam: 5.056038e-1, ax: 1.091525e0, ay: 2.253696e0, gam: 1.930678e0, b2: 3.372673e-2, b8: 1.348829e-1, am: 4.477821e-1, beta: 3.069272e-1 },
        Node { kx: 2.313438e0, ky: 2.443406e0, t: 3.773505e-2, ma: 3.811837e-1, mb: 1.000000e0, p1: 4.416977e-2, q1: 2.246222e-14, q2: 5.021428e-1, p2: 9.362053e-2, q3: 5.045555e-2, lam: 5.263736e-1, ax: 1.199533e0, ay: 3.321848e0, gam: 2.294222e0, b2: 6.976433e-2, b8: 1.342791e-1, am: 5.567834e-1, beta: 2.867301e-1 },
    ],
    [
        Node { kx: 2.433894e0, ky: 2.442335e0, t: 5.643401e-2, ma: 6.455137e-1, mb: 1.000000e0, p1: 6.176125e3, q1: 5.824159e3, q2: 4.687258e4, p2: 5.343067e4, q3: 1.192570e5, lam: 3.404293e-1, ax: 1.188071e0, ay: 7.405491e0, gam: 1.638939e0, b2: -3.072570e-1, b8: 4.426917e-1, am: 2.795895e-1, beta: 0.000000e0 },
        Node { kx: 2.415942e0, ky: 2.460985e0, t: 1.726315e-2, ma: 1.055389e0, mb: 1.000000e0, p1: 1.426909e2, q1: 1.222452e2, q2: 3.724311e2, p2: 2.136235e2, q3: 4.914907e2, lam: 4.205817e-1, ax: 1.213549e0, ay: 8.563199e0, gam: 1.554396e0, b2: -3.466603e-1, b8: 3.746745e-1, am: 1.763508e-1, beta: 4.868145e-2 },
        Node { kx: 2.376749e0, ky: 2.508218e0, t: 1.570672e-2, ma: 2.027965e0, mb: 1.000000e0, p1: 8.735168e2, q1: 7.721148e2, q2: 1.687008e3, p2: 1.049834e3, q3: 2.439595e3, lam: 5.117583e-1, ax: 1.238659e0, ay: 9.897607e0, gam: 1.571110e0, b2: -4.207728e-1, b8: 3.966568e-1, am: -1.585533e-1, beta: 1.598666e-1 },
    ],
    [
        Node { kx: 2.555862e0, ky: 2.586788e0, t: 5.211680e-2, ma: 6.065990e0, mb: 1.000000e0, p1: 4.214159e1, q1: 4.031377e-13, q2: 4.200670e3, p2: 2.523722e3, q3: 7.560554e3, lam: 6.197477e-1, ax: 9.527948e-1, ay: 4.530421e0, gam: 7.208130e-1, b2: -3.273544e-1, b8: 2.383107e-1, am: 3.264450e-2, beta: 0.000000e0 },
        Node { kx: 2.533300e0, ky: 2.540045e0, t: 8.258565e-3, ma: 1.467235e1, mb: 1.000000e0, p1: 3.377731e1, q1: 7.797338e-7, q2: 5.138554e3, p2: 2.884690e3, q3: 8.135320e3, lam: 6.739521e-1, ax: 9.003169e-1, ay: 3.951531e0, gam: 6.477522e-1, b2: -1.673646e-1, b8: 6.188836e-2, am: 2.698223e-1, beta: 7.344013e-1 },
        Node { kx: 2.506589e0, ky: 2.592260e0, t: 4.972726e-3, ma: 5.744819e1, mb: 1.000000e0, p1: 4.536877e1, q1: 1.467465e-11, q2: 1.195346e4, p2: 8.532349e3, q3: 1.154848e5, lam: 2.651868e-1, ax: 1.018653e0, ay: 1.517589e1, gam: 1.479466e0, b2: -1.443217e-1, b8: 5.427902e-2, am: 2.289638e-1, beta: 7.565872e-1 },
    ],
];

/// Below this `|t_0|^2` (normalised translation creepage below ~1e-35) the translation alone
/// is taken as linear (`e = 0`, `M_l = -C23 eta_n`, exact to ~1e-35 relative): the divisor
/// of its shared division, `q r^4 |t_0|^2`, is of eighth order in the creepage and stays a
/// normal float above it (~1e-283 at the threshold). It was `1e-140`, and a translation of
/// 1e-40 ... 1e-70 next to a finite spin gave NaN loads (the divisor underflowed to zero).
const T02_MIN: f64 = 1e-70;

/// Weight below which a row of the table is dropped from the blend between rows (see
/// [`Steady3d::two_row_blend`]).
pub const ROW_SNAP: f64 = 1e-6;

/// Normalised creepages are clamped to `[-CREEPAGE_CLAMP, CREEPAGE_CLAMP]` (deep in full slip).
pub const CREEPAGE_CLAMP: f64 = 1e6;

/// Below this normalised creepage (every component) the law returns Kalker's linear theory,
/// exact to rounding there (the non-linear terms are relatively `O(creepage)`).
pub const TINY_CREEPAGE: f64 = 1e-30;

/// The law at one axis ratio and Poisson ratio: Kalker's coefficients, the interpolated
/// constants and the per-contact factors, computed once (build one per contact shape and
/// material pair; [`Steady3d::loads`] evaluates per step).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steady3d {
    c: KalkerCoefficients,
    /// Constants interpolated in `ln(a/b)` and `nu` (the translation's `kx, ky, t, beta` are
    /// used from here).
    n: Node,
    /// `nu t`: the coupling's full-slip moment factor.
    nu_t: f64,
    m_max: f64,
    /// `C33/M_max`.
    m_per_phi: f64,
    /// `C22/C11 - 1`: the turn of the force towards the creepage direction.
    turn: f64,
    /// The (one or two) rows whose spin loads are blended.
    rows: [SpinRow; 2],
    /// Between rows: the tabulated spin terms with the pure-spin correction (module
    /// documentation, "Between nodes"); off at a row and in [`Steady3d::two_row_blend`].
    corr: correction::SpinCorrection,
    /// The boundary-element table where it covers `(a/b, nu)` (module documentation, "The
    /// table"); `None`: the fitted law above.
    lut: Option<lut::Lut>,
    /// The loads of full slip at this `a/b` (beyond the box, module documentation).
    fs: full_slip::FullSlip,
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

/// `S(x; k)` of the module documentation given `x/k >= 0`, for `k` in `[2, 3]`.
#[inline]
fn saturation_of_ratio(x_over_k: f64, k: f64) -> f64 {
    let u = x_over_k.min(1.0);
    // 1 - (1 - u)^2 (1 + (2 - k) u) expanded, free of cancellation at small u.
    u * (k - u * (2.0 * k - 3.0 + (2.0 - k) * u))
}

/// `(fx, fy)/sqrt(f2)`, `f2 = fx^2 + fy^2 > 1`: the projection onto the friction limit.
#[cold]
#[inline(never)]
fn project_to_unit(fx: f64, fy: f64, f2: f64) -> (f64, f64) {
    let inv = 1.0 / f2.sqrt();
    (fx * inv, fy * inv)
}

/// Inverse of [`saturation_of_ratio`] on `[0, 1)`: the `x` with `S(x; k) = s`, by Newton's method on the
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

/// Piecewise-linear bracket of `x` in the increasing `nodes` (clamped): `(i, w)` with
/// `x ~ (1 - w) nodes[i] + w nodes[i + 1]`.
fn bracket<const N: usize>(nodes: &[f64; N], x: f64) -> (usize, f64) {
    let x = x.clamp(nodes[0], nodes[N - 1]);
    let mut i = 0;
    while i + 2 < N && x > nodes[i + 1] {
        i += 1;
    }
    (i, (x - nodes[i]) / (nodes[i + 1] - nodes[i]))
}

/// The (up to four) nodes around `(ab, nu)` with their interpolation weights: piecewise linear
/// in `ln(a/b)` between the rows [`NODE_AB`] and in `nu` between the columns [`NODE_NU`]
/// (clamped: below `a/b = 0.2` the `0.2` row, above `5` the `5` row). Weights are convex.
fn surrounding(ab: f64, nu: f64) -> [((usize, usize), f64); 4] {
    let (i, wa) = bracket(&NODE_LN_AB, ab.ln());
    let (j, wn) = bracket(&NODE_NU, nu);
    [
        ((i, j), (1.0 - wa) * (1.0 - wn)),
        ((i, j + 1), (1.0 - wa) * wn),
        ((i + 1, j), wa * (1.0 - wn)),
        ((i + 1, j + 1), wa * wn),
    ]
}

/// The shape constants at the axis ratio `ab = a/b` and `nu` (module documentation: piecewise
/// linear in `ln(a/b)` and in `nu`, constant beyond the end rows).
///
/// A convex combination of admissible nodes is admissible, but in floating point only to
/// rounding (`mb = 1` at four nodes blended gave `0.9999999999999999`, and `Steady3d::new`
/// failed at e.g. `a/b = 1.04, nu = 0.3`); the bounds of [`Node::is_admissible`] are applied
/// to the sum (a change of at most a rounding error).
pub fn node_at(ab: f64, nu: f64) -> Node {
    let mut out = [0.0; 18];
    for ((i, j), w) in surrounding(ab, nu) {
        let v = NODES[i][j].to_array();
        for k in 0..18 {
            out[k] += w * v[k];
        }
    }
    let mut n = Node::from_array(out);
    n.kx = n.kx.clamp(2.0, 3.0);
    n.ky = n.ky.clamp(2.0, 3.0);
    n.mb = n.mb.max(1.0);
    n.lam = n.lam.clamp(0.0, 1.0);
    n.beta = n.beta.clamp(0.0, 1.0);
    for v in [
        &mut n.ma, &mut n.p1, &mut n.q1, &mut n.q2, &mut n.p2, &mut n.q3, &mut n.gam,
    ] {
        *v = v.max(0.0);
    }
    n
}

/// Where [`Steady3d::loads`] takes a contact's loads from (module documentation, "The table").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coverage {
    /// The boundary-element table at a computed `a/b` (between computed `nu` of it, linear in
    /// `nu`): within 2 % of `mu P` in each force and 3 % of `mu P a` in the moment on the
    /// error map.
    Table,
    /// Between two computed `a/b`, the cubic in `ln(a/b)` through up to four rows: within 2 % of
    /// `mu P` in each force and 3 % of `mu P a` in the moment on the error map and its off-grid
    /// validation (worst measured: Fy 1.57 % at `a/b = 0.85`, Mz 1.56 % at `a/b = 0.7`;
    /// docs/CREEP3D.md).
    BetweenRatios,
    /// The table at the nearest computed `nu` (a `nu` outside the range its rows compute) with
    /// the creepages scaled by Kalker's coefficients (module documentation, "Beyond the computed
    /// nu"): looser, within 9 % of `mu P` in each force and 9 % of `mu P a` in the moment on
    /// the error map and its off-grid validation (worst measured at `nu = 0`, 0.5 from the
    /// computed: Fx 6.80 % at `a/b = 1.4`, Fy 8.79 % and Mz 4.88 % of `mu P a` at `a/b = 2`).
    ExtrapolatedNu,
    /// The fitted law (no computed `a/b` on both sides).
    Fitted,
}

impl Steady3d {
    /// The law for the axis ratio `ab = a/b` in `[0.1, 10]` (`a` along the rolling direction)
    /// and Poisson ratio `nu` in `[0, 0.5]` (Kalker's table range), with the fitted constants.
    ///
    /// Build it once per contact shape and material pair (it interpolates the constants and
    /// prepares the rows, see the module documentation); [`Steady3d::loads`] evaluates per step.
    pub fn new(ab: f64, nu: f64) -> Result<Self, LawError> {
        let mut law = Self::two_row_blend(ab, nu)?;
        if law.rows[1].w > 0.0 {
            // Between rows: one translation on the two rows' blended spin terms, and the
            // correction that makes its pure spin the blend's (module documentation).
            law.corr = correction::SpinCorrection::build(&law);
        }
        law.lut = lut::Lut::at_with(ab, nu, true);
        Ok(law)
    }

    /// The law with explicit shape constants (for fitting them; [`Steady3d::new`] uses the
    /// fitted ones): one row, one spin shape. Inadmissible constants ([`Node::is_admissible`])
    /// give [`LawError::OutOfRange`].
    pub fn with_node(ab: f64, nu: f64, node: Node) -> Result<Self, LawError> {
        let c = kalker3d::coefficients(ab, nu)?;
        if !node.is_admissible() {
            return Err(LawError::OutOfRange {
                name: "steady3d shape constants",
                value: f64::NAN,
                range: "kx, ky in [2, 3]; ma, p*, q*, gam >= 0; mb >= 1; lam, beta in [0, 1]",
            });
        }
        let g = ab.min(1.0 / ab);
        let (_, e, _) = complete_elliptic(1.0 - g * g)?;
        // a_M / c = sqrt(a_M / b_m) = 1/sqrt(g).
        let m_max = 0.375 * e / g.sqrt();
        let n = node;
        let row = SpinRow::new(1.0, n, (1.0, &n), (0.0, &n));
        Ok(Steady3d {
            c,
            n,
            nu_t: nu * n.t,
            m_max,
            m_per_phi: c.c33 / m_max,
            turn: c.c22 / c.c11 - 1.0,
            rows: [row, SpinRow { w: 0.0, ..row }],
            corr: correction::SpinCorrection::OFF,
            lut: None,
            fs: full_slip::FullSlip::at(ab),
        })
    }

    /// Whether the boundary-element table answers for this contact, at its `nu` or extrapolated
    /// in `nu` (module documentation, "The table"): then [`Steady3d::loads`] interpolates it;
    /// otherwise the fitted law ([`Steady3d::coverage`] says which).
    pub fn tabulated(&self) -> bool {
        self.lut.is_some()
    }

    /// Which of the law's sources gives this contact's loads, and so its accuracy (module
    /// documentation, "The table").
    pub fn coverage(&self) -> Coverage {
        match &self.lut {
            Some(l) if l.extrapolated() => Coverage::ExtrapolatedNu,
            Some(l) if l.between_ratios() => Coverage::BetweenRatios,
            Some(_) => Coverage::Table,
            None => Coverage::Fitted,
        }
    }

    /// The fitted law at this contact, without the table (as [`Steady3d::new`] where the table
    /// does not cover the contact).
    pub fn without_table(&self) -> Steady3d {
        Steady3d { lut: None, ..*self }
    }

    /// Kalker's coefficients in use.
    pub fn coefficients(&self) -> KalkerCoefficients {
        self.c
    }

    /// The shape constants interpolated in `ln(a/b)` and `nu` (the translation uses these; with
    /// spin, the rows' own constants, module documentation).
    pub fn node(&self) -> Node {
        self.n
    }

    /// The full-slip spin moment `M_max` over `mu P c`.
    pub fn max_moment(&self) -> f64 {
        self.m_max
    }

    /// Saturation point for a translational linear force `(tx, ty)` with `|t|^2 = tm2 > 0`.
    #[inline]
    fn k_of(&self, tx: f64, ty: f64, tm2: f64) -> f64 {
        (self.n.kx * tx * tx + self.n.ky * ty * ty) / tm2
    }

    /// Loads for normalised creepages, project signs (module documentation). Non-finite
    /// creepages give zero loads (a sanitised no-contact answer, never NaN).
    #[inline]
    pub fn loads(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        // One test for the rare inputs (not finite, beyond the clamp, all tiny): the sum of
        // the magnitudes is NaN or above the clamp for the first two.
        let (ax, ay, az) = (xi_n.abs(), eta_n.abs(), phi_n.abs());
        // The largest magnitude by selects (one `maxsd` each; a NaN fails the first test).
        let m = if ax > ay { ax } else { ay };
        let m = if m > az { m } else { az };
        if !(ax + ay + az <= CREEPAGE_CLAMP && m >= TINY_CREEPAGE) {
            return self.loads_rare(xi_n, eta_n, phi_n);
        }
        self.loads_in_range(xi_n, eta_n, phi_n)
    }

    /// [`Steady3d::loads`] for inputs not finite (zero loads), beyond [`CREEPAGE_CLAMP`]
    /// (clamped: the loads there are full slip's to ~1e-6 of `mu P`, and clamping keeps
    /// the squares below finite overflow for any finite input) or all below
    /// [`TINY_CREEPAGE`] (Kalker's linear theory, exact to rounding there, where the products
    /// of the shared divisions would underflow).
    #[cold]
    #[inline(never)]
    fn loads_rare(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        if !(xi_n.is_finite() && eta_n.is_finite() && phi_n.is_finite()) {
            return Loads::default();
        }
        let xi_n = xi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let eta_n = eta_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let phi_n = phi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let c = &self.c;
        if xi_n.abs().max(eta_n.abs()).max(phi_n.abs()) < TINY_CREEPAGE {
            // Kalker's linear theory, exact to rounding here (and the products of the
            // shared divisions below would underflow).
            return Loads {
                fx: c.c11 * xi_n,
                fy: c.c22 * eta_n + c.c23 * phi_n,
                mz: -c.c23 * eta_n + c.c33 * phi_n,
            };
        }
        self.loads_in_range(xi_n, eta_n, phi_n)
    }

    /// [`Steady3d::loads`] for finite creepages within the clamp, not all tiny: within the
    /// box `|xi_n|, |eta_n| <= 2`, `|phi_n| <= 4` the table or the fitted law; beyond it,
    /// [`Steady3d::beyond_the_box`].
    #[inline(always)]
    fn loads_in_range(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        let (ax, ay) = (xi_n.abs(), eta_n.abs());
        let m = if ax > ay { ax } else { ay };
        let s = (m * (1.0 / lut::XI_MAX)).max(phi_n.abs() * (1.0 / lut::PHI_MAX));
        if s > 1.0 {
            return self.beyond_the_box(xi_n, eta_n, phi_n, s);
        }
        self.in_the_box(xi_n, eta_n, phi_n)
    }

    /// Beyond the box (`s > 1` the largest of `|xi_n|/2, |eta_n|/2, |phi_n|/4`): the loads
    /// approach full slip's ([`full_slip`], a function of the creepage's direction) as `1/s`,
    /// `L = L_fs + (L_edge - L_fs)/s` from the loads `L_edge` where the ray of the creepage
    /// leaves the box. Where a spin keeps a sticking patch around its pole, the boundary
    /// elements show this decay (the patch shrinks as `1/s`; `steady3d_far`, creep-reference);
    /// where a translation dominates, the edge is in full slip already. A convex combination of
    /// two loads within Coulomb's bound, so within it.
    #[inline(never)]
    fn beyond_the_box(&self, xi_n: f64, eta_n: f64, phi_n: f64, s: f64) -> Loads {
        let k = 1.0 / s;
        // At the box's edge (`|xi_n|` or `|eta_n|` = 2, or `|phi_n|` = 4) the table is read as
        // it is: its linear theory near zero does not reach there.
        let (x, y, p) = (xi_n * k, eta_n * k, phi_n * k);
        let e = match &self.lut {
            Some(t) => t.read(x, y, p),
            None => self.in_the_box(x, y, p),
        };
        let f = self.fs.loads(xi_n, eta_n, phi_n);
        Loads {
            fx: f.fx + (e.fx - f.fx) * k,
            fy: f.fy + (e.fy - f.fy) * k,
            mz: f.mz + (e.mz - f.mz) * k,
        }
    }

    /// The loads within the box: the table where it covers the contact, else the fitted law.
    #[inline(always)]
    fn in_the_box(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        if let Some(t) = &self.lut {
            return t.loads(xi_n, eta_n, phi_n);
        }
        let c = &self.c;
        let tx0 = c.c11 * xi_n;
        let ty0 = c.c22 * eta_n;
        let t02 = tx0 * tx0 + ty0 * ty0;
        if phi_n == 0.0 {
            return self.translation_only(xi_n, eta_n, tx0, ty0, t02);
        }
        if self.rows[1].w == 0.0 {
            // At a row of the table.
            return self.one_row(xi_n, eta_n, phi_n, tx0, ty0, t02);
        }
        let (e, ml) = if t02 > T02_MIN {
            self.lateral_moment(xi_n, eta_n, tx0, ty0, t02)
        } else {
            (0.0, -self.c.c23 * eta_n)
        };
        // 1-2 for the tabulated blend of the two rows (between rows), then 3-5 on those
        // terms (module documentation).
        if self.corr.on {
            let e2 = e * e;
            match self
                .corr
                .terms(&self.rows, phi_n, e2, (e2 * e2) * (e2 * e2))
            {
                Some(t) => self.with_spin(phi_n, tx0, ty0, ml, &t),
                None => self.beyond_the_knots(phi_n, e, tx0, ty0, ml),
            }
        } else {
            self.two_rows_blended(phi_n, e, tx0, ty0, ml)
        }
    }

    /// [`Steady3d::loads`] at a row of the table with spin: steps 1-5, the division of the
    /// translation alone's utilisation and the row's spin division shared (`1/(A B)`).
    #[inline(always)]
    fn one_row(&self, xi_n: f64, eta_n: f64, phi_n: f64, tx0: f64, ty0: f64, t02: f64) -> Loads {
        let row = &self.rows[0];
        let nr = &row.n;
        let m = self.m_per_phi * phi_n.abs();
        let u = phi_n * phi_n;
        let (u2, u4) = (u * u, (u * u) * (u * u));
        let ns = m * (1.0 + nr.ma * m);
        let ds = 1.0 + m * (nr.mb + nr.ma * m);
        let (num, den) = row.shape_parts(u, u2, u4);
        let b = ds * den;
        // The translation alone (module documentation, step 5): |t0|/k = |t0|^3/q,
        // k = q/|t0|^2 and 1/r^4 from 1/A, A = q r^4 |t0|^2.
        let n = &self.n;
        let has_t = t02 > T02_MIN;
        let q = n.kx * tx0 * tx0 + n.ky * ty0 * ty0;
        let r2 = xi_n * xi_n + eta_n * eta_n;
        let r4 = r2 * r2;
        let a = if has_t { q * r4 * t02 } else { 1.0 };
        let i = 1.0 / (a * b);
        let (inv_a, inv_b) = (b * i, a * i);
        let (e, ml) = if has_t {
            let e = saturation_of_ratio(t02.sqrt() * t02 * t02 * r4 * inv_a, q * q * r4 * inv_a);
            // nu t e^3 eta^3/r^4 with 1/r^4 = q t02/A.
            let p = e * eta_n;
            let ml = -self.c.c23 * eta_n * (1.0 - e) - self.nu_t * (p * p * p) * (q * t02 * inv_a);
            (e, ml)
        } else {
            (0.0, -self.c.c23 * eta_n)
        };
        let e2 = e * e;
        let t = SpinTerms::of_row(
            row,
            ns * den * inv_b,
            self.c.c23 * phi_n * num * ds * inv_b,
            e2,
            (e2 * e2) * (e2 * e2),
        );
        self.with_spin(phi_n, tx0, ty0, ml, &t)
    }

    /// The spin terms of the first `R` rows (module documentation, steps 1-2); `e` is the
    /// utilisation of the translation alone. One division serves every row's spin utilisation
    /// `s = ns/ds` and spin-force shape `N/D`.
    #[inline(always)]
    fn spin_terms<const R: usize>(&self, phi_n: f64, e: f64) -> [SpinTerms; R] {
        let m = self.m_per_phi * phi_n.abs();
        let u = phi_n * phi_n;
        let (u2, u4) = (u * u, (u * u) * (u * u));
        let e2 = e * e;
        let e8 = (e2 * e2) * (e2 * e2);
        let mut ns = [0.0; R];
        let mut ds = [0.0; R];
        let mut num = [0.0; R];
        let mut den = [0.0; R];
        for r in 0..R {
            let n = &self.rows[r].n;
            ns[r] = m * (1.0 + n.ma * m);
            ds[r] = 1.0 + m * (n.mb + n.ma * m);
            (num[r], den[r]) = self.rows[r].shape_parts(u, u2, u4);
        }
        let c23_phi = self.c.c23 * phi_n;
        // inv_r = 1/A_r, A_r = ds_r den_r; with two rows 1/(A0 A1) gives both.
        let mut inv = [0.0; R];
        if R == 1 {
            inv[0] = 1.0 / (ds[0] * den[0]);
        } else {
            let (a0, a1) = (ds[0] * den[0], ds[1] * den[1]);
            let i = 1.0 / (a0 * a1);
            inv[0] = a1 * i;
            inv[1] = a0 * i;
        }
        std::array::from_fn(|r| {
            SpinTerms::of_row(
                &self.rows[r],
                ns[r] * den[r] * inv[r],
                c23_phi * num[r] * ds[r] * inv[r],
                e2,
                e8,
            )
        })
    }

    /// Steps 3-5 of the module documentation at nonzero spin, given the spin terms, the linear
    /// translation `t_0 = (tx0, ty0)` and the moment `M_l` of lateral creepage. One division
    /// serves the translation's utilisation; the direction's square root and division run in
    /// parallel.
    #[inline(always)]
    fn with_spin(&self, phi_n: f64, tx0: f64, ty0: f64, ml: f64, t: &SpinTerms) -> Loads {
        let (mut fx, mut fy) = self.force_unprojected(tx0, ty0, t);
        // 4: the friction limit.
        let f2 = fx * fx + fy * fy;
        if f2 > 1.0 {
            // Rare: a real branch (a select would put a square root and a division on every
            // evaluation's critical path).
            (fx, fy) = project_to_unit(fx, fy, f2);
        }
        // 5: moment.
        let mz = ml * t.ml_factor + self.m_max * t.spin_moment.copysign(phi_n);
        Loads { fx, fy, mz }
    }

    /// Steps 3-4 of the module documentation before the projection onto `|F| <= 1`: the force
    /// for the spin terms `t` and the linear translation `t_0 = (tx0, ty0)`.
    #[inline(always)]
    fn force_unprojected(&self, tx0: f64, ty0: f64, t: &SpinTerms) -> (f64, f64) {
        // 3: translation t = t'/w, t' = (C11 xi, C22 eta + lam f_s).
        let (kx, ky) = (self.n.kx, self.n.ky);
        let tx = tx0;
        let ty = ty0 + t.f_sat;
        let tm2 = tx * tx + ty * ty;
        let (fx, fy, st) = if tm2 > 0.0 {
            let q = kx * tx * tx + ky * ty * ty;
            let wq = t.w * q;
            let inv = 1.0 / (wq * tm2);
            // |t|/k = |t'|^3/(w q) and k = q/|t'|^2 with one division.
            let x = tm2.sqrt() * tm2 * tm2 * inv;
            let st = saturation_of_ratio(x, q * wq * inv);
            let b = turn_weight(self.n.beta, x, st);
            let dx = tx * (1.0 + b * self.turn);
            // st/|d| as (st/|d|^2) |d|: the square root and the division in parallel.
            let d2 = dx * dx + ty * ty;
            let scale = (st / d2) * d2.sqrt();
            (dx * scale, ty * scale, st)
        } else {
            (0.0, 0.0, 0.0)
        };
        // 4: the rest of the spin's lateral force.
        (
            fx * t.cap_x,
            fy * t.cap_y + t.f_rest * (1.0 - st).sqrt().sqrt(),
        )
    }

    /// The utilisation `e` of the translation alone and the moment `M_l` of lateral creepage
    /// (module documentation, step 5), for `t02 = |t_0|^2 > 0`; the three divisions share one.
    #[inline]
    fn lateral_moment(&self, xi_n: f64, eta_n: f64, tx0: f64, ty0: f64, t02: f64) -> (f64, f64) {
        let (e, ml, _) = self.lateral_moment_x(xi_n, eta_n, tx0, ty0, t02);
        (e, ml)
    }

    /// [`Steady3d::lateral_moment`] with the translation's linear ratio `x = |t_0|/k`.
    #[inline(always)]
    fn lateral_moment_x(
        &self,
        xi_n: f64,
        eta_n: f64,
        tx0: f64,
        ty0: f64,
        t02: f64,
    ) -> (f64, f64, f64) {
        let n = &self.n;
        let q = n.kx * tx0 * tx0 + n.ky * ty0 * ty0;
        let r2 = xi_n * xi_n + eta_n * eta_n;
        let r4 = r2 * r2;
        // |t0|/k = |t0|^3/q, k = q/|t0|^2 and 1/r^4 with one division.
        let inv = 1.0 / (q * r4 * t02);
        let x = t02.sqrt() * t02 * t02 * r4 * inv;
        let e = saturation_of_ratio(x, q * q * r4 * inv);
        // nu t e^3 eta^3/r^4 with 1/r^4 = q t02 inv.
        let p = e * eta_n;
        let ml = -self.c.c23 * eta_n * (1.0 - e) - self.nu_t * (p * p * p) * (q * t02 * inv);
        (e, ml, x)
    }

    /// [`Steady3d::loads`] at `phi_n = 0`: no spin terms.
    #[inline]
    fn translation_only(&self, xi_n: f64, eta_n: f64, tx0: f64, ty0: f64, t02: f64) -> Loads {
        if !(t02 > 0.0) {
            return Loads::default();
        }
        let (e, mz, x) = self.lateral_moment_x(xi_n, eta_n, tx0, ty0, t02);
        let b = turn_weight(self.n.beta, x, e);
        let dx = tx0 * (1.0 + b * self.turn);
        let d2 = dx * dx + ty0 * ty0;
        let scale = (e / d2) * d2.sqrt();
        Loads {
            fx: dx * scale,
            fy: ty0 * scale,
            mz,
        }
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
    ///
    /// At zero spin `|F| = s_t` and `F` is parallel to `d = (t_x (1 + b (C22/C11 - 1)), t_y)`
    /// with `b = beta |F|^4` known (partial slip), so the direction of `t` follows from that of `F`, and
    /// `|t| = S^-1(|F|; k)` with `k` from that direction (Newton on a cubic).
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
        let b = self.n.beta * (f * f) * (f * f);
        let dx = fx / (1.0 + b * self.turn);
        let dm2 = dx * dx + fy * fy;
        let dm = dm2.sqrt();
        let tm = saturation_inverse(f, self.k_of(dx, fy, dm2));
        Ok((tm * dx / dm / self.c.c11, tm * fy / dm / self.c.c22))
    }
}

/// The weight `b` of the force's turn from the linear direction towards the creepage direction
/// (module documentation, step 3), given the translation's linear ratio `x = |t|/k` and its
/// utilisation `s = S(x; k)`: `beta s^4` in partial slip (`x < 1`), and beyond the onset of
/// full slip `1 - (1 - beta)/x^2`, continuous at `x = 1` and tending to `1` (the force along
/// the creepage `(xi_n, eta_n)`): in full slip the traction is `mu p` along the slip, whose
/// elastic part stays bounded while the rigid slip grows with the creepage. The power 2 is
/// the best of `1/x, 1/x^2, 1/x^3` on the error map at zero spin (worst force error 4.8 %,
/// 2.6 %, 2.6 % of `mu P`; `beta s^4` alone, 12.7 %).
#[inline(always)]
fn turn_weight(beta: f64, x: f64, s: f64) -> f64 {
    if x > 1.0 {
        1.0 - (1.0 - beta) / (x * x)
    } else {
        beta * (s * s) * (s * s)
    }
}

mod between;
mod correction;
pub mod full_slip;
mod full_slip_data;
pub mod lut;
mod lut_data;
mod row;

use row::{SpinRow, SpinTerms};

#[cfg(test)]
mod tests;
