//! The engine's constructor (validation, arrays, first list and forces) and its accessors.

use creep_law::Vec3;
use creep_law::pair::{ContactHistory, TangentialLaw};

use crate::{
    Dem, DemConfig, DemCounts, DemEnergy, DemError, Kernels, MaterialTable, Particle, Wall, grid,
};

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
            kernels: Kernels::detected()?,
            #[cfg(feature = "parallel")]
            par: crate::par::Buffers::default(),
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
    /// The compiled copy of the force loops the engine runs ([`Kernels::detected`] at first).
    pub fn kernels(&self) -> Kernels {
        self.kernels
    }
    /// Runs the force loops' copy `kernels` from now on (the same bits as any other); one the
    /// CPU does not run ([`Kernels::available`]) is an error.
    pub fn set_kernels(&mut self, kernels: Kernels) -> Result<(), DemError> {
        if !kernels.available() {
            return Err(DemError::Parameter {
                name: "kernels",
                value: f64::NAN,
                why: "this CPU lacks the instruction set (Kernels::available)",
            });
        }
        self.kernels = kernels;
        Ok(())
    }
    /// The material table.
    pub fn table(&self) -> &MaterialTable {
        &self.table
    }
    /// Sets the time step \[s\] (finite and > 0) from the next step on. Velocity Verlet's
    /// state between steps (positions, velocities, the forces at the positions) does not depend
    /// on the step, so the run continues as if started with the new one; the contact histories
    /// are kept (each step's tangential increment is its relative motion over that step).
    pub fn set_time_step(&mut self, dt: f64) -> Result<(), DemError> {
        check(
            "time step dt",
            dt,
            dt.is_finite() && dt > 0.0,
            "must be finite and > 0 [s]",
        )?;
        self.cfg.dt = dt;
        Ok(())
    }
    /// Sets the neighbour-list skin \[m\] (finite and > 0) and rebuilds the list now, with the
    /// contact histories carried over (the cells are refitted to `2 r_max + skin`). The physics
    /// does not depend on the skin; a larger one rebuilds less often and tests more pairs per
    /// step. Results change at the rounding level only (the list's order, and so the order of
    /// each particle's force sum, follows the rebuilds).
    pub fn set_skin(&mut self, skin: f64) -> Result<(), DemError> {
        check(
            "skin",
            skin,
            skin.is_finite() && skin > 0.0,
            "must be finite and > 0 [m]",
        )?;
        let r_max = self.r.iter().fold(0.0_f64, |m, &r| m.max(r));
        self.grid = grid::Grid::new(self.cfg.periodic, 2.0 * r_max + skin)?;
        self.cfg.skin = skin;
        self.rebuild();
        Ok(())
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
    /// Angular velocities in the engine's order [rad/s].
    pub fn angular_velocities(&self) -> &[Vec3] {
        &self.w
    }
    /// Forces of the last evaluation in the engine's order \[N\].
    pub fn particle_forces(&self) -> &[Vec3] {
        &self.f
    }
    /// Position of particle `id` in the engine's order.
    pub fn index_of(&self, id: usize) -> usize {
        self.index[id] as usize
    }
}

/// Checkpoints (`checkpoint`): the state out and back in. The lists are not stored: they are
/// rebuilt from the positions of the last rebuild (module `checkpoint`), so only the histories
/// are read from them, keyed by particle ids.
impl<T: TangentialLaw> Dem<T> {
    /// The state, with every non-virgin history keyed by ids.
    pub(crate) fn raw_state(&self) -> crate::checkpoint::RawState<T> {
        let mut pairs = Vec::new();
        for i in 0..self.len() {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                if !self.nl_h[k].is_virgin() {
                    let (a, b) = (self.id[i], self.id[self.nl_j[k] as usize]);
                    pairs.push((a.min(b), a.max(b), self.nl_h[k]));
                }
            }
        }
        let wall_pairs = (0..self.wl_i.len())
            .filter(|&e| !self.wl_h[e].is_virgin())
            .map(|e| (self.wl_k[e], self.id[self.wl_i[e] as usize], self.wl_h[e]))
            .collect();
        crate::checkpoint::RawState {
            id: self.id.clone(),
            mat: self.mat.clone(),
            r: self.r.clone(),
            mass: self.mass.clone(),
            inv_m: self.inv_m.clone(),
            inv_i: self.inv_i.clone(),
            x: self.x.clone(),
            v: self.v.clone(),
            w: self.w.clone(),
            f: self.f.clone(),
            t: self.t.clone(),
            x_build: self.x_build.clone(),
            walls: self.walls.clone(),
            wall_build: self.wall_build.clone(),
            wall_force: self.wall_force.clone(),
            pairs,
            wall_pairs,
            energy: self.energy,
            counts: self.counts,
            time: self.time,
            steps: self.steps,
        }
    }

    /// The engine of a [`Dem::raw_state`]: the lists rebuilt at the positions of the last
    /// rebuild (the particles are in that rebuild's cell order, which the stable sort keeps:
    /// checked), the histories put back by ids, then the current state.
    pub(crate) fn from_raw_state(
        cfg: DemConfig,
        table: MaterialTable,
        s: crate::checkpoint::RawState<T>,
    ) -> Result<Self, DemError> {
        let n = s.id.len();
        let bad = |why: &'static str| DemError::Parameter {
            name: "checkpoint",
            value: n as f64,
            why,
        };
        let lens = [
            s.mat.len(),
            s.r.len(),
            s.mass.len(),
            s.inv_m.len(),
            s.inv_i.len(),
        ];
        let vlens = [
            s.x.len(),
            s.v.len(),
            s.w.len(),
            s.f.len(),
            s.t.len(),
            s.x_build.len(),
        ];
        let nw = s.walls.len();
        if lens.iter().chain(&vlens).any(|&l| l != n)
            || s.wall_build.len() != nw
            || s.wall_force.len() != nw
        {
            return Err(bad("arrays of different lengths"));
        }
        // The constructor checks the settings, materials and walls, and sizes everything.
        let particles: Vec<Particle> = (0..n)
            .map(|i| Particle {
                position: s.x_build[i],
                velocity: s.v[i],
                angular_velocity: s.w[i],
                radius: s.r[i],
                material: s.mat[i] as usize,
            })
            .collect();
        let build_walls: Vec<Wall> = s
            .walls
            .iter()
            .zip(&s.wall_build)
            .map(|(w, &p)| Wall { point: p, ..*w })
            .collect();
        let mut dem = Self::new(cfg, table, &particles, &build_walls)?;
        let mut index = vec![u32::MAX; n];
        for (i, &id) in s.id.iter().enumerate() {
            match index.get_mut(id as usize) {
                Some(slot) if *slot == u32::MAX => *slot = i as u32,
                _ => return Err(bad("particle ids are not 0..n, each once")),
            }
        }
        // The engine's order and arrays, with an old list holding the histories by ids.
        dem.x = s.x_build.clone();
        dem.x_build.clone_from(&s.x_build);
        dem.id = s.id;
        dem.index = index;
        dem.mat = s.mat;
        dem.r = s.r;
        dem.mass = s.mass;
        dem.inv_m = s.inv_m;
        dem.inv_i = s.inv_i;
        let mut rows: Vec<Vec<(u32, ContactHistory<T>)>> = vec![Vec::new(); n];
        for (a, b, h) in s.pairs {
            let (ia, ib) = (dem.index.get(a as usize), dem.index.get(b as usize));
            let (Some(&ia), Some(&ib)) = (ia, ib) else {
                return Err(bad("a contact names a particle that is not there"));
            };
            rows[ia as usize].push((ib, h));
        }
        dem.nl_start = vec![0];
        dem.nl_j.clear();
        dem.nl_h.clear();
        for row in rows {
            for (j, h) in row {
                dem.nl_j.push(j);
                dem.nl_h.push(h);
            }
            dem.nl_start.push(dem.nl_j.len() as u32);
        }
        dem.wl_k.clear();
        dem.wl_i.clear();
        dem.wl_h.clear();
        for (k, id, h) in s.wall_pairs {
            match dem.index.get(id as usize) {
                Some(&i) if (k as usize) < nw => {
                    dem.wl_k.push(k);
                    dem.wl_i.push(i);
                    dem.wl_h.push(h);
                }
                _ => {
                    return Err(bad(
                        "a wall contact names a wall or particle that is not there",
                    ));
                }
            }
        }
        let order = dem.id.clone();
        dem.rebuild();
        if dem.id != order {
            return Err(bad(
                "the particles are not in the cell order of their last rebuild",
            ));
        }
        dem.x = s.x;
        dem.v = s.v;
        dem.w = s.w;
        dem.f = s.f;
        dem.t = s.t;
        dem.walls = s.walls;
        dem.wall_force = s.wall_force;
        dem.energy = s.energy;
        dem.counts = s.counts;
        dem.time = s.time;
        dem.steps = s.steps;
        Ok(dem)
    }
}
