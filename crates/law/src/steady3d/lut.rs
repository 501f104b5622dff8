//! The tabulated 3-D steady law: per `(a/b, nu)` node, the boundary-element loads on a grid of
//! the normalised creepages; refined once, at first use, onto a read grid (along the spin the
//! midpoints added, thirds in `|phi| = 0.2 ... 0.26`, along `xi` and `eta` points in the widest
//! cells; cubic through the four
//! nearest computed points), and read trilinearly (module documentation of
//! [`crate::steady3d`], "The table").

/// Non-negative normalised longitudinal and lateral creepages of the table's grid (both axes):
/// geometric below `0.1` (the secant slope of the first cell within 0.5 % of Kalker's linear
/// theory), dense where the loads curve most (the onset of full slip of translation,
/// `0.3 ... 0.9`), every node a multiple of [`BUCKET`].
pub const LUT_XI: [f64; 19] = [
    0.0, 0.004, 0.012, 0.036, 0.068, 0.1, 0.14, 0.2, 0.24, 0.3, 0.38, 0.46, 0.54, 0.62, 0.72, 0.86,
    1.06, 1.4, 2.0,
];
/// Normalised spins of the table's grid (both signs): denser at `0.3 ... 0.9`, where a lateral
/// creepage against the spin turns the lateral force fast; every node a multiple of [`BUCKET`].
pub const LUT_PHI: [f64; 43] = [
    -4.0, -3.0, -2.3, -1.7, -1.3, -1.0, -0.88, -0.76, -0.68, -0.62, -0.56, -0.48, -0.42, -0.36,
    -0.3, -0.26, -0.2, -0.1, -0.036, -0.012, -0.004, 0.0, 0.004, 0.012, 0.036, 0.1, 0.2, 0.26, 0.3,
    0.36, 0.42, 0.48, 0.56, 0.62, 0.68, 0.76, 0.88, 1.0, 1.3, 1.7, 2.3, 3.0, 4.0,
];
/// Width of the buckets that locate a creepage's cell in one multiplication.
pub const BUCKET: f64 = 0.004;
/// Points of one node's table (`xi x eta x phi`).
pub const LUT_LEN: usize = LUT_XI.len() * LUT_XI.len() * LUT_PHI.len();

use super::Loads;
use std::sync::{Mutex, OnceLock};

/// Points of the read grid [`FINE_PHI`] per cell of [`LUT_PHI`] (2: the midpoints added), but
/// in the cells of [`PHI_THIRDS`] (3). Finer read grids everywhere are closer to the cubic too,
/// but they move the light ball on the heavy slab of creep-scenes' hard cases into a step
/// where Rapier's penetration correction lifts the ball 9 um further than in its Coulomb twin
/// (2.5e-5 of its energy in that step, returned over the next ones), which the single-step
/// energy check refuses.
pub const REFINE: usize = 2;
/// The lower computed spins of the cells read in thirds: `|phi_n|` from `0.2` to `0.26`,
/// where the pure spin's lateral force of `a > b` peaks with a small lateral creepage and bends
/// faster than the midpoint follows (the error map, `a/b = 5`, `nu = 0`, `(0, -0.15, 0.25)`:
/// 2.07 % of `mu P` read at the midpoint, 1.78 % in thirds).
pub const PHI_THIRDS: [f64; 2] = [-0.26, 0.2];
/// Spins of the read grid [`FINE_PHI`]: the computed ones, `REFINE - 1` between each two, one
/// more in each cell of [`PHI_THIRDS`].
pub const FINE_NP: usize = REFINE * (LUT_PHI.len() - 1) + 1 + PHI_THIRDS.len();
/// Spins per `(xi, eta)` line of a read table.
const NP: usize = FINE_NP;
/// The read grid of `|xi_n|` and `|eta_n|`: [`LUT_XI`] with points added in its widest cells
/// (`0.86 ... 2`, where full slip of translation sets in and the loads bend fastest: `0.86 ...
/// 1.06` halved, `1.06 ... 1.4` quartered, `1.4 ... 2` in three) and in the cell `0.14 ... 0.2`
/// (where the lateral force of `a/b = 5` turns against a small spin), each filled by the cubic
/// through the four nearest computed creepages (the quadratic through the last three in the
/// end cell), every point a multiple of [`BUCKET`].
pub const FINE_XI: [f64; 26] = [
    0.0, 0.004, 0.012, 0.036, 0.068, 0.1, 0.14, 0.172, 0.2, 0.24, 0.3, 0.38, 0.46, 0.54, 0.62,
    0.72, 0.86, 0.96, 1.06, 1.152, 1.232, 1.32, 1.4, 1.6, 1.8, 2.0,
];
/// Creepages per axis of a read table.
const NX: usize = FINE_XI.len();
/// Points per `xi` plane of a read table.
const NPLANE: usize = NX * NP;
/// Points of one node's read table ([`FINE_XI`] `x` [`FINE_XI`] `x` [`FINE_PHI`]).
pub const FINE_LEN: usize = NX * NPLANE;
/// Width of the spin's buckets: every node of [`FINE_PHI`] is a multiple of it.
const PHI_BUCKET: f64 = BUCKET / REFINE as f64;
/// Buckets over `[0, 2]` (xi, eta) and `[-4, 4]` (phi).
const XI_BUCKETS: usize = 500;
const PHI_BUCKETS: usize = 2000 * REFINE;
/// Largest tabulated `|xi_n|, |eta_n|` and `|phi_n|` (the box of the table).
pub const XI_MAX: f64 = 2.0;
/// Largest tabulated `|phi_n|`.
pub const PHI_MAX: f64 = 4.0;

/// One node's loads: `[Fx/(mu P), Fy/(mu P), Mz/(mu P c)]` at `(LUT_XI[i], LUT_XI[j], LUT_PHI[k])`,
/// index `(i LUT_XI.len() + j) LUT_PHI.len() + k` (project signs, `c = sqrt(a b)`).
pub type Table = [[f32; 3]; LUT_LEN];

/// One node's read table: [`Table`] on the grid `(FINE_XI, FINE_XI, FINE_PHI)`, index
/// `(i FINE_XI.len() + j) FINE_NP + k`.
pub type Fine = [[f32; 3]; FINE_LEN];

/// The read grid of the spin: [`LUT_PHI`] with `REFINE - 1` equally spaced spins in each cell
/// (two in the cells of [`PHI_THIRDS`]).
pub static FINE_PHI: [f64; FINE_NP] = fine_grid(&LUT_PHI);

const fn fine_grid<const N: usize, const M: usize>(nodes: &[f64; N]) -> [f64; M] {
    let mut out = [0.0; M];
    let (mut k, mut i) = (0, 0);
    while k < N {
        out[i] = nodes[k];
        i += 1;
        if k + 1 < N {
            let parts = if nodes[k] == PHI_THIRDS[0] || nodes[k] == PHI_THIRDS[1] {
                REFINE + 1
            } else {
                REFINE
            };
            let mut r = 1;
            while r < parts {
                out[i] = nodes[k] + (nodes[k + 1] - nodes[k]) * r as f64 / parts as f64;
                i += 1;
                r += 1;
            }
        }
        k += 1;
    }
    out
}

/// A computed node of the table: the contact's `(a/b, nu)`, the boundary elements' grid
/// (`N` across the shorter axis, extrapolated with `N/2`) and the loads.
#[derive(Debug)]
pub struct LutNode {
    /// Axis ratio `a/b` (`a` along the rolling direction).
    pub ab: f64,
    /// Poisson ratio.
    pub nu: f64,
    /// Boundary-element grid `N`.
    pub grid: usize,
    /// The loads on the grid.
    pub loads: &'static Table,
}

/// The cell `i` (`nodes[i] <= x < nodes[i + 1]`, the last cell for `x = nodes[last]`) of each
/// bucket `[b h, (b + 1) h)` over `[x0, x0 + B h]` (every node is a multiple of the width `h`,
/// so no bucket straddles a node).
const fn cells<const N: usize, const B: usize>(nodes: &[f64; N], x0: f64, h: f64) -> [u8; B] {
    let mut out = [0u8; B];
    let mut b = 0;
    while b < B {
        let x = x0 + (b as f64 + 0.5) * h;
        let mut i = 0;
        while i + 2 < N && nodes[i + 1] <= x {
            i += 1;
        }
        out[b] = i as u8;
        b += 1;
    }
    out
}

/// `1/(nodes[i + 1] - nodes[i])`.
const fn inverse_steps<const N: usize>(nodes: &[f64; N]) -> [f64; N] {
    let mut out = [0.0; N];
    let mut i = 0;
    while i + 1 < N {
        out[i] = 1.0 / (nodes[i + 1] - nodes[i]);
        i += 1;
    }
    out
}

static XI_CELL: [u8; XI_BUCKETS + 1] = cells(&FINE_XI, 0.0, BUCKET);
static PHI_CELL: [u8; PHI_BUCKETS + 1] = cells(&FINE_PHI, -PHI_MAX, PHI_BUCKET);
static XI_INV: [f64; NX] = inverse_steps(&FINE_XI);
static PHI_INV: [f64; FINE_NP] = inverse_steps(&FINE_PHI);

/// A computed table on the read grid: the computed points as they are; between the computed
/// spins the cubic through the cell's two computed spins and one on each side (Lagrange on the
/// non-uniform grid; linear in the end cells); then at the added `xi_n`, and at the added
/// `eta_n`, the cubic through the four computed creepages around it (the quadratic through the
/// last three in the end cell, [`FINE_XI`]); each added point's force scaled onto `|F| = mu P`
/// where the polynomial overshoots it; at `eta_n = 0` the reflection `phi -> -phi` kept exact.
/// Linear interpolation between the computed points misses the loads where they bend fast (the
/// pure spin's lateral force of `a > b` peaks between the spins `0.2` and `0.26`; the loads
/// saturate between `xi_n = 1.06` and `2` near full slip); the polynomials' points follow the
/// bend at the trilinear read's cost.
pub fn refine(table: &Table) -> Box<Fine> {
    let n = LUT_PHI.len();
    let nx = LUT_XI.len();
    // The computed (xi, eta) lines on the read grid of the spin (linear in its end cells).
    let pw = grid_weights(&FINE_PHI, &LUT_PHI, false);
    let mut lines = vec![[0.0f32; 3]; nx * nx * NP];
    for line in 0..nx * nx {
        for (f, &w) in pw.iter().enumerate() {
            lines[line * NP + f] = along(table, line * n, 1, w);
        }
        if line % nx == 0 {
            symmetrise(&mut lines[line * NP..(line + 1) * NP]);
        }
    }
    // Along xi, then along eta: the computed creepages as they are, the added ones from the
    // computed ones around them (the quadratic in the end cell).
    let xw = grid_weights(&FINE_XI, &LUT_XI, true);
    let mut half = vec![[0.0f32; 3]; NX * nx * NP];
    for (fi, &w) in xw.iter().enumerate() {
        for j in 0..nx {
            for f in 0..NP {
                half[(fi * nx + j) * NP + f] = along(&lines, j * NP + f, nx * NP, w);
            }
        }
    }
    let mut out: Box<Fine> = vec![[0.0f32; 3]; FINE_LEN]
        .into_boxed_slice()
        .try_into()
        .unwrap_or_else(|_| unreachable!("FINE_LEN elements"));
    for fi in 0..NX {
        for (fj, &w) in xw.iter().enumerate() {
            for f in 0..NP {
                out[(fi * NX + fj) * NP + f] = along(&half, fi * nx * NP + f, NP, w);
            }
        }
        // At eta_n = 0 (a computed creepage) the added xi's lines keep the reflection exact.
        symmetrise(&mut out[fi * NPLANE..fi * NPLANE + NP]);
    }
    out
}

/// The loads at a point of the read grid along one axis, from the points `base + k stride` of
/// `src` on the computed grid: the computed one as it is (`m = 1`), or the weighted sum of `m`
/// from `k0` on, onto Coulomb's bound ([`grid_weights`]).
fn along(src: &[[f32; 3]], base: usize, stride: usize, (k0, w, m): Weights) -> [f32; 3] {
    if m == 1 {
        return src[base + k0 * stride];
    }
    onto_coulomb([0, 1, 2].map(|c| {
        (0..m)
            .map(|q| w[q] * f64::from(src[base + (k0 + q) * stride][c]))
            .sum::<f64>()
    }))
}

/// Lagrange's weights at `t` of the polynomial through the points `x` (two to four; the
/// unused weights zero).
pub(crate) fn lagrange(x: &[f64], t: f64) -> [f64; 4] {
    std::array::from_fn(|j| {
        if j >= x.len() {
            return 0.0;
        }
        (0..x.len())
            .filter(|&m| m != j)
            .map(|m| (t - x[m]) / (x[j] - x[m]))
            .product()
    })
}

/// One point of a read grid from its computed grid: the first computed point it is read
/// from, the weights and their number.
type Weights = (usize, [f64; 4], usize);

/// Per point of the read grid `fine`: the first point of the computed grid `nodes` it is read
/// from, the weights and their number (1 at a computed point; the cubic through the cell's two
/// computed points and one on each side; linear in the first cell, and in the last, or with
/// `quadratic_end` the quadratic through the last three).
fn grid_weights(fine: &[f64], nodes: &[f64], quadratic_end: bool) -> Vec<Weights> {
    let n = nodes.len();
    fine.iter()
        .map(|&t| {
            if let Some(k) = nodes.iter().position(|&x| x == t) {
                return (k, [1.0, 0.0, 0.0, 0.0], 1);
            }
            let k = nodes.iter().rposition(|&x| x < t).unwrap_or(0);
            let (k0, x) = if k == 0 || (k + 2 == n && !quadratic_end) {
                (k, &nodes[k..k + 2])
            } else if k + 2 == n {
                (k - 1, &nodes[k - 1..k + 2])
            } else {
                (k - 1, &nodes[k - 1..k + 3])
            };
            (k0, lagrange(x, t), x.len())
        })
        .collect()
}

/// The loads `v` in `f32`, the force scaled onto `|F| = mu P` where an interpolation
/// overshoots it.
fn onto_coulomb(v: [f64; 3]) -> [f32; 3] {
    let s = 1.0f64.min(1.0 / v[0].hypot(v[1]));
    [(v[0] * s) as f32, (v[1] * s) as f32, v[2] as f32]
}

/// At `eta_n = 0` the reflection `phi -> -phi` negates `Fy` and `Mz` exactly (as in the
/// computed spins), not only up to the rounding of the weights' products.
fn symmetrise(line: &mut [[f32; 3]]) {
    let np = line.len();
    for f in 0..np / 2 {
        let (a, b) = (line[f], line[np - 1 - f]);
        let v = [
            0.5 * (a[0] + b[0]),
            0.5 * (a[1] - b[1]),
            0.5 * (a[2] - b[2]),
        ];
        line[f] = v;
        line[np - 1 - f] = [v[0], -v[1], -v[2]];
    }
}

/// The computed nodes' read tables, each refined ([`refine`]) at its first use.
fn fine(node: usize) -> &'static Fine {
    static FINE: [OnceLock<Box<Fine>>; super::lut_data::NODES.len()] =
        [const { OnceLock::new() }; super::lut_data::NODES.len()];
    FINE[node].get_or_init(|| refine(nodes()[node].loads))
}

/// The computed nodes (generated, `lut_data.rs`).
pub fn nodes() -> &'static [LutNode] {
    &super::lut_data::NODES
}

/// Tolerance on `ln(a/b)` and on `nu` within which a contact is taken at a node's `a/b` and `nu`.
pub const SNAP: f64 = 1e-3;

/// The tables at `(a/b, nu)` with their weights: one at a computed node (within [`SNAP`]), two
/// between two computed `nu` of one computed `a/b` (linear in `nu`), up to eight between two
/// computed `a/b` (Lagrange's cubic in `ln(a/b)` through up to four rows, each at `nu`).
#[derive(Clone, Copy)]
pub struct Lut {
    /// The read tables: a node's, or the blend of several ([`baked`]); the parts themselves
    /// when more than [`BAKED_MAX`] blends are kept.
    tables: [&'static Fine; 8],
    w: [f64; 8],
    /// The moment's weights: between computed `a/b`, `w` times the full-slip spin moment of the
    /// contact over the table's row's ([`super::full_slip::max_moment`]: the moment is
    /// interpolated in units of it; module documentation of [`super`], "The table"); `w` within
    /// one computed `a/b`.
    wm: [f64; 8],
    /// Tables read at each evaluation: 1, but for more than [`BAKED_MAX`] blends.
    n: usize,
    /// Computed tables blended into the loads (1 at a node, up to 8 between computed `a/b`).
    parts: usize,
    between_ratios: bool,
    /// Factors on `(|xi_n|, |eta_n|, phi_n)` before the lookup: 1 within the computed `nu`;
    /// extrapolated in `nu`, Kalker's `C11, C22, C23` at the contact's `nu` over the tables'
    /// ([`Lut::at`]).
    scale: [f64; 3],
    extrapolated: bool,
    /// Kalker's linear theory at the contact's `(a/b, nu)` minus the tables' own slopes at zero
    /// creepage, `[d11, d22, d23, d32, d33]` (`Fx += d11 xi_n`, `Fy += d22 eta_n + d23 phi_n`,
    /// `Mz += d32 eta_n + d33 phi_n`), added faded by [`linear_fade`] ([`Lut::at_with`]).
    lin: [f64; 5],
}

/// Sum of the normalised creepages' magnitudes `|xi_n| + |eta_n| + |phi_n|` from which on the
/// table is read as it is: below it Kalker's linear theory is restored at zero creepage
/// ([`linear_fade`]).
pub const LINEAR_REACH: f64 = 0.1;

/// The weight `(1 - r/LINEAR_REACH)^2` (0 from [`LINEAR_REACH`] on) with which the difference
/// between Kalker's linear theory and the tables' own slopes is added at `r = |xi_n| + |eta_n| +
/// |phi_n|`: 1 at zero creepage, so the slopes there are Kalker's (Kalker 1967/1990, Table E.3,
/// [`crate::kalker3d`]), as the fitted law's are; the tables' first cell, linear interpolation
/// from zero, has the secant slope of its first computed creepage, which is a few per cent off
/// between two computed `nu` or `a/b`. Continuous with its slope at `LINEAR_REACH`.
#[inline(always)]
pub fn linear_fade(r: f64) -> f64 {
    let v = 1.0 - r * (1.0 / LINEAR_REACH);
    v * v
}

impl std::fmt::Debug for Lut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lut")
            .field("tables", &self.parts)
            .field("read", &self.n)
            .field("between_ratios", &self.between_ratios)
            .field("w", &&self.w[..self.n])
            .field("scale", &self.scale)
            .finish()
    }
}

impl PartialEq for Lut {
    fn eq(&self, o: &Self) -> bool {
        self.n == o.n
            && self.between_ratios == o.between_ratios
            && self.w == o.w
            && self.wm == o.wm
            && self.scale == o.scale
            && self.lin == o.lin
            && (0..self.n).all(|i| std::ptr::eq(self.tables[i], o.tables[i]))
    }
}

/// The tables of one computed `a/b` around `nu`, with weights: the node at `nu`, or linear
/// between the two computed `nu` around it.
fn row_at(ab: f64, nu: f64) -> Option<Vec<(&'static Fine, f64)>> {
    let mut col: Vec<(usize, &LutNode)> = nodes()
        .iter()
        .enumerate()
        .filter(|(_, n)| (n.ab.ln() - ab.ln()).abs() < SNAP)
        .collect();
    col.sort_by(|a, b| a.1.nu.total_cmp(&b.1.nu));
    if let Some(&(i, _)) = col.iter().find(|(_, n)| (n.nu - nu).abs() < SNAP) {
        return Some(vec![(fine(i), 1.0)]);
    }
    let hi = col.iter().position(|(_, n)| n.nu > nu)?;
    if hi == 0 {
        return None;
    }
    let ((ia, a), (ib, b)) = (col[hi - 1], col[hi]);
    let w = (nu - a.nu) / (b.nu - a.nu);
    Some(vec![(fine(ia), 1.0 - w), (fine(ib), w)])
}

/// The tables at `(a/b, nu)` with weights and their rows' `a/b`, and whether they are blended
/// between computed `a/b`: the row of the computed `a/b` at `ab` ([`rows_of`]), or, between
/// two computed `a/b`, Lagrange's cubic in `ln(a/b)` through the rows of those two and, beyond
/// each, of the nearest computed `a/b` at least half the interval's width (in `ln(a/b)`) away
/// (the quadratic through three in the end intervals). Its weights sum to one and are one at
/// each row; a cubic follows the loads' curvature across the rows, which linear blending of the
/// two rows around `a/b` misses by up to 4 % (docs/CREEP3D.md). A row closer than that (a row
/// added to refine the next interval) would take a large negative weight and carry its
/// interval's features into this one: with the rows `0.5, 1, 1.4`, the four nearest put
/// `a/b = 0.7` at 2.21 % of `mu P`, the stencil `0.2, 0.5, 1, 2` at 1.79 %.
type Parts = (Vec<(&'static Fine, f64, f64)>, bool);
fn tables_at(ab: f64, nu: f64) -> Option<Parts> {
    let rows = rows_of(ab)?;
    if let [row] = rows[..] {
        let tables = row_at(row, nu)?;
        return Some((
            tables.into_iter().map(|(t, w)| (t, w, row)).collect(),
            false,
        ));
    }
    let mut all: Vec<f64> = nodes().iter().map(|n| n.ab).collect();
    all.dedup_by(|a, b| (a.ln() - b.ln()).abs() < SNAP);
    let lo = all.iter().position(|&x| x == rows[0])?;
    // Beyond each end of the interval, the nearest computed a/b at least half its width away.
    let half = 0.5 * (rows[1].ln() - rows[0].ln());
    let left = all[..lo]
        .iter()
        .rev()
        .find(|&&r| rows[0].ln() - r.ln() >= half);
    let right = all[lo + 2..]
        .iter()
        .find(|&&r| r.ln() - rows[1].ln() >= half);
    let stencil: Vec<f64> = left
        .into_iter()
        .chain(&rows)
        .chain(right)
        .copied()
        .collect();
    let ln: Vec<f64> = stencil.iter().map(|r| r.ln()).collect();
    let weights = lagrange(&ln, ab.ln());
    let mut out = Vec::with_capacity(2 * stencil.len());
    for (&r, &w) in stencil.iter().zip(&weights) {
        out.extend(row_at(r, nu)?.into_iter().map(|(t, v)| (t, v * w, r)));
    }
    Some((out, true))
}

/// The computed `a/b` whose rows serve `ab`: itself (within [`SNAP`]) or the two around it.
fn rows_of(ab: f64) -> Option<Vec<f64>> {
    let l = ab.ln();
    if let Some(n) = nodes().iter().find(|n| (n.ab.ln() - l).abs() < SNAP) {
        return Some(vec![n.ab]);
    }
    let lo = nodes()
        .iter()
        .map(|n| n.ab)
        .filter(|&x| x < ab)
        .reduce(f64::max)?;
    let hi = nodes()
        .iter()
        .map(|n| n.ab)
        .filter(|&x| x > ab)
        .reduce(f64::min)?;
    Some(vec![lo, hi])
}

/// The range of `nu` that every row serving `ab` computes (`None` where none is shared).
fn shared_nu(ab: f64) -> Option<(f64, f64)> {
    let rows = rows_of(ab)?;
    let range = |r: f64| {
        let v = nodes()
            .iter()
            .filter(|n| (n.ab.ln() - r.ln()).abs() < SNAP)
            .map(|n| n.nu);
        (
            v.clone().fold(f64::INFINITY, f64::min),
            v.fold(0.0, f64::max),
        )
    };
    let (lo, hi) = rows
        .iter()
        .map(|&r| range(r))
        .fold((0.0f64, 1.0f64), |(a, b), (c, d)| (a.max(c), b.min(d)));
    (lo <= hi).then_some((lo, hi))
}

impl Lut {
    /// The table at `(a/b, nu)` within the computed `nu`, or `None` outside its coverage
    /// (module documentation; [`Lut::at_with`] extrapolates in `nu`).
    pub fn at(ab: f64, nu: f64) -> Option<Lut> {
        Self::at_with(ab, nu, false)
    }

    /// [`Lut::at`]; with `extrapolate`, a `nu` outside the range the rows compute takes the
    /// nearest computed `nu` with the creepages scaled by Kalker's coefficients (module
    /// documentation of [`super`], "Beyond the computed nu").
    pub fn at_with(ab: f64, nu: f64, extrapolate: bool) -> Option<Lut> {
        Self::build(ab, nu, extrapolate, true)
    }

    /// [`Lut::at_with`]; with `bake` false a blend reads its computed tables at each
    /// evaluation, as beyond [`BAKED_MAX`] blends (for the tests).
    pub(crate) fn build(ab: f64, nu: f64, extrapolate: bool, bake: bool) -> Option<Lut> {
        if !(ab.is_finite() && ab > 0.0 && nu.is_finite()) {
            return None;
        }
        let (parts, between_ratios, scale, nu_t) = match tables_at(ab, nu) {
            Some((p, b)) => (p, b, [1.0; 3], nu),
            // Beyond the computed nu: the nearest computed nu of the rows, scaled.
            None if extrapolate => {
                let (lo, hi) = shared_nu(ab)?;
                let nu_r = nu.clamp(lo, hi);
                let (p, b) = tables_at(ab, nu_r)?;
                let t = crate::kalker3d::coefficients(ab, nu).ok()?;
                let r = crate::kalker3d::coefficients(ab, nu_r).ok()?;
                (p, b, [t.c11 / r.c11, t.c22 / r.c22, t.c23 / r.c23], nu_r)
            }
            None => return None,
        };
        let first = parts[0].0;
        let mut lut = Lut {
            tables: [first; 8],
            w: [0.0; 8],
            wm: [0.0; 8],
            n: parts.len(),
            parts: parts.len(),
            between_ratios,
            scale,
            extrapolated: scale != [1.0; 3],
            lin: [0.0; 5],
        };
        let m = super::full_slip::max_moment(ab);
        for (i, (t, w, row)) in parts.into_iter().enumerate() {
            lut.tables[i] = t;
            lut.w[i] = w;
            lut.wm[i] = if between_ratios {
                w * m / super::full_slip::max_moment(row)
            } else {
                w
            };
        }
        if bake
            && lut.n > 1
            && let Some(t) = baked((ab.to_bits(), nu_t.to_bits()), &lut)
        {
            lut.tables = [t; 8];
            lut.w = [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            lut.wm = lut.w;
            lut.n = 1;
        }
        // The tables' slopes at zero creepage: the first cell is linear from zero along each
        // axis, so one read within it gives them exactly.
        let c = crate::kalker3d::coefficients(ab, nu).ok()?;
        let h = 1e-3;
        let (x, y, p) = (
            lut.read(h, 0.0, 0.0),
            lut.read(0.0, h, 0.0),
            lut.read(0.0, 0.0, h),
        );
        lut.lin = [
            c.c11 - x.fx / h,
            c.c22 - y.fy / h,
            c.c23 - p.fy / h,
            -c.c23 - y.mz / h,
            c.c33 - p.mz / h,
        ];
        Some(lut)
    }

    /// The loads of one read table ([`refine`]), not necessarily a computed node's (for checking
    /// a table before it is emitted; [`super::Steady3d::new`] finds the nodes itself).
    pub fn of_table(table: &'static Fine) -> Lut {
        Lut {
            tables: [table; 8],
            w: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            wm: [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
            n: 1,
            parts: 1,
            between_ratios: false,
            scale: [1.0; 3],
            extrapolated: false,
            lin: [0.0; 5],
        }
    }

    /// `Lut::loads` for any creepages: non-finite ones give zero loads.
    pub fn loads_checked(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        if !(xi_n.is_finite() && eta_n.is_finite() && phi_n.is_finite()) {
            return Loads::default();
        }
        self.loads(xi_n, eta_n, phi_n)
    }

    /// Whether `nu` is outside the computed ones (the creepages scaled, [`Lut::at_with`]).
    pub fn extrapolated(&self) -> bool {
        self.extrapolated
    }

    /// Whether the tables are blended between two computed `a/b` (cubic in `ln(a/b)`).
    pub fn between_ratios(&self) -> bool {
        self.between_ratios
    }

    /// The number of computed tables blended (1 at a node; read as one table, [`BAKED_MAX`]).
    pub fn len(&self) -> usize {
        self.parts
    }

    /// Whether no table is blended (never: a `Lut` has at least one).
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The loads at normalised creepages (project signs): the signs by the exact symmetries
    /// (`xi -> -xi` negates `Fx`; `(eta, phi) -> -(eta, phi)` negates `Fy, Mz`), creepages
    /// beyond the table's box scaled onto it along their direction, trilinear in the cell.
    /// The creepages must be finite ([`super::Steady3d::loads`] sees to it).
    #[inline]
    pub(crate) fn loads(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        let l = self.read(xi_n, eta_n, phi_n);
        let r = xi_n.abs() + eta_n.abs() + phi_n.abs();
        if r >= LINEAR_REACH {
            return l;
        }
        self.near_zero(l, xi_n, eta_n, phi_n, linear_fade(r))
    }

    /// The loads `l` read from the tables near zero creepage with the faded difference to
    /// Kalker's linear theory added ([`linear_fade`], weight `f`).
    #[inline(always)]
    fn near_zero(&self, l: Loads, xi_n: f64, eta_n: f64, phi_n: f64, f: f64) -> Loads {
        let [d11, d22, d23, d32, d33] = self.lin;
        Loads {
            fx: l.fx + f * d11 * xi_n,
            fy: l.fy + f * (d22 * eta_n + d23 * phi_n),
            mz: l.mz + f * (d32 * eta_n + d33 * phi_n),
        }
    }

    /// The tables' loads, without the linear theory near zero ([`Lut::loads`]; the same
    /// from `|xi_n| + |eta_n| + |phi_n| >=` [`LINEAR_REACH`] on).
    #[inline(always)]
    pub(crate) fn read(&self, xi_n: f64, eta_n: f64, phi_n: f64) -> Loads {
        let sx = 1.0f64.copysign(xi_n);
        let sy = 1.0f64.copysign(eta_n);
        let [kx, ky, kp] = self.scale;
        let (mut x, mut y, mut p) = (xi_n.abs() * kx, eta_n.abs() * ky, phi_n * sy * kp);
        let s = (x.max(y) * (1.0 / XI_MAX)).max(p.abs() * (1.0 / PHI_MAX));
        if s > 1.0 {
            (x, y, p) = to_box(x, y, p, s);
        }
        // (Through i64: x86-64 converts an f64 to an i64 in one instruction, to a usize in
        // several; the values are finite and not below -1, so both truncate alike.)
        let ix = XI_CELL[((x * (1.0 / BUCKET)) as i64 as usize).min(XI_BUCKETS)] as usize;
        let iy = XI_CELL[((y * (1.0 / BUCKET)) as i64 as usize).min(XI_BUCKETS)] as usize;
        let ip = PHI_CELL[(((p + PHI_MAX) * (1.0 / PHI_BUCKET)) as i64 as usize).min(PHI_BUCKETS)]
            as usize;
        let wx = (x - FINE_XI[ix]) * XI_INV[ix];
        let wy = (y - FINE_XI[iy]) * XI_INV[iy];
        let wp = (p - FINE_PHI[ip]) * PHI_INV[ip];
        let base = ix * NPLANE + iy * NP + ip;
        // The corners' offsets from `base` (each table's cell is one slice: one bounds check).
        let corners = [
            0,
            1,
            NP,
            NP + 1,
            NPLANE,
            NPLANE + 1,
            NPLANE + NP,
            NPLANE + NP + 1,
        ];
        let (vx, vy, vp) = (1.0 - wx, 1.0 - wy, 1.0 - wp);
        let cw = [
            vx * vy * vp,
            vx * vy * wp,
            vx * wy * vp,
            vx * wy * wp,
            wx * vy * vp,
            wx * vy * wp,
            wx * wy * vp,
            wx * wy * wp,
        ];
        let out = if self.n == 1 {
            // One table (a node, or a blend made into one: `baked`).
            cell_loads(self.tables[0], base, &corners, &cw)
        } else {
            self.read_parts(base, &corners, &cw)
        };
        Loads {
            fx: sx * out[0],
            fy: sy * out[1],
            mz: sy * out[2],
        }
    }

    /// The loads of a blend read from its computed tables (more than [`BAKED_MAX`] blends):
    /// each table's cell `base` with the corners' weights `cw`, weighted `w` (forces) and `wm`
    /// (moment), the force scaled onto Coulomb's bound where the cubic's weights overshoot it
    /// (which `baked` does at every point of its table).
    #[cold]
    #[inline(never)]
    fn read_parts(&self, base: usize, corners: &[usize; 8], cw: &[f64; 8]) -> [f64; 3] {
        let mut out = [0.0f64; 3];
        for t in 0..self.n {
            let acc = cell_loads(self.tables[t], base, corners, cw);
            out[0] += self.w[t] * acc[0];
            out[1] += self.w[t] * acc[1];
            out[2] += self.wm[t] * acc[2];
        }
        let s = 1.0f64.min(1.0 / out[0].hypot(out[1]));
        [out[0] * s, out[1] * s, out[2]]
    }
}

/// The loads of one table at a point of its cell `base`: the corners' (offsets `corners` from
/// `base`; each table's cell is one slice, so one bounds check) weighted trilinearly by `cw`.
#[inline(always)]
fn cell_loads(table: &Fine, base: usize, corners: &[usize; 8], cw: &[f64; 8]) -> [f64; 3] {
    let cell = &table[base..base + NPLANE + NP + 2];
    let mut acc = [0.0f64; 3];
    for k in 0..8 {
        let v = cell[corners[k]];
        acc[0] += cw[k] * f64::from(v[0]);
        acc[1] += cw[k] * f64::from(v[1]);
        acc[2] += cw[k] * f64::from(v[2]);
    }
    acc
}

/// Most blended read tables kept (706 KB each, 45 MB in all). A contact whose
/// `(a/b, nu)` needs more than one computed table (between computed `nu` or `a/b`) reads one
/// table made for it once; beyond this many distinct `(a/b, nu)` in a process, a contact
/// reads its computed tables at each evaluation (up to eight reads; the same loads but for
/// `f32` rounding and Coulomb's bound applied to the read loads rather than at the grid's points).
pub const BAKED_MAX: usize = 64;

/// The read table of `lut`'s blend, `sum w_t F_t` and `sum wm_t M_t` at every point of the read
/// grid, the force scaled onto `|F| = mu P` where the cubic's weights overshoot it (as
/// [`refine`] does), made at the first request of `key` (the contact's `a/b` and the tables'
/// `nu`) and kept; `None` once [`BAKED_MAX`] are kept.
fn baked(key: (u64, u64), lut: &Lut) -> Option<&'static Fine> {
    static BAKED: Mutex<Vec<((u64, u64), &'static Fine)>> = Mutex::new(Vec::new());
    kept(&BAKED, key, BAKED_MAX, || {
        let mut out: Box<Fine> = vec![[0.0f32; 3]; FINE_LEN]
            .into_boxed_slice()
            .try_into()
            .unwrap_or_else(|_| unreachable!("FINE_LEN elements"));
        for (i, o) in out.iter_mut().enumerate() {
            let mut v = [0.0f64; 3];
            for t in 0..lut.n {
                let x = lut.tables[t][i];
                v[0] += lut.w[t] * f64::from(x[0]);
                v[1] += lut.w[t] * f64::from(x[1]);
                v[2] += lut.wm[t] * f64::from(x[2]);
            }
            *o = onto_coulomb(v);
        }
        out
    })
}

/// The value of `key` in `cache`, made by `make` at its first request and kept for the
/// process (leaked: the tables the law reads by `'static` reference); `None` once `max` are
/// kept.
pub(crate) fn kept<K: PartialEq, T>(
    cache: &Mutex<Vec<(K, &'static T)>>,
    key: K,
    max: usize,
    make: impl FnOnce() -> Box<T>,
) -> Option<&'static T> {
    let mut kept = cache.lock().unwrap_or_else(|e| e.into_inner());
    if let Some(&(_, t)) = kept.iter().find(|(k, _)| *k == key) {
        return Some(t);
    }
    if kept.len() >= max {
        return None;
    }
    let t: &'static T = Box::leak(make());
    kept.push((key, t));
    Some(t)
}

/// Creepages beyond the table's box (`s > 1` the largest of `|xi|/XI_MAX, |eta|/XI_MAX,
/// |phi|/PHI_MAX`) scaled by `1/s` onto it: deep in full slip the loads depend on the
/// creepage's direction only (the traction is `mu p` along the rigid slip).
#[cold]
#[inline(never)]
fn to_box(x: f64, y: f64, p: f64, s: f64) -> (f64, f64, f64) {
    let k = 1.0 / s;
    (
        (x * k).min(XI_MAX),
        (y * k).min(XI_MAX),
        (p * k).clamp(-PHI_MAX, PHI_MAX),
    )
}
