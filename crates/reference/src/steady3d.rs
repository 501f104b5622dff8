//! Boundary-element reference curves of steady rolling with longitudinal, lateral and spin
//! creepage for elliptic contacts (`a/b = 1, 0.5, 0.2, 2, 5`, `nu = 0, 0.25, 0.5`), the table the
//! fast 3-D steady law of creep-law (`creep_law::steady3d`) is graded against.
//!
//! Each case is solved on two grids `N/2` and `N` (elements across the shorter axis; see
//! [`crate::grid::Grid::elliptic`]) and extrapolated as `2 f(N) - f(N/2)` (the grid error of the
//! steady boundary elements is `O(h)`, see the circular coefficients in the crate README). Units
//! are Kalker's normalised ones with `c = sqrt(a b)`: creepages `xi_n = xi G c^2/(mu P)`,
//! `eta_n` likewise, `phi_n = phi G c^3/(mu P)`; forces over `mu P`, moment over `mu P c`; signs
//! of this crate (creepage of q relative to p, force on p: a positive creepage gives a positive
//! force; Kalker's and CONTACT's signs are the opposite).
//!
//! The table is written by `cargo run --release -p creep-reference --example steady3d_bem` to
//! `crates/reference/data/steady3d_bem.csv` and read back by [`read_csv`].

use crate::bem::{EllipticContact, EllipticSteadySolver, SolverOptions};
use crate::error::RefError;

/// Which family of creepages a point belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Pure longitudinal creepage.
    Longitudinal,
    /// Pure lateral creepage.
    Lateral,
    /// Pure spin.
    Spin,
    /// Combined creepages.
    Combined,
}

impl Kind {
    /// Name used in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Longitudinal => "xi",
            Kind::Lateral => "eta",
            Kind::Spin => "phi",
            Kind::Combined => "combined",
        }
    }
    fn parse(s: &str) -> Result<Self, RefError> {
        [
            Kind::Longitudinal,
            Kind::Lateral,
            Kind::Spin,
            Kind::Combined,
        ]
        .into_iter()
        .find(|k| k.name() == s)
        .ok_or(RefError::InvalidParameter {
            name: "kind",
            value: f64::NAN,
            expected: "one of xi, eta, phi, combined",
        })
    }
}

/// One point of the table: the creepages and the extrapolated force and moment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Axis ratio `a/b`.
    pub ab: f64,
    /// Poisson ratio.
    pub nu: f64,
    /// Family of the point.
    pub kind: Kind,
    /// Normalised creepages `(xi_n, eta_n, phi_n)`.
    pub creepage: [f64; 3],
    /// `(Fx/(mu P), Fy/(mu P), Mz/(mu P c))`, extrapolated `2 f(N) - f(N/2)`.
    pub load: [f64; 3],
    /// The same on the finer grid `N` alone.
    pub fine: [f64; 3],
}

/// Axis ratios of the table.
pub const RATIOS: [f64; 5] = [1.0, 0.5, 0.2, 2.0, 5.0];
/// Poisson ratios of the table.
pub const POISSON: [f64; 3] = [0.0, 0.25, 0.5];
/// Pure longitudinal and lateral creepages of the table.
pub const TRANSLATION: [f64; 10] = [0.05, 0.1, 0.15, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.2];
/// Pure spins of the table.
pub const SPIN: [f64; 9] = [0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 3.0];
/// Combined creepages `(xi_n, eta_n, phi_n)` of the table.
pub const COMBINED: [[f64; 3]; 10] = [
    [0.1, 0.1, 0.0],
    [0.2, -0.1, 0.0],
    [0.3, 0.2, 0.0],
    [0.1, 0.0, 0.3],
    [0.0, 0.1, 0.3],
    [0.0, -0.1, 0.3],
    [0.2, 0.1, 0.5],
    [0.05, 0.05, 1.0],
    [0.4, 0.0, 1.0],
    [0.0, 0.3, -0.5],
];

/// Every `(kind, creepage)` of the table, in solve order.
pub fn cases() -> Vec<(Kind, [f64; 3])> {
    let mut v = Vec::new();
    v.extend(
        TRANSLATION
            .iter()
            .map(|&x| (Kind::Longitudinal, [x, 0.0, 0.0])),
    );
    v.extend(TRANSLATION.iter().map(|&x| (Kind::Lateral, [0.0, x, 0.0])));
    v.extend(SPIN.iter().map(|&x| (Kind::Spin, [0.0, 0.0, x])));
    v.extend(COMBINED.iter().map(|&c| (Kind::Combined, c)));
    v
}

/// Richardson's extrapolation of loads solved on grids `N` (`fine`) and `N/2` (`coarse`):
/// `2 f(N) - f(N/2)`, exact for a grid error linear in the element size `h`, as the steady
/// boundary elements' is (module documentation).
pub fn extrapolate(fine: (f64, f64, f64), coarse: (f64, f64, f64)) -> [f64; 3] {
    [
        2.0 * fine.0 - coarse.0,
        2.0 * fine.1 - coarse.1,
        2.0 * fine.2 - coarse.2,
    ]
}

/// The fine grid used for an axis ratio: 32 elements across the shorter axis for
/// `min(a/b, b/a) >= 0.5`,
/// 20 below (the element count grows as `N^2 b/a`).
pub fn default_grid(ab: f64) -> usize {
    if ab.min(1.0 / ab) >= 0.5 { 32 } else { 20 }
}

/// Pure spins below the table's smallest ([`SPIN`]) for the rows `a/b > 1`
/// (`data/steady3d_bem_lowspin.csv`): there the lateral force of spin peaks at `phi_n ~
/// 0.2-0.4`, and without these points nothing constrains the fitted shapes below `0.1`.
pub const LOW_SPIN: [f64; 3] = [0.025, 0.05, 0.075];

/// Solves pure spins `phis` for one `(a/b, nu)` on grids `grid/2` and `grid` (as
/// [`solve_case`], warm-started along `phis`).
pub fn solve_spins(ab: f64, nu: f64, grid: usize, phis: &[f64]) -> Result<Vec<Point>, RefError> {
    let contact = EllipticContact::normalised(nu, ab)?;
    let mut coarse = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid / 2))?;
    let mut fine = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid))?;
    let mut out = Vec::new();
    for &phi in phis {
        let p = coarse.solve_normalised(0.0, 0.0, phi)?;
        let q = fine.solve_normalised(0.0, 0.0, phi)?;
        out.push(Point {
            ab,
            nu,
            kind: Kind::Spin,
            creepage: [0.0, 0.0, phi],
            load: extrapolate(q, p),
            fine: [q.0, q.1, q.2],
        });
    }
    Ok(out)
}

/// Solves every case of the table for one `(a/b, nu)` on grids `grid/2` and `grid`.
pub fn solve_case(ab: f64, nu: f64, grid: usize) -> Result<Vec<Point>, RefError> {
    let contact = EllipticContact::normalised(nu, ab)?;
    let mut coarse = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid / 2))?;
    let mut fine = EllipticSteadySolver::new(contact, SolverOptions::with_grid(grid))?;
    let mut out = Vec::new();
    let mut last = None;
    for (kind, c) in cases() {
        if last != Some(kind) || kind == Kind::Combined {
            coarse.reset();
            fine.reset();
        }
        last = Some(kind);
        let p = coarse.solve_normalised(c[0], c[1], c[2])?;
        let q = fine.solve_normalised(c[0], c[1], c[2])?;
        let fine_v = [q.0, q.1, q.2];
        let load = extrapolate(q, p);
        out.push(Point {
            ab,
            nu,
            kind,
            creepage: c,
            load,
            fine: fine_v,
        });
    }
    Ok(out)
}

/// CSV header of the table.
pub const HEADER: &str = "ab,nu,kind,xi_n,eta_n,phi_n,fx_n,fy_n,mz_n,fx_fine,fy_fine,mz_fine";

/// One CSV line (no newline).
pub fn csv_line(p: &Point) -> String {
    format!(
        "{},{},{},{},{},{},{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}",
        p.ab,
        p.nu,
        p.kind.name(),
        p.creepage[0],
        p.creepage[1],
        p.creepage[2],
        p.load[0],
        p.load[1],
        p.load[2],
        p.fine[0],
        p.fine[1],
        p.fine[2]
    )
}

/// The data rows of a table this crate writes: blank lines, lines starting with `#` and the
/// header (starting `ab,`) skipped, each row split at its commas and checked to have `columns`
/// fields ([`RefError::InvalidGrid`] naming `name` otherwise).
pub(crate) fn table_rows<'a>(
    text: &'a str,
    name: &'static str,
    columns: usize,
) -> Result<Vec<Vec<&'a str>>, RefError> {
    let mut rows = Vec::new();
    for line in text.lines() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') || line.starts_with("ab,") {
            continue;
        }
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != columns {
            return Err(RefError::InvalidGrid {
                name,
                value: f.len(),
                expected: "the table's column count",
            });
        }
        rows.push(f);
    }
    Ok(rows)
}

/// A number of a row of [`table_rows`]; [`RefError::InvalidParameter`] naming `name` otherwise.
pub(crate) fn table_number(field: &str, name: &'static str) -> Result<f64, RefError> {
    field
        .parse::<f64>()
        .map_err(|_| RefError::InvalidParameter {
            name,
            value: f64::NAN,
            expected: "numbers as this crate writes them",
        })
}

/// Parses the table (lines starting with `#` and the header are skipped).
pub fn read_csv(text: &str) -> Result<Vec<Point>, RefError> {
    let mut v = Vec::new();
    for f in table_rows(text, "steady3d table columns", 12)? {
        let n = |i: usize| table_number(f[i], "steady3d table");
        v.push(Point {
            ab: n(0)?,
            nu: n(1)?,
            kind: Kind::parse(f[2])?,
            creepage: [n(3)?, n(4)?, n(5)?],
            load: [n(6)?, n(7)?, n(8)?],
            fine: [n(9)?, n(10)?, n(11)?],
        });
    }
    Ok(v)
}

/// The checked-in table (`data/steady3d_bem.csv`).
pub fn table() -> Result<Vec<Point>, RefError> {
    read_csv(include_str!("../data/steady3d_bem.csv"))
}

/// The checked-in pure spins below the table for `a > b` (`data/steady3d_bem_lowspin.csv`,
/// [`LOW_SPIN`]), which the fit uses with the table.
pub fn low_spin_table() -> Result<Vec<Point>, RefError> {
    read_csv(include_str!("../data/steady3d_bem_lowspin.csv"))
}

/// Largest errors of creep-law's fast 3-D steady law (`creep_law::steady3d::Steady3d`) against
/// the table for one `(a/b, nu, kind)`: force `|F_law - F_bem|` over `mu P` and moment
/// `|M_law - M_bem|` over `mu P c`, and where they occur.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LawError3d {
    /// Axis ratio.
    pub ab: f64,
    /// Poisson ratio.
    pub nu: f64,
    /// Family.
    pub kind: Kind,
    /// Largest force error over `mu P` (vector difference).
    pub force: f64,
    /// Creepages of the largest force error.
    pub force_at: [f64; 3],
    /// Largest moment error over `mu P c`.
    pub moment: f64,
    /// Creepages of the largest moment error.
    pub moment_at: [f64; 3],
}

/// Grades the fast law (`Steady3d::new`) against every point of `points`, grouped by
/// `(a/b, nu, kind)` in table order.
pub fn law_errors(points: &[Point]) -> Result<Vec<LawError3d>, RefError> {
    law_errors_of(points, creep_law::steady3d::Steady3d::new)
}

/// [`law_errors`] for the law `make(a/b, nu)` (for instance
/// `creep_law::steady3d::Steady3d::two_row_blend`, the previous round's law between rows),
/// built once per `(a/b, nu)`.
pub fn law_errors_of(
    points: &[Point],
    make: impl Fn(f64, f64) -> Result<creep_law::steady3d::Steady3d, creep_law::LawError>,
) -> Result<Vec<LawError3d>, RefError> {
    let mut out: Vec<LawError3d> = Vec::new();
    let mut built: Option<(f64, f64, creep_law::steady3d::Steady3d)> = None;
    for p in points {
        let law = match built {
            Some((ab, nu, law)) if ab == p.ab && nu == p.nu => law,
            _ => {
                let law = make(p.ab, p.nu).map_err(|_| RefError::InvalidParameter {
                    name: "a/b or nu",
                    value: p.ab,
                    expected: "in Kalker's table range",
                })?;
                built = Some((p.ab, p.nu, law));
                law
            }
        };
        let l = law.loads(p.creepage[0], p.creepage[1], p.creepage[2]);
        let ef = (l.fx - p.load[0]).hypot(l.fy - p.load[1]);
        let em = (l.mz - p.load[2]).abs();
        let slot = out
            .iter_mut()
            .find(|e| e.ab == p.ab && e.nu == p.nu && e.kind == p.kind);
        match slot {
            Some(e) => {
                if ef > e.force {
                    e.force = ef;
                    e.force_at = p.creepage;
                }
                if em > e.moment {
                    e.moment = em;
                    e.moment_at = p.creepage;
                }
            }
            None => out.push(LawError3d {
                ab: p.ab,
                nu: p.nu,
                kind: p.kind,
                force: ef,
                force_at: p.creepage,
                moment: em,
                moment_at: p.creepage,
            }),
        }
    }
    Ok(out)
}

/// The error table as markdown: one row per `(a/b, nu)`, force and moment errors per family in
/// per cent of `mu P` (`mu P c` for the moment).
pub fn error_markdown(errors: &[LawError3d]) -> String {
    let mut s = String::from(
        "| a/b | nu | long. F | lat. F | lat. M | spin F | spin M | comb. F | comb. M |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    let mut keys: Vec<(f64, f64)> = Vec::new();
    for e in errors {
        if !keys.contains(&(e.ab, e.nu)) {
            keys.push((e.ab, e.nu));
        }
    }
    let pct = |v: f64| format!("{:.2} %", 100.0 * v);
    for (ab, nu) in keys {
        let get = |k: Kind| {
            errors
                .iter()
                .find(|e| e.ab == ab && e.nu == nu && e.kind == k)
                .copied()
        };
        let (x, y, z, c) = (
            get(Kind::Longitudinal),
            get(Kind::Lateral),
            get(Kind::Spin),
            get(Kind::Combined),
        );
        let f = |e: Option<LawError3d>, m: bool| {
            e.map_or("-".into(), |e| pct(if m { e.moment } else { e.force }))
        };
        s.push_str(&format!(
            "| {ab} | {nu} | {} | {} | {} | {} | {} | {} | {} |\n",
            f(x, false),
            f(y, false),
            f(y, true),
            f(z, false),
            f(z, true),
            f(c, false),
            f(c, true)
        ));
    }
    s
}
