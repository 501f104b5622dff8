//! The force loop on rayon's threads with a deterministic reduction: each list entry's force
//! goes to a buffer (the entries of a fixed-size chunk of particles per task), then each
//! particle sums the entries it owns and the entries it is the partner of, merged in list
//! order: the order in which the serial loop adds them. Energies and counts are summed per
//! chunk, then chunk by chunk, as the serial loop sums them too. So the results are the same
//! bits as the serial loop's, for any thread count (test `parallel_force_loop_is_deterministic`).

use crate::step::weight;
use crate::step::{CHUNK, WallOut, add_partial};
use crate::{Dem, DemCounts, DemEnergy, tally};
use creep_law::Vec3;
use creep_law::pair::{ContactHistory, PairForces, TangentialLaw};
use rayon::prelude::*;

/// One task: the first particle of a chunk, its entries' histories and outputs.
type Task<'a, T> = (usize, &'a mut [ContactHistory<T>], &'a mut [Entry]);

/// One entry's contribution: force and torque on its owner `i`, torque on its partner `j`
/// (the force on `j` is `-force_i`).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Entry {
    force_i: Vec3,
    torque_i: Vec3,
    torque_j: Vec3,
}

#[derive(Debug, Clone, Default)]
pub(crate) struct Buffers {
    out: Vec<Entry>,
    /// For each particle, the entries whose partner it is (CSR), rebuilt with the list.
    rev_start: Vec<u32>,
    rev_k: Vec<u32>,
    /// The wall contacts' outputs (the kernel's, or the energy a history released).
    wall_out: Vec<Result<WallOut, f64>>,
    /// List length the reverse index was built for.
    built_for: usize,
    built_rebuilds: usize,
}

impl Buffers {
    /// Bytes held (capacities).
    pub(crate) fn bytes(&self) -> usize {
        use std::mem::size_of;
        self.out.capacity() * size_of::<Entry>()
            + (self.rev_start.capacity() + self.rev_k.capacity()) * 4
            + self.wall_out.capacity() * size_of::<Result<WallOut, f64>>()
    }
}

impl<T: TangentialLaw> Dem<T> {
    fn reverse_index(&mut self) {
        let n = self.len();
        let b = &mut self.par;
        if b.built_rebuilds == self.counts.rebuilds
            && b.built_for == self.nl_j.len()
            && b.rev_start.len() == n + 1
        {
            return;
        }
        b.rev_start.clear();
        b.rev_start.resize(n + 1, 0);
        for &j in &self.nl_j {
            b.rev_start[j as usize + 1] += 1;
        }
        for i in 0..n {
            b.rev_start[i + 1] += b.rev_start[i];
        }
        let mut fill = b.rev_start.clone();
        b.rev_k.clear();
        b.rev_k.reserve_exact(self.nl_j.len());
        b.rev_k.resize(self.nl_j.len(), 0);
        for (k, &j) in self.nl_j.iter().enumerate() {
            let s = &mut fill[j as usize];
            b.rev_k[*s as usize] = k as u32;
            *s += 1;
        }
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
    }

    pub(crate) fn pair_forces_parallel(
        &mut self,
        dt: f64,
        counts: &mut DemCounts,
        energy: &mut DemEnergy,
    ) {
        self.reverse_index();
        let n = self.len();
        let mut hist = std::mem::take(&mut self.nl_h);
        let mut out = std::mem::take(&mut self.par.out);
        // Split the histories and outputs at chunk boundaries.
        let mut tasks: Vec<Task<'_, T>> = Vec::new();
        {
            let (mut h_rest, mut o_rest) = (&mut hist[..], &mut out[..]);
            let mut i0 = 0;
            while i0 < n {
                let i1 = (i0 + CHUNK).min(n);
                let len = (self.nl_start[i1] - self.nl_start[i0]) as usize;
                let (h, hr) = h_rest.split_at_mut(len);
                let (o, or) = o_rest.split_at_mut(len);
                tasks.push((i0, h, o));
                h_rest = hr;
                o_rest = or;
                i0 = i1;
            }
        }
        let this = &*self;
        let partial: Vec<(DemCounts, DemEnergy)> = tasks
            .into_par_iter()
            .map(|(i0, h, o)| {
                let mut c = DemCounts::default();
                let mut e = DemEnergy::default();
                let base = this.nl_start[i0] as usize;
                let i1 = (i0 + CHUNK).min(n);
                for i in i0..i1 {
                    for k in this.nl_start[i] as usize..this.nl_start[i + 1] as usize {
                        let j = this.nl_j[k] as usize;
                        let slot = &mut o[k - base];
                        *slot = match this.pair(i, j, &mut h[k - base], dt) {
                            Ok((p, _, f)) => {
                                tally(&mut c, &mut e, &f);
                                c.contacts += 1;
                                entry(p == i, &f)
                            }
                            Err(released) => {
                                e.slip += released;
                                Entry::default()
                            }
                        };
                    }
                }
                (c, e)
            })
            .collect();
        for (c, e) in &partial {
            add_partial(counts, energy, c, e);
        }
        // Gather from the particle's weight (`forces` leaves the arrays to this loop in
        // parallel mode: one pass over them instead of two), the owned entries (one range of
        // the list) and the partnered ones (ascending in the reverse index) merged by entry
        // number: the serial loop's order. An open pair's entry is zero, which the serial loop
        // does not add; adding `+0.0` changes no sum except `-0.0`, and these sums never are
        // `-0.0`: they start from `+0.0` or a nonzero weight (`forces` makes the weight's zero
        // components `+0.0`), and in round-to-nearest a sum is `-0.0` only if both terms are.
        let (start, rev_start, rev_k) = (&self.nl_start, &self.par.rev_start, &self.par.rev_k);
        let (outs, mass, g) = (&out, &self.mass, self.cfg.gravity);
        self.f
            .par_iter_mut()
            .zip(self.t.par_iter_mut())
            .enumerate()
            .with_min_len(CHUNK)
            .for_each(|(i, (f, t))| {
                *f = weight(g, mass[i]);
                *t = Vec3::ZERO;
                let (mut k, end) = (start[i] as usize, start[i + 1] as usize);
                for &r in &rev_k[rev_start[i] as usize..rev_start[i + 1] as usize] {
                    let r = r as usize;
                    while k < end && k < r {
                        *f += outs[k].force_i;
                        *t += outs[k].torque_i;
                        k += 1;
                    }
                    *f -= outs[r].force_i;
                    *t += outs[r].torque_j;
                }
                for o in &outs[k..end] {
                    *f += o.force_i;
                    *t += o.torque_i;
                }
            });
        self.nl_h = hist;
        self.par.out = out;
    }
}

impl<T: TangentialLaw> Dem<T> {
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

    /// The wall contacts on rayon's threads: the kernel per entry in parallel, then the
    /// outputs added in list order, as the serial loop adds them (same sums, same results).
    pub(crate) fn wall_forces_parallel(
        &mut self,
        dt: f64,
        counts: &mut DemCounts,
        energy: &mut DemEnergy,
    ) {
        for f in &mut self.wall_force {
            *f = Vec3::ZERO;
        }
        let mut hist = std::mem::take(&mut self.wl_h);
        let mut outs = std::mem::take(&mut self.par.wall_out);
        outs.clear();
        let this = &*self;
        hist.par_iter_mut()
            .enumerate()
            .with_min_len(CHUNK)
            .map(|(e, h)| this.wall_pair(e, h, dt))
            .collect_into_vec(&mut outs);
        for (e, out) in outs.drain(..).enumerate() {
            self.apply_wall(e, out, counts, energy);
        }
        self.wl_h = hist;
        self.par.wall_out = outs;
    }
}

/// The entry of a pair whose owner is p (`owner_is_p`) or q.
#[inline]
fn entry(owner_is_p: bool, f: &PairForces) -> Entry {
    if owner_is_p {
        Entry {
            force_i: f.force_p,
            torque_i: f.torque_p,
            torque_j: f.torque_q,
        }
    } else {
        Entry {
            force_i: -f.force_p,
            torque_i: f.torque_q,
            torque_j: f.torque_p,
        }
    }
}
