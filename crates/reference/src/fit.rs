//! Boundary-element tables of steady and transient rolling for grading (and fitting) the creep
//! laws of crate `creep-law`, and the constrained least-squares fit of its steady law
//! ("fitted" tier). Driven by `creep ref fit` (crate `creep-cli`).
//!
//! Everything is in normalised units of the circular contact ([`CircularContact::normalised`]):
//! force ratio `s = Q/(mu P)`, normalised creepage `xi_n = xi G a^2/(mu P)`, rolled distance in
//! contact radii. Grid extrapolation is Richardson's for an `O(h)` error, `2 f(N) - f(N/2)`
//! (the boundary-element error is first order in the element size, see the crate's README).

use crate::bem::{
    Creepage, SolverOptions, SteadySolver, TransientInput, transient_hold_creepage,
    transient_hold_force,
};
use crate::contact::CircularContact;
use crate::error::{RefError, check_range};
use crate::parallel::parallel_map;

/// Force ratios `Q/(mu P)` of the steady tables.
pub const STEADY_RATIOS: [f64; 22] = [
    0.01, 0.02, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7, 0.75, 0.8, 0.85, 0.9, 0.93,
    0.95, 0.97, 0.98, 0.99, 0.995,
];

/// Creepages beyond saturation, as multiples of the saturation creepage, of the steady tables.
pub const BEYOND_SATURATION: [f64; 5] = [1.0001, 1.02, 1.1, 1.5, 3.0];

/// Poisson ratios at which the fitted law's coefficients are tabulated (interpolation nodes).
pub const FIT_NUS: [f64; 5] = [0.0, 0.125, 0.25, 0.375, 0.5];

/// Poisson ratios between the nodes at which the interpolation in `nu` is checked.
pub const CHECK_NUS: [f64; 3] = [0.0625, 0.3, 0.45];

/// The steady creep curve of the exact theory at one Poisson ratio, on one grid (or
/// extrapolated from two).
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyCurve {
    /// Poisson ratio.
    pub nu: f64,
    /// Label of the grid: `"32"`, `"64"`, or `"ext"` for the extrapolation.
    pub grid: String,
    /// Linear creep coefficient `C11` (slope `Q/(G a^2 xi)` at `xi = 1e-7` normalised).
    pub c11: f64,
    /// Saturation creepage: the smallest normalised creepage at which every element slips.
    pub x_sat: f64,
    /// Force ratio just above the saturation creepage (below 1 when `nu > 0`: the slip turns
    /// slightly off the rolling direction).
    pub s_sat: f64,
    /// Normalised creepage at each of [`STEADY_RATIOS`].
    pub creepage: Vec<f64>,
    /// Force ratio at each creepage `k x_sat`, `k` in [`BEYOND_SATURATION`].
    pub beyond: Vec<f64>,
}

/// Smallest normalised creepage at which every element of the grid slips, by bisection to
/// `1e-7` (the solver warm-starts from the previous solution).
fn saturation(s: &mut SteadySolver) -> Result<f64, RefError> {
    let nu = s.contact().nu();
    // Closed-form bound (uncoupled theory): 3 (4 - 3 nu)/16, see `creep_law::steady_law`.
    let (mut lo, mut hi) = (
        0.3 * 3.0 * (4.0 - 3.0 * nu) / 16.0,
        3.0 * (4.0 - 3.0 * nu) / 16.0,
    );
    let all_slip = |s: &mut SteadySolver, x: f64| -> Result<bool, RefError> {
        Ok(s.solve(Creepage::longitudinal(x))?
            .traction
            .slip
            .iter()
            .all(|&b| b))
    };
    while !all_slip(s, hi)? {
        hi *= 1.2;
    }
    while hi - lo > 1e-7 {
        let m = 0.5 * (lo + hi);
        if all_slip(s, m)? {
            hi = m;
        } else {
            lo = m;
        }
    }
    Ok(hi)
}

/// Solves the steady curve of the normalised contact at `nu` on an `N = grid` grid.
pub fn steady_curve(nu: f64, grid: usize) -> Result<SteadyCurve, RefError> {
    let c = CircularContact::normalised(nu)?;
    let mut s = SteadySolver::new(c, SolverOptions::with_grid(grid))?;
    let e = 1e-7;
    let c11 = s.solve(Creepage::longitudinal(e))?.fx / e;
    let mut creepage = Vec::with_capacity(STEADY_RATIOS.len());
    for r in STEADY_RATIOS {
        creepage.push(s.solve_force(r)?.0);
    }
    let x_sat = saturation(&mut s)?;
    let mut beyond = Vec::with_capacity(BEYOND_SATURATION.len());
    for k in BEYOND_SATURATION {
        beyond.push(s.solve(Creepage::longitudinal(k * x_sat))?.fx);
    }
    Ok(SteadyCurve {
        nu,
        grid: grid.to_string(),
        c11,
        x_sat,
        s_sat: beyond[0],
        creepage,
        beyond,
    })
}

/// Richardson extrapolation `2 f(fine) - f(coarse)` of every entry (creepages at fixed force,
/// `C11`, `x_sat`, `s_sat`; the forces beyond saturation at fixed multiples of each grid's own
/// saturation creepage).
pub fn extrapolate(fine: &SteadyCurve, coarse: &SteadyCurve) -> SteadyCurve {
    let r = |f: f64, c: f64| 2.0 * f - c;
    SteadyCurve {
        nu: fine.nu,
        grid: "ext".into(),
        c11: r(fine.c11, coarse.c11),
        x_sat: r(fine.x_sat, coarse.x_sat),
        s_sat: r(fine.s_sat, coarse.s_sat).min(1.0),
        creepage: fine
            .creepage
            .iter()
            .zip(&coarse.creepage)
            .map(|(f, c)| r(*f, *c))
            .collect(),
        beyond: fine
            .beyond
            .iter()
            .zip(&coarse.beyond)
            .map(|(f, c)| r(*f, *c).min(1.0))
            .collect(),
    }
}

/// Steady curves at `nus` on grids `grid / 2` and `grid`, and their extrapolation, computed on
/// `threads` threads: for each `nu`, `[coarse, fine, extrapolated]`.
pub fn steady_curves(
    nus: &[f64],
    grid: usize,
    threads: usize,
) -> Result<Vec<[SteadyCurve; 3]>, RefError> {
    for &nu in nus {
        check_range("nu", nu, 0.0, 0.5, "in [0, 0.5]")?;
    }
    let one = |&nu: &f64| -> Result<[SteadyCurve; 3], RefError> {
        let coarse = steady_curve(nu, grid / 2)?;
        let fine = steady_curve(nu, grid)?;
        let ext = extrapolate(&fine, &coarse);
        Ok([coarse, fine, ext])
    };
    parallel_map(nus, threads, one)
}

/// One transient case of the tables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TransientCase {
    /// Force held at this `Q/(mu P)` from the first step on (applied by that step's shift).
    HoldForce(f64),
    /// Creepage held from zero traction at the steady creepage of this `Q/(mu P)` (grid's own).
    HoldCreepage(f64),
}

/// A transient curve of the exact theory: one entry per step of rolling distance `dq`.
#[derive(Debug, Clone, PartialEq)]
pub struct TransientCurve {
    /// Poisson ratio.
    pub nu: f64,
    /// Grid label (`"ext"` for the extrapolation).
    pub grid: String,
    /// The case.
    pub case: TransientCase,
    /// Steady creepage at the case's force ratio (normalised, same grid).
    pub steady_creepage: f64,
    /// Rolled distance at the end of each step, in contact radii.
    pub rolled: Vec<f64>,
    /// Normalised creepage of each step (`dW/dq` over `mu P/(G a^2)`).
    pub creepage: Vec<f64>,
    /// Force ratio after each step.
    pub force: Vec<f64>,
}

/// Transient curve at `nu` on an `N = grid` grid, rolling `dq` contact radii per step for
/// `steps` steps.
pub fn transient_curve(
    nu: f64,
    grid: usize,
    case: TransientCase,
    dq: f64,
    steps: usize,
) -> Result<TransientCurve, RefError> {
    let c = CircularContact::normalised(nu)?;
    let opts = SolverOptions::with_grid(grid);
    let mut st = SteadySolver::new(c, opts)?;
    let ratio = match case {
        TransientCase::HoldForce(r) | TransientCase::HoldCreepage(r) => r,
    };
    let (steady_creepage, _) = st.solve_force(ratio)?;
    let input = TransientInput {
        contact: c,
        options: opts,
        step: dq,
        steps,
    };
    let rec = match case {
        TransientCase::HoldForce(r) => transient_hold_force(&input, r)?,
        TransientCase::HoldCreepage(_) => {
            transient_hold_creepage(&input, Creepage::longitudinal(steady_creepage))?
        }
    };
    Ok(TransientCurve {
        nu,
        grid: grid.to_string(),
        case,
        steady_creepage,
        rolled: rec.iter().map(|r| r.rolled).collect(),
        creepage: rec.iter().map(|r| r.creepage).collect(),
        force: rec.iter().map(|r| r.fx_over_mu_p).collect(),
    })
}

/// Transient curves on grids `grid / 2` and `grid` (same `dq`) for every `(nu, case)`, on
/// `threads` threads: `[coarse, fine]`. No extrapolation: with `dq` the fine grid's element side
/// the fine run is the steady discretisation (it tends to that grid's steady solution), the
/// coarse run shows the grid sensitivity of the curves' shape.
pub fn transient_curves(
    nus: &[f64],
    cases: &[TransientCase],
    grid: usize,
    dq: f64,
    steps: usize,
    threads: usize,
) -> Result<Vec<[TransientCurve; 2]>, RefError> {
    let jobs: Vec<(f64, TransientCase)> = nus
        .iter()
        .flat_map(|&nu| cases.iter().map(move |&c| (nu, c)))
        .collect();
    parallel_map(&jobs, threads, |&(nu, case)| {
        let coarse = transient_curve(nu, grid / 2, case, dq, steps)?;
        let fine = transient_curve(nu, grid, case, dq, steps)?;
        Ok([coarse, fine])
    })
}

/// Column header of the transient table CSV written by [`transient_csv`].
pub const TRANSIENT_CSV_HEADER: &str =
    "nu,grid,case,q_over_mu_p,steady_creepage_n,step,rolled_over_a,creepage_n,force_over_mu_p";

/// Writes transient curves as CSV (after [`TRANSIENT_CSV_HEADER`]); `case` is `force` (held
/// force) or `creepage` (held at the steady creepage of `q_over_mu_p`).
pub fn transient_csv(curves: &[TransientCurve]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "{TRANSIENT_CSV_HEADER}");
    for c in curves {
        let (case, r) = match c.case {
            TransientCase::HoldForce(r) => ("force", r),
            TransientCase::HoldCreepage(r) => ("creepage", r),
        };
        for i in 0..c.rolled.len() {
            let _ = writeln!(
                s,
                "{},{},{case},{r},{:.8},{},{:.6},{:.8},{:.8}",
                c.nu,
                c.grid,
                c.steady_creepage,
                i + 1,
                c.rolled[i],
                c.creepage[i],
                c.force[i]
            );
        }
    }
    s
}

/// Reads the CSV of [`transient_csv`] back (lines starting with `#` are comments).
pub fn read_transient_csv(text: &str) -> Result<Vec<TransientCurve>, RefError> {
    let bad = |what: &'static str| RefError::InvalidParameter {
        name: "transient table CSV",
        value: f64::NAN,
        expected: what,
    };
    let mut out: Vec<TransientCurve> = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line == TRANSIENT_CSV_HEADER {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 9 {
            return Err(bad("9 columns"));
        }
        let num = |s: &str| s.parse::<f64>().map_err(|_| bad("numbers"));
        let (nu, grid, r) = (num(f[0])?, f[1], num(f[3])?);
        let case = match f[2] {
            "force" => TransientCase::HoldForce(r),
            "creepage" => TransientCase::HoldCreepage(r),
            _ => return Err(bad("case force or creepage")),
        };
        let step = num(f[5])?;
        if step == 1.0 {
            out.push(TransientCurve {
                nu,
                grid: grid.to_string(),
                case,
                steady_creepage: num(f[4])?,
                rolled: Vec::new(),
                creepage: Vec::new(),
                force: Vec::new(),
            });
        }
        let c = out.last_mut().ok_or(bad("curves starting at step 1"))?;
        c.rolled.push(num(f[6])?);
        c.creepage.push(num(f[7])?);
        c.force.push(num(f[8])?);
    }
    Ok(out)
}

/// Column header of the steady table CSV written by [`steady_csv`].
pub const STEADY_CSV_HEADER: &str = "nu,grid,kind,q_over_mu_p,creepage_n";

/// Writes steady curves as CSV rows `nu,grid,kind,q_over_mu_p,creepage_n` (after
/// [`STEADY_CSV_HEADER`]), with `kind` one of `slope` (`q_over_mu_p` holds `C11`, `creepage_n`
/// is 1), `curve` (force-prescribed solves), `saturation` (`x_sat`, force just above it) and
/// `beyond` (creepage-prescribed solves beyond saturation).
pub fn steady_csv(curves: &[SteadyCurve]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let _ = writeln!(s, "{STEADY_CSV_HEADER}");
    for c in curves {
        let (nu, g) = (c.nu, &c.grid);
        let _ = writeln!(s, "{nu},{g},slope,{:.8},1", c.c11);
        for (r, x) in STEADY_RATIOS.iter().zip(&c.creepage) {
            let _ = writeln!(s, "{nu},{g},curve,{r},{x:.8}");
        }
        let _ = writeln!(s, "{nu},{g},saturation,{:.8},{:.8}", c.s_sat, c.x_sat);
        for (k, q) in BEYOND_SATURATION.iter().zip(&c.beyond) {
            let _ = writeln!(s, "{nu},{g},beyond,{q:.8},{:.8}", k * c.x_sat);
        }
    }
    s
}

/// Reads the CSV of [`steady_csv`] back (lines starting with `#` are comments).
pub fn read_steady_csv(text: &str) -> Result<Vec<SteadyCurve>, RefError> {
    let bad = |what: &'static str| RefError::InvalidParameter {
        name: "steady table CSV",
        value: f64::NAN,
        expected: what,
    };
    let mut out: Vec<SteadyCurve> = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line == STEADY_CSV_HEADER {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != 5 {
            return Err(bad("5 columns nu,grid,kind,q_over_mu_p,creepage_n"));
        }
        let num = |s: &str| s.parse::<f64>().map_err(|_| bad("numbers"));
        let (nu, grid, kind, q, x) = (num(f[0])?, f[1], f[2], num(f[3])?, num(f[4])?);
        let fresh = out.last().is_none_or(|c| c.nu != nu || c.grid != grid);
        if fresh {
            out.push(SteadyCurve {
                nu,
                grid: grid.to_string(),
                c11: f64::NAN,
                x_sat: f64::NAN,
                s_sat: f64::NAN,
                creepage: Vec::new(),
                beyond: Vec::new(),
            });
        }
        let c = out.last_mut().ok_or(bad("rows"))?;
        match kind {
            "slope" => c.c11 = q,
            "curve" => c.creepage.push(x),
            "saturation" => {
                c.x_sat = x;
                c.s_sat = q;
            }
            "beyond" => c.beyond.push(q),
            _ => return Err(bad("kind slope, curve, saturation or beyond")),
        }
    }
    for c in &out {
        if c.creepage.len() != STEADY_RATIOS.len()
            || c.beyond.len() != BEYOND_SATURATION.len()
            || !c.c11.is_finite()
            || !c.x_sat.is_finite()
        {
            return Err(bad("complete curves (the rows of `steady_csv`)"));
        }
    }
    Ok(out)
}

/// Number of coefficients of the fitted law's polynomial `Q(r)` (degree `FIT_TERMS - 1`).
pub const FIT_TERMS: usize = 5;

/// The fitted steady law of crate `creep-law` (`creep_law::steady_law`), tabulated at the
/// Poisson-ratio nodes: `xi_n(s) = (1 - r) Q(r)`, `r = sqrt(1 - s)`,
/// `Q(r) = sum_k q_k r^k`, with the constraints `Q(0) = x_sat` (the saturation creepage) and
/// `Q(1) = 2 / C11` (Kalker's linear slope, since `1 - r ~ s/2` as `s -> 0`); the remaining
/// `FIT_TERMS - 2` coefficients minimise the squared relative creepage error over the fitted
/// force ratios.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyFit {
    /// Poisson-ratio nodes.
    pub nus: Vec<f64>,
    /// `C11` at the nodes.
    pub c11: Vec<f64>,
    /// Saturation creepage at the nodes.
    pub x_sat: Vec<f64>,
    /// `q_k` at each node.
    pub q: Vec<[f64; FIT_TERMS]>,
    /// For each `k`, the monomial coefficients in `nu` (ascending powers) of the polynomial
    /// through the nodes' `q_k` (Lagrange interpolation, degree `nodes - 1`).
    pub q_nu: Vec<Vec<f64>>,
    /// Largest force ratio used in the fit.
    pub s_max: f64,
}

/// Solves the dense linear system `m x = b` by Gaussian elimination with partial pivoting.
fn solve_dense(mut m: Vec<Vec<f64>>, mut b: Vec<f64>) -> Result<Vec<f64>, RefError> {
    let n = b.len();
    for col in 0..n {
        let piv = (col..n)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .unwrap_or(col);
        if m[piv][col].abs() < 1e-300 {
            return Err(RefError::NoConvergence {
                solver: "fit: singular normal equations",
                iterations: col,
                residual: 0.0,
            });
        }
        m.swap(col, piv);
        b.swap(col, piv);
        let (top, rest) = m.split_at_mut(col + 1);
        let pivot_row = &top[col];
        for (i, row) in rest.iter_mut().enumerate() {
            let f = row[col] / pivot_row[col];
            for (x, p) in row.iter_mut().zip(pivot_row).skip(col) {
                *x -= f * p;
            }
            b[col + 1 + i] -= f * b[col];
        }
    }
    let mut x = vec![0.0; n];
    for row in (0..n).rev() {
        let s: f64 = (row + 1..n).map(|k| m[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / m[row][row];
    }
    Ok(x)
}

/// `Q(r)` coefficients for one curve: `Q(r) = x_sat + (2/C11 - x_sat) r + r (1 - r) B(r)`
/// with `B(r) = sum_j b_j r^j` (`FIT_TERMS - 2` terms) by least squares on the relative
/// creepage error at the force ratios `<= s_max`.
fn fit_one(c: &SteadyCurve, s_max: f64) -> Result<[f64; FIT_TERMS], RefError> {
    let nb = FIT_TERMS - 2;
    let (x0, x1) = (c.x_sat, 2.0 / c.c11 - c.x_sat);
    let mut ata = vec![vec![0.0; nb]; nb];
    let mut atb = vec![0.0; nb];
    for (&s, &x) in STEADY_RATIOS.iter().zip(&c.creepage) {
        if s > s_max {
            continue;
        }
        let r = (1.0 - s).sqrt();
        let base = (1.0 - r) * (x0 + x1 * r);
        // Row: d xi / d b_j = (1 - r) r (1 - r) r^j, relative to x.
        let row: Vec<f64> = (0..nb)
            .map(|j| (1.0 - r) * r * (1.0 - r) * r.powi(j as i32) / x)
            .collect();
        let rhs = (x - base) / x;
        for i in 0..nb {
            for j in 0..nb {
                ata[i][j] += row[i] * row[j];
            }
            atb[i] += row[i] * rhs;
        }
    }
    let b = solve_dense(ata, atb)?;
    // Expand to monomials in r: x0 + x1 r + (r - r^2) sum b_j r^j.
    let mut q = [0.0; FIT_TERMS];
    q[0] = x0;
    q[1] = x1;
    for (j, bj) in b.iter().enumerate() {
        q[j + 1] += bj;
        q[j + 2] -= bj;
    }
    Ok(q)
}

/// Fits the law at each node curve (extrapolated curves at [`FIT_NUS`], in order).
pub fn fit_steady(curves: &[SteadyCurve], s_max: f64) -> Result<SteadyFit, RefError> {
    let nus: Vec<f64> = curves.iter().map(|c| c.nu).collect();
    let q = curves
        .iter()
        .map(|c| fit_one(c, s_max))
        .collect::<Result<Vec<_>, _>>()?;
    // Interpolating polynomial in nu through the nodes, monomial form (Vandermonde system).
    let n = nus.len();
    let vander: Vec<Vec<f64>> = nus
        .iter()
        .map(|nu| (0..n).map(|j| nu.powi(j as i32)).collect())
        .collect();
    let q_nu = (0..FIT_TERMS)
        .map(|k| solve_dense(vander.clone(), q.iter().map(|c| c[k]).collect()))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(SteadyFit {
        nus,
        c11: curves.iter().map(|c| c.c11).collect(),
        x_sat: curves.iter().map(|c| c.x_sat).collect(),
        q,
        q_nu,
        s_max,
    })
}

impl SteadyFit {
    /// The law's normalised creepage at force ratio `s` in `[0, 1]` and `nu` in `[0, 0.5]`
    /// (the generator's own evaluation, for its report; crate `creep-law` evaluates the table).
    pub fn creepage_n(&self, s: f64, nu: f64) -> f64 {
        let r = (1.0 - s.clamp(0.0, 1.0)).sqrt();
        let q: Vec<f64> = self
            .q_nu
            .iter()
            .map(|c| c.iter().rev().fold(0.0, |acc, v| acc * nu + v))
            .collect();
        (1.0 - r) * q.iter().rev().fold(0.0, |acc, v| acc * r + v)
    }
}

/// The Rust source of `creep-law`'s `steady_table` module for `fit`, with `provenance` (comment
/// lines, without the `//!`) in its header.
pub fn rust_table(fit: &SteadyFit, provenance: &str) -> String {
    use std::fmt::Write as _;
    let n = fit.nus.len();
    let list = |v: &[f64]| -> String {
        v.iter()
            .map(|x| format!("{x:e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "//! Coefficients of the fitted steady creep law ([`crate::steady_law`]), generated from the\n\
         //! project's boundary-element solution of Kalker's exact theory (crate `creep-reference`).\n\
         //! DO NOT EDIT: regenerate with the command below.\n//!"
    );
    for line in provenance.lines() {
        let _ = writeln!(s, "//! {line}");
    }
    let _ = writeln!(
        s,
        "//!\n//! Law: `xi_n(s) = (1 - r) Q(r)`, `r = sqrt(1 - s)`, `Q(r) = sum_k q_k r^k`, with\n\
         //! `Q(0) = x_sat` and `Q(1) = 2/C11` imposed at each node and the other coefficients\n\
         //! fitted by least squares on the relative creepage error for `s <= {}`.\n",
        fit.s_max
    );
    let _ = writeln!(
        s,
        "/// Number of Poisson-ratio nodes.\npub const NODES: usize = {n};"
    );
    let _ = writeln!(
        s,
        "/// Number of coefficients `q_k` of `Q(r)`.\npub const TERMS: usize = {FIT_TERMS};"
    );
    let _ = writeln!(
        s,
        "/// Poisson-ratio nodes [-].\npub const NU_NODES: [f64; NODES] = [{}];",
        list(&fit.nus)
    );
    let _ = writeln!(
        s,
        "/// Boundary-element `C11` at the nodes (grid-extrapolated) [-].\npub const C11_NODES: [f64; NODES] = [{}];",
        list(&fit.c11)
    );
    let _ = writeln!(
        s,
        "/// Boundary-element saturation creepage `xi_n` at the nodes (grid-extrapolated) [-].\npub const X_SAT_NODES: [f64; NODES] = [{}];",
        list(&fit.x_sat)
    );
    let _ = writeln!(
        s,
        "/// `q_k` at each node: `Q_NODES[node][k]`.\npub const Q_NODES: [[f64; TERMS]; NODES] = ["
    );
    for q in &fit.q {
        let _ = writeln!(s, "    [{}],", list(q));
    }
    let _ = writeln!(s, "];");
    let _ = writeln!(
        s,
        "/// `q_k(nu) = sum_j Q_NU[k][j] nu^j`: the polynomial of degree `NODES - 1` through the\n\
         /// nodes (Lagrange interpolation in monomial form).\npub const Q_NU: [[f64; NODES]; TERMS] = ["
    );
    for q in &fit.q_nu {
        let _ = writeln!(s, "    [{}],", list(q));
    }
    let _ = writeln!(s, "];");
    s
}
