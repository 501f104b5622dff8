//! The history of one contact and its flat `[f64]` form (for a C ABI).

use super::{PairConstants, TangentialLaw};
use crate::LawError;
use crate::hertz;
use crate::material::Surface;
use crate::rolling_torque::RollingState;
use crate::vector::Vec3;

/// The history of one contact: the tangential law's memory, the carried tangent basis, the
/// rolling spring and the last overlap. `Default` is a virgin contact.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactHistory<T: TangentialLaw> {
    /// The tangential law's memory (2-D vectors in `(t1, n x t1)`).
    pub tangential: T::History,
    /// First tangent of the carried basis [-] (zero: virgin).
    pub t1: Vec3,
    /// Unit normal of the last step [-] (zero: virgin).
    pub normal: Vec3,
    /// Contact-torque rolling spring (EPSD).
    pub rolling: RollingState,
    /// Overlap of the last step \[m\].
    pub overlap: f64,
}

impl<T: TangentialLaw> ContactHistory<T> {
    /// Number of `f64` of the flat form: `[t1 (3), normal (3), rolling spring (3), overlap,
    /// tangential history (T::HISTORY_LEN)]`.
    pub const LEN: usize = 10 + T::HISTORY_LEN;

    /// Whether the contact has never been stepped (or was reset).
    #[inline]
    pub fn is_virgin(&self) -> bool {
        self.normal == Vec3::ZERO
    }

    /// Writes the flat form into `out` (length [`ContactHistory::LEN`]).
    pub fn write(&self, out: &mut [f64]) -> Result<(), LawError> {
        if out.len() != Self::LEN {
            return Err(len_error(out.len()));
        }
        let s = self.rolling.spring;
        out[..10].copy_from_slice(&[
            self.t1.x,
            self.t1.y,
            self.t1.z,
            self.normal.x,
            self.normal.y,
            self.normal.z,
            s.x,
            s.y,
            s.z,
            self.overlap,
        ]);
        T::write(&self.tangential, &mut out[10..]);
        Ok(())
    }

    /// Reads the flat form written by [`ContactHistory::write`].
    pub fn read(v: &[f64]) -> Result<Self, LawError> {
        if v.len() != Self::LEN {
            return Err(len_error(v.len()));
        }
        if let Some(&bad) = v[..10].iter().find(|x| !x.is_finite()) {
            return Err(LawError::OutOfRange {
                name: "contact history entry",
                value: bad,
                range: "finite",
            });
        }
        Ok(Self {
            tangential: T::read(&v[10..])?,
            t1: Vec3::new(v[0], v[1], v[2]),
            normal: Vec3::new(v[3], v[4], v[5]),
            rolling: RollingState {
                spring: Vec3::new(v[6], v[7], v[8]),
            },
            overlap: v[9],
        })
    }

    /// Stored elastic energies `(normal, tangential)` \[J\] of the contact as of its last step,
    /// between surfaces `sp` and `sq` with constants `c`: Hertz's `(8/15) E* sqrt(R*)
    /// delta^(5/2)` and the tangential law's.
    pub fn elastic_energy(&self, c: &PairConstants, sp: Surface, sq: Surface) -> (f64, f64) {
        let pm = c.pair_material(sp, sq);
        (
            hertz::normal_energy(&pm, self.overlap),
            T::elastic_energy(&self.tangential, &pm),
        )
    }
}

fn len_error(len: usize) -> LawError {
    LawError::OutOfRange {
        name: "contact history buffer length",
        value: len as f64,
        range: "ContactHistory::LEN",
    }
}
