//! The material table: the constants of every pair of materials, computed once and indexed
//! by material id.

use creep_law::pair::PairConstants;
use creep_law::rolling_torque::RollingModel;
use creep_law::{CreepModel, Material};

use crate::DemError;

/// The constants of every pair of materials: `n x n` [`PairConstants`], indexed by material id.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialTable {
    pub(crate) materials: Vec<Material>,
    pub(crate) pairs: Vec<PairConstants>,
}

impl MaterialTable {
    /// The table of `materials` with every pair's friction the `Average` of the two (creep-law
    /// `FrictionCombine::Average`), one restitution `e` [-], the creep model (`None`: plain
    /// Coulomb-Mindlin) and optional rolling resistance.
    pub fn new(
        materials: &[Material],
        restitution: f64,
        creep: Option<CreepModel>,
        rolling: Option<RollingModel>,
    ) -> Result<Self, DemError> {
        if materials.is_empty() {
            return Err(DemError::Parameter {
                name: "number of materials",
                value: 0.0,
                why: "at least one material is needed",
            });
        }
        let n = materials.len();
        let mut pairs = Vec::with_capacity(n * n);
        for p in materials {
            for q in materials {
                let mu = 0.5 * (p.friction() + q.friction());
                pairs.push(PairConstants::new(p, q, mu, restitution, creep, rolling)?);
            }
        }
        Ok(Self {
            materials: materials.to_vec(),
            pairs,
        })
    }

    /// Number of materials.
    pub fn len(&self) -> usize {
        self.materials.len()
    }
    /// Whether the table is empty (never, by construction).
    pub fn is_empty(&self) -> bool {
        self.materials.is_empty()
    }
    /// Material `i`.
    pub fn material(&self, i: usize) -> Option<&Material> {
        self.materials.get(i)
    }

    /// Replaces the constants of the pair `(i, j)` (both orders).
    pub fn set_pair(&mut self, i: usize, j: usize, c: PairConstants) -> Result<(), DemError> {
        let n = self.len();
        if i >= n {
            return Err(DemError::Material(i));
        }
        if j >= n {
            return Err(DemError::Material(j));
        }
        self.pairs[i * n + j] = c;
        self.pairs[j * n + i] = c;
        Ok(())
    }

    /// The constants of the pair `(i, j)`.
    #[inline]
    pub fn pair(&self, i: usize, j: usize) -> &PairConstants {
        &self.pairs[self.pair_index(i, j)]
    }

    /// Where the constants of the pair `(i, j)` are in `pairs`.
    #[inline]
    pub(crate) fn pair_index(&self, i: usize, j: usize) -> usize {
        i * self.materials.len() + j
    }
}
