//! The flat `f64` form of the Cattaneo-Mindlin memory (docs/ARCHITECTURE.md §3): the layout
//! hosts store between steps (creep-dem's history arrays, the LAMMPS plugin's per-atom rows),
//! written and read back exactly.

use super::*;

/// Number of `f64` in the flat form of a [`MindlinState`] ([`MindlinState::to_array`]): the
/// contact radius, the piece count, the force (2) and `MAX_PIECES + 1` pieces of 5 numbers.
pub const MINDLIN_FLAT_LEN: usize = 4 + 5 * (MAX_PIECES + 1);

impl<const N: usize, const COALESCE: u32> MindlinMemory<N, COALESCE> {
    /// The state as a flat array of `f64` (for hosts that pass contact history through a C
    /// ABI, e.g. a LAMMPS pair style): `[a, n, q.x, q.y, (x_hi, beta.x, beta.y, c.x, c.y) x 9]`.
    pub fn to_array(&self) -> [f64; MINDLIN_FLAT_LEN] {
        let mut out = [0.0; MINDLIN_FLAT_LEN];
        out[0] = self.a;
        out[1] = self.n as f64;
        out[2] = self.q.x;
        out[3] = self.q.y;
        for (i, p) in self.pieces.iter().enumerate() {
            let o = 4 + 5 * i;
            out[o..o + 5].copy_from_slice(&[p.x_hi, p.beta.x, p.beta.y, p.c.x, p.c.y]);
        }
        out
    }

    /// The inverse of [`MindlinState::to_array`]. A non-finite entry, a negative radius, a
    /// piece count that is not an integer in `[0, N]` or pieces whose outer radii do not
    /// increase from above 0 is an error.
    pub fn from_array(v: &[f64; MINDLIN_FLAT_LEN]) -> Result<Self, crate::LawError> {
        if let Some(&bad) = v.iter().find(|x| !x.is_finite()) {
            return Err(crate::LawError::OutOfRange {
                name: "Mindlin history entry",
                value: bad,
                range: "finite",
            });
        }
        let n = v[1];
        if !(n >= 0.0 && n <= N as f64 && n.fract() == 0.0) || v[0] < 0.0 {
            return Err(crate::LawError::OutOfRange {
                name: "Mindlin history piece count",
                value: n,
                range: "an integer in [0, N] (the capacity, 8 for MindlinState) with a >= 0",
            });
        }
        let mut pieces = [Piece::default(); MAX_PIECES + 1];
        for (i, p) in pieces.iter_mut().enumerate() {
            let o = 4 + 5 * i;
            *p = Piece {
                x_hi: v[o],
                beta: Vec2::new(v[o + 1], v[o + 2]),
                c: Vec2::new(v[o + 3], v[o + 4]),
            };
        }
        // The pieces an update leaves: non-empty annuli, inner to outer (`update_with_radius`
        // relies on it).
        let mut x_lo = 0.0;
        for p in &pieces[..n as usize] {
            if !(p.x_hi > x_lo) {
                return Err(crate::LawError::OutOfRange {
                    name: "Mindlin history piece radius",
                    value: p.x_hi,
                    range: "above the previous piece's (0 for the first): pieces inner to outer",
                });
            }
            x_lo = p.x_hi;
        }
        Ok(Self {
            a: v[0],
            n: n as usize,
            pieces,
            q: Vec2::new(v[2], v[3]),
        })
    }
}
