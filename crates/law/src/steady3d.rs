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
//!    `b = beta s_t^4` (with `nu > 0` the force turns from the linear direction `t` towards the
//!    creepage direction as the contact slips), times the capacities left by the spin,
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
//! (module `steady3d`: `a/b = 1, 0.5, 0.2` x `nu = 0, 0.25, 0.5`, grid-extrapolated), minimax
//! in stages (`kx` on pure longitudinal, `ky, t` on pure lateral creepage, `beta` on combined
//! translation, `ma, mb` on the pure spin moment, then the rest jointly on pure spin and combined
//! creepage), by `cargo run --release -p creep-reference --example steady3d_fit`, which prints
//! [`NODES`]. Between nodes the constants are interpolated piecewise linearly in
//! `g = min(a/b, b/a)` and in `nu` (convex weights: the sign constraints that keep every
//! denominator positive hold between nodes too), except the shape of the spin's lateral force,
//! whose *outputs* at the (up to four) surrounding nodes are interpolated with the same
//! weights (its coefficients differ by orders of magnitude between nodes); below `g = 0.2` the
//! `g = 0.2` constants are used. For `a/b > 1` the constants of `g = b/a` are used: **the table
//! covers `a <= b` only, so that is an extrapolation** (Kalker's coefficients themselves are
//! tabulated for both).
//!
//! # Accuracy (docs/CREEP3D.md)
//!
//! At the nodes: pure cases within 1.7 % of `mu P` (forces) and 0.8 % of `mu P c` (moments),
//! combined creepage within 5.0 % / 3.7 %. Off the nodes (a validation table the fit never saw,
//! `data/steady3d_bem_validation.csv` of crate creep-reference): translation within 0.5 %
//! between nodes, but the lateral force of pure spin up to 13 % and combined creepage up to
//! 10.4 % off; for `a/b > 1` (a/b = 2) translation within 1.2 % (moment 2.0 %) and **every spin
//! load wrong** (force up to 77 %). Use it with spin only near the nodes, or at `a <= b`
//! accepting those errors.
//!
//! Cost: no `powf`; without spin one square root and three divisions (about 1.2 times
//! `F_ss`, Kalker's closed form with its cube root), with spin five square roots and three to
//! six divisions (about 2.8 times `F_ss`, 3.4 times between nodes); criterion bench
//! `cargo bench -p creep-law --bench steady3d`, numbers in docs/CREEP3D.md.

use crate::elliptic::complete_elliptic;
use crate::error::LawError;
use crate::kalker3d::{self, KalkerCoefficients};

/// Fitted shape constants of the law at one node `(g, nu)` (module documentation, steps 1-5).
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
    /// Turning of the force towards the creepage direction, `b = beta s_t^4`, in `[0, 1]`.
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

/// Ratios `g = min(a/b, b/a)` of the nodes (rows of [`NODES`]).
pub const NODE_G: [f64; 3] = [0.2, 0.5, 1.0];
/// Poisson ratios of the nodes (columns of [`NODES`]).
pub const NODE_NU: [f64; 3] = [0.0, 0.25, 0.5];

/// The fitted constants, `NODES[i][j]` at `g = NODE_G[i]`, `nu = NODE_NU[j]` (printed by
/// `cargo run --release -p creep-reference --example steady3d_fit`).
#[rustfmt::skip]
pub const NODES: [[Node; 3]; 3] = [
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
];

/// Normalised creepages are clamped to `[-CREEPAGE_CLAMP, CREEPAGE_CLAMP]` (deep in full slip).
pub const CREEPAGE_CLAMP: f64 = 1e6;

/// Below this normalised creepage (every component) the law returns Kalker's linear theory,
/// exact to rounding there (the non-linear terms are relatively `O(creepage)`).
pub const TINY_CREEPAGE: f64 = 1e-30;

/// The law at one axis ratio and Poisson ratio (coefficients and shape constants interpolated
/// once; build once per contact shape and material pair).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Steady3d {
    c: KalkerCoefficients,
    n: Node,
    nu: f64,
    m_max: f64,
    /// `C33/M_max`.
    m_per_phi: f64,
    /// `C22/C11 - 1`: the turn of the force towards the creepage direction.
    turn: f64,
    /// The spin force's rational functions of the (up to four) nodes around `(g, nu)` with
    /// their interpolation weights: `[w, p1, q1, q2, p2, q3]` (outputs are interpolated, not
    /// coefficients).
    fs_nodes: [[f64; 6]; 4],
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

/// Piecewise-linear bracket of `x` in `nodes` (clamped): `(i, w)` with `x ~ (1 - w) nodes[i] +
/// w nodes[i + 1]`.
fn bracket(nodes: &[f64; 3], x: f64) -> (usize, f64) {
    let x = x.clamp(nodes[0], nodes[2]);
    let i = if x <= nodes[1] { 0 } else { 1 };
    (i, (x - nodes[i]) / (nodes[i + 1] - nodes[i]))
}

/// The shape constants at `g = min(a/b, b/a)` and `nu` (module documentation: piecewise linear
/// in both, constant below `g = 0.2`).
pub fn node_at(g: f64, nu: f64) -> Node {
    let (i, wg) = bracket(&NODE_G, g);
    let (j, wn) = bracket(&NODE_NU, nu);
    let mut out = [0.0; 18];
    for (di, a) in [(0, 1.0 - wg), (1, wg)] {
        for (dj, b) in [(0, 1.0 - wn), (1, wn)] {
            let v = NODES[i + di][j + dj].to_array();
            for k in 0..18 {
                out[k] += a * b * v[k];
            }
        }
    }
    Node::from_array(out)
}

impl Steady3d {
    /// The law for the axis ratio `ab = a/b` in `[0.1, 10]` (`a` along the rolling direction)
    /// and Poisson ratio `nu` in `[0, 0.5]` (Kalker's table range), with the fitted constants.
    pub fn new(ab: f64, nu: f64) -> Result<Self, LawError> {
        kalker3d::coefficients(ab, nu)?;
        let g = ab.min(1.0 / ab);
        let mut law = Self::with_node(ab, nu, node_at(g, nu))?;
        let (i, wg) = bracket(&NODE_G, g);
        let (j, wn) = bracket(&NODE_NU, nu);
        let mut k = 0;
        for (di, a) in [(0, 1.0 - wg), (1, wg)] {
            for (dj, b) in [(0, 1.0 - wn), (1, wn)] {
                let n = &NODES[i + di][j + dj];
                law.fs_nodes[k] = [a * b, n.p1, n.q1, n.q2, n.p2, n.q3];
                k += 1;
            }
        }
        Ok(law)
    }

    /// The law with explicit shape constants (for fitting them; [`Steady3d::new`] uses the
    /// fitted ones). Inadmissible constants ([`Node::is_admissible`]) give
    /// [`LawError::OutOfRange`].
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
        Ok(Steady3d {
            c,
            n: node,
            nu,
            m_max,
            m_per_phi: c.c33 / m_max,
            turn: c.c22 / c.c11 - 1.0,
            fs_nodes: [
                [1.0, node.p1, node.q1, node.q2, node.p2, node.q3],
                [0.0; 6],
                [0.0; 6],
                [0.0; 6],
            ],
        })
    }

    /// Kalker's coefficients in use.
    pub fn coefficients(&self) -> KalkerCoefficients {
        self.c
    }

    /// The shape constants in use.
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
        if !(xi_n.is_finite() && eta_n.is_finite() && phi_n.is_finite()) {
            return Loads::default();
        }
        // Far in full slip the loads no longer change (to ~1e-6); clamping keeps the squares
        // below finite overflow for any finite input.
        let xi_n = xi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let eta_n = eta_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let phi_n = phi_n.clamp(-CREEPAGE_CLAMP, CREEPAGE_CLAMP);
        let (c, n) = (&self.c, &self.n);
        if xi_n.abs().max(eta_n.abs()).max(phi_n.abs()) < TINY_CREEPAGE {
            // Kalker's linear theory, exact to rounding here (and the products of the
            // shared divisions below would underflow).
            return Loads {
                fx: c.c11 * xi_n,
                fy: c.c22 * eta_n + c.c23 * phi_n,
                mz: -c.c23 * eta_n + c.c33 * phi_n,
            };
        }
        let tx0 = c.c11 * xi_n;
        let ty0 = c.c22 * eta_n;
        let t02 = tx0 * tx0 + ty0 * ty0;
        if phi_n == 0.0 {
            return self.translation_only(xi_n, eta_n, tx0, ty0, t02);
        }
        // 1-2: spin; one division for both rational functions.
        let m = self.m_per_phi * phi_n.abs();
        let u = phi_n * phi_n;
        let s = m * (1.0 + n.ma * m) / (1.0 + m * (n.mb + n.ma * m));
        let mut shape = 0.0;
        for f in &self.fs_nodes {
            if f[0] != 0.0 {
                shape += f[0] * (1.0 + u * (f[1] + f[4] * u))
                    / (1.0 + u * (f[2] + u * (f[3] + f[5] * u)));
            }
        }
        let f_s = c.c23 * phi_n * shape;
        let s2 = s * s;
        let w = 1.0 + n.gam * s2;
        // 3: translation t = t'/w, t' = (C11 xi, C22 eta + lam f_s).
        let tx = tx0;
        let ty = ty0 + n.lam * f_s;
        let tm2 = tx * tx + ty * ty;
        let (mut fx, mut fy, st) = if tm2 > 0.0 {
            let q = n.kx * tx * tx + n.ky * ty * ty;
            let wq = w * q;
            let inv = 1.0 / (wq * tm2);
            // |t|/k = |t'|^3/(w q) and k = q/|t'|^2 with one division.
            let st = saturation_of_ratio(tm2.sqrt() * tm2 * tm2 * inv, q * wq * inv);
            let b = n.beta * (st * st) * (st * st);
            let dx = tx * (1.0 + b * self.turn);
            let scale = st / (dx * dx + ty * ty).sqrt();
            (dx * scale, ty * scale, st)
        } else {
            (0.0, 0.0, 0.0)
        };
        fx *= w * (1.0 - n.ax * s2).max(0.0);
        fy *= w * (1.0 - n.ay * s2 * s2).max(0.0);
        // 4: the rest of the spin's lateral force, the friction limit.
        fy += (1.0 - n.lam) * f_s * (1.0 - st).sqrt().sqrt();
        let f2 = fx * fx + fy * fy;
        if f2 > 1.0 {
            let inv = 1.0 / f2.sqrt();
            fx *= inv;
            fy *= inv;
        }
        // 5: moment, with e the utilisation of the translation alone.
        let spin_moment = self.m_max * s.copysign(phi_n);
        let mz = if t02 > 0.0 {
            let (e, ml) = self.lateral_moment(xi_n, eta_n, tx0, ty0, t02);
            let e2 = e * e;
            let e8 = (e2 * e2) * (e2 * e2);
            ml * (1.0 - n.am * s2) + spin_moment * (1.0 - n.b2 * e2 - n.b8 * e8).max(0.0)
        } else {
            spin_moment
        };
        Loads { fx, fy, mz }
    }

    /// The utilisation `e` of the translation alone and the moment `M_l` of lateral creepage
    /// (module documentation, step 5), for `t02 = |t_0|^2 > 0`; the three divisions share one.
    #[inline]
    fn lateral_moment(&self, xi_n: f64, eta_n: f64, tx0: f64, ty0: f64, t02: f64) -> (f64, f64) {
        let n = &self.n;
        let q = n.kx * tx0 * tx0 + n.ky * ty0 * ty0;
        let r2 = xi_n * xi_n + eta_n * eta_n;
        let r4 = r2 * r2;
        // |t0|/k = |t0|^3/q, k = q/|t0|^2 and 1/r^4 with one division.
        let inv = 1.0 / (q * r4 * t02);
        let e = saturation_of_ratio(t02.sqrt() * t02 * t02 * r4 * inv, q * q * r4 * inv);
        let ml = -self.c.c23 * eta_n * (1.0 - e)
            - self.nu * n.t * e * e * e * eta_n * eta_n * eta_n * q * t02 * inv;
        (e, ml)
    }

    /// [`Steady3d::loads`] at `phi_n = 0`: no spin terms.
    #[inline]
    fn translation_only(&self, xi_n: f64, eta_n: f64, tx0: f64, ty0: f64, t02: f64) -> Loads {
        if !(t02 > 0.0) {
            return Loads::default();
        }
        let (e, mz) = self.lateral_moment(xi_n, eta_n, tx0, ty0, t02);
        let b = self.n.beta * (e * e) * (e * e);
        let dx = tx0 * (1.0 + b * self.turn);
        let scale = e / (dx * dx + ty0 * ty0).sqrt();
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
    /// with `b = beta |F|^4` known, so the direction of `t` follows from that of `F`, and
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
    fn constants_at_and_between_nodes() {
        for (i, &g) in NODE_G.iter().enumerate() {
            for (j, &nu) in NODE_NU.iter().enumerate() {
                assert!(NODES[i][j].is_admissible(), "node {g} {nu}");
                assert_eq!(Steady3d::new(g, nu).unwrap().node(), NODES[i][j]);
                // a/b > 1 uses the node of b/a.
                assert_eq!(Steady3d::new(1.0 / g, nu).unwrap().node(), NODES[i][j]);
            }
        }
        // Between nodes every constant lies between the four surrounding nodes' values.
        let mid = node_at(0.35, 0.125).to_array();
        let corners = [NODES[0][0], NODES[0][1], NODES[1][0], NODES[1][1]].map(|n| n.to_array());
        for k in 0..18 {
            let lo = corners.iter().map(|c| c[k]).fold(f64::INFINITY, f64::min);
            let hi = corners
                .iter()
                .map(|c| c[k])
                .fold(f64::NEG_INFINITY, f64::max);
            assert!(mid[k] >= lo - 1e-12 && mid[k] <= hi + 1e-12, "constant {k}");
        }
        assert!(node_at(0.35, 0.125).is_admissible());
        // Below g = 0.2: the g = 0.2 constants.
        assert_eq!(node_at(0.1, 0.25), NODES[0][1]);
        // Inadmissible constants are a typed error.
        let mut bad = NODES[1][1];
        bad.q3 = -1.0;
        assert!(Steady3d::with_node(0.5, 0.25, bad).is_err());
    }

    #[test]
    fn tiny_creepages_are_the_linear_theory_without_a_seam() {
        let law = Steady3d::new(0.7, 0.3).unwrap();
        let c = law.coefficients();
        let e = 1e-40;
        let l = law.loads(e, 2.0 * e, -3.0 * e);
        assert_eq!(l.fx, c.c11 * e);
        assert!((l.fy - (2.0 * c.c22 - 3.0 * c.c23) * e).abs() < 1e-12 * e);
        assert!((l.mz - (-2.0 * c.c23 - 3.0 * c.c33) * e).abs() < 1e-12 * e);
        // Just above the threshold the non-linear path agrees to rounding.
        let e = 2.0 * TINY_CREEPAGE;
        let l = law.loads(e, 2.0 * e, -3.0 * e);
        assert!((l.fx / (c.c11 * e) - 1.0).abs() < 1e-9);
        assert!((l.fy / ((2.0 * c.c22 - 3.0 * c.c23) * e) - 1.0).abs() < 1e-9);
        assert!((l.mz / ((-2.0 * c.c23 - 3.0 * c.c33) * e) - 1.0).abs() < 1e-9);
    }

    /// Largest rise of the pure spin's lateral force from `phi_n = 3` to `3e4` (log-spaced) and
    /// its value at `3e4`.
    fn spin_force_rise(law: &Steady3d) -> (f64, f64) {
        let mut last = law.loads(0.0, 0.0, 3.0).fy;
        let mut rise = 0.0f64;
        for k in 1..=40 {
            let fy = law.loads(0.0, 0.0, 3.0 * 10f64.powf(k as f64 / 10.0)).fy;
            assert!(fy >= 0.0);
            rise = rise.max(fy - last);
            last = fy;
        }
        (rise, last)
    }

    #[test]
    fn spin_force_fades_in_full_slip() {
        // In full slip of pure spin the traction carries no force: beyond the table the
        // lateral force of spin decreases (to 1e-6 of mu P: flat to 1e-10 in places) and is
        // below 1 % of mu P at phi_n = 3e4, at every node.
        for g in NODE_G {
            for nu in NODE_NU {
                let (rise, end) = spin_force_rise(&Steady3d::new(g, nu).unwrap());
                assert!(rise < 1e-6 && end < 0.01, "{g} {nu}: {rise} {end}");
            }
        }
        // Between nodes the blend of the nodes' constants lets it rise a little first
        // (measured at most 0.043 of mu P on this grid of a/b = 0.2 ... 1, nu = 0 ... 0.5); it still
        // fades.
        let mut worst = 0.0f64;
        for i in 0..=16 {
            for j in 0..=4 {
                let law = Steady3d::new(0.2 + 0.05 * i as f64, 0.125 * j as f64).unwrap();
                let (rise, end) = spin_force_rise(&law);
                assert!(end < 0.01, "{i} {j}: {end}");
                worst = worst.max(rise);
            }
        }
        assert!(worst < 0.045, "{worst}");
        // And the spin moment grows monotonically towards M_max.
        for (ab, nu) in [(1.0, 0.0), (0.5, 0.5), (0.35, 0.125), (0.7, 0.4)] {
            let law = Steady3d::new(ab, nu).unwrap();
            let mut m = 0.0;
            for k in 0..60 {
                let mz = law.loads(0.0, 0.0, 0.01 * 1.3f64.powi(k)).mz;
                assert!(mz > m && mz < law.max_moment(), "{ab} {nu} {k}");
                m = mz;
            }
        }
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
