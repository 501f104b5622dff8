//! What the engine reports: energy bookkeeping, counters, contacts and memory.

use creep_law::pair::{ContactHistory, TangentialLaw};
use creep_law::{Surface, Vec3};

use crate::Dem;

/// Energy bookkeeping \[J\], as creep-rapier's `CompliantEnergy`: the elastic terms are the
/// current stored energies ([`Dem::energy`] computes them), the others accumulate from the
/// creation of the engine. Balance: work of the contact forces = change of `elastic()` +
/// `dissipated()`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DemEnergy {
    /// Hertz normal springs \[J\].
    pub normal_elastic: f64,
    /// Tangential springs \[J\].
    pub tangential_elastic: f64,
    /// Normal damping \[J\].
    pub damping: f64,
    /// Micro-slip and gross slip \[J\].
    pub slip: f64,
    /// Creep \[J\].
    pub creep: f64,
    /// Contact-torque rolling resistance \[J\].
    pub rolling: f64,
    /// Energy added by the tangential law's simplifications \[J\].
    pub truncation: f64,
}

impl DemEnergy {
    /// Stored elastic energy \[J\].
    pub fn elastic(&self) -> f64 {
        self.normal_elastic + self.tangential_elastic
    }
    /// Net dissipated energy \[J\].
    pub fn dissipated(&self) -> f64 {
        self.damping + self.slip + self.creep + self.rolling - self.truncation
    }
}

/// What the last force evaluation saw.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DemCounts {
    /// Touching particle-particle contacts.
    pub contacts: usize,
    /// Touching particle-wall contacts.
    pub wall_contacts: usize,
    /// Of all touching contacts, those at the Coulomb limit.
    pub sliding: usize,
    /// Of all touching contacts, those with a creep displacement this step.
    pub creeping: usize,
    /// Entries of the half neighbour list (candidate pairs).
    pub neighbours: usize,
    /// Neighbour-list rebuilds so far.
    pub rebuilds: usize,
}

/// One touching contact, as reported by [`Dem::for_each_contact`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactView {
    /// Particle id of p, or `None` when p is a wall.
    pub p: Option<usize>,
    /// Wall index when p is a wall.
    pub wall: Option<usize>,
    /// Particle id of q.
    pub q: usize,
    /// Unit normal from p to q.
    pub normal: Vec3,
    /// Overlap \[m\].
    pub overlap: f64,
}
impl<T: TangentialLaw> Dem<T> {
    /// Kinetic energy, translational plus rotational \[J\].
    pub fn kinetic_energy(&self) -> f64 {
        let mut e = 0.0;
        for i in 0..self.len() {
            e += 0.5 * self.mass[i] * self.v[i].dot(self.v[i])
                + 0.5 / self.inv_i[i] * self.w[i].dot(self.w[i]);
        }
        e
    }

    /// Energy bookkeeping, with the stored elastic energies of the current contacts.
    pub fn energy(&self) -> DemEnergy {
        let mut e = self.energy;
        let (mut wn, mut wt) = (0.0, 0.0);
        for i in 0..self.len() {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                let h = &self.nl_h[k];
                if h.is_virgin() {
                    continue;
                }
                let j = self.nl_j[k] as usize;
                let c = self.table.pair(self.mat[i] as usize, self.mat[j] as usize);
                let (a, b) =
                    h.elastic_energy(c, Surface::Sphere(self.r[i]), Surface::Sphere(self.r[j]));
                wn += a;
                wt += b;
            }
        }
        for k in 0..self.wl_i.len() {
            let h = &self.wl_h[k];
            if h.is_virgin() {
                continue;
            }
            let i = self.wl_i[k] as usize;
            let wall = &self.walls[self.wl_k[k] as usize];
            let c = self.table.pair(wall.material, self.mat[i] as usize);
            let (a, b) = h.elastic_energy(c, Surface::Plane, Surface::Sphere(self.r[i]));
            wn += a;
            wt += b;
        }
        e.normal_elastic = wn;
        e.tangential_elastic = wt;
        e
    }

    /// Calls `f` for every touching contact.
    pub fn for_each_contact(&self, mut f: impl FnMut(ContactView)) {
        for i in 0..self.len() {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                let h = &self.nl_h[k];
                if h.is_virgin() {
                    continue;
                }
                let j = self.nl_j[k] as usize;
                let (p, q) = if self.id[i] < self.id[j] {
                    (i, j)
                } else {
                    (j, i)
                };
                f(ContactView {
                    p: Some(self.id[p] as usize),
                    wall: None,
                    q: self.id[q] as usize,
                    normal: h.normal,
                    overlap: h.overlap,
                });
            }
        }
        for k in 0..self.wl_i.len() {
            let h = &self.wl_h[k];
            if h.is_virgin() {
                continue;
            }
            f(ContactView {
                p: None,
                wall: Some(self.wl_k[k] as usize),
                q: self.id[self.wl_i[k] as usize] as usize,
                normal: h.normal,
                overlap: h.overlap,
            });
        }
    }

    /// Bytes held per particle by the engine's arrays, neighbour and wall lists and histories
    /// (and, with the `parallel` feature, the parallel loop's buffers once it has run)
    /// (capacities, so an upper bound of what is in use).
    pub fn bytes_per_particle(&self) -> f64 {
        use std::mem::size_of;
        let v3 = size_of::<Vec3>();
        let per = 6 * v3 + 4 * size_of::<f64>() + 3 * size_of::<u32>();
        let lists = self.nl_start.capacity() * 4
            + self.nl_j.capacity() * 4
            + self.nl_h.capacity() * size_of::<ContactHistory<T>>()
            + self.wl_k.capacity() * 4
            + self.wl_i.capacity() * 4
            + self.wl_h.capacity() * size_of::<ContactHistory<T>>();
        #[cfg(feature = "parallel")]
        let lists = lists + self.par.bytes();
        let n = self.len().max(1);
        (per * self.len() + lists + self.grid.bytes()) as f64 / n as f64
    }
}
