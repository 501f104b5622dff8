//! Coefficients of the fitted steady creep law ([`crate::steady_law`]), generated from the
//! project's boundary-element solution of Kalker's exact theory (crate `creep-reference`).
//! DO NOT EDIT: regenerate with the command below.
//!
//! Boundary-element curves read from crates/reference/data/steady_bem.csv; fit and table generated 2026-11-22 by
//! `creep ref fit steady --from crates/reference/data/steady_bem.csv --out crates/law/src/steady_table.rs`
//! (the curves themselves: `creep ref fit steady --grid 64 --data crates/reference/data/steady_bem.csv`,
//! grids N = 32 and 64, Richardson extrapolation 2 f(64) - f(32) of C11, x_sat and the creepage at
//! each force ratio; Poisson-ratio nodes [0.0, 0.125, 0.25, 0.375, 0.5]).
//!
//! Law: `xi_n(s) = (1 - r) Q(r)`, `r = sqrt(1 - s)`, `Q(r) = sum_k q_k r^k`, with
//! `Q(0) = x_sat` and `Q(1) = 2/C11` imposed at each node and the other coefficients
//! fitted by least squares on the relative creepage error for `s <= 0.99`.

/// Number of Poisson-ratio nodes.
pub const NODES: usize = 5;
/// Number of coefficients `q_k` of `Q(r)`.
pub const TERMS: usize = 5;
/// Poisson-ratio nodes [-].
pub const NU_NODES: [f64; NODES] = [0e0, 1.25e-1, 2.5e-1, 3.75e-1, 5e-1];
/// Boundary-element `C11` at the nodes (grid-extrapolated) [-].
pub const C11_NODES: [f64; NODES] = [
    3.39724084e0,
    3.72228611e0,
    4.11477367e0,
    4.59786793e0,
    5.2065713e0,
];
/// Boundary-element saturation creepage `xi_n` at the nodes (grid-extrapolated) [-].
pub const X_SAT_NODES: [f64; NODES] = [
    7.5694398e-1,
    6.8538217e-1,
    6.1318663e-1,
    5.4017736e-1,
    4.6607152e-1,
];
/// `q_k` at each node: `Q_NODES[node][k]`.
pub const Q_NODES: [[f64; TERMS]; NODES] = [
    [
        7.5694398e-1,
        -6.278537854402334e-1,
        1.313676658274717e0,
        -1.3914758787446178e0,
        5.374220710529684e-1,
    ],
    [
        6.8538217e-1,
        -5.474406866149996e-1,
        1.1354804205621436e0,
        -1.197799367310944e0,
        4.616816739743057e-1,
    ],
    [
        6.1318663e-1,
        -4.5017180173323534e-1,
        8.934915138574788e-1,
        -9.206024687816741e-1,
        3.501495916588239e-1,
    ],
    [
        5.4017736e-1,
        -3.2896314982257013e-1,
        5.589876750236771e-1,
        -5.212183486869173e-1,
        1.8600068453106344e-1,
    ],
    [
        4.6607152e-1,
        -1.7418448832959815e-1,
        9.123264438279167e-2,
        5.690469300404163e-2,
        -5.589441389845343e-2,
    ],
];
/// `q_k(nu) = sum_j Q_NU[k][j] nu^j`: the polynomial of degree `NODES - 1` through the
/// nodes (Lagrange interpolation in monomial form).
pub const Q_NU: [[f64; NODES]; TERMS] = [
    [
        7.5694398e-1,
        -5.702338799999978e-1,
        -1.75360000000242e-2,
        -2.196479999917974e-3,
        -1.755136000008406e-2,
    ],
    [
        -6.278537854402334e-1,
        5.896797391400002e-1,
        3.873881024034807e-1,
        2.785782272697818e-1,
        4.3456197649667655e-1,
    ],
    [
        1.313676658274717e0,
        -1.22296393434921e0,
        -1.4746635525612075e0,
        -9.131748971259507e-1,
        -2.050388742980393e0,
    ],
    [
        -1.391475878744618e0,
        1.2826723705517347e0,
        1.9599364071400647e0,
        1.010307082978547e0,
        3.0523503890473194e0,
    ],
    [
        5.374220710529685e-1,
        -4.9101502072188075e-1,
        -8.505201173080328e-1,
        -3.7280419877824994e-1,
        -1.4172547266590716e0,
    ],
];
