//! The cell grid: periodic wrapping, minimum image, the counting sort of the particles by cell
//! and the half stencil of neighbour cells.

use crate::DemError;
use creep_law::Vec3;

/// The half stencil: the 13 neighbour cells after the own cell in lexicographic `(z, y, x)`
/// order (with the own cell, each pair of neighbouring cells is visited once).
const HALF: [[i32; 3]; 13] = [
    [1, 0, 0],
    [-1, 1, 0],
    [0, 1, 0],
    [1, 1, 0],
    [-1, -1, 1],
    [0, -1, 1],
    [1, -1, 1],
    [-1, 0, 1],
    [0, 0, 1],
    [1, 0, 1],
    [-1, 1, 1],
    [0, 1, 1],
    [1, 1, 1],
];

/// Most cells per particle (a sparse cloud gets larger cells instead).
const MAX_CELLS_PER_PARTICLE: f64 = 4.0;

/// The half stencil's particle ranges of one cell (see [`Grid::half_neighbour_ranges`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stencil {
    /// The cell they are of (`u32::MAX`: none yet).
    cell: u32,
    /// End of the cell's own particles.
    end: u32,
    /// The non-empty stencil cells' particle ranges, `len` of them.
    ranges: [(u32, u32); 13],
    len: usize,
}

impl Default for Stencil {
    fn default() -> Self {
        Self {
            cell: u32::MAX,
            end: 0,
            ranges: [(0, 0); 13],
            len: 0,
        }
    }
}

#[derive(Debug, Clone, Default)]
pub(crate) struct Grid {
    /// Periodic box per axis `(lo, length)`.
    periodic: [Option<(f64, f64)>; 3],
    /// Smallest cell size \[m\] (largest cut-off).
    cell_min: f64,
    lo: [f64; 3],
    size: [f64; 3],
    n: [i32; 3],
    /// Cell of each particle, in the sorted order.
    cell_of: Vec<u32>,
    /// Offsets of the cells' particles (CSR).
    start: Vec<u32>,
}

impl Grid {
    pub(crate) fn new(periodic: [Option<(f64, f64)>; 3], cell_min: f64) -> Result<Self, DemError> {
        let mut p = [None; 3];
        for (a, b) in periodic.iter().enumerate() {
            if let Some((lo, hi)) = *b {
                let len = hi - lo;
                if !(lo.is_finite() && hi.is_finite() && len >= 3.0 * cell_min) {
                    return Err(DemError::Parameter {
                        name: "periodic box length",
                        value: len,
                        why: "must be finite and at least 3 (2 r_max + skin)",
                    });
                }
                p[a] = Some((lo, len));
            }
        }
        Ok(Self {
            periodic: p,
            cell_min,
            ..Self::default()
        })
    }

    /// `x` wrapped into the periodic box on periodic axes.
    #[inline]
    pub(crate) fn wrap(&self, mut x: Vec3) -> Vec3 {
        let w = |v: &mut f64, b: Option<(f64, f64)>| {
            if let Some((lo, len)) = b
                && (*v < lo || *v >= lo + len)
            {
                *v = lo + (*v - lo).rem_euclid(len);
                if *v >= lo + len {
                    *v = lo;
                }
            }
        };
        w(&mut x.x, self.periodic[0]);
        w(&mut x.y, self.periodic[1]);
        w(&mut x.z, self.periodic[2]);
        x
    }

    /// Whether some axis is periodic (else [`Grid::min_image`] returns its argument).
    #[inline]
    pub(crate) fn is_periodic(&self) -> bool {
        self.periodic.iter().any(Option::is_some)
    }

    /// The minimum image of a separation `d` on periodic axes.
    #[inline]
    pub(crate) fn min_image(&self, mut d: Vec3) -> Vec3 {
        let m = |v: &mut f64, b: Option<(f64, f64)>| {
            if let Some((_, len)) = b
                && v.abs() > 0.5 * len
            {
                *v -= len * (*v / len).round();
            }
        };
        m(&mut d.x, self.periodic[0]);
        m(&mut d.y, self.periodic[1]);
        m(&mut d.z, self.periodic[2]);
        d
    }

    #[inline]
    fn coord(&self, x: Vec3) -> [i32; 3] {
        let c = [x.x, x.y, x.z];
        std::array::from_fn(|a| {
            let k = ((c[a] - self.lo[a]) / self.size[a]).floor();
            (k.max(0.0) as i32).min(self.n[a] - 1)
        })
    }

    #[inline]
    fn flat(&self, c: [i32; 3]) -> usize {
        ((c[2] * self.n[1] + c[1]) * self.n[0] + c[0]) as usize
    }

    /// Fits the grid to the particles, sorts them by cell (counting sort, stable) and returns
    /// the order: the new position `i` holds the old particle `order[i]`.
    pub(crate) fn sort(&mut self, x: &[Vec3]) -> Vec<u32> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in x {
            for (a, v) in [p.x, p.y, p.z].into_iter().enumerate() {
                lo[a] = lo[a].min(v);
                hi[a] = hi[a].max(v);
            }
        }
        let np = x.len().max(1) as f64;
        let mut cell = self.cell_min;
        loop {
            let mut total = 1.0;
            for a in 0..3 {
                let (l, len) = match self.periodic[a] {
                    Some((l, len)) => (l, len),
                    None if x.is_empty() => (0.0, cell),
                    None => (
                        lo[a],
                        (hi[a] - lo[a]).max(0.0) + 1e-12 * cell.max(hi[a].abs()),
                    ),
                };
                let n = match self.periodic[a] {
                    // At least 3 cells (len >= 3 cell_min, so the cells stay >= cell_min).
                    Some(_) => (len / cell).floor().max(3.0),
                    None => (len / cell).floor().max(0.0) + 1.0,
                };
                self.lo[a] = l;
                self.n[a] = n as i32;
                self.size[a] = match self.periodic[a] {
                    Some(_) => len / n,
                    None => cell,
                };
                total *= n;
            }
            if total <= MAX_CELLS_PER_PARTICLE * np + 27.0 {
                break;
            }
            cell *= 1.5;
        }
        let ncell = (self.n[0] * self.n[1] * self.n[2]) as usize;
        let cells: Vec<u32> = x.iter().map(|&p| self.flat(self.coord(p)) as u32).collect();
        self.start.clear();
        self.start.resize(ncell + 1, 0);
        for &c in &cells {
            self.start[c as usize + 1] += 1;
        }
        for c in 0..ncell {
            self.start[c + 1] += self.start[c];
        }
        let mut fill = self.start.clone();
        let mut order = vec![0u32; x.len()];
        for (i, &c) in cells.iter().enumerate() {
            let s = &mut fill[c as usize];
            order[*s as usize] = i as u32;
            *s += 1;
        }
        self.cell_of.clear();
        self.cell_of
            .extend(order.iter().map(|&o| cells[o as usize]));
        order
    }

    /// The particles `j` of the own cell with `j > i` and of the 13 half-stencil cells of
    /// particle `i` (sorted order), in that order. Needs at least 3 cells on periodic
    /// axes (checked in [`Grid::new`]) so that no cell is visited twice. `stencil` caches the
    /// stencil's particle ranges for the cell of the last call (consecutive particles of one
    /// cell share it: about two per cell in a dense packing); start with
    /// `Stencil::default()`.
    ///
    /// Returned as the particle ranges to sweep, `i + 1..` the end of `i`'s cell first, then
    /// the stencil's, so that the caller's loop body is written once, inline (a closure called
    /// from two loops was not inlined: a call per candidate).
    #[inline(always)]
    pub(crate) fn half_neighbour_ranges<'s>(
        &self,
        i: usize,
        stencil: &'s mut Stencil,
    ) -> ((u32, u32), &'s [(u32, u32)]) {
        let c = self.cell_of[i];
        if stencil.cell != c {
            self.fill_stencil(c as usize, stencil);
        }
        ((i as u32 + 1, stencil.end), &stencil.ranges[..stencil.len])
    }

    /// The particle ranges of cell `c`'s half stencil (the 13 cells after it in [`HALF`]'s
    /// order; those off a non-periodic edge left out; empty ones too).
    fn fill_stencil(&self, c: usize, s: &mut Stencil) {
        s.cell = c as u32;
        s.end = self.start[c + 1];
        s.len = 0;
        let nx = self.n[0] as usize;
        let ny = self.n[1] as usize;
        let cx = (c % nx) as i32;
        let cy = ((c / nx) % ny) as i32;
        let cz = (c / (nx * ny)) as i32;
        if (1..self.n[0] - 1).contains(&cx)
            && (1..self.n[1] - 1).contains(&cy)
            && (0..self.n[2] - 1).contains(&cz)
        {
            // Every stencil cell inside the grid (HALF's offsets are -1..=1 in x and y, 0..=1
            // in z): no wrap nor edge test, the same cells in the same order.
            let (nx, nxy) = (nx as isize, (nx * ny) as isize);
            for o in HALF {
                let k = (c as isize + o[2] as isize * nxy + o[1] as isize * nx + o[0] as isize)
                    as usize;
                let (a, b) = (self.start[k], self.start[k + 1]);
                if a < b {
                    s.ranges[s.len] = (a, b);
                    s.len += 1;
                }
            }
            return;
        }
        for o in HALF {
            let mut nc = [cx + o[0], cy + o[1], cz + o[2]];
            let mut ok = true;
            for a in 0..3 {
                if nc[a] < 0 || nc[a] >= self.n[a] {
                    if self.periodic[a].is_some() && self.n[a] >= 3 {
                        nc[a] = nc[a].rem_euclid(self.n[a]);
                    } else {
                        ok = false;
                    }
                }
            }
            // Periodic axes with fewer than 3 cells would visit a cell twice: such a box has
            // one or two cells, and all pairs are in the own cell's sweep.
            if !ok {
                continue;
            }
            let k = self.flat(nc);
            let (a, b) = (self.start[k], self.start[k + 1]);
            if a < b {
                s.ranges[s.len] = (a, b);
                s.len += 1;
            }
        }
    }

    /// Bytes held by the grid.
    pub(crate) fn bytes(&self) -> usize {
        (self.cell_of.capacity() + self.start.capacity()) * 4
    }
}
