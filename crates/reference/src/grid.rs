//! The boundary-element grid: square elements of side `h = 2a/N` covering the circular contact.

use crate::contact::CircularContact;
use crate::error::RefError;

/// Smallest number of elements across the diameter accepted by the solvers.
pub const MIN_GRID: usize = 4;
/// Largest number of elements across the diameter accepted by the solvers (memory and time grow
/// as `N^4` for the dense Gauss-Seidel sweeps).
pub const MAX_GRID: usize = 256;

/// One row (constant `y`) of contact elements; its elements are contiguous in `x`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Row {
    /// Row index `j` (element centre `y = -a + (j + 1/2) h`).
    pub iy: i64,
    /// Column index of the row's first (smallest `x`) element.
    pub ix_lo: i64,
    /// Index of the row's first element in the element arrays.
    pub start: usize,
    /// Number of elements in the row.
    pub len: usize,
}

/// Square elements covering the contact circle of radius `a`, `N` across the diameter.
///
/// The elements are the cells of the lattice of pitch `h0 = 2a/N` (centres
/// `x_i = -a + (i + 1/2) h0`, `y_j = -a + (j + 1/2) h0`, `i, j in 0..N`) whose centres lie inside
/// the circle; the lattice is then stretched about the centre by `s = sqrt(pi a^2 / (n h0^2))`
/// (`n` elements), so that the elements' total area is exactly `pi a^2` and `h = s h0`. The count
/// of lattice cells in a disc fluctuates by `O(h0)` in relative area (+3.5 % at `N = 16`,
/// +1.0 % at `N = 32`), and that fluctuation, not the discretisation of the tractions, would
/// otherwise dominate the grid error of the creep coefficients; after the stretch `|s - 1| < 2 %`
/// for `N >= 16` and the error decreases smoothly as `O(h)`. Elements are stored row by row
/// (increasing `y`), each row by increasing `x`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    n: usize,
    h: f64,
    pub(crate) rows: Vec<Row>,
    pub(crate) ix: Vec<i64>,
    pub(crate) iy: Vec<i64>,
    x: Vec<f64>,
    y: Vec<f64>,
    stretch: f64,
}

impl Grid {
    /// Builds the grid with `n` elements across the diameter `2a` of a contact of radius `a` \[m\].
    /// `n` must be in `[MIN_GRID, MAX_GRID]`.
    pub fn new(a: f64, n: usize) -> Result<Self, RefError> {
        Self::elliptic(a, a, n)
    }

    /// Builds the grid of an elliptic contact with semi-axes `a` along `x` (rolling direction)
    /// and `b` along `y` \[m\], with `n` square elements across the shorter axis `2 min(a, b)`
    /// (so `h0 = 2 min(a, b)/n`). The lattice is centred (`x_i = (i + 1/2 - nx/2) h0` with
    /// `nx = ceil(2a/h0)`, likewise in `y`), the cells whose centres lie inside the ellipse are
    /// kept and the lattice is stretched as for the circle so that the elements' total area is
    /// exactly `pi a b`. For `a = b` this is the grid of [`Grid::new`].
    pub fn elliptic(a: f64, b: f64, n: usize) -> Result<Self, RefError> {
        if !(MIN_GRID..=MAX_GRID).contains(&n) {
            return Err(RefError::InvalidGrid {
                name: "grid",
                value: n,
                expected: "elements across the diameter, in [4, 256]",
            });
        }
        crate::error::check_positive("a", a)?;
        crate::error::check_positive("b", b)?;
        let h = 2.0 * a.min(b) / n as f64;
        let cells = |half: f64| {
            if half == a.min(b) {
                n as i64
            } else {
                (2.0 * half / h - 1e-9).ceil() as i64
            }
        };
        let (nx, ny) = (cells(a), cells(b));
        // Half-width of the lattice: the semi-axis itself along the shorter axis (as the circle's
        // grid always had), `m h0 / 2` along the longer one.
        let half_width = |half: f64, m: i64| {
            if half == a.min(b) {
                half
            } else {
                0.5 * m as f64 * h
            }
        };
        let (wx, wy) = (half_width(a, nx), half_width(b, ny));
        let centre = |i: i64, w: f64| -w + (i as f64 + 0.5) * h;
        let inside = |x: f64, y: f64| {
            if a == b {
                x * x + y * y < a * a
            } else {
                (x / a) * (x / a) + (y / b) * (y / b) < 1.0
            }
        };
        let mut g = Grid {
            n,
            h,
            rows: Vec::new(),
            ix: Vec::new(),
            iy: Vec::new(),
            x: Vec::new(),
            y: Vec::new(),
            stretch: 1.0,
        };
        for j in 0..ny {
            let y = centre(j, wy);
            let start = g.ix.len();
            let mut lo = None;
            for i in 0..nx {
                let x = centre(i, wx);
                if inside(x, y) {
                    lo.get_or_insert(i);
                    g.ix.push(i);
                    g.iy.push(j);
                    g.x.push(x);
                    g.y.push(y);
                }
            }
            if let Some(ix_lo) = lo {
                g.rows.push(Row {
                    iy: j,
                    ix_lo,
                    start,
                    len: g.ix.len() - start,
                });
            }
        }
        let s = (std::f64::consts::PI * a * b / (g.len() as f64 * h * h)).sqrt();
        g.stretch = s;
        g.h = s * h;
        g.x.iter_mut().chain(g.y.iter_mut()).for_each(|v| *v *= s);
        Ok(g)
    }

    /// Largest column and row index of the lattice in use (`(max ix, max iy)`), for kernel
    /// tables that must cover every offset between two elements.
    pub(crate) fn extent(&self) -> (i64, i64) {
        (
            self.ix.iter().copied().max().unwrap_or(0),
            self.iy.iter().copied().max().unwrap_or(0),
        )
    }

    /// The stretch factor `s` of the lattice (element side over `2a/N`).
    pub fn stretch(&self) -> f64 {
        self.stretch
    }

    /// Number of elements across the diameter.
    pub fn n(&self) -> usize {
        self.n
    }
    /// Element side `h` \[m\].
    pub fn h(&self) -> f64 {
        self.h
    }
    /// Element area `h^2` \[m^2\].
    pub fn area(&self) -> f64 {
        self.h * self.h
    }
    /// Number of elements in the contact.
    pub fn len(&self) -> usize {
        self.x.len()
    }
    /// Whether the grid has no element (never true for a valid grid).
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
    /// Element centres' `x` \[m\] (rolling direction).
    pub fn x(&self) -> &[f64] {
        &self.x
    }
    /// Element centres' `y` \[m\].
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// Hertz pressure at the element centres \[Pa\] (evaluated at the unstretched lattice position,
    /// so every element has a positive pressure), rescaled so that `sum p_I h^2 = P` exactly (the
    /// discrete contact then carries the prescribed normal force, so full slip gives `|Q| = mu P`
    /// to solver precision).
    pub fn pressure(&self, contact: &CircularContact) -> Vec<f64> {
        let s = self.stretch;
        let mut p: Vec<f64> = (0..self.len())
            .map(|e| contact.pressure(self.x[e] / s, self.y[e] / s))
            .collect();
        let total: f64 = p.iter().sum::<f64>() * self.area();
        let scale = contact.p() / total;
        p.iter_mut().for_each(|v| *v *= scale);
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn grid_covers_the_circle() {
        for n in [8, 16, 33, 64] {
            let g = Grid::new(1.0, n).unwrap();
            let area = g.len() as f64 * g.area();
            // The stretched lattice has exactly the disc's area, with a stretch close to 1.
            assert!((area / PI - 1.0).abs() < 1e-12, "n={n}: {area}");
            assert!(
                (g.stretch() - 1.0).abs() < 2.0 / n as f64,
                "n={n}: {}",
                g.stretch()
            );
            // Rows are contiguous and symmetric in x.
            for r in &g.rows {
                let hi = r.ix_lo + r.len as i64 - 1;
                assert_eq!(r.ix_lo, n as i64 - 1 - hi);
                for k in 0..r.len {
                    assert_eq!(g.ix[r.start + k], r.ix_lo + k as i64);
                    assert_eq!(g.iy[r.start + k], r.iy);
                }
            }
        }
        assert!(Grid::new(1.0, 3).is_err());
        assert!(Grid::new(1.0, 1000).is_err());
        assert!(Grid::new(-1.0, 16).is_err());
    }

    #[test]
    fn discrete_pressure_carries_p() {
        let c = CircularContact::new(1e-3, 10.0, 1e9, 0.3, 0.3).unwrap();
        let g = Grid::new(c.a(), 20).unwrap();
        let p = g.pressure(&c);
        let total: f64 = p.iter().sum::<f64>() * g.area();
        assert!((total / c.p() - 1.0).abs() < 1e-12);
        assert!(p.iter().all(|&v| v > 0.0));
    }
}
