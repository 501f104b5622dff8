//! The tabulated 3-D steady law: per `(a/b, nu)` node, the boundary-element loads on a grid of
//! the normalised creepages, interpolated trilinearly (module documentation of
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

/// Spins per `(xi, eta)` line of a table.
const NP: usize = LUT_PHI.len();
/// Points per `xi` plane of a table.
const NPLANE: usize = LUT_XI.len() * NP;
/// Buckets over `[0, 2]` (xi, eta) and `[-4, 4]` (phi).
const XI_BUCKETS: usize = 500;
const PHI_BUCKETS: usize = 2000;
/// Largest tabulated `|xi_n|, |eta_n|` and `|phi_n|` (the box of the table).
pub const XI_MAX: f64 = 2.0;
/// Largest tabulated `|phi_n|`.
pub const PHI_MAX: f64 = 4.0;

/// One node's loads: `[Fx/(mu P), Fy/(mu P), Mz/(mu P c)]` at `(LUT_XI[i], LUT_XI[j], LUT_PHI[k])`,
/// index `(i LUT_XI.len() + j) LUT_PHI.len() + k` (project signs, `c = sqrt(a b)`).
pub type Table = [[f32; 3]; LUT_LEN];

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
/// bucket `[b BUCKET, (b + 1) BUCKET)` over `[x0, x0 + B BUCKET]` (every node is a multiple of
/// [`BUCKET`], so no bucket straddles a node).
const fn cells<const N: usize, const B: usize>(nodes: &[f64; N], x0: f64) -> [u8; B] {
    let mut out = [0u8; B];
    let mut b = 0;
    while b < B {
        let x = x0 + (b as f64 + 0.5) * BUCKET;
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

static XI_CELL: [u8; XI_BUCKETS + 1] = cells(&LUT_XI, 0.0);
static PHI_CELL: [u8; PHI_BUCKETS + 1] = cells(&LUT_PHI, -PHI_MAX);
static XI_INV: [f64; LUT_XI.len()] = inverse_steps(&LUT_XI);
static PHI_INV: [f64; LUT_PHI.len()] = inverse_steps(&LUT_PHI);

/// The computed nodes (generated, `lut_data.rs`).
pub fn nodes() -> &'static [LutNode] {
    &super::lut_data::NODES
}

/// Tolerance on `ln(a/b)` and on `nu` within which a contact is taken at a node's `a/b` and `nu`.
pub const SNAP: f64 = 1e-3;

/// The tables at `(a/b, nu)` with their weights: one at a computed node (within [`SNAP`]), two
/// between two computed `nu` of one computed `a/b` (linear in `nu`), up to four between two
/// computed `a/b` (linear in `ln(a/b)` between the two rows, each at `nu`).
#[derive(Clone, Copy)]
pub struct Lut {
    tables: [&'static Table; 4],
    w: [f64; 4],
    n: usize,
    between_ratios: bool,
    /// Factors on `(|xi_n|, |eta_n|, phi_n)` before the lookup: 1 within the computed `nu`;
    /// extrapolated in `nu`, Kalker's `C11, C22, C23` at the contact's `nu` over the tables'
    /// ([`Lut::at`]).
    scale: [f64; 3],
    extrapolated: bool,
}

impl std::fmt::Debug for Lut {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Lut")
            .field("tables", &self.n)
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
            && self.scale == o.scale
            && (0..self.n).all(|i| std::ptr::eq(self.tables[i], o.tables[i]))
    }
}

/// The tables of one computed `a/b` around `nu`, with weights: the node at `nu`, or linear
/// between the two computed `nu` around it.
fn row_at(ab: f64, nu: f64) -> Option<Vec<(&'static Table, f64)>> {
    let mut col: Vec<&LutNode> = nodes()
        .iter()
        .filter(|n| (n.ab.ln() - ab.ln()).abs() < SNAP)
        .collect();
    col.sort_by(|a, b| a.nu.total_cmp(&b.nu));
    if let Some(n) = col.iter().find(|n| (n.nu - nu).abs() < SNAP) {
        return Some(vec![(n.loads, 1.0)]);
    }
    let hi = col.iter().position(|n| n.nu > nu)?;
    if hi == 0 {
        return None;
    }
    let (a, b) = (col[hi - 1], col[hi]);
    let w = (nu - a.nu) / (b.nu - a.nu);
    Some(vec![(a.loads, 1.0 - w), (b.loads, w)])
}

/// The tables at `(a/b, nu)` with weights, and whether they are blended between two computed
/// `a/b`: one computed `a/b`'s row, or linear in `ln(a/b)` between the rows of the two computed
/// `a/b` around it.
type Parts = (Vec<(&'static Table, f64)>, bool);
fn tables_at(ab: f64, nu: f64) -> Option<Parts> {
    if nodes().iter().any(|n| (n.ab.ln() - ab.ln()).abs() < SNAP) {
        return row_at(ab, nu).map(|row| (row, false));
    }
    let l = ab.ln();
    let lo = nodes()
        .iter()
        .map(|n| n.ab.ln())
        .filter(|&x| x < l)
        .reduce(f64::max)?;
    let hi = nodes()
        .iter()
        .map(|n| n.ab.ln())
        .filter(|&x| x > l)
        .reduce(f64::min)?;
    let w = (l - lo) / (hi - lo);
    let mut out = row_at(lo.exp(), nu)?;
    out.iter_mut().for_each(|p| p.1 *= 1.0 - w);
    out.extend(row_at(hi.exp(), nu)?.into_iter().map(|(t, v)| (t, v * w)));
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
        if !(ab.is_finite() && ab > 0.0 && nu.is_finite()) {
            return None;
        }
        let (parts, between_ratios, scale) = match tables_at(ab, nu) {
            Some((p, b)) => (p, b, [1.0; 3]),
            // Beyond the computed nu: the nearest computed nu of the rows, scaled.
            None if extrapolate => {
                let (lo, hi) = shared_nu(ab)?;
                let nu_r = nu.clamp(lo, hi);
                let (p, b) = tables_at(ab, nu_r)?;
                let t = crate::kalker3d::coefficients(ab, nu).ok()?;
                let r = crate::kalker3d::coefficients(ab, nu_r).ok()?;
                (p, b, [t.c11 / r.c11, t.c22 / r.c22, t.c23 / r.c23])
            }
            None => return None,
        };
        let first = parts[0].0;
        let mut lut = Lut {
            tables: [first; 4],
            w: [0.0; 4],
            n: parts.len(),
            between_ratios,
            scale,
            extrapolated: scale != [1.0; 3],
        };
        for (i, (t, w)) in parts.into_iter().enumerate() {
            lut.tables[i] = t;
            lut.w[i] = w;
        }
        Some(lut)
    }

    /// The loads of one table, not necessarily a computed node's (for checking a table before
    /// it is emitted; [`super::Steady3d::new`] finds the nodes itself).
    pub fn of_table(table: &'static Table) -> Lut {
        Lut {
            tables: [table; 4],
            w: [1.0, 0.0, 0.0, 0.0],
            n: 1,
            between_ratios: false,
            scale: [1.0; 3],
            extrapolated: false,
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

    /// Whether the tables are blended between two computed `a/b` (linear in `ln(a/b)`).
    pub fn between_ratios(&self) -> bool {
        self.between_ratios
    }

    /// The number of tables blended (1 at a node).
    pub fn len(&self) -> usize {
        self.n
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
        let ip =
            PHI_CELL[(((p + PHI_MAX) * (1.0 / BUCKET)) as i64 as usize).min(PHI_BUCKETS)] as usize;
        let wx = (x - LUT_XI[ix]) * XI_INV[ix];
        let wy = (y - LUT_XI[iy]) * XI_INV[iy];
        let wp = (p - LUT_PHI[ip]) * PHI_INV[ip];
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
        let mut out = [0.0f64; 3];
        for t in 0..self.n {
            let cell = &self.tables[t][base..base + NPLANE + NP + 2];
            let wt = self.w[t];
            for k in 0..8 {
                let v = cell[corners[k]];
                let w = wt * cw[k];
                out[0] += w * f64::from(v[0]);
                out[1] += w * f64::from(v[1]);
                out[2] += w * f64::from(v[2]);
            }
        }
        Loads {
            fx: sx * out[0],
            fy: sy * out[1],
            mz: sy * out[2],
        }
    }
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
