//! The force loop on rayon's threads with a deterministic reduction: each list entry's force
//! goes to a buffer (the entries of a fixed-size chunk of particles per task), then each
//! particle sums, in list order, the entries it owns and the entries it is the partner of.
//! The sums do not depend on the number of threads, so the results are identical run to run
//! and for any thread count.

use crate::{Dem, DemCounts, DemEnergy, tally};
use creep_law::Vec3;
use creep_law::pair::{ContactHistory, PairForces, TangentialLaw};
use rayon::prelude::*;

/// One task: the first particle of a chunk, its entries' histories and outputs.
type Task<'a, T> = (usize, &'a mut [ContactHistory<T>], &'a mut [Entry]);

/// Particles per task.
const CHUNK: usize = 128;

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
    /// List length the reverse index was built for.
    built_for: usize,
    built_rebuilds: usize,
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
        b.rev_k.resize(self.nl_j.len(), 0);
        for (k, &j) in self.nl_j.iter().enumerate() {
            let s = &mut fill[j as usize];
            b.rev_k[*s as usize] = k as u32;
            *s += 1;
        }
        b.built_for = self.nl_j.len();
        b.built_rebuilds = self.counts.rebuilds;
        b.out.clear();
        b.out.resize(self.nl_j.len(), Entry::default());
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
        for (c, e) in partial {
            counts.contacts += c.contacts;
            counts.sliding += c.sliding;
            counts.creeping += c.creeping;
            energy.damping += e.damping;
            energy.slip += e.slip;
            energy.creep += e.creep;
            energy.rolling += e.rolling;
            energy.truncation += e.truncation;
        }
        // Gather, in list order per particle.
        let (start, rev_start, rev_k) = (&self.nl_start, &self.par.rev_start, &self.par.rev_k);
        let outs = &out;
        self.f
            .par_iter_mut()
            .zip(self.t.par_iter_mut())
            .enumerate()
            .with_min_len(CHUNK)
            .for_each(|(i, (f, t))| {
                for k in start[i] as usize..start[i + 1] as usize {
                    *f += outs[k].force_i;
                    *t += outs[k].torque_i;
                }
                for &k in &rev_k[rev_start[i] as usize..rev_start[i + 1] as usize] {
                    *f -= outs[k as usize].force_i;
                    *t += outs[k as usize].torque_j;
                }
            });
        self.nl_h = hist;
        self.par.out = out;
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
