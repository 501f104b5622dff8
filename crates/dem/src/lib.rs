//! # creep-dem
//!
//! A soft-sphere DEM engine for creep-friction, built the way the fast codes (LAMMPS,
//! LIGGGHTS) are, in f64:
//!
//! * per-property arrays (positions, velocities, angular velocities, forces, torques, radii,
//!   masses, material ids), re-sorted by cell at every neighbour rebuild for locality;
//! * a cell grid and a *half* neighbour list with a skin, rebuilt only when some particle has
//!   moved more than half the skin (or a particle and a wall together more than the skin);
//!   the contact history sits beside the list (CSR: `start[i]..start[i+1]`), and is carried
//!   over by partner id only at a rebuild; no hashing in the inner loop;
//! * per material pair constants ([`creep_law::pair::PairConstants`]: combined moduli, damping
//!   from restitution, friction, the steady creep law) computed once, in a small table indexed
//!   by material ids ([`MaterialTable`]);
//! * the pair force is creep-law's pure kernel [`creep_law::pair::pair_force`], with the
//!   tangential tier a generic parameter ([`creep_law::pair::Exact`]: Cattaneo-Mindlin memory
//!   with Kuhn's creep; [`creep_law::pair::Cheap`]: incremental `8 G* a` spring, rescaled at
//!   `mu P`, plus creep), monomorphised;
//! * velocity Verlet (Swope et al. 1982) for translation and rotation (spheres: isotropic
//!   inertia `I = (2/5) m r^2`), the contact forces evaluated at the half-step velocities as in
//!   LAMMPS;
//! * plane walls (any number; moving with a prescribed velocity, e.g. the servo-controlled
//!   walls of a triaxial box, with the force on each wall reported) and periodic boundaries per
//!   axis (minimum image);
//! * with the `parallel` feature and [`DemConfig::parallel`], the force loop runs on rayon's
//!   threads: each pair's force goes to a buffer, then each particle sums its pairs' forces in
//!   list order, so results are identical run to run and for any number of threads.
//!
//! Conventions are creep-law's: in a pair the particle with the smaller id is body p, the
//! normal points from p to q; for a wall contact the wall is p, its normal points into the
//! domain. SI units throughout.
#![forbid(unsafe_code)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Loops index several per-particle arrays at once (structure of arrays) on purpose.
#![allow(clippy::needless_range_loop)]

mod external;
mod grid;
mod probe;

pub use external::{ExternalForces, ExternalView, NoExternal};
pub use probe::{ContactForce, ContactLoad};

use creep_law::pair::{
    ContactGeometry, ContactHistory, PairBody, PairConstants, pair_force, release,
};
use creep_law::rolling_torque::RollingModel;
use creep_law::{CreepModel, LawError, Material, Surface, Vec3};

pub use creep_law::pair::{Cheap, Exact, TangentialLaw};

/// Errors of the engine's constructors and steps.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DemError {
    /// A law parameter was refused by creep-law.
    #[error(transparent)]
    Law(#[from] LawError),
    /// An invalid engine parameter.
    #[error("{name} = {value} is invalid: {why}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// Why it was refused.
        why: &'static str,
    },
    /// A material id out of the table.
    #[error("material id {0} is not in the table")]
    Material(usize),
    /// The tangential tier does not implement the creep model.
    #[error("the {tier} tangential tier does not implement the creep model {model:?}")]
    Unsupported {
        /// Tier name.
        tier: &'static str,
        /// The creep model.
        model: Option<CreepModel>,
    },
    /// A particle's state became non-finite (the time step is too large for the stiffness).
    #[error("particle {0} has a non-finite position or velocity (time step too large?)")]
    NonFinite(usize),
}

/// The constants of every pair of materials: `n x n` [`PairConstants`], indexed by material id.
#[derive(Debug, Clone, PartialEq)]
pub struct MaterialTable {
    materials: Vec<Material>,
    pairs: Vec<PairConstants>,
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
        &self.pairs[i * self.materials.len() + j]
    }
}

/// One particle's initial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Particle {
    /// Centre \[m\].
    pub position: Vec3,
    /// Velocity [m/s].
    pub velocity: Vec3,
    /// Angular velocity [rad/s].
    pub angular_velocity: Vec3,
    /// Radius \[m\], finite and > 0.
    pub radius: f64,
    /// Material id (index in the [`MaterialTable`]).
    pub material: usize,
}

/// A plane wall: the half-space behind `point` along `-normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// A point on the plane \[m\].
    pub point: Vec3,
    /// Unit normal pointing into the domain [-].
    pub normal: Vec3,
    /// Velocity of the wall [m/s] (the plane moves by `velocity dt` each step).
    pub velocity: Vec3,
    /// Material id.
    pub material: usize,
}

/// Settings of the engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemConfig {
    /// Time step \[s\], finite and > 0.
    pub dt: f64,
    /// Neighbour-list skin \[m\], finite and > 0 (LAMMPS' default for granular runs is of the
    /// order of a tenth of the diameter).
    pub skin: f64,
    /// Periodic axes: `Some((lo, hi))` \[m\] makes axis `x`, `y` or `z` periodic with that box.
    pub periodic: [Option<(f64, f64)>; 3],
    /// Gravity [m/s^2].
    pub gravity: Vec3,
    /// Run the force loop on rayon's threads (needs the `parallel` feature; ignored without).
    pub parallel: bool,
}

impl Default for DemConfig {
    fn default() -> Self {
        Self {
            dt: 1e-6,
            skin: 1e-4,
            periodic: [None; 3],
            gravity: Vec3::ZERO,
            parallel: false,
        }
    }
}

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

/// The engine, generic over the tangential tier `T` ([`Exact`] or [`Cheap`]).
#[derive(Debug, Clone)]
pub struct Dem<T: TangentialLaw> {
    cfg: DemConfig,
    table: MaterialTable,
    // Per-particle arrays, in cell order.
    x: Vec<Vec3>,
    v: Vec<Vec3>,
    w: Vec<Vec3>,
    f: Vec<Vec3>,
    t: Vec<Vec3>,
    r: Vec<f64>,
    mass: Vec<f64>,
    inv_m: Vec<f64>,
    inv_i: Vec<f64>,
    mat: Vec<u32>,
    id: Vec<u32>,
    /// Index of each id.
    index: Vec<u32>,
    /// Positions at the last rebuild.
    x_build: Vec<Vec3>,
    walls: Vec<Wall>,
    wall_build: Vec<Vec3>,
    wall_force: Vec<Vec3>,
    // Half neighbour list (CSR) with the histories beside it.
    nl_start: Vec<u32>,
    nl_j: Vec<u32>,
    nl_h: Vec<ContactHistory<T>>,
    // Wall lists: (wall, particle) entries with their histories.
    wl_k: Vec<u32>,
    wl_i: Vec<u32>,
    wl_h: Vec<ContactHistory<T>>,
    grid: grid::Grid,
    energy: DemEnergy,
    counts: DemCounts,
    time: f64,
    steps: u64,
    #[cfg(feature = "parallel")]
    par: par::Buffers,
}

fn check(name: &'static str, value: f64, ok: bool, why: &'static str) -> Result<(), DemError> {
    if ok {
        Ok(())
    } else {
        Err(DemError::Parameter { name, value, why })
    }
}

impl<T: TangentialLaw> Dem<T> {
    /// An engine with the given particles (their ids are their indices in `particles`) and
    /// walls. Validates everything, builds the neighbour list and evaluates the initial forces.
    pub fn new(
        cfg: DemConfig,
        table: MaterialTable,
        particles: &[Particle],
        walls: &[Wall],
    ) -> Result<Self, DemError> {
        check(
            "time step dt",
            cfg.dt,
            cfg.dt.is_finite() && cfg.dt > 0.0,
            "must be finite and > 0 [s]",
        )?;
        check(
            "skin",
            cfg.skin,
            cfg.skin.is_finite() && cfg.skin > 0.0,
            "must be finite and > 0 [m]",
        )?;
        check(
            "gravity",
            cfg.gravity.length(),
            cfg.gravity.is_finite(),
            "must be finite [m/s^2]",
        )?;
        for (i, c) in table.pairs.iter().enumerate() {
            if !T::supports(c.creep()) {
                let _ = i;
                return Err(DemError::Unsupported {
                    tier: T::NAME,
                    model: c.creep(),
                });
            }
        }
        if particles.len() >= u32::MAX as usize {
            return Err(DemError::Parameter {
                name: "number of particles",
                value: particles.len() as f64,
                why: "must be below 2^32 - 1",
            });
        }
        let mut r_max: f64 = 0.0;
        for p in particles {
            check(
                "particle radius",
                p.radius,
                p.radius.is_finite() && p.radius > 0.0,
                "must be finite and > 0 [m]",
            )?;
            if !(p.position.is_finite() && p.velocity.is_finite() && p.angular_velocity.is_finite())
            {
                return Err(DemError::Parameter {
                    name: "particle state",
                    value: f64::NAN,
                    why: "position and velocities must be finite",
                });
            }
            if p.material >= table.len() {
                return Err(DemError::Material(p.material));
            }
            if !(table.materials[p.material].density() > 0.0) {
                return Err(DemError::Parameter {
                    name: "particle density",
                    value: table.materials[p.material].density(),
                    why: "a particle's material must have a density > 0 [kg/m^3]",
                });
            }
            r_max = r_max.max(p.radius);
        }
        for wall in walls {
            let nl = wall.normal.length();
            check(
                "wall normal length",
                nl,
                (nl - 1.0).abs() < 1e-9,
                "must be a unit vector",
            )?;
            if !(wall.point.is_finite() && wall.velocity.is_finite()) {
                return Err(DemError::Parameter {
                    name: "wall state",
                    value: f64::NAN,
                    why: "point and velocity must be finite",
                });
            }
            if wall.material >= table.len() {
                return Err(DemError::Material(wall.material));
            }
        }
        let grid = grid::Grid::new(cfg.periodic, 2.0 * r_max + cfg.skin)?;
        let n = particles.len();
        let mass: Vec<f64> = particles
            .iter()
            .map(|p| {
                4.0 / 3.0
                    * std::f64::consts::PI
                    * p.radius.powi(3)
                    * table.materials[p.material].density()
            })
            .collect();
        let mut dem = Self {
            cfg,
            x: particles.iter().map(|p| p.position).collect(),
            v: particles.iter().map(|p| p.velocity).collect(),
            w: particles.iter().map(|p| p.angular_velocity).collect(),
            f: vec![Vec3::ZERO; n],
            t: vec![Vec3::ZERO; n],
            r: particles.iter().map(|p| p.radius).collect(),
            inv_m: mass.iter().map(|m| 1.0 / m).collect(),
            // Solid sphere: I = (2/5) m r^2.
            inv_i: particles
                .iter()
                .zip(&mass)
                .map(|(p, m)| 1.0 / (0.4 * m * p.radius * p.radius))
                .collect(),
            mass,
            mat: particles.iter().map(|p| p.material as u32).collect(),
            id: (0..n as u32).collect(),
            index: (0..n as u32).collect(),
            x_build: Vec::new(),
            walls: walls.to_vec(),
            wall_build: Vec::new(),
            wall_force: vec![Vec3::ZERO; walls.len()],
            nl_start: Vec::new(),
            nl_j: Vec::new(),
            nl_h: Vec::new(),
            wl_k: Vec::new(),
            wl_i: Vec::new(),
            wl_h: Vec::new(),
            grid,
            table,
            energy: DemEnergy::default(),
            counts: DemCounts::default(),
            time: 0.0,
            steps: 0,
            #[cfg(feature = "parallel")]
            par: par::Buffers::default(),
        };
        for i in 0..n {
            dem.x[i] = dem.grid.wrap(dem.x[i]);
        }
        dem.rebuild();
        // Initial forces with dt = 0: the histories see no displacement.
        dem.forces(0.0);
        Ok(dem)
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }
    /// Whether there are no particles.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
    /// The settings.
    pub fn config(&self) -> &DemConfig {
        &self.cfg
    }
    /// The material table.
    pub fn table(&self) -> &MaterialTable {
        &self.table
    }
    /// Replaces the material table (e.g. to switch friction on after compaction); the contact
    /// histories are kept. The table must have as many materials.
    pub fn set_table(&mut self, table: MaterialTable) -> Result<(), DemError> {
        if table.len() != self.table.len() {
            return Err(DemError::Parameter {
                name: "number of materials",
                value: table.len() as f64,
                why: "must equal the current table's",
            });
        }
        for c in &table.pairs {
            if !T::supports(c.creep()) {
                return Err(DemError::Unsupported {
                    tier: T::NAME,
                    model: c.creep(),
                });
            }
        }
        self.table = table;
        Ok(())
    }
    /// Simulated time \[s\].
    pub fn time(&self) -> f64 {
        self.time
    }
    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.steps
    }
    /// What the last force evaluation saw.
    pub fn counts(&self) -> DemCounts {
        self.counts
    }
    /// The walls.
    pub fn walls(&self) -> &[Wall] {
        &self.walls
    }
    /// Sets the velocity of wall `k` [m/s] (servo control).
    pub fn set_wall_velocity(&mut self, k: usize, velocity: Vec3) -> Result<(), DemError> {
        if !velocity.is_finite() {
            return Err(DemError::Parameter {
                name: "wall velocity",
                value: velocity.length(),
                why: "must be finite [m/s]",
            });
        }
        let wall = self.walls.get_mut(k).ok_or(DemError::Parameter {
            name: "wall index",
            value: k as f64,
            why: "no such wall",
        })?;
        wall.velocity = velocity;
        Ok(())
    }
    /// Force of the particles on wall `k` in the last force evaluation \[N\].
    pub fn wall_force(&self, k: usize) -> Vec3 {
        self.wall_force[k]
    }

    /// The state of particle `id` (as given to [`Dem::new`]; material and radius unchanged).
    pub fn particle(&self, id: usize) -> Particle {
        let i = self.index[id] as usize;
        Particle {
            position: self.x[i],
            velocity: self.v[i],
            angular_velocity: self.w[i],
            radius: self.r[i],
            material: self.mat[i] as usize,
        }
    }
    /// Mass of particle `id` \[kg\].
    pub fn mass(&self, id: usize) -> f64 {
        self.mass[self.index[id] as usize]
    }
    /// Positions in the engine's current (cell) order \[m\]; see [`Dem::ids`].
    pub fn positions(&self) -> &[Vec3] {
        &self.x
    }
    /// Velocities in the engine's order [m/s].
    pub fn velocities(&self) -> &[Vec3] {
        &self.v
    }
    /// Radii in the engine's order \[m\].
    pub fn radii(&self) -> &[f64] {
        &self.r
    }
    /// The particle id at each position of the engine's order.
    pub fn ids(&self) -> &[u32] {
        &self.id
    }

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
        let n = self.len().max(1);
        (per * self.len() + lists + self.grid.bytes()) as f64 / n as f64
    }

    /// One velocity-Verlet step of [`DemConfig::dt`].
    pub fn step(&mut self) -> Result<(), DemError> {
        self.step_with(&mut NoExternal)
    }

    /// One velocity-Verlet step of [`DemConfig::dt`] with forces from outside the engine:
    /// `external` adds its forces after the contact forces, at the same positions and
    /// half-step velocities, before the second half-kick.
    pub fn step_with<E: ExternalForces>(&mut self, external: &mut E) -> Result<(), DemError> {
        let dt = self.cfg.dt;
        let h = 0.5 * dt;
        let n = self.len();
        let mut d2_max: f64 = 0.0;
        for i in 0..n {
            self.v[i] += self.f[i] * (h * self.inv_m[i]);
            self.w[i] += self.t[i] * (h * self.inv_i[i]);
            let x = self.grid.wrap(self.x[i] + self.v[i] * dt);
            self.x[i] = x;
            let d = self.grid.min_image(x - self.x_build[i]);
            d2_max = d2_max.max(d.dot(d));
        }
        let mut wall_max: f64 = 0.0;
        for (k, wall) in self.walls.iter_mut().enumerate() {
            wall.point += wall.velocity * dt;
            wall_max = wall_max.max((wall.point - self.wall_build[k]).dot(wall.normal).abs());
        }
        let d_max = d2_max.sqrt();
        if !d_max.is_finite() {
            let i = (0..n).find(|&i| !self.x[i].is_finite()).unwrap_or(0);
            return Err(DemError::NonFinite(self.id[i] as usize));
        }
        if 2.0 * d_max > self.cfg.skin || d_max + wall_max > self.cfg.skin {
            self.rebuild();
        }
        self.forces(dt);
        external.add_forces(self.external_view(dt))?;
        for i in 0..n {
            self.v[i] += self.f[i] * (h * self.inv_m[i]);
            self.w[i] += self.t[i] * (h * self.inv_i[i]);
        }
        self.time += dt;
        self.steps += 1;
        Ok(())
    }

    /// Evaluates every contact force (and gravity) into `f`, `t` and the wall forces.
    fn forces(&mut self, dt: f64) {
        let n = self.len();
        let g = self.cfg.gravity;
        for i in 0..n {
            self.f[i] = g * self.mass[i];
            self.t[i] = Vec3::ZERO;
        }
        let mut counts = DemCounts {
            neighbours: self.nl_j.len(),
            rebuilds: self.counts.rebuilds,
            ..DemCounts::default()
        };
        let mut energy = self.energy;
        #[cfg(feature = "parallel")]
        let done = if self.cfg.parallel {
            self.pair_forces_parallel(dt, &mut counts, &mut energy);
            true
        } else {
            false
        };
        #[cfg(not(feature = "parallel"))]
        let done = false;
        if !done {
            self.pair_forces_serial(dt, &mut counts, &mut energy);
        }
        self.wall_forces(dt, &mut counts, &mut energy);
        self.counts = counts;
        self.energy = energy;
    }

    #[inline]
    fn body(&self, i: usize, position: Vec3) -> PairBody {
        PairBody {
            position,
            velocity: self.v[i],
            angular_velocity: self.w[i],
            surface: Surface::Sphere(self.r[i]),
            mass: self.mass[i],
        }
    }

    /// The pair `(i, j)` of list entry `k`: `None` when apart (the history is reset), else the
    /// indices of p and q and the kernel's output.
    /// `Err(released energy)` when the pair is apart (its history reset).
    #[inline]
    fn pair(
        &self,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
    ) -> Result<(usize, usize, creep_law::pair::PairForces), f64> {
        let d = self.grid.min_image(self.x[j] - self.x[i]);
        let rs = self.r[i] + self.r[j];
        if d.dot(d) >= rs * rs {
            if h.is_virgin() {
                return Err(0.0);
            }
            let c = self.table.pair(self.mat[i] as usize, self.mat[j] as usize);
            return Err(release(
                c,
                Surface::Sphere(self.r[i]),
                Surface::Sphere(self.r[j]),
                h,
            ));
        }
        let (p, q, dpq) = if self.id[i] < self.id[j] {
            (i, j, d)
        } else {
            (j, i, -d)
        };
        let xp = self.x[p];
        let xq = xp + dpq;
        let c = self.table.pair(self.mat[p] as usize, self.mat[q] as usize);
        let Some(geo) = ContactGeometry::sphere_sphere(xp, self.r[p], xq, self.r[q]) else {
            return Err(release(
                c,
                Surface::Sphere(self.r[p]),
                Surface::Sphere(self.r[q]),
                h,
            ));
        };
        let out = pair_force(c, &self.body(p, xp), &self.body(q, xq), &geo, h, dt);
        if out.touching {
            Ok((p, q, out))
        } else {
            Err(out.dissipation.slip)
        }
    }

    fn pair_forces_serial(&mut self, dt: f64, counts: &mut DemCounts, energy: &mut DemEnergy) {
        let n = self.len();
        let mut hist = std::mem::take(&mut self.nl_h);
        for i in 0..n {
            let (a, b) = (self.nl_start[i] as usize, self.nl_start[i + 1] as usize);
            for k in a..b {
                let j = self.nl_j[k] as usize;
                match self.pair(i, j, &mut hist[k], dt) {
                    Ok((p, q, out)) => {
                        self.f[p] += out.force_p;
                        self.f[q] -= out.force_p;
                        self.t[p] += out.torque_p;
                        self.t[q] += out.torque_q;
                        tally(counts, energy, &out);
                        counts.contacts += 1;
                    }
                    Err(released) => energy.slip += released,
                }
            }
        }
        self.nl_h = hist;
    }

    fn wall_forces(&mut self, dt: f64, counts: &mut DemCounts, energy: &mut DemEnergy) {
        for f in &mut self.wall_force {
            *f = Vec3::ZERO;
        }
        let mut hist = std::mem::take(&mut self.wl_h);
        for (e, h) in hist.iter_mut().enumerate() {
            let k = self.wl_k[e] as usize;
            let i = self.wl_i[e] as usize;
            let wall = self.walls[k];
            let geo = ContactGeometry::plane_sphere(wall.point, wall.normal, self.x[i], self.r[i]);
            let c = self.table.pair(wall.material, self.mat[i] as usize);
            if !(geo.overlap > 0.0) {
                energy.slip += release(c, Surface::Plane, Surface::Sphere(self.r[i]), h);
                continue;
            }
            let bp = PairBody {
                position: geo.point,
                velocity: wall.velocity,
                angular_velocity: Vec3::ZERO,
                surface: Surface::Plane,
                mass: f64::INFINITY,
            };
            let out = pair_force(c, &bp, &self.body(i, self.x[i]), &geo, h, dt);
            if out.touching {
                self.f[i] -= out.force_p;
                self.t[i] += out.torque_q;
                self.wall_force[k] += out.force_p;
                tally(counts, energy, &out);
                counts.wall_contacts += 1;
            }
        }
        self.wl_h = hist;
    }

    /// Re-sorts the particles by cell, rebuilds the half neighbour list and the wall lists, and
    /// carries the histories of the contacts over by partner id.
    fn rebuild(&mut self) {
        let n = self.len();
        self.counts.rebuilds += 1;
        // Old histories stay where they are; the carry-over indexes them by the smaller id
        // (CSR), partner by the larger, so each history is copied once, into the new list (the
        // exact tier's history is ~0.5 kB: copying it through the sort cost more than the rest
        // of the rebuild).
        let old_h = std::mem::replace(&mut self.nl_h, Vec::with_capacity(self.nl_j.len()));
        let old_wh = std::mem::replace(&mut self.wl_h, Vec::with_capacity(self.wl_i.len()));
        let mut carry = Carry::default();
        for i in 0..n {
            for k in self.nl_start.get(i).copied().unwrap_or(0) as usize
                ..self.nl_start.get(i + 1).copied().unwrap_or(0) as usize
            {
                if !old_h[k].is_virgin() {
                    let (a, b) = (self.id[i], self.id[self.nl_j[k] as usize]);
                    carry.push(a.min(b), a.max(b), k as u32);
                }
            }
        }
        for e in 0..self.wl_i.len() {
            if !old_wh[e].is_virgin() {
                carry.push_wall(self.id[self.wl_i[e] as usize], self.wl_k[e], e as u32);
            }
        }
        carry.finish(n);

        // Sort by cell (counting sort, stable).
        let order = self.grid.sort(&self.x);
        permute(&mut self.x, &order);
        permute(&mut self.v, &order);
        permute(&mut self.w, &order);
        permute(&mut self.f, &order);
        permute(&mut self.t, &order);
        permute(&mut self.r, &order);
        permute(&mut self.mass, &order);
        permute(&mut self.inv_m, &order);
        permute(&mut self.inv_i, &order);
        permute(&mut self.mat, &order);
        permute(&mut self.id, &order);
        for (i, &id) in self.id.iter().enumerate() {
            self.index[id as usize] = i as u32;
        }

        // Half neighbour list.
        let skin = self.cfg.skin;
        self.nl_start.clear();
        self.nl_j.clear();
        self.nl_start.push(0);
        for i in 0..n {
            let xi = self.x[i];
            let ri = self.r[i];
            let (x, r, grid) = (&self.x, &self.r, &self.grid);
            let (nl_j, nl_h, id) = (&mut self.nl_j, &mut self.nl_h, &self.id);
            grid.for_half_neighbours(i, |j| {
                let d = grid.min_image(x[j] - xi);
                let cut = ri + r[j] + skin;
                if d.dot(d) < cut * cut {
                    let (a, b) = (id[i], id[j]);
                    nl_j.push(j as u32);
                    nl_h.push(
                        carry
                            .find(a.min(b), a.max(b))
                            .map_or_else(ContactHistory::default, |k| old_h[k]),
                    );
                }
            });
            self.nl_start.push(self.nl_j.len() as u32);
        }

        // Wall lists.
        self.wl_k.clear();
        self.wl_i.clear();
        for (k, wall) in self.walls.iter().enumerate() {
            for i in 0..n {
                if (self.x[i] - wall.point).dot(wall.normal) < self.r[i] + skin {
                    self.wl_k.push(k as u32);
                    self.wl_i.push(i as u32);
                    self.wl_h.push(
                        carry
                            .find_wall(self.id[i], k as u32)
                            .map_or_else(ContactHistory::default, |e| old_wh[e]),
                    );
                }
            }
        }
        self.x_build.clone_from(&self.x);
        self.wall_build = self.walls.iter().map(|w| w.point).collect();
    }
}

fn tally(counts: &mut DemCounts, energy: &mut DemEnergy, out: &creep_law::pair::PairForces) {
    let d = out.dissipation;
    energy.damping += d.damping;
    energy.slip += d.slip;
    energy.creep += d.creep;
    energy.rolling += d.rolling;
    energy.truncation += d.truncation;
    counts.sliding += usize::from(out.sliding);
    counts.creeping += usize::from(out.creep_displacement != creep_law::Vec2::ZERO);
}

/// `v[i] = old[order[i]]`.
fn permute<X: Copy>(v: &mut Vec<X>, order: &[u32]) {
    let old = std::mem::take(v);
    v.extend(order.iter().map(|&o| old[o as usize]));
}

/// Where the histories of the last list are, keyed by particle id (CSR), for the carry-over
/// at a rebuild: `(smaller id, partner id or wall, index in the old list)`.
#[derive(Default)]
struct Carry {
    entries: Vec<(u32, u32, u32)>,
    walls: Vec<(u32, u32, u32)>,
    start: Vec<u32>,
    wall_start: Vec<u32>,
}

impl Carry {
    fn push(&mut self, lo: u32, hi: u32, k: u32) {
        self.entries.push((lo, hi, k));
    }
    fn push_wall(&mut self, id: u32, wall: u32, e: u32) {
        self.walls.push((id, wall, e));
    }
    /// Sorts the entries by key (counting sort) and builds the offsets.
    fn finish(&mut self, n: usize) {
        fn csr(v: &mut Vec<(u32, u32, u32)>, n: usize) -> Vec<u32> {
            let mut start = vec![0u32; n + 1];
            for e in v.iter() {
                start[e.0 as usize + 1] += 1;
            }
            for i in 0..n {
                start[i + 1] += start[i];
            }
            let mut fill = start.clone();
            let mut out = vec![(0, 0, 0); v.len()];
            for e in v.iter() {
                let s = &mut fill[e.0 as usize];
                out[*s as usize] = *e;
                *s += 1;
            }
            *v = out;
            start
        }
        self.start = csr(&mut self.entries, n);
        self.wall_start = csr(&mut self.walls, n);
    }
    /// Index in the old pair list of the contact `(lo, hi)`, if it was touching.
    fn find(&self, lo: u32, hi: u32) -> Option<usize> {
        lookup(&self.start, &self.entries, lo, hi)
    }
    /// Index in the old wall list of the contact of particle `id` with `wall`.
    fn find_wall(&self, id: u32, wall: u32) -> Option<usize> {
        lookup(&self.wall_start, &self.walls, id, wall)
    }
}

/// In CSR rows `start` over `entries` `(owner, partner, index)`, the index stored for
/// `partner` in `owner`'s row.
fn lookup(start: &[u32], entries: &[(u32, u32, u32)], owner: u32, partner: u32) -> Option<usize> {
    let (a, b) = (
        start[owner as usize] as usize,
        start[owner as usize + 1] as usize,
    );
    entries[a..b]
        .iter()
        .find(|e| e.1 == partner)
        .map(|e| e.2 as usize)
}

#[cfg(feature = "parallel")]
mod par;

/// Runs `f` on a rayon pool of `threads` threads (the engines it steps with
/// [`DemConfig::parallel`] use them). Without the `parallel` feature only `threads == 1` runs.
pub fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> Result<R, DemError> {
    if threads == 0 {
        return Err(DemError::Parameter {
            name: "threads",
            value: 0.0,
            why: "at least one thread",
        });
    }
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|_| DemError::Parameter {
                name: "threads",
                value: threads as f64,
                why: "rayon could not start the pool",
            })?;
        Ok(pool.install(f))
    }
    #[cfg(not(feature = "parallel"))]
    {
        if threads == 1 {
            Ok(f())
        } else {
            Err(DemError::Parameter {
                name: "threads",
                value: threads as f64,
                why: "more than one thread needs creep-dem's `parallel` feature",
            })
        }
    }
}
