//! A small reference DEM driver over the same kernel as the plugin: it reads a LAMMPS data file
//! (`atom_style sphere`: `id type diameter density x y z`, then `Velocities`), finds the
//! touching pairs with a cell list, evaluates them with [`Model::compute`] and integrates with
//! the velocity-Verlet scheme of LAMMPS' `fix nve/sphere` (same operations in the same order:
//! `v += (dt/2) f/m; x += dt v; w += (dt/2) T / (0.4 m r^2)` before the forces, the two kicks
//! after). The forces of the set-up step (step 0) are evaluated with no displacement (`dt = 0`),
//! as in the plugin (LAMMPS' `update->setupflag`) and in creep-dem's initial forces. Contacts are oriented from the lower atom tag to
//! the higher, as in the plugin, so both evaluate each pair identically; only the order in
//! which pair forces are summed per atom differs (rounding).
//!
//! It is the "our engine" side of the plugin's tests: `creep-lammps-ref` prints its pressure
//! and kinetic energy per step for `test.sh` to compare with LAMMPS' thermo output.

use std::f64::consts::PI;

use crate::model::{Body, Contact, ContactOutput, Model, ModelError};

/// A bad data or parameter file.
#[derive(Debug, thiserror::Error)]
pub enum DriverError {
    /// The text could not be parsed.
    #[error("{0}")]
    Parse(String),
    /// The law refused something.
    #[error(transparent)]
    Model(#[from] ModelError),
}

fn perr(msg: impl Into<String>) -> DriverError {
    DriverError::Parse(msg.into())
}

/// Spheres of a LAMMPS data file (SI units).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Packing {
    /// Atom tags (IDs), as in the file.
    pub tag: Vec<i64>,
    /// Atom types.
    pub kind: Vec<i64>,
    /// Radii (m) (half the file's diameters).
    pub radius: Vec<f64>,
    /// Densities (kg/m^3) as in the file.
    pub density: Vec<f64>,
    /// Masses (kg), computed as LAMMPS' `atom_style sphere` does:
    /// `rho * (4 pi / 3 * r * r * r)`.
    pub mass: Vec<f64>,
    /// Centres (m).
    pub x: Vec<[f64; 3]>,
    /// Velocities (m/s).
    pub v: Vec<[f64; 3]>,
    /// Angular velocities (rad/s).
    pub omega: Vec<[f64; 3]>,
    /// Box lower corner (m).
    pub lo: [f64; 3],
    /// Box upper corner (m).
    pub hi: [f64; 3],
    /// Number of atom types declared.
    pub types: i64,
    /// Periodic in x, y and z (LAMMPS `boundary p p p`); otherwise open (`f f f`, no walls).
    pub periodic: bool,
}

fn nums(line: &str) -> Result<Vec<f64>, DriverError> {
    line.split_whitespace()
        .take_while(|w| !w.starts_with('#'))
        .map(|w| w.parse::<f64>().map_err(|e| perr(format!("`{line}`: {e}"))))
        .collect()
}

/// Mass of a sphere of radius `r` (m) and density `rho` (kg/m^3), in LAMMPS' operation order
/// (`atom_style sphere`: `rmass = density; rmass *= 4 pi / 3 * r * r * r`).
pub fn sphere_mass(r: f64, rho: f64) -> f64 {
    rho * (4.0 * PI / 3.0 * r * r * r)
}

impl Packing {
    /// Parses a LAMMPS data file with `atom_style sphere` columns.
    pub fn read_data(text: &str) -> Result<Self, DriverError> {
        let mut p = Packing::default();
        let mut atoms = 0usize;
        let mut section = "";
        let mut index = std::collections::HashMap::new();
        for line in text.lines().skip(1) {
            let t = line.trim();
            if t.is_empty() {
                continue;
            }
            let head = t.split('#').next().unwrap_or("").trim();
            match head {
                "Atoms" | "Velocities" => {
                    section = if head == "Atoms" {
                        "Atoms"
                    } else {
                        "Velocities"
                    };
                    continue;
                }
                _ => {}
            }
            if section.is_empty() {
                if head.ends_with(" atoms") {
                    atoms = head
                        .split_whitespace()
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or_else(|| perr(format!("bad atom count `{t}`")))?;
                } else if head.ends_with(" atom types") {
                    p.types = head
                        .split_whitespace()
                        .next()
                        .and_then(|w| w.parse().ok())
                        .ok_or_else(|| perr(format!("bad type count `{t}`")))?;
                } else if let Some(axis) = ["xlo xhi", "ylo yhi", "zlo zhi"]
                    .iter()
                    .position(|k| head.ends_with(k))
                {
                    let v = nums(&head[..head.len() - 7])?;
                    if v.len() != 2 {
                        return Err(perr(format!("bad box line `{t}`")));
                    }
                    p.lo[axis] = v[0];
                    p.hi[axis] = v[1];
                }
                continue;
            }
            let v = nums(head)?;
            if section == "Atoms" {
                if v.len() < 7 {
                    return Err(perr(format!("Atoms line needs 7 columns: `{t}`")));
                }
                let r = 0.5 * v[2];
                index.insert(v[0] as i64, p.tag.len());
                p.tag.push(v[0] as i64);
                p.kind.push(v[1] as i64);
                p.radius.push(r);
                p.density.push(v[3]);
                p.mass.push(sphere_mass(r, v[3]));
                p.x.push([v[4], v[5], v[6]]);
                p.v.push([0.0; 3]);
                p.omega.push([0.0; 3]);
            } else {
                if v.len() < 7 {
                    return Err(perr(format!("Velocities line needs 7 columns: `{t}`")));
                }
                let i = *index
                    .get(&(v[0] as i64))
                    .ok_or_else(|| perr(format!("velocity of unknown atom `{t}`")))?;
                p.v[i] = [v[1], v[2], v[3]];
                p.omega[i] = [v[4], v[5], v[6]];
            }
        }
        if p.tag.len() != atoms || atoms == 0 {
            return Err(perr(format!(
                "header says {atoms} atoms, Atoms section has {}",
                p.tag.len()
            )));
        }
        if let Some(i) = (0..atoms).find(|&i| !(p.radius[i] > 0.0 && p.mass[i] > 0.0)) {
            return Err(perr(format!(
                "atom {} has no positive size and mass",
                p.tag[i]
            )));
        }
        Ok(p)
    }

    /// The packing as a LAMMPS data file (`atom_style sphere`), every number with 17
    /// significant digits so LAMMPS reads back the same doubles.
    pub fn write_data(&self, title: &str) -> String {
        let mut s = format!(
            "{title}\n\n{} atoms\n{} atom types\n\n",
            self.tag.len(),
            self.types.max(1)
        );
        for (a, n) in ["x", "y", "z"].iter().enumerate() {
            s.push_str(&format!(
                "{:.16e} {:.16e} {n}lo {n}hi\n",
                self.lo[a], self.hi[a]
            ));
        }
        s.push_str("\nAtoms\n\n");
        for i in 0..self.tag.len() {
            let x = self.x[i];
            s.push_str(&format!(
                "{} {} {:.16e} {:.16e} {:.16e} {:.16e} {:.16e}\n",
                self.tag[i],
                self.kind[i],
                2.0 * self.radius[i],
                self.density[i],
                x[0],
                x[1],
                x[2]
            ));
        }
        s.push_str("\nVelocities\n\n");
        for i in 0..self.tag.len() {
            let (v, w) = (self.v[i], self.omega[i]);
            s.push_str(&format!(
                "{} {:.16e} {:.16e} {:.16e} {:.16e} {:.16e} {:.16e}\n",
                self.tag[i], v[0], v[1], v[2], w[0], w[1], w[2]
            ));
        }
        s
    }

    /// A quick test packing (seconds, not the minute of a compaction): `n^3` spheres of mean
    /// radius `r` (m) and density `rho` on a simple cubic lattice of spacing `2 r (1 - squeeze)`,
    /// with radii and positions perturbed by a fixed pseudo-random sequence of relative size
    /// `jitter` (of `r`), so neighbours overlap by different amounts; the box is the lattice's
    /// bounding box plus one radius.
    pub fn lattice(n: usize, r: f64, rho: f64, squeeze: f64, jitter: f64) -> Self {
        // Knuth's MMIX LCG: a reproducible sequence without a dependency.
        let mut state: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        let s = 2.0 * r * (1.0 - squeeze);
        let mut p = Packing {
            types: 1,
            ..Packing::default()
        };
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let ri = r * (1.0 + jitter * next());
                    let x = [
                        i as f64 * s + r * jitter * next(),
                        j as f64 * s + r * jitter * next(),
                        k as f64 * s + r * jitter * next(),
                    ];
                    p.tag.push(p.tag.len() as i64 + 1);
                    p.kind.push(1);
                    p.radius.push(ri);
                    p.density.push(rho);
                    p.mass.push(sphere_mass(ri, rho));
                    p.x.push(x);
                    p.v.push([0.0; 3]);
                    p.omega.push([0.0; 3]);
                }
            }
        }
        // A periodic box of exactly n spacings: every sphere is squeezed by its neighbours on
        // all sides, also across the boundaries.
        p.lo = [-0.5 * s; 3];
        p.hi = [(n as f64 - 0.5) * s; 3];
        p.periodic = true;
        p
    }

    /// Adds the periodic shear velocity field `v_x += rate L / (2 pi) sin(2 pi (z - z_lo) / L)`
    /// (m/s), `L` the box height: a shear rate of at most `rate` (1/s), continuous across a
    /// periodic boundary.
    pub fn add_shear(&mut self, rate: f64) {
        let l = self.hi[2] - self.lo[2];
        let amp = rate * l / (2.0 * PI);
        for (v, x) in self.v.iter_mut().zip(&self.x) {
            v[0] += amp * (2.0 * PI * (x[2] - self.lo[2]) / l).sin();
        }
    }

    /// Box volume (m^3).
    pub fn volume(&self) -> f64 {
        (0..3).map(|a| self.hi[a] - self.lo[a]).product()
    }
}

/// `variable NAME equal VALUE` of a LAMMPS include file (e.g. `params.lmp` of
/// `creep bench dem --export`).
pub fn lammps_variable(text: &str, name: &str) -> Result<f64, DriverError> {
    for line in text.lines() {
        let w: Vec<&str> = line.split_whitespace().collect();
        if w.len() >= 4 && w[0] == "variable" && w[1] == name && w[2] == "equal" {
            return w[3]
                .parse()
                .map_err(|e| perr(format!("variable {name} = `{}`: {e}", w[3])));
        }
    }
    Err(perr(format!("no `variable {name} equal ...`")))
}

/// Thermo of one step, as LAMMPS prints it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Thermo {
    /// Step number (0: set-up).
    pub step: u64,
    /// Pair pressure `sum r_ij . f_ij / (3 V)` (Pa) (LAMMPS `compute pressure NULL pair`).
    pub pressure: f64,
    /// Translational kinetic energy `sum m v^2 / 2` (J) (LAMMPS `compute ke`).
    pub ke: f64,
    /// Touching contacts.
    pub contacts: usize,
}

/// The driver: a packing, one model for all pairs, per-atom contact histories.
#[derive(Debug, Clone)]
pub struct Sim {
    /// The spheres.
    pub packing: Packing,
    model: Model,
    dt: f64,
    stride: usize,
    /// Per atom: partner indices and histories (a contact lives under its lower-tag atom).
    partners: Vec<Vec<(usize, usize)>>, // (partner, offset into store)
    store: Vec<f64>,
    f: Vec<[f64; 3]>,
    t: Vec<[f64; 3]>,
    // Batch buffers.
    /// Touching pairs `(p, q, image shift of q)`.
    pairs: Vec<(usize, usize, [f64; 3])>,
    contacts: Vec<Contact>,
    hist: Vec<f64>,
    out: Vec<ContactOutput>,
    cells: Vec<Vec<usize>>,
    step: u64,
}

impl Sim {
    /// A driver over `packing` with `model` for every pair and time step `dt` (s); computes the
    /// set-up forces (step 0) with no displacement (`dt = 0`).
    pub fn new(packing: Packing, model: Model, dt: f64) -> Result<(Self, Thermo), DriverError> {
        let n = packing.tag.len();
        let mut s = Sim {
            stride: model.tier().history_len(),
            packing,
            model,
            dt,
            partners: vec![Vec::new(); n],
            store: Vec::new(),
            f: vec![[0.0; 3]; n],
            t: vec![[0.0; 3]; n],
            pairs: Vec::new(),
            contacts: Vec::new(),
            hist: Vec::new(),
            out: Vec::new(),
            cells: Vec::new(),
            step: 0,
        };
        let th = s.forces_with(0.0, true)?;
        Ok((s, th))
    }

    /// Finds the overlapping pairs `(p, q, shift)`, `tag[p] < tag[q]`, with a cell list of cell
    /// size at least twice the largest radius; with a periodic box, q's nearest image is
    /// `x_q + shift` with `shift` a box length or zero per axis (as LAMMPS' ghosts: `x + L`).
    fn find_pairs(&mut self) -> Result<(), DriverError> {
        let p = &self.packing;
        let n = p.tag.len();
        let rmax = p.radius.iter().cloned().fold(0.0, f64::max);
        let h = 2.0 * rmax;
        let (lo, hi) = if p.periodic {
            (p.lo, p.hi)
        } else {
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [f64::NEG_INFINITY; 3];
            for x in &p.x {
                for a in 0..3 {
                    lo[a] = lo[a].min(x[a]);
                    hi[a] = hi[a].max(x[a]);
                }
            }
            (lo, hi)
        };
        let len: [f64; 3] = std::array::from_fn(|a| p.hi[a] - p.lo[a]);
        let dims: [usize; 3] = if p.periodic {
            std::array::from_fn(|a| ((hi[a] - lo[a]) / h) as usize)
        } else {
            std::array::from_fn(|a| (((hi[a] - lo[a]) / h) as usize + 1).max(1))
        };
        if p.periodic && dims.iter().any(|&d| d < 3) {
            return Err(perr("periodic box shorter than three contact diameters"));
        }
        let cell = |x: &[f64; 3]| -> [usize; 3] {
            std::array::from_fn(|a| {
                let c = ((x[a] - lo[a]) / h).floor();
                if p.periodic {
                    (c as i64).rem_euclid(dims[a] as i64) as usize
                } else {
                    (c.max(0.0) as usize).min(dims[a] - 1)
                }
            })
        };
        let ncell = dims[0] * dims[1] * dims[2];
        self.cells.resize_with(ncell, Vec::new);
        for c in &mut self.cells {
            c.clear();
        }
        for i in 0..n {
            let c = cell(&p.x[i]);
            self.cells[c[0] + dims[0] * (c[1] + dims[1] * c[2])].push(i);
        }
        self.pairs.clear();
        for i in 0..n {
            let c = cell(&p.x[i]);
            for dz in -1i64..=1 {
                for dy in -1i64..=1 {
                    for dx in -1i64..=1 {
                        let mut cc = [c[0] as i64 + dx, c[1] as i64 + dy, c[2] as i64 + dz];
                        if p.periodic {
                            for a in 0..3 {
                                cc[a] = cc[a].rem_euclid(dims[a] as i64);
                            }
                        } else if (0..3).any(|a| cc[a] < 0 || cc[a] >= dims[a] as i64) {
                            continue;
                        }
                        let idx =
                            cc[0] as usize + dims[0] * (cc[1] as usize + dims[1] * cc[2] as usize);
                        for &j in &self.cells[idx] {
                            if p.tag[j] <= p.tag[i] {
                                continue;
                            }
                            let mut shift = [0.0; 3];
                            if p.periodic {
                                for a in 0..3 {
                                    let d = p.x[j][a] - p.x[i][a];
                                    if d > 0.5 * len[a] {
                                        shift[a] = -len[a];
                                    } else if d < -0.5 * len[a] {
                                        shift[a] = len[a];
                                    }
                                }
                            }
                            let d: [f64; 3] =
                                std::array::from_fn(|a| (p.x[j][a] + shift[a]) - p.x[i][a]);
                            let rs = p.radius[i] + p.radius[j];
                            if d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < rs * rs {
                                self.pairs.push((i, j, shift));
                            }
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// Zeroes and computes the forces and torques at the current state over one step `dt`;
    /// `commit` false leaves the histories as they were (evaluated with `dt = 0`).
    fn forces(&mut self, commit: bool) -> Result<Thermo, DriverError> {
        self.forces_with(if commit { self.dt } else { 0.0 }, commit)
    }

    /// [`Sim::forces`] with the step `dt` given (s).
    fn forces_with(&mut self, dt: f64, commit: bool) -> Result<Thermo, DriverError> {
        self.find_pairs()?;
        let p = &self.packing;
        let body = |i: usize, shift: [f64; 3]| Body {
            x: std::array::from_fn(|a| p.x[i][a] + shift[a]),
            v: p.v[i],
            omega: p.omega[i],
            radius: p.radius[i],
            mass: p.mass[i],
        };
        self.contacts.clear();
        self.hist.clear();
        for &(i, j, shift) in &self.pairs {
            self.contacts.push(Contact {
                p: body(i, [0.0; 3]),
                q: body(j, shift),
            });
            let at = self.hist.len();
            self.hist.resize(at + self.stride, 0.0);
            if let Some(&(_, off)) = self.partners[i].iter().find(|(q, _)| *q == j) {
                self.hist[at..at + self.stride]
                    .copy_from_slice(&self.store[off..off + self.stride]);
            }
        }
        self.out
            .resize(self.contacts.len(), ContactOutput::default());
        let model = &self.model;
        Model::compute_by(
            |_| Some(model),
            dt,
            &self.contacts,
            &mut self.hist,
            self.stride,
            &mut self.out,
        )?;
        for f in self.f.iter_mut().chain(self.t.iter_mut()) {
            *f = [0.0; 3];
        }
        let mut virial = 0.0;
        let mut touching = 0;
        for (k, &(i, j, shift)) in self.pairs.iter().enumerate() {
            let o = &self.out[k];
            #[allow(clippy::needless_range_loop)] // four arrays indexed alike
            for a in 0..3 {
                self.f[i][a] += o.force_p[a];
                self.f[j][a] -= o.force_p[a];
                self.t[i][a] += o.torque_p[a];
                self.t[j][a] += o.torque_q[a];
                virial += (p.x[i][a] - (p.x[j][a] + shift[a])) * o.force_p[a];
            }
            touching += o.touching as usize;
        }
        if commit {
            for l in &mut self.partners {
                l.clear();
            }
            self.store.clear();
            for (k, &(i, j, _)) in self.pairs.iter().enumerate() {
                if self.out[k].touching == 1 {
                    let off = self.store.len();
                    self.store
                        .extend_from_slice(&self.hist[k * self.stride..(k + 1) * self.stride]);
                    self.partners[i].push((j, off));
                }
            }
        }
        let ke = 0.5
            * p.mass
                .iter()
                .zip(&p.v)
                .map(|(m, v)| m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
                .sum::<f64>();
        Ok(Thermo {
            step: self.step,
            pressure: virial / (3.0 * p.volume()),
            ke,
            contacts: touching,
        })
    }

    /// Throughput of the kernel alone: evaluates the touching pairs of the current state
    /// `steps` times through [`Model::compute`] (one batch, histories advancing, no neighbour
    /// search, no integration) and returns the seconds per batch and the batch size. What a
    /// host pays for the law itself, without the C ABI's gathering or LAMMPS.
    pub fn time_kernel(&mut self, steps: usize) -> Result<(f64, usize), DriverError> {
        self.forces(false)?;
        let mut hist = vec![0.0; self.contacts.len() * self.stride];
        let model = &self.model;
        let start = std::time::Instant::now();
        for _ in 0..steps {
            Model::compute_by(
                |_| Some(model),
                self.dt,
                &self.contacts,
                &mut hist,
                self.stride,
                &mut self.out,
            )?;
        }
        Ok((
            start.elapsed().as_secs_f64() / steps.max(1) as f64,
            self.contacts.len(),
        ))
    }

    /// [`Sim::time_kernel`] through the batched store path instead ([`crate::compute_pairs`]
    /// over a [`crate::HistoryStore`], one contact at a time, forces added into per-atom
    /// arrays; a pair across a periodic boundary gets a ghost copy of q, as LAMMPS' ghosts):
    /// the law with LAMMPS' neighbour loop, integration and communication taken away. The
    /// pair style's own loop ([`crate::compute_list`]) runs in an AVX2 copy where the CPU has
    /// it and steps the spring tier four contacts at a time, so it can be the faster.
    pub fn time_kernel_store(&mut self, steps: usize) -> Result<(f64, usize), DriverError> {
        self.forces(false)?;
        let p = &self.packing;
        let n = p.tag.len();
        let (mut x, mut v, mut w) = (p.x.clone(), p.v.clone(), p.omega.clone());
        let (mut r, mut m) = (p.radius.clone(), p.mass.clone());
        let mut pairs = Vec::with_capacity(self.pairs.len());
        for (k, &(i, j, shift)) in self.pairs.iter().enumerate() {
            let q = if shift == [0.0; 3] {
                j
            } else {
                x.push(std::array::from_fn(|a| p.x[j][a] + shift[a]));
                v.push(p.v[j]);
                w.push(p.omega[j]);
                r.push(p.radius[j]);
                m.push(p.mass[j]);
                x.len() - 1
            };
            let idx =
                |a: usize| i32::try_from(a).map_err(|_| perr("too many atoms for i32 indices"));
            pairs.push(crate::PairIndex {
                p: idx(i)?,
                q: idx(q)?,
                slot: idx(k)?,
            });
        }
        let kind = vec![1; x.len()];
        let atoms = crate::Atoms {
            x: &x,
            v: &v,
            omega: &w,
            radius: &r,
            mass: &m,
            kind: &kind,
        };
        let (mut f, mut t) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
        let mut store = crate::HistoryStore::new(self.model.tier());
        let model = &self.model;
        let table = crate::ModelTable {
            ntypes: 1,
            model_of: |k: usize| (k == 3).then_some(model),
        };
        let start = std::time::Instant::now();
        for _ in 0..steps {
            let mut acc = crate::Accumulators {
                force: &mut f,
                torque: &mut t,
            };
            crate::compute_pairs(
                &table,
                &mut store,
                &atoms,
                &mut acc,
                &pairs,
                pairs.len(),
                self.dt,
                crate::PairOutputs::default(),
            )?;
        }
        Ok((
            start.elapsed().as_secs_f64() / steps.max(1) as f64,
            pairs.len(),
        ))
    }

    /// One velocity-Verlet step as LAMMPS' `fix nve/sphere` does it (inertia factor 0.4 of a
    /// solid sphere); returns the step's thermo.
    pub fn step(&mut self) -> Result<Thermo, DriverError> {
        let dtv = self.dt;
        let dtf = 0.5 * self.dt;
        let dtfrot = dtf / 0.4;
        let p = &mut self.packing;
        for i in 0..p.tag.len() {
            let dtfm = dtf / p.mass[i];
            for a in 0..3 {
                p.v[i][a] += dtfm * self.f[i][a];
            }
            for a in 0..3 {
                p.x[i][a] += dtv * p.v[i][a];
            }
            let dtirotate = dtfrot / (p.radius[i] * p.radius[i] * p.mass[i]);
            for a in 0..3 {
                p.omega[i][a] += dtirotate * self.t[i][a];
            }
        }
        if p.periodic {
            // Back into the box (LAMMPS remaps at its neighbour-list builds; either way the
            // image used for a pair is the nearest one).
            for x in &mut p.x {
                for (a, xa) in x.iter_mut().enumerate() {
                    let l = p.hi[a] - p.lo[a];
                    if *xa >= p.hi[a] {
                        *xa -= l;
                    } else if *xa < p.lo[a] {
                        *xa += l;
                    }
                }
            }
        }
        self.step += 1;
        let mut th = self.forces(true)?;
        let p = &mut self.packing;
        for i in 0..p.tag.len() {
            let dtfm = dtf / p.mass[i];
            for a in 0..3 {
                p.v[i][a] += dtfm * self.f[i][a];
            }
            let dtirotate = dtfrot / (p.radius[i] * p.radius[i] * p.mass[i]);
            for a in 0..3 {
                p.omega[i][a] += dtirotate * self.t[i][a];
            }
        }
        th.ke = 0.5
            * p.mass
                .iter()
                .zip(&p.v)
                .map(|(m, v)| m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
                .sum::<f64>();
        Ok(th)
    }
}
