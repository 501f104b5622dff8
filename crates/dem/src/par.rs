//! The step on rayon's threads with a deterministic reduction (the `parallel` feature and
//! [`DemConfig::parallel`](crate::DemConfig::parallel)).
//!
//! A step is three parallel regions and little in between:
//! 1. the first half-kick and the drift (the largest displacement is a maximum, so it does
//!    not depend on the split);
//! 2. every contact's kernel: the pair-list entries of a block of [`CHUNK`] particles per task
//!    and the wall-list entries, [`CHUNK`] per task, in one parallel loop, each entry's output
//!    to a buffer; energies and counts summed per block;
//! 3. per particle: the sum of the entries it owns and of those it is the partner of, merged
//!    in list order (the order in which the serial loop adds them), then its wall entries in
//!    list order (as the serial wall loop adds them after the pairs), then (unless an
//!    [`ExternalForces`] adds forces in between) the second half-kick.
//!
//! Between 2 and 3, serially: the blocks' energies and counts in block order, then the wall
//! entries' in list order, and each wall's force in list order, as the serial loop sums them.
//! At a rebuild the half list is built per block of particles in parallel and the blocks
//! joined in order. So the results are the same bits as the serial loop's, for any thread
//! count (test `parallel_force_loop_is_deterministic`).

use crate::grid::Stencil;
use crate::neighbour::{Carry, half_neighbours_of};
use crate::step::{APART, CHUNK, WallOut, WindowOut, add_partial, tally_block, tally_wall, weight};
use crate::{Dem, DemCounts, DemEnergy, DemError, ExternalForces, tally};
use creep_law::Vec3;
use creep_law::pair::{ContactHistory, TangentialLaw};
use rayon::prelude::*;

/// One task of the contact loop.
enum Task<'a, T: TangentialLaw> {
    /// The first particle of a block, its entries' histories and outputs.
    Pairs(usize, &'a mut [ContactHistory<T>], &'a mut [Entry]),
    /// The first wall-list entry of a run of entries, their histories and outputs.
    Walls(usize, &'a mut [ContactHistory<T>], &'a mut [WallResult]),
}

/// A wall entry's output: the kernel's, or the energy its history released.
type WallResult = Result<WallOut, f64>;

/// One entry's contribution: force and torque on its owner `i`, torque on its partner `j`
/// (the force on `j` is `-force_i`).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Entry {
    force_i: Vec3,
    torque_i: Vec3,
    torque_j: Vec3,
}

/// Particles per block of the parallel list build.
const LIST_BLOCK: usize = 256;

/// One block's part of the half list (the parallel rebuild).
#[derive(Debug, Clone, Default)]
pub(crate) struct ListBlock {
    /// Partners, in list order.
    j: Vec<u32>,
    /// Where each entry's history is in the old list.
    src: Vec<u32>,
    /// Entries of the block after each of its particles (relative CSR ends).
    ends: Vec<u32>,
}

#[derive(Debug, Clone, Default)]
pub(crate) struct Buffers {
    out: Vec<Entry>,
    /// For each particle, the entries whose partner it is (CSR), rebuilt with the list.
    rev_start: Vec<u32>,
    rev_k: Vec<u32>,
    /// For each particle, its wall-list entries (CSR, ascending), rebuilt with the list.
    wrev_start: Vec<u32>,
    wrev_e: Vec<u32>,
    /// The wall contacts' outputs.
    wall_out: Vec<WallResult>,
    /// List length the reverse index was built for.
    built_for: usize,
    built_rebuilds: usize,
    /// The parallel list build's blocks (kept between rebuilds).
    blocks: Vec<ListBlock>,
}

impl Buffers {
    /// Bytes held (capacities).
    pub(crate) fn bytes(&self) -> usize {
        use std::mem::size_of;
        self.out.capacity() * size_of::<Entry>()
            + (self.rev_start.capacity()
                + self.rev_k.capacity()
                + self.wrev_start.capacity()
                + self.wrev_e.capacity())
                * 4
            + self.wall_out.capacity() * size_of::<WallResult>()
            + self
                .blocks
                .iter()
                .map(|b| (b.j.capacity() + b.src.capacity() + b.ends.capacity()) * 4)
                .sum::<usize>()
    }
}

/// CSR rows of `keys` (`start[key]..start[key + 1]` lists the indices with that key,
/// ascending): a counting sort into `start` and `idx`.
fn csr_rows(
    keys: impl Iterator<Item = u32> + Clone,
    n: usize,
    start: &mut Vec<u32>,
    idx: &mut Vec<u32>,
) {
    start.clear();
    start.resize(n + 2, 0);
    let mut len = 0;
    for key in keys.clone() {
        start[key as usize + 2] += 1;
        len += 1;
    }
    for i in 0..n {
        start[i + 2] += start[i + 1];
    }
    idx.clear();
    idx.resize(len, 0);
    // `start[key + 1]` is the fill position of row `key`; after the fill it is the row's end.
    for (k, key) in keys.enumerate() {
        let s = &mut start[key as usize + 1];
        idx[*s as usize] = k as u32;
        *s += 1;
    }
    start.truncate(n + 1);
}

impl<T: TangentialLaw> Dem<T> {
    /// The reverse indices of the pair and wall lists and the output buffers, once per list.
    fn reverse_index(&mut self) {
        let n = self.len();
        let b = &mut self.par;
        if b.built_rebuilds == self.counts.rebuilds
            && b.built_for == self.nl_j.len()
            && b.rev_start.len() == n + 1
            && b.wrev_start.len() == n + 1
        {
            return;
        }
        csr_rows(self.nl_j.iter().copied(), n, &mut b.rev_start, &mut b.rev_k);
        csr_rows(
            self.wl_i.iter().copied(),
            n,
            &mut b.wrev_start,
            &mut b.wrev_e,
        );
        b.built_for = self.nl_j.len();
        b.built_rebuilds = self.counts.rebuilds;
        b.out.clear();
        // Exactly the list's length (`resize` alone would double the capacity as the list
        // grows); give back more than an eighth over it, as the lists do.
        b.out.reserve_exact(self.nl_j.len());
        b.out.resize(self.nl_j.len(), Entry::default());
        let len = b.out.len();
        if b.out.capacity() > len + len / 4 {
            b.out.shrink_to(len + len / 8);
        }
        b.wall_out.clear();
        b.wall_out.resize(self.wl_i.len(), Err(0.0));
    }

    /// The contact kernels of the pair entries of the block of particles from `i0` (their
    /// histories `h` and outputs `o`): the block's counts and energies. Inlined into each
    /// compiled copy (`kernels`; `wide` as for [`Dem::use_block`]).
    #[inline(always)]
    fn pairs_task(
        &self,
        i0: usize,
        h: &mut [ContactHistory<T>],
        o: &mut [Entry],
        dt: f64,
        wide: bool,
    ) -> (DemCounts, DemEnergy) {
        let n = self.len();
        let mut c = DemCounts::default();
        let mut e = DemEnergy::default();
        let base = self.nl_start[i0] as usize;
        let i1 = (i0 + CHUNK).min(n);
        if Self::use_block(wide) {
            // Windows of entries through the block kernel (`pair_outputs`), the outputs to
            // entries.
            let mut outs = WindowOut::default();
            let mut w0 = i0;
            while w0 < i1 {
                let w1 = self.window_end(w0, i1);
                let (a, b) = (
                    self.nl_start[w0] as usize - base,
                    self.nl_start[w1] as usize - base,
                );
                self.pair_outputs(w0, w1, &mut h[a..b], dt, &mut outs);
                for i in w0..w1 {
                    for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                        let w = k - base - a;
                        let [p, _] = outs.pq[w];
                        let f = &outs.f[w];
                        o[k - base] = if p == APART {
                            e.slip += f.dissipation.slip;
                            Entry::default()
                        } else {
                            tally_block(&mut c, &mut e, f);
                            c.contacts += 1;
                            entry(p as usize == i, f.force_p, f.torque_p, f.torque_q)
                        };
                    }
                }
                w0 = w1;
            }
            return (c, e);
        }
        let arrays = self.arrays();
        for i in i0..i1 {
            for k in self.nl_start[i] as usize..self.nl_start[i + 1] as usize {
                let j = self.nl_j[k] as usize;
                let slot = &mut o[k - base];
                *slot = match self.pair_in(&arrays, i, j, &mut h[k - base], dt) {
                    Ok((p, _, f)) => {
                        tally(&mut c, &mut e, &f);
                        c.contacts += 1;
                        entry(p == i, f.force_p, f.torque_p, f.torque_q)
                    }
                    Err(released) => {
                        e.slip += released;
                        Entry::default()
                    }
                };
            }
        }
        (c, e)
    }

    /// One velocity-Verlet step on rayon's threads (see the module docs).
    pub(crate) fn step_parallel<E: ExternalForces>(
        &mut self,
        external: &mut E,
    ) -> Result<(), DemError> {
        let dt = self.cfg.dt;
        let h = 0.5 * dt;
        let d2_max = self.kick_drift_parallel(dt);
        self.move_walls_and_check(d2_max, dt)?;
        if external.adds_forces() {
            self.forces_parallel(dt, None);
            external.add_forces(self.external_view(dt))?;
            self.kick_parallel(h);
        } else {
            self.forces_parallel(dt, Some(h));
        }
        self.time += dt;
        self.steps += 1;
        Ok(())
    }

    /// Every contact force (and gravity) into `f`, `t` and the wall forces, on rayon's
    /// threads; with `kick = Some(dt/2)` also the second half-kick, in the same pass.
    pub(crate) fn forces_parallel(&mut self, dt: f64, kick: Option<f64>) {
        self.reverse_index();
        let n = self.len();
        let mut counts = DemCounts {
            neighbours: self.nl_j.len(),
            rebuilds: self.counts.rebuilds,
            ..DemCounts::default()
        };
        let mut energy = self.energy;
        let mut hist = std::mem::take(&mut self.nl_h);
        let mut out = std::mem::take(&mut self.par.out);
        let mut wall_hist = std::mem::take(&mut self.wl_h);
        let mut wall_out = std::mem::take(&mut self.par.wall_out);
        // Split the histories and outputs at block boundaries.
        let mut tasks: Vec<Task<'_, T>> =
            Vec::with_capacity(n.div_ceil(CHUNK) + wall_hist.len().div_ceil(CHUNK));
        {
            let (mut h_rest, mut o_rest) = (&mut hist[..], &mut out[..]);
            let mut i0 = 0;
            while i0 < n {
                let i1 = (i0 + CHUNK).min(n);
                let len = (self.nl_start[i1] - self.nl_start[i0]) as usize;
                let (h, hr) = h_rest.split_at_mut(len);
                let (o, or) = o_rest.split_at_mut(len);
                tasks.push(Task::Pairs(i0, h, o));
                h_rest = hr;
                o_rest = or;
                i0 = i1;
            }
            for (c, (h, o)) in wall_hist
                .chunks_mut(CHUNK)
                .zip(wall_out.chunks_mut(CHUNK))
                .enumerate()
            {
                tasks.push(Task::Walls(c * CHUNK, h, o));
            }
        }
        let this = &*self;
        let partial: Vec<Option<(DemCounts, DemEnergy)>> = tasks
            .into_par_iter()
            .with_max_len(1)
            .map(|task| match task {
                Task::Pairs(i0, h, o) => {
                    let pair = crate::kernels::dispatch!(this.kernels, pairs_avx2<T>(
                        dem: &Dem<T> = this,
                        i0: usize = i0,
                        h: &mut [ContactHistory<T>] = h,
                        o: &mut [Entry] = o,
                        dt: f64 = dt,
                    ) -> (DemCounts, DemEnergy) {
                        dem.pairs_task(i0, h, o, dt, WIDE)
                    });
                    Some(pair)
                }
                Task::Walls(e0, h, o) => {
                    crate::kernels::dispatch!(this.kernels, walls_avx2<T>(
                        dem: &Dem<T> = this,
                        e0: usize = e0,
                        h: &mut [ContactHistory<T>] = h,
                        o: &mut [WallResult] = o,
                        dt: f64 = dt,
                    ) -> () {
                        for (k, (h, o)) in h.iter_mut().zip(o.iter_mut()).enumerate() {
                            *o = dem.wall_pair(e0 + k, h, dt);
                        }
                    });
                    None
                }
            })
            .collect();
        for (c, e) in partial.iter().flatten() {
            add_partial(&mut counts, &mut energy, c, e);
        }
        // The walls' tallies and forces in list order, as the serial wall loop adds them.
        for f in &mut self.wall_force {
            *f = Vec3::ZERO;
        }
        for (e, o) in wall_out.iter().enumerate() {
            tally_wall(
                o,
                self.wl_k[e] as usize,
                &mut self.wall_force,
                &mut counts,
                &mut energy,
            );
        }
        // Gather from the particle's weight, the owned entries (one range of the list) and the
        // partnered ones (ascending in the reverse index) merged by entry number: the serial
        // loop's order; then the wall entries in list order. An open pair's entry is zero,
        // which the serial loop does not add; adding `+0.0` changes no sum except `-0.0`, and
        // these sums never are `-0.0`: they start from `+0.0` or a nonzero weight (`weight`
        // makes the weight's zero components `+0.0`), and in round-to-nearest a sum is `-0.0`
        // only if both terms are. An open wall contact adds nothing, as in the serial loop.
        let (start, rev_start, rev_k) = (&self.nl_start, &self.par.rev_start, &self.par.rev_k);
        let (wrev_start, wrev_e) = (&self.par.wrev_start, &self.par.wrev_e);
        let (outs, walls, mass, g) = (&out, &wall_out, &self.mass, self.cfg.gravity);
        let (inv_m, inv_i) = (&self.inv_m, &self.inv_i);
        self.f
            .par_chunks_mut(CHUNK)
            .zip(self.t.par_chunks_mut(CHUNK))
            .zip(self.v.par_chunks_mut(CHUNK))
            .zip(self.w.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (((f, t), v), w))| {
                for o in 0..f.len() {
                    let i = c * CHUNK + o;
                    let mut fi = weight(g, mass[i]);
                    let mut ti = Vec3::ZERO;
                    let (mut k, end) = (start[i] as usize, start[i + 1] as usize);
                    for &r in &rev_k[rev_start[i] as usize..rev_start[i + 1] as usize] {
                        let r = r as usize;
                        while k < end && k < r {
                            fi += outs[k].force_i;
                            ti += outs[k].torque_i;
                            k += 1;
                        }
                        fi -= outs[r].force_i;
                        ti += outs[r].torque_j;
                    }
                    for e in &outs[k..end] {
                        fi += e.force_i;
                        ti += e.torque_i;
                    }
                    for &e in &wrev_e[wrev_start[i] as usize..wrev_start[i + 1] as usize] {
                        if let Ok(wo) = &walls[e as usize] {
                            fi -= wo.force_p;
                            ti += wo.torque_q;
                        }
                    }
                    f[o] = fi;
                    t[o] = ti;
                    if let Some(h) = kick {
                        v[o] += fi * (h * inv_m[i]);
                        w[o] += ti * (h * inv_i[i]);
                    }
                }
            });
        self.nl_h = hist;
        self.par.out = out;
        self.wl_h = wall_hist;
        self.par.wall_out = wall_out;
        self.counts = counts;
        self.energy = energy;
    }

    /// The half list built per block of [`LIST_BLOCK`] particles on rayon's threads, the
    /// blocks joined in order (the serial rebuild's list, entry for entry); `src` gets where
    /// each entry's history is in the old list.
    pub(crate) fn half_list_parallel(&mut self, carry: &Carry, src: &mut Vec<u32>) {
        let n = self.len();
        let nb = n.div_ceil(LIST_BLOCK);
        let mut blocks = std::mem::take(&mut self.par.blocks);
        blocks.resize_with(nb, ListBlock::default);
        let (grid, x, r, id, skin) = (&self.grid, &self.x, &self.r, &self.id, self.cfg.skin);
        blocks
            .par_iter_mut()
            .with_max_len(1)
            .enumerate()
            .for_each(|(b, blk)| {
                blk.j.clear();
                blk.src.clear();
                blk.ends.clear();
                let mut stencil = Stencil::default();
                for i in b * LIST_BLOCK..((b + 1) * LIST_BLOCK).min(n) {
                    half_neighbours_of(
                        grid,
                        &mut stencil,
                        x,
                        r,
                        id,
                        skin,
                        carry,
                        i,
                        &mut blk.j,
                        &mut blk.src,
                    );
                    blk.ends.push(blk.j.len() as u32);
                }
            });
        self.nl_start.clear();
        self.nl_j.clear();
        src.clear();
        self.nl_start.push(0);
        for blk in &blocks {
            let base = self.nl_j.len() as u32;
            self.nl_start.extend(blk.ends.iter().map(|&e| base + e));
            self.nl_j.extend_from_slice(&blk.j);
            src.extend_from_slice(&blk.src);
        }
        self.par.blocks = blocks;
    }

    /// [`Dem::kick_drift`](crate::Dem) on rayon's threads, in chunks of particles; the
    /// largest displacement is a maximum, so it does not depend on the split.
    pub(crate) fn kick_drift_parallel(&mut self, dt: f64) -> f64 {
        let h = 0.5 * dt;
        let (f, t, inv_m, inv_i, x_build, grid) = (
            &self.f,
            &self.t,
            &self.inv_m,
            &self.inv_i,
            &self.x_build,
            &self.grid,
        );
        self.v
            .par_chunks_mut(CHUNK)
            .zip(self.w.par_chunks_mut(CHUNK))
            .zip(self.x.par_chunks_mut(CHUNK))
            .enumerate()
            .map(|(c, ((v, w), x))| {
                let base = c * CHUNK;
                let mut d2_max: f64 = 0.0;
                for (o, ((v, w), x)) in v.iter_mut().zip(w.iter_mut()).zip(x.iter_mut()).enumerate()
                {
                    let i = base + o;
                    *v += f[i] * (h * inv_m[i]);
                    *w += t[i] * (h * inv_i[i]);
                    *x = grid.wrap(*x + *v * dt);
                    let d = grid.min_image(*x - x_build[i]);
                    d2_max = d2_max.max(d.dot(d));
                }
                d2_max
            })
            .reduce(|| 0.0, f64::max)
    }

    /// [`Dem::kick`](crate::Dem) on rayon's threads.
    pub(crate) fn kick_parallel(&mut self, h: f64) {
        let (f, t, inv_m, inv_i) = (&self.f, &self.t, &self.inv_m, &self.inv_i);
        self.v
            .par_chunks_mut(CHUNK)
            .zip(self.w.par_chunks_mut(CHUNK))
            .enumerate()
            .for_each(|(c, (v, w))| {
                let base = c * CHUNK;
                for (o, (v, w)) in v.iter_mut().zip(w.iter_mut()).enumerate() {
                    let i = base + o;
                    *v += f[i] * (h * inv_m[i]);
                    *w += t[i] * (h * inv_i[i]);
                }
            });
    }
}

/// The entry of a pair whose owner is p (`owner_is_p`) or q, from the force on p and the two
/// torques (a `PairForces`' or a window's `SphereForces`').
#[inline]
fn entry(owner_is_p: bool, force_p: Vec3, torque_p: Vec3, torque_q: Vec3) -> Entry {
    if owner_is_p {
        Entry {
            force_i: force_p,
            torque_i: torque_p,
            torque_j: torque_q,
        }
    } else {
        Entry {
            force_i: -force_p,
            torque_i: torque_q,
            torque_j: torque_p,
        }
    }
}
