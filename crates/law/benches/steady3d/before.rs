//! A verbatim copy of main's `creep_law::steady3d` evaluation (commit a52a104, before issue
//! #17's one-row evaluation between rows), for the bench's before/after table in one process:
//! at a row it evaluates one row, between rows two rows' loads blended (convex weights).
//! Only the imports (`crate::` -> `creep_law::`) and the tests module differ.
#![allow(dead_code, clippy::all)]
use creep_law::LawError;
use creep_law::elliptic::complete_elliptic;
use creep_law::kalker3d::{self, KalkerCoefficients};

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

/// Normalised creepages are clamped to `[-CREEPAGE_CLAMP, CREEPAGE_CLAMP]` (deep in full slip).
pub const CREEPAGE_CLAMP: f64 = 1e6;

/// Below this normalised creepage (every component) the law returns Kalker's linear theory,
/// exact to rounding there (the non-linear terms are relatively `O(creepage)`).
pub const TINY_CREEPAGE: f64 = 1e-30;

/// The spin constants of one row `a/b = NODE_AB[i]` of the table at the contact's `nu` (module
/// documentation, "Between nodes"), with the row's weight, prepared once per contact.
#[derive(Debug, Clone, Copy, PartialEq)]
struct SpinRow {
    /// Weight of the row's spin terms in the blend (`0`: not evaluated).
    w: f64,
    /// Constants of the row interpolated in `nu` (only the spin constants `ma .. am` are used).
    n: Node,
    /// The spin force's shape as one rational function of `u = phi_n^2`, `N(u)/D(u)` with
    /// `N = sum num[k] u^k`, `D = sum den[k] u^k`: at a column of the table the node's own
    /// `(1 + p1 u + p2 u^2)/(1 + q1 u + q2 u^2 + q3 u^3)`; between columns the blend of the
    /// two nodes' shapes by their outputs, `w0 n0/d0 + w1 n1/d1 = (w0 n0 d1 + w1 n1 d0)/(d0 d1)`,
    /// multiplied out here once (every coefficient is `>= 0`: no cancellation).
    num: [f64; 6],
    den: [f64; 7],
}

/// Product of two polynomials (coefficients in increasing powers) into `out` (zeroed first).
fn poly_mul(a: &[f64], b: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|o| *o = 0.0);
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            if x * y != 0.0 {
                out[i + j] += x * y;
            }
        }
    }
}

impl SpinRow {
    /// The row from its weight, its constants interpolated in `nu`, and the spin shapes of the
    /// row's two `nu` nodes with their weights `(w0, lo), (w1, hi)` (`w1 = 0`: `lo` alone).
    fn new(w: f64, n: Node, (w0, lo): (f64, &Node), (w1, hi): (f64, &Node)) -> Self {
        let n0 = [1.0, lo.p1, lo.p2];
        let d0 = [1.0, lo.q1, lo.q2, lo.q3];
        let mut num = [0.0; 6];
        let mut den = [0.0; 7];
        if w1 == 0.0 {
            num[..3].copy_from_slice(&n0);
            den[..4].copy_from_slice(&d0);
        } else {
            let n1 = [1.0, hi.p1, hi.p2];
            let d1 = [1.0, hi.q1, hi.q2, hi.q3];
            let (mut a, mut b) = ([0.0; 6], [0.0; 6]);
            poly_mul(&n0, &d1, &mut a);
            poly_mul(&n1, &d0, &mut b);
            for k in 0..6 {
                num[k] = w0 * a[k] + w1 * b[k];
            }
            poly_mul(&d0, &d1, &mut den);
        }
        SpinRow { w, n, num, den }
    }

    /// `(N(u), D(u))` of the spin force's shape (Estrin's scheme: short dependency chains).
    #[inline(always)]
    fn shape_parts(&self, u: f64, u2: f64, u4: f64) -> (f64, f64) {
        let (a, b) = (&self.num, &self.den);
        let num = (a[0] + a[1] * u) + u2 * (a[2] + a[3] * u) + u4 * (a[4] + a[5] * u);
        let den = (b[0] + b[1] * u) + u2 * (b[2] + b[3] * u) + u4 * (b[4] + b[5] * u + b[6] * u2);
        (num, den)
    }
}

/// The spin's terms of one row (or their blend over two rows) that the translation and the
/// moment use (module documentation, steps 1-5): `w`, the capacities `w (1 - ax s^2)`,
/// `w (1 - ay s^4)` (floored at 0), `lam f_s`, `(1 - lam) f_s`, the moment-of-lateral-creepage
/// factor `1 - am s^2` and the spin moment `M_max s max(0, 1 - b2 e^2 - b8 e^8)` over `M_max`.
#[derive(Debug, Clone, Copy, Default)]
struct SpinTerms {
    w: f64,
    cap_x: f64,
    cap_y: f64,
    f_sat: f64,
    f_rest: f64,
    ml_factor: f64,
    spin_moment: f64,
}

impl SpinTerms {
    /// The terms of `row` given its spin utilisation `s`, the lateral force of pure spin `f_s`,
    /// and `(e^2, e^8)` of the translation alone.
    #[inline(always)]
    fn of_row(row: &SpinRow, s: f64, f_s: f64, e2: f64, e8: f64) -> Self {
        let n = &row.n;
        let s2 = s * s;
        let w = 1.0 + n.gam * s2;
        SpinTerms {
            w,
            cap_x: w * (1.0 - n.ax * s2).max(0.0),
            cap_y: w * (1.0 - n.ay * s2 * s2).max(0.0),
            f_sat: n.lam * f_s,
            f_rest: (1.0 - n.lam) * f_s,
            ml_factor: 1.0 - n.am * s2,
            spin_moment: s * (1.0 - n.b2 * e2 - n.b8 * e8).max(0.0),
        }
    }
}

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
pub fn node_at(ab: f64, nu: f64) -> Node {
    let mut out = [0.0; 18];
    for ((i, j), w) in surrounding(ab, nu) {
        let v = NODES[i][j].to_array();
        for k in 0..18 {
            out[k] += w * v[k];
        }
    }
    Node::from_array(out)
}

impl Steady3d {
    /// The law for the axis ratio `ab = a/b` in `[0.1, 10]` (`a` along the rolling direction)
    /// and Poisson ratio `nu` in `[0, 0.5]` (Kalker's table range), with the fitted constants.
    ///
    /// Build it once per contact shape and material pair (it interpolates the constants and
    /// prepares the rows, see the module documentation); [`Steady3d::loads`] evaluates per step.
    pub fn new(ab: f64, nu: f64) -> Result<Self, LawError> {
        kalker3d::coefficients(ab, nu)?;
        let mut law = Self::with_node(ab, nu, node_at(ab, nu))?;
        let (i, wa) = bracket(&NODE_LN_AB, ab.ln());
        let (j, wn) = bracket(&NODE_NU, nu);
        for (k, (row, w)) in [(i, 1.0 - wa), (i + 1, wa)].into_iter().enumerate() {
            let (lo, hi) = (&NODES[row][j], &NODES[row][j + 1]);
            let mut n = [0.0; 18];
            for (o, (x, y)) in n.iter_mut().zip(lo.to_array().iter().zip(hi.to_array())) {
                *o = (1.0 - wn) * x + wn * y;
            }
            // At the column nu = 0.5 the shape of `hi` alone.
            let shapes = if wn == 1.0 {
                ((1.0, hi), (0.0, lo))
            } else {
                ((1.0 - wn, lo), (wn, hi))
            };
            law.rows[k] = SpinRow::new(w, Node::from_array(n), shapes.0, shapes.1);
        }
        if law.rows[0].w == 0.0 {
            // At a row (ab at or beyond the last row): evaluate that row only.
            law.rows.swap(0, 1);
        }
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
        })
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
        if !(xi_n.is_finite() && eta_n.is_finite() && phi_n.is_finite()) {
            return Loads::default();
        }
        // Far in full slip the loads no longer change (to ~1e-6); clamping keeps the squares
        // below finite overflow for any finite input.
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
        let tx0 = c.c11 * xi_n;
        let ty0 = c.c22 * eta_n;
        let t02 = tx0 * tx0 + ty0 * ty0;
        if phi_n == 0.0 {
            return self.translation_only(xi_n, eta_n, tx0, ty0, t02);
        }
        let (e, ml) = if t02 > 0.0 {
            self.lateral_moment(xi_n, eta_n, tx0, ty0, t02)
        } else {
            (0.0, 0.0)
        };
        // 1-2 for the (one or two) rows, then 3-5 per row; between rows their loads blended.
        if self.rows[1].w == 0.0 {
            let [t] = self.spin_terms::<1>(phi_n, e);
            self.with_spin(phi_n, tx0, ty0, ml, &t)
        } else {
            let [t0, t1] = self.spin_terms::<2>(phi_n, e);
            let a = self.with_spin(phi_n, tx0, ty0, ml, &t0);
            let b = self.with_spin(phi_n, tx0, ty0, ml, &t1);
            let (w0, w1) = (self.rows[0].w, self.rows[1].w);
            Loads {
                fx: w0 * a.fx + w1 * b.fx,
                fy: w0 * a.fy + w1 * b.fy,
                mz: w0 * a.mz + w1 * b.mz,
            }
        }
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
        // 3: translation t = t'/w, t' = (C11 xi, C22 eta + lam f_s).
        let (kx, ky) = (self.n.kx, self.n.ky);
        let tx = tx0;
        let ty = ty0 + t.f_sat;
        let tm2 = tx * tx + ty * ty;
        let (mut fx, mut fy, st) = if tm2 > 0.0 {
            let q = kx * tx * tx + ky * ty * ty;
            let wq = t.w * q;
            let inv = 1.0 / (wq * tm2);
            // |t|/k = |t'|^3/(w q) and k = q/|t'|^2 with one division.
            let st = saturation_of_ratio(tm2.sqrt() * tm2 * tm2 * inv, q * wq * inv);
            let b = self.n.beta * (st * st) * (st * st);
            let dx = tx * (1.0 + b * self.turn);
            // st/|d| as (st/|d|^2) |d|: the square root and the division in parallel.
            let d2 = dx * dx + ty * ty;
            let scale = (st / d2) * d2.sqrt();
            (dx * scale, ty * scale, st)
        } else {
            (0.0, 0.0, 0.0)
        };
        fx *= t.cap_x;
        fy *= t.cap_y;
        // 4: the rest of the spin's lateral force, the friction limit.
        fy += t.f_rest * (1.0 - st).sqrt().sqrt();
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
            - self.nu_t * e * e * e * eta_n * eta_n * eta_n * q * t02 * inv;
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
