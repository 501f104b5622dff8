//! One velocity-Verlet step and the force loops (serial; the parallel one is in `par`).

#[cfg(feature = "parallel")]
use creep_law::pair::SphereForces;
use creep_law::pair::{
    ContactGeometry, ContactHistory, LANES, PairBody, SphereForceLanes, SphereLanes, SpherePair,
    TangentialLaw, WallForceLanes, WallLanes, WallSphere, block_supports, pair_force, release,
    wall_block_lanes,
};
use creep_law::{Surface, Vec3};

use crate::{Dem, DemCounts, DemEnergy, DemError, ExternalForces, NoExternal};

impl<T: TangentialLaw> Dem<T> {
    /// One velocity-Verlet step of [`DemConfig::dt`](crate::DemConfig::dt).
    pub fn step(&mut self) -> Result<(), DemError> {
        self.step_with(&mut NoExternal)
    }

    /// One velocity-Verlet step of [`DemConfig::dt`](crate::DemConfig::dt) with forces from outside the engine:
    /// `external` adds its forces after the contact forces, at the same positions and
    /// half-step velocities, before the second half-kick.
    pub fn step_with<E: ExternalForces>(&mut self, external: &mut E) -> Result<(), DemError> {
        let dt = self.cfg.dt;
        #[cfg(feature = "parallel")]
        if self.cfg.parallel {
            return self.step_parallel(external);
        }
        let h = 0.5 * dt;
        let d2_max = self.kick_drift(dt);
        self.move_walls_and_check(d2_max, dt)?;
        self.forces(dt);
        external.add_forces(self.external_view(dt))?;
        self.kick(h);
        self.time += dt;
        self.steps += 1;
        Ok(())
    }

    /// What comes between the drift and the forces: the walls move, and the list is rebuilt if
    /// a particle has moved more than half the skin (or a particle and a wall together more
    /// than the skin) since the last rebuild; `d2_max` is the drift's largest squared
    /// displacement \[m^2\]. A non-finite position is an error.
    pub(crate) fn move_walls_and_check(&mut self, d2_max: f64, dt: f64) -> Result<(), DemError> {
        let mut wall_max: f64 = 0.0;
        for (k, wall) in self.walls.iter_mut().enumerate() {
            wall.point += wall.velocity * dt;
            wall_max = wall_max.max((wall.point - self.wall_build[k]).dot(wall.normal).abs());
        }
        let d_max = d2_max.sqrt();
        if !d_max.is_finite() {
            let i = (0..self.len())
                .find(|&i| !self.x[i].is_finite())
                .unwrap_or(0);
            return Err(DemError::NonFinite(self.id[i] as usize));
        }
        if 2.0 * d_max > self.cfg.skin || d_max + wall_max > self.cfg.skin {
            self.rebuild();
        }
        Ok(())
    }

    /// Velocity Verlet's first half-kick and the drift: `v += f/m dt/2`, `w += t/I dt/2`,
    /// `x += v dt` (wrapped); returns the largest squared displacement since the last rebuild
    /// \[m^2\] (minimum image).
    fn kick_drift(&mut self, dt: f64) -> f64 {
        let h = 0.5 * dt;
        let mut d2_max: f64 = 0.0;
        if !self.grid.is_periodic() {
            // No periodic axis: `wrap` and `min_image` return their arguments, so the loop
            // without them (and with the arrays sliced to one length, one bounds check) gives
            // the same bits.
            let n = self.len();
            let (v, w, x) = (&mut self.v[..n], &mut self.w[..n], &mut self.x[..n]);
            let (f, t) = (&self.f[..n], &self.t[..n]);
            let (inv_m, inv_i, x_build) = (&self.inv_m[..n], &self.inv_i[..n], &self.x_build[..n]);
            for i in 0..n {
                v[i] += f[i] * (h * inv_m[i]);
                w[i] += t[i] * (h * inv_i[i]);
                let xi = x[i] + v[i] * dt;
                x[i] = xi;
                let d = xi - x_build[i];
                d2_max = d2_max.max(d.dot(d));
            }
            return d2_max;
        }
        for i in 0..self.len() {
            self.v[i] += self.f[i] * (h * self.inv_m[i]);
            self.w[i] += self.t[i] * (h * self.inv_i[i]);
            let x = self.grid.wrap(self.x[i] + self.v[i] * dt);
            self.x[i] = x;
            let d = self.grid.min_image(x - self.x_build[i]);
            d2_max = d2_max.max(d.dot(d));
        }
        d2_max
    }

    /// Velocity Verlet's second half-kick, `h = dt/2` \[s\].
    fn kick(&mut self, h: f64) {
        let n = self.len();
        let (v, w) = (&mut self.v[..n], &mut self.w[..n]);
        let (f, t) = (&self.f[..n], &self.t[..n]);
        let (inv_m, inv_i) = (&self.inv_m[..n], &self.inv_i[..n]);
        for i in 0..n {
            v[i] += f[i] * (h * inv_m[i]);
            w[i] += t[i] * (h * inv_i[i]);
        }
    }

    /// Evaluates every contact force (and gravity) into `f`, `t` and the wall forces.
    pub(crate) fn forces(&mut self, dt: f64) {
        #[cfg(feature = "parallel")]
        if self.cfg.parallel {
            self.forces_parallel(dt, None);
            return;
        }
        let n = self.len();
        let g = self.cfg.gravity;
        let (f, t, mass) = (&mut self.f[..n], &mut self.t[..n], &self.mass[..n]);
        for i in 0..n {
            f[i] = weight(g, mass[i]);
            t[i] = Vec3::ZERO;
        }
        let mut counts = DemCounts {
            neighbours: self.nl_j.len(),
            rebuilds: self.counts.rebuilds,
            ..DemCounts::default()
        };
        let mut energy = self.energy;
        self.pair_forces_serial(dt, &mut counts, &mut energy);
        self.wall_forces(dt, &mut counts, &mut energy);
        self.counts = counts;
        self.energy = energy;
    }

    #[inline(always)]
    pub(crate) fn body(&self, i: usize, position: Vec3) -> PairBody {
        self.arrays().body(i, position)
    }

    /// The per-particle arrays the contact kernels read ([`Arrays`]).
    #[inline(always)]
    pub(crate) fn arrays(&self) -> Arrays<'_> {
        arrays!(self)
    }

    /// The pair `(i, j)` of a list entry with history `h`: the indices of p and q and the
    /// kernel's output when touching, `Err(released energy)` when the pair is apart (its
    /// history reset).
    #[inline(always)]
    pub(crate) fn pair(
        &self,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
    ) -> Result<(usize, usize, creep_law::pair::PairForces), f64> {
        self.pair_in(&self.arrays(), i, j, h, dt)
    }

    /// [`Dem::pair`] reading the arrays `a` (built once per loop).
    #[inline(always)]
    pub(crate) fn pair_in(
        &self,
        a: &Arrays<'_>,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
    ) -> Result<(usize, usize, creep_law::pair::PairForces), f64> {
        a.pair(i, j, h, dt)
    }

    /// The pair forces, one particle after another. Each particle's force and torque sum its
    /// entries' contributions in list order (whether it owns the entry or is its partner), and
    /// the energies and counts are summed per block of [`CHUNK`] particles, then block by
    /// block: the parallel loop (`par`) sums in exactly these orders, so both give the same
    /// bits. A tier with a block kernel ([`TangentialLaw::HAS_BLOCK_LANES`]) runs
    /// [`Dem::pair_chunk_block`], which adds the contacts in the same order.
    fn pair_forces_serial(&mut self, dt: f64, counts: &mut DemCounts, energy: &mut DemEnergy) {
        crate::kernels::dispatch!(self.kernels, pair_forces_avx2<T>(
            dem: &mut Dem<T> = self,
            dt: f64 = dt,
            counts: &mut DemCounts = counts,
            energy: &mut DemEnergy = energy,
        ) -> () {
            dem.pair_forces_body(dt, counts, energy, WIDE)
        })
    }

    /// [`Dem::pair_forces_serial`]'s loop, inlined into each compiled copy (`kernels`; `wide`:
    /// the copy with four-lane vector registers, see [`Dem::use_block`]).
    #[inline(always)]
    fn pair_forces_body(
        &mut self,
        dt: f64,
        counts: &mut DemCounts,
        energy: &mut DemEnergy,
        wide: bool,
    ) {
        let n = self.len();
        let mut hist = std::mem::take(&mut self.nl_h);
        // The material of every particle, where they share one.
        let uniform_mat = match self.mat.split_first() {
            Some((&m0, rest)) if rest.iter().all(|&m| m == m0) => Some(m0),
            _ => None,
        };
        let mut i0 = 0;
        while i0 < n {
            let i1 = (i0 + CHUNK).min(n);
            let mut c = DemCounts::default();
            let mut e = DemEnergy::default();
            if Self::use_block_lanes(wide) {
                self.pair_chunk_block(i0, i1, uniform_mat, &mut hist, dt, &mut c, &mut e);
            } else {
                let arrays = arrays!(self);
                for i in i0..i1 {
                    let (a, b) = (self.nl_start[i] as usize, self.nl_start[i + 1] as usize);
                    for k in a..b {
                        if let Some(ahead) = hist.get(k + crate::kernels::PREFETCH_AHEAD) {
                            crate::kernels::prefetch(ahead);
                        }
                        let j = self.nl_j[k] as usize;
                        match arrays.pair(i, j, &mut hist[k], dt) {
                            Ok((p, q, out)) => {
                                self.f[p] += out.force_p;
                                self.f[q] -= out.force_p;
                                self.t[p] += out.torque_p;
                                self.t[q] += out.torque_q;
                                tally(&mut c, &mut e, &out);
                                c.contacts += 1;
                            }
                            Err(released) => e.slip += released,
                        }
                    }
                }
            }
            add_partial(counts, energy, &c, &e);
            i0 = i1;
        }
        self.nl_h = hist;
    }

    /// The pair forces of the list entries of particles `i0..i1` (histories `hist`, the whole
    /// list's) with the block kernel, added to the particles' forces and torques and to the
    /// counts `c` and energies `e` in list order, as [`Dem::pair_outputs`] followed by a walk
    /// over its outputs: touching sphere pairs with constants the block kernel takes and a
    /// history that is not virgin wait, [`LANES`] at a time, for
    /// [`TangentialLaw::sphere_block_lanes`], whose lanes are added as they come; an entry
    /// the block does not take first runs the waiting lanes (so that the sums keep the list's
    /// order), then the one-contact kernel ([`Arrays::pair`]), unless it is a virgin entry
    /// apart (which adds nothing). The lanes the block leaves go to the one-contact kernel in
    /// their place. The same bits as the one-contact loop. `uniform_mat`: the material of
    /// every particle where they share one (its pair's constants then serve every entry).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn pair_chunk_block(
        &mut self,
        i0: usize,
        i1: usize,
        uniform_mat: Option<u32>,
        hist: &mut [ContactHistory<T>],
        dt: f64,
        c: &mut DemCounts,
        e: &mut DemEnergy,
    ) {
        let arr = arrays!(self);
        let n = arr.x.len();
        let mut acc = Acc {
            f: &mut self.f[..n],
            t: &mut self.t[..n],
            c,
            e,
        };
        let (nl_start, nl_j) = (&self.nl_start[..], &self.nl_j[..]);
        let mut pend = Pending::default();
        let mut lanes = SphereForceLanes::default();
        // The branch on the periodic axes once per entry instead of once per axis, and the
        // pair constants' index and whether the block takes them once per pair of materials
        // met in a row (the materials of two particles in contact rarely change from one
        // entry to the next).
        let periodic = arr.grid.is_periodic();
        let mut last_mats = (u32::MAX, u32::MAX);
        let (mut last_ci, mut last_block) = (0, false);
        // One material for every particle (the rule): its pair's constants for every entry,
        // without the two loads and the compare per entry.
        let uniform = uniform_mat.is_some();
        if let Some(m0) = uniform_mat {
            last_ci = arr.table.pair_index(m0 as usize, m0 as usize);
            last_block = block_supports(&arr.table.pairs[last_ci]);
        }
        for i in i0..i1 {
            let (a, b) = (nl_start[i] as usize, nl_start[i + 1] as usize);
            let (xi, ri, id_i) = (arr.x[i], arr.r[i], arr.id[i]);
            for (k, &j) in (a..b).zip(&nl_j[a..b]) {
                let j = j as usize;
                let (xj, rj) = (arr.x[j], arr.r[j]);
                let d = if periodic {
                    arr.grid.min_image(xj - xi)
                } else {
                    xj - xi
                };
                let rs = ri + rj;
                let touching = d.dot(d) < rs * rs;
                let h = &mut hist[k];
                if touching && !h.is_virgin() {
                    // p's centre and both radii as loaded for the test, not loaded again.
                    let (p, q, dpq, xp, rp, rq) = if id_i < arr.id[j] {
                        (i, j, d, xi, ri, rj)
                    } else {
                        (j, i, -d, xj, rj, ri)
                    };
                    if !uniform {
                        let mats = (arr.mat[p], arr.mat[q]);
                        if mats != last_mats {
                            last_mats = mats;
                            last_ci = arr.table.pair_index(mats.0 as usize, mats.1 as usize);
                            last_block = block_supports(&arr.table.pairs[last_ci]);
                        }
                    }
                    let ci = last_ci;
                    if last_block {
                        if !uniform && pend.len > 0 && pend.constants != ci {
                            flush_lanes(&arr, &mut pend, hist, dt, &mut lanes, &mut acc);
                        }
                        if pend.push(&arr, ci, (k as u32, p as u32, q as u32), xp, dpq, rp, rq) {
                            flush_lanes(&arr, &mut pend, hist, dt, &mut lanes, &mut acc);
                        }
                        continue;
                    }
                } else if !touching && h.is_virgin() {
                    // The one-contact kernel would give `Err(0.0)`: nothing to add.
                    continue;
                }
                if pend.len > 0 {
                    flush_lanes(&arr, &mut pend, hist, dt, &mut lanes, &mut acc);
                }
                acc.add_one(arr.pair(i, j, &mut hist[k], dt));
            }
        }
        if pend.len > 0 {
            flush_lanes(&arr, &mut pend, hist, dt, &mut lanes, &mut acc);
        }
    }

    /// Whether the serial force loop runs the tier's block kernel ([`Dem::pair_chunk_block`]):
    /// where it has one for a loop without a buffer of outputs
    /// ([`TangentialLaw::HAS_BLOCK_LANES`]), unless the block pays only with four-lane vector
    /// registers ([`TangentialLaw::BLOCK_NEEDS_WIDE`]) and the copy (`wide`) has none. The
    /// results are the same bits either way.
    #[inline(always)]
    pub(crate) fn use_block_lanes(wide: bool) -> bool {
        T::HAS_BLOCK_LANES && (wide || !T::BLOCK_NEEDS_WIDE)
    }

    #[cfg(feature = "parallel")]
    /// Whether the parallel force loop runs the tier's block kernel: where it has one
    /// ([`TangentialLaw::HAS_BLOCK`]), unless the block pays only with four-lane vector
    /// registers ([`TangentialLaw::BLOCK_NEEDS_WIDE`]) and the copy (`wide`) has none. The
    /// results are the same bits either way.
    #[inline(always)]
    pub(crate) fn use_block(wide: bool) -> bool {
        T::HAS_BLOCK && (wide || !T::BLOCK_NEEDS_WIDE)
    }

    #[cfg(feature = "parallel")]
    /// The end of the window of particles from `w0` (before `i1`) holding about [`WINDOW`]
    /// list entries (at least one particle).
    #[inline(always)]
    pub(crate) fn window_end(&self, w0: usize, i1: usize) -> usize {
        let mut w1 = w0 + 1;
        while w1 < i1 && ((self.nl_start[w1] - self.nl_start[w0]) as usize) < WINDOW {
            w1 += 1;
        }
        w1
    }

    #[cfg(feature = "parallel")]
    /// The outputs of the list entries of particles `w0..w1` (histories `hist`, from entry
    /// `nl_start[w0]` on) into `outs`, in list order: touching sphere pairs with constants the
    /// block kernel takes and a history that is not virgin go [`LANES`] at a time to
    /// [`TangentialLaw::sphere_block`], the rest (and the lanes the block leaves) to the
    /// one-contact kernel ([`Dem::pair`]); each entry's output depends on its own history only,
    /// so the results are the one-contact kernel's, entry for entry.
    #[inline(always)]
    pub(crate) fn pair_outputs(
        &self,
        w0: usize,
        w1: usize,
        hist: &mut [ContactHistory<T>],
        dt: f64,
        outs: &mut WindowOut,
    ) {
        let base = self.nl_start[w0] as usize;
        // Every entry is written below (a touching pair's outputs, or `APART` and the energy
        // its history released): the buffers are only sized, not cleared.
        outs.f.resize(hist.len(), SphereForces::default());
        outs.pq.resize(hist.len(), [APART, 0]);
        let mut pend = Pending::default();
        let arr = self.arrays();
        for i in w0..w1 {
            let (a, b) = (self.nl_start[i] as usize, self.nl_start[i + 1] as usize);
            let (xi, ri, id_i) = (arr.x[i], arr.r[i], arr.id[i]);
            for (k, &j) in (a..b).zip(&self.nl_j[a..b]) {
                let j = j as usize;
                let o = k - base;
                let (xj, rj) = (arr.x[j], arr.r[j]);
                let d = self.grid.min_image(xj - xi);
                let rs = ri + rj;
                let h = &mut hist[o];
                if d.dot(d) < rs * rs && !h.is_virgin() {
                    let (p, q, dpq, xp, rp, rq) = if id_i < arr.id[j] {
                        (i, j, d, xi, ri, rj)
                    } else {
                        (j, i, -d, xj, rj, ri)
                    };
                    let ci = self
                        .table
                        .pair_index(arr.mat[p] as usize, arr.mat[q] as usize);
                    if block_supports(&self.table.pairs[ci]) {
                        if pend.len > 0 && pend.constants != ci {
                            self.flush(&mut pend, hist, dt, outs);
                        }
                        if pend.push(&arr, ci, (o as u32, p as u32, q as u32), xp, dpq, rp, rq) {
                            self.flush(&mut pend, hist, dt, outs);
                        }
                        continue;
                    }
                }
                self.pair_out(&arr, i, j, &mut hist[o], dt, o, outs);
            }
        }
        if pend.len > 0 {
            self.flush(&mut pend, hist, dt, outs);
        }
    }

    #[cfg(feature = "parallel")]
    /// Runs the pending lanes through the block kernel (the unused lanes repeat the first,
    /// their results dropped), the lanes it leaves through the one-contact kernel.
    #[inline(always)]
    fn flush(
        &self,
        pend: &mut Pending,
        hist: &mut [ContactHistory<T>],
        dt: f64,
        outs: &mut WindowOut,
    ) {
        let n = pend.len;
        for l in n..LANES {
            pend.pairs.copy_lane(0, l);
        }
        let idx = std::array::from_fn(|l| pend.entry[if l < n { l } else { 0 }].0 as usize);
        let mask = T::sphere_block(
            &self.table.pairs[pend.constants],
            &pend.pairs,
            hist,
            &mut outs.f,
            idx,
            n,
            dt,
        );
        for l in 0..n {
            let (o, p, q) = pend.entry[l];
            let o = o as usize;
            if mask >> l & 1 == 1 {
                outs.pq[o] = [p, q];
            } else {
                // The entry's pair as (p, q) rather than (i, j): the one-contact kernel orders
                // them by id itself, on the same separation (`x_q - x_p` is `-(x_j - x_i)`
                // exactly, and so is its minimum image).
                self.pair_out_rare(p as usize, q as usize, &mut hist[o], dt, o, outs);
            }
        }
        pend.len = 0;
    }

    #[cfg(feature = "parallel")]
    /// [`Dem::pair_out`] for the lanes the block kernel leaves (rare: a contact that opens,
    /// or whose normal turned far): out of line, so that it does not crowd the loop (the
    /// baseline copy only).
    #[inline(never)]
    #[cold]
    fn pair_out_rare(
        &self,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
        o: usize,
        outs: &mut WindowOut,
    ) {
        self.pair_out(&self.arrays(), i, j, h, dt, o, outs);
    }

    #[cfg(feature = "parallel")]
    /// [`Dem::pair`] into window entry `o` of `outs`.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn pair_out(
        &self,
        a: &Arrays<'_>,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
        o: usize,
        outs: &mut WindowOut,
    ) {
        match self.pair_in(a, i, j, h, dt) {
            Ok((p, q, out)) => {
                outs.pq[o] = [p as u32, q as u32];
                outs.f[o] = SphereForces {
                    force_p: out.force_p,
                    torque_p: out.torque_p,
                    torque_q: out.torque_q,
                    sliding: out.sliding,
                    creep_displacement: out.creep_displacement,
                    dissipation: out.dissipation,
                };
            }
            Err(released) => {
                outs.pq[o] = [APART, 0];
                outs.f[o].dissipation.slip = released;
            }
        }
    }

    fn wall_forces(&mut self, dt: f64, counts: &mut DemCounts, energy: &mut DemEnergy) {
        crate::kernels::dispatch!(self.kernels, wall_forces_avx2<T>(
            dem: &mut Dem<T> = self,
            dt: f64 = dt,
            counts: &mut DemCounts = counts,
            energy: &mut DemEnergy = energy,
        ) -> () {
            dem.wall_forces_body(dt, counts, energy)
        })
    }

    /// [`Dem::wall_forces`]' loop, inlined into each compiled copy (`kernels`): touching
    /// contacts with constants the block kernel takes and a history that is not virgin wait,
    /// [`LANES`] at a time, for [`wall_block_lanes`], whose lanes are added as they come; an
    /// entry the block does not take first runs the waiting lanes (so that the sums keep the
    /// list's order), then the one-contact kernel ([`Dem::wall_pair`]), as do the lanes the
    /// block leaves, in their place. The same bits as the one-contact loop.
    #[inline(always)]
    fn wall_forces_body(&mut self, dt: f64, counts: &mut DemCounts, energy: &mut DemEnergy) {
        for f in &mut self.wall_force {
            *f = Vec3::ZERO;
        }
        let mut hist = std::mem::take(&mut self.wl_h);
        let ne = hist.len();
        // The arrays sliced once (one bounds check of an index serves every array), the
        // forces borrowed apart from what the kernels read.
        let arr = arrays!(self);
        let n = arr.x.len();
        let wa = WallArrays {
            walls: &self.walls,
            wl_k: &self.wl_k[..ne],
            wl_i: &self.wl_i[..ne],
        };
        let mut acc = WallAcc {
            f: &mut self.f[..n],
            t: &mut self.t[..n],
            wall_force: &mut self.wall_force,
            counts,
            energy,
        };
        let mut pend = WallPending::default();
        let mut lanes = WallForceLanes::default();
        let mut last_mats = (usize::MAX, u32::MAX);
        let (mut last_ci, mut last_block) = (0, false);
        for e in 0..ne {
            if let Some(ahead) = hist.get(e + crate::kernels::PREFETCH_AHEAD) {
                crate::kernels::prefetch(ahead);
            }
            let k = wa.wl_k[e] as usize;
            let i = wa.wl_i[e] as usize;
            let wall = &wa.walls[k];
            let (xq, rq) = (arr.x[i], arr.r[i]);
            // The overlap as `ContactGeometry::plane_sphere` computes it.
            let overlap = rq - (xq - wall.point).dot(wall.normal);
            if overlap > 0.0 && !hist[e].is_virgin() {
                let mats = (wall.material, arr.mat[i]);
                if mats != last_mats {
                    last_mats = mats;
                    last_ci = arr.table.pair_index(mats.0, mats.1 as usize);
                    last_block = block_supports(&arr.table.pairs[last_ci]);
                }
                if last_block {
                    if pend.len > 0 && pend.constants != last_ci {
                        flush_walls(&arr, &wa, &mut pend, &mut hist, dt, &mut lanes, &mut acc);
                    }
                    let l = pend.len % LANES;
                    pend.constants = last_ci;
                    pend.entry[l] = e as u32;
                    pend.walls.set(
                        l,
                        &WallSphere {
                            point: wall.point,
                            normal: wall.normal,
                            velocity: wall.velocity,
                            xq,
                            vq: arr.v[i],
                            wq: arr.w[i],
                            rq,
                            mq: arr.mass[i],
                        },
                    );
                    pend.len += 1;
                    if pend.len == LANES {
                        flush_walls(&arr, &wa, &mut pend, &mut hist, dt, &mut lanes, &mut acc);
                    }
                    continue;
                }
            }
            if pend.len > 0 {
                flush_walls(&arr, &wa, &mut pend, &mut hist, dt, &mut lanes, &mut acc);
            }
            let out = wall_pair_in(&arr, &wa, e, &mut hist[e], dt);
            acc.apply(i, k, out);
        }
        if pend.len > 0 {
            flush_walls(&arr, &wa, &mut pend, &mut hist, dt, &mut lanes, &mut acc);
        }
        self.wl_h = hist;
    }

    /// The contact of wall-list entry `e` (the wall is p): the kernel's output when touching,
    /// else the energy its history released.
    #[cfg(feature = "parallel")]
    #[inline(always)]
    pub(crate) fn wall_pair(
        &self,
        e: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
    ) -> Result<WallOut, f64> {
        let wa = WallArrays {
            walls: &self.walls,
            wl_k: &self.wl_k,
            wl_i: &self.wl_i,
        };
        wall_pair_in(&self.arrays(), &wa, e, h, dt)
    }
}

/// The wall list's arrays the wall loops read: the walls and each entry's wall and particle.
#[derive(Clone, Copy)]
pub(crate) struct WallArrays<'a> {
    walls: &'a [crate::Wall],
    wl_k: &'a [u32],
    wl_i: &'a [u32],
}

/// [`Dem::wall_pair`] on the arrays `a` and `wa`.
#[inline(always)]
fn wall_pair_in<T: TangentialLaw>(
    a: &Arrays<'_>,
    wa: &WallArrays<'_>,
    e: usize,
    h: &mut ContactHistory<T>,
    dt: f64,
) -> Result<WallOut, f64> {
    let k = wa.wl_k[e] as usize;
    let i = wa.wl_i[e] as usize;
    let wall = wa.walls[k];
    let geo = ContactGeometry::plane_sphere(wall.point, wall.normal, a.x[i], a.r[i]);
    let c = a.table.pair(wall.material, a.mat[i] as usize);
    if !(geo.overlap > 0.0) {
        return Err(release(c, Surface::Plane, Surface::Sphere(a.r[i]), h));
    }
    let bp = wall.body_at(geo.point);
    let out = pair_force(c, &bp, &a.body(i, a.x[i]), &geo, h, dt);
    if out.touching {
        Ok(WallOut {
            force_p: out.force_p,
            torque_q: out.torque_q,
            dissipation: out.dissipation,
            sliding: out.sliding,
            creeping: out.creep_displacement != creep_law::Vec2::ZERO,
        })
    } else {
        Err(0.0)
    }
}

/// Where the serial wall loop adds the contacts' outputs: the particles' forces and torques,
/// the walls' forces, the counts and the energies.
struct WallAcc<'a> {
    f: &'a mut [Vec3],
    t: &'a mut [Vec3],
    wall_force: &'a mut [Vec3],
    counts: &'a mut DemCounts,
    energy: &'a mut DemEnergy,
}

impl WallAcc<'_> {
    /// Adds a wall-list entry's output (particle `i`, wall `k`) to its particle, its wall and
    /// the tallies.
    #[inline(always)]
    fn apply(&mut self, i: usize, k: usize, out: Result<WallOut, f64>) {
        if let Ok(o) = &out {
            self.f[i] -= o.force_p;
            self.t[i] += o.torque_q;
        }
        tally_wall(&out, k, self.wall_force, self.counts, self.energy);
    }
}

/// Runs the waiting wall lanes through the block kernel (the unused lanes repeat the first,
/// their results dropped) and adds each lane's outputs in order; a lane the block leaves
/// goes through the one-contact kernel in its place.
#[inline(always)]
fn flush_walls<T: TangentialLaw>(
    arr: &Arrays<'_>,
    wa: &WallArrays<'_>,
    pend: &mut WallPending,
    hist: &mut [ContactHistory<T>],
    dt: f64,
    lanes: &mut WallForceLanes,
    acc: &mut WallAcc<'_>,
) {
    let n = pend.len;
    for l in n..LANES {
        pend.walls.copy_lane(0, l);
    }
    let idx = std::array::from_fn(|l| pend.entry[if l < n { l } else { 0 }] as usize);
    let mask = wall_block_lanes(
        &arr.table.pairs[pend.constants],
        &pend.walls,
        hist,
        idx,
        n,
        dt,
        lanes,
    );
    for (l, &e) in pend.entry[..n.min(LANES)].iter().enumerate() {
        let e = e as usize;
        let out = if mask >> l & 1 == 1 {
            let v = |a: &[[f64; LANES]; 3]| Vec3::new(a[0][l], a[1][l], a[2][l]);
            Ok(WallOut {
                force_p: v(&lanes.force_p),
                torque_q: v(&lanes.torque_q),
                dissipation: lanes.dissipation(l),
                sliding: lanes.sliding[l],
                creeping: lanes.creeping[l],
            })
        } else {
            wall_pair_in(arr, wa, e, &mut hist[e], dt)
        };
        acc.apply(wa.wl_i[e] as usize, wa.wl_k[e] as usize, out);
    }
    pend.len = 0;
}

/// A wall-list entry's share of the counts, the energies and its wall's force `k` (both
/// loops, in list order): a touching contact's dissipation, or the energy an opening one
/// released.
#[inline]
pub(crate) fn tally_wall(
    out: &Result<WallOut, f64>,
    k: usize,
    wall_force: &mut [Vec3],
    counts: &mut DemCounts,
    energy: &mut DemEnergy,
) {
    match out {
        Ok(o) => {
            wall_force[k] += o.force_p;
            tally_parts(counts, energy, &o.dissipation, o.sliding, o.creeping);
            counts.wall_contacts += 1;
        }
        Err(released) => energy.slip += released,
    }
}

/// The weight `g m` \[N\] a particle's force sum starts from, with `+0.0` for `-0.0`
/// components (so that no force sum is ever `-0.0`: see `par`'s gather).
#[inline]
pub(crate) fn weight(g: Vec3, m: f64) -> Vec3 {
    g * m + Vec3::ZERO
}

/// Particles per block of the force loop: a task of the parallel loop, and the block over
/// which both loops sum energies and counts before adding them to the totals.
pub(crate) const CHUNK: usize = 128;

/// Adds one block's counts and energies to the totals (both loops, block by block in order).
#[inline]
pub(crate) fn add_partial(
    counts: &mut DemCounts,
    energy: &mut DemEnergy,
    c: &DemCounts,
    e: &DemEnergy,
) {
    counts.contacts += c.contacts;
    counts.sliding += c.sliding;
    counts.creeping += c.creeping;
    energy.damping += e.damping;
    energy.slip += e.slip;
    energy.creep += e.creep;
    energy.rolling += e.rolling;
    energy.truncation += e.truncation;
}

#[inline(always)]
pub(crate) fn tally(
    counts: &mut DemCounts,
    energy: &mut DemEnergy,
    out: &creep_law::pair::PairForces,
) {
    tally_parts(
        counts,
        energy,
        &out.dissipation,
        out.sliding,
        out.creep_displacement != creep_law::Vec2::ZERO,
    );
}

#[inline(always)]
fn tally_parts(
    counts: &mut DemCounts,
    energy: &mut DemEnergy,
    d: &creep_law::pair::PairDissipation,
    sliding: bool,
    creeping: bool,
) {
    energy.damping += d.damping;
    energy.slip += d.slip;
    energy.creep += d.creep;
    energy.rolling += d.rolling;
    energy.truncation += d.truncation;
    counts.sliding += usize::from(sliding);
    counts.creeping += usize::from(creeping);
}

/// What a touching wall contact adds: the kernel's outputs the engine uses.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WallOut {
    pub(crate) force_p: Vec3,
    pub(crate) torque_q: Vec3,
    pub(crate) dissipation: creep_law::pair::PairDissipation,
    pub(crate) sliding: bool,
    pub(crate) creeping: bool,
}

#[cfg(feature = "parallel")]
/// List entries per window of [`Dem::pair_outputs`] (evaluated, then added in list order). The
/// block kernel's last block of a window is partly empty: a long window wastes fewer lanes,
/// and its outputs (about 17 kB) still stay in the level-1 cache.
pub(crate) const WINDOW: usize = 128;

#[cfg(feature = "parallel")]
/// The outputs of a window's list entries: a touching pair's p and q and its outputs, or
/// `[APART, 0]` and the energy an opening contact's history released (as the slip
/// dissipation).
#[derive(Debug, Clone, Default)]
pub(crate) struct WindowOut {
    pub(crate) pq: Vec<[u32; 2]>,
    pub(crate) f: Vec<SphereForces>,
}

/// The per-particle arrays the contact kernels read, each sliced to the particle count (one
/// bounds check of an index serves every array), with the grid and the material table.
/// `arrays!(dem)` borrows the fields one by one, so that the force arrays stay free.
macro_rules! arrays {
    ($d:expr) => {{
        let n = $d.x.len();
        $crate::step::Arrays {
            grid: &$d.grid,
            table: &$d.table,
            x: &$d.x[..n],
            v: &$d.v[..n],
            w: &$d.w[..n],
            r: &$d.r[..n],
            mass: &$d.mass[..n],
            mat: &$d.mat[..n],
            id: &$d.id[..n],
        }
    }};
}
pub(crate) use arrays;

/// The per-particle arrays the contact kernels read, each sliced to the particle count: one
/// bounds check of an index serves every array.
#[derive(Clone, Copy)]
pub(crate) struct Arrays<'a> {
    pub(crate) grid: &'a crate::grid::Grid,
    pub(crate) table: &'a crate::MaterialTable,
    pub(crate) x: &'a [Vec3],
    pub(crate) v: &'a [Vec3],
    pub(crate) w: &'a [Vec3],
    pub(crate) r: &'a [f64],
    pub(crate) mass: &'a [f64],
    pub(crate) mat: &'a [u32],
    pub(crate) id: &'a [u32],
}

impl Arrays<'_> {
    /// [`Dem::pair`] on these arrays.
    #[inline(always)]
    pub(crate) fn pair<T: TangentialLaw>(
        &self,
        i: usize,
        j: usize,
        h: &mut ContactHistory<T>,
        dt: f64,
    ) -> Result<(usize, usize, creep_law::pair::PairForces), f64> {
        let a = self;
        let d = a.grid.min_image(a.x[j] - a.x[i]);
        let rs = a.r[i] + a.r[j];
        if d.dot(d) >= rs * rs {
            if h.is_virgin() {
                return Err(0.0);
            }
            let c = a.table.pair(a.mat[i] as usize, a.mat[j] as usize);
            return Err(release(
                c,
                Surface::Sphere(a.r[i]),
                Surface::Sphere(a.r[j]),
                h,
            ));
        }
        let (p, q, dpq) = if a.id[i] < a.id[j] {
            (i, j, d)
        } else {
            (j, i, -d)
        };
        let xp = a.x[p];
        let xq = xp + dpq;
        let c = a.table.pair(a.mat[p] as usize, a.mat[q] as usize);
        let Some(geo) = ContactGeometry::sphere_sphere(xp, a.r[p], xq, a.r[q]) else {
            return Err(release(
                c,
                Surface::Sphere(a.r[p]),
                Surface::Sphere(a.r[q]),
                h,
            ));
        };
        let out = pair_force(c, &a.body(p, xp), &a.body(q, xq), &geo, h, dt);
        if out.touching {
            Ok((p, q, out))
        } else {
            Err(out.dissipation.slip)
        }
    }

    /// Particle `i` as body of a pair, at `position` \[m\].
    #[inline(always)]
    pub(crate) fn body(&self, i: usize, position: Vec3) -> PairBody {
        PairBody {
            position,
            velocity: self.v[i],
            angular_velocity: self.w[i],
            surface: Surface::Sphere(self.r[i]),
            mass: self.mass[i],
        }
    }
}

/// Where [`Dem::pair_chunk_block`] adds the contacts' outputs: the particles' forces and
/// torques, the counts and the energies.
struct Acc<'a> {
    f: &'a mut [Vec3],
    t: &'a mut [Vec3],
    c: &'a mut DemCounts,
    e: &'a mut DemEnergy,
}

impl Acc<'_> {
    /// Adds lane `l` of a block's outputs (read in place) for the pair p, q, as the one-contact
    /// loop adds a touching pair's.
    #[inline(always)]
    fn add_lane(&mut self, p: usize, q: usize, o: &SphereForceLanes, l: usize) {
        let v = |a: &[[f64; LANES]; 3]| Vec3::new(a[0][l], a[1][l], a[2][l]);
        let force_p = v(&o.force_p);
        self.f[p] += force_p;
        self.f[q] -= force_p;
        self.t[p] += v(&o.torque_p);
        self.t[q] += v(&o.torque_q);
        // `tally_parts` without the rolling dissipation, zero for a block lane: the sum starts
        // at +0 and so is never -0, which `+ 0.0` alone would change.
        let e = &mut *self.e;
        e.damping += o.damping[l];
        e.slip += o.slip[l];
        e.creep += o.creep[l];
        e.truncation += o.truncation[l];
        self.c.sliding += usize::from(o.sliding[l]);
        self.c.creeping +=
            usize::from(o.creep_displacement[0][l] != 0.0 || o.creep_displacement[1][l] != 0.0);
        self.c.contacts += 1;
    }

    /// Adds the one-contact kernel's result for an entry ([`Arrays::pair`]).
    #[inline(always)]
    fn add_one(&mut self, r: Result<(usize, usize, creep_law::pair::PairForces), f64>) {
        match r {
            Ok((p, q, out)) => {
                self.f[p] += out.force_p;
                self.f[q] -= out.force_p;
                self.t[p] += out.torque_p;
                self.t[q] += out.torque_q;
                tally(self.c, self.e, &out);
                self.c.contacts += 1;
            }
            Err(released) => self.e.slip += released,
        }
    }
}

/// Runs the pending lanes through the block kernel (the unused lanes repeat the first, their
/// results dropped) and adds each lane's outputs in order; a lane the block leaves goes
/// through the one-contact kernel in its place.
#[inline(always)]
fn flush_lanes<T: TangentialLaw>(
    arr: &Arrays<'_>,
    pend: &mut Pending,
    hist: &mut [ContactHistory<T>],
    dt: f64,
    lanes: &mut SphereForceLanes,
    acc: &mut Acc<'_>,
) {
    let n = pend.len;
    for l in n..LANES {
        pend.pairs.copy_lane(0, l);
    }
    let idx = std::array::from_fn(|l| pend.entry[if l < n { l } else { 0 }].0 as usize);
    let mask = T::sphere_block_lanes(
        &arr.table.pairs[pend.constants],
        &pend.pairs,
        hist,
        idx,
        n,
        dt,
        lanes,
    );
    for l in 0..n {
        let (k, p, q) = pend.entry[l];
        if mask >> l & 1 == 1 {
            acc.add_lane(p as usize, q as usize, lanes, l);
        } else {
            // The entry's pair as (p, q) rather than (i, j): the one-contact kernel orders them
            // by id itself, on the same separation (`x_q - x_p` is `-(x_j - x_i)` exactly, and
            // so is its minimum image).
            pair_one_rare(arr, p as usize, q as usize, &mut hist[k as usize], dt, acc);
        }
    }
    pend.len = 0;
}

/// [`Acc::add_one`] of [`Arrays::pair`] for a lane the block kernel leaves (rare: a contact
/// that opens, or whose normal turned far): out of line, so that it does not crowd the loop
/// (the baseline copy only).
#[inline(never)]
#[cold]
fn pair_one_rare<T: TangentialLaw>(
    arr: &Arrays<'_>,
    i: usize,
    j: usize,
    h: &mut ContactHistory<T>,
    dt: f64,
    acc: &mut Acc<'_>,
) {
    acc.add_one(arr.pair(i, j, h, dt));
}

#[cfg(feature = "parallel")]
/// The `p` of an entry whose pair is apart.
pub(crate) const APART: u32 = u32::MAX;

/// The lanes waiting for the block kernel: their entry (its history's index), p, q, bodies,
/// and the index of their pair constants.
#[derive(Default)]
struct Pending {
    len: usize,
    constants: usize,
    entry: [(u32, u32, u32); LANES],
    pairs: SphereLanes,
}

impl Pending {
    /// Adds the pair of bodies `p, q` (`entry`'s last two; p's centre `xp`, `dpq` from `p` to
    /// `q`, the minimum image; radii `rp`, `rq`) with pair constants `ci` as the next lane;
    /// whether the block is full.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn push(
        &mut self,
        arr: &Arrays,
        ci: usize,
        entry: (u32, u32, u32),
        xp: Vec3,
        dpq: Vec3,
        rp: f64,
        rq: f64,
    ) -> bool {
        let (p, q) = (entry.1 as usize, entry.2 as usize);
        // `len < LANES` here (a full block is flushed); the mask tells the compiler so, which
        // drops the lane checks and lets it store each value as it loads it.
        let l = self.len % LANES;
        self.constants = ci;
        self.entry[l] = entry;
        self.pairs.set(
            l,
            &SpherePair {
                xp,
                xq: xp + dpq,
                rp,
                rq,
                vp: arr.v[p],
                vq: arr.v[q],
                wp: arr.w[p],
                wq: arr.w[q],
                mp: arr.mass[p],
                mq: arr.mass[q],
            },
        );
        self.len += 1;
        self.len == LANES
    }
}

/// The wall contacts waiting for the block kernel: their wall-list entries, bodies, and the
/// index of their pair constants.
#[derive(Default)]
struct WallPending {
    len: usize,
    constants: usize,
    entry: [u32; LANES],
    walls: WallLanes,
}

/// [`tally`] of a window entry's outputs.
#[cfg(feature = "parallel")]
#[inline(always)]
pub(crate) fn tally_block(counts: &mut DemCounts, energy: &mut DemEnergy, out: &SphereForces) {
    tally_parts(
        counts,
        energy,
        &out.dissipation,
        out.sliding,
        out.creep_displacement != creep_law::Vec2::ZERO,
    );
}
