//! The neighbour list: re-sorting by cell, the half list with a skin, the wall lists, and the
//! carry-over of the contact histories by partner id at a rebuild.

use creep_law::pair::{ContactHistory, TangentialLaw};

use crate::Dem;

impl<T: TangentialLaw> Dem<T> {
    /// Re-sorts the particles by cell, rebuilds the half neighbour list and the wall lists, and
    /// carries the histories of the contacts over by partner id.
    pub(crate) fn rebuild(&mut self) {
        let n = self.len();
        self.counts.rebuilds += 1;
        // Old histories stay where they are; the carry-over indexes them by the smaller id
        // (CSR), partner by the larger, so each history is moved once, to its place in the new
        // list (the exact tier's history is ~0.5 kB: copying it through the sort cost more than
        // the rest of the rebuild). The new list first records where each entry's history is
        // in the old one (`src`), then the histories are moved within their own array
        // ([`carry_in_place`]): a new array per rebuild was fresh memory from the system each
        // time, page faults costing as much as the copy (the triaxial compaction rebuilds every
        // other step).
        let mut carry = Carry::default();
        for i in 0..n {
            for k in self.nl_start.get(i).copied().unwrap_or(0) as usize
                ..self.nl_start.get(i + 1).copied().unwrap_or(0) as usize
            {
                if !self.nl_h[k].is_virgin() {
                    let (a, b) = (self.id[i], self.id[self.nl_j[k] as usize]);
                    carry.push(a.min(b), a.max(b), k as u32);
                }
            }
        }
        for e in 0..self.wl_i.len() {
            if !self.wl_h[e].is_virgin() {
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
        let mut src = Vec::with_capacity(self.nl_h.len());
        #[cfg(feature = "parallel")]
        let done = if self.cfg.parallel {
            self.half_list_parallel(&carry, &mut src);
            true
        } else {
            false
        };
        #[cfg(not(feature = "parallel"))]
        let done = false;
        if !done {
            self.nl_start.clear();
            self.nl_j.clear();
            self.nl_start.push(0);
            let mut stencil = crate::grid::Stencil::default();
            for i in 0..n {
                half_neighbours_of(
                    &self.grid,
                    &mut stencil,
                    &self.x,
                    &self.r,
                    &self.id,
                    self.cfg.skin,
                    &carry,
                    i,
                    &mut self.nl_j,
                    &mut src,
                );
                self.nl_start.push(self.nl_j.len() as u32);
            }
        }
        carry_in_place(&mut self.nl_h, &src, ContactHistory::default());

        // Wall lists.
        let skin = self.cfg.skin;
        self.wl_k.clear();
        self.wl_i.clear();
        src.clear();
        for (k, wall) in self.walls.iter().enumerate() {
            for i in 0..n {
                if (self.x[i] - wall.point).dot(wall.normal) < self.r[i] + skin {
                    self.wl_k.push(k as u32);
                    self.wl_i.push(i as u32);
                    src.push(
                        carry
                            .find_wall(self.id[i], k as u32)
                            .map_or(NONE, |e| e as u32),
                    );
                }
            }
        }
        carry_in_place(&mut self.wl_h, &src, ContactHistory::default());
        // The lists grow by doubling at the first build (and when they grow later): give back
        // what is more than an eighth over their length, so the engine holds about what it uses.
        trim(&mut self.nl_j);
        trim(&mut self.nl_h);
        trim(&mut self.wl_k);
        trim(&mut self.wl_i);
        trim(&mut self.wl_h);
        self.x_build.clone_from(&self.x);
        self.wall_build = self.walls.iter().map(|w| w.point).collect();
    }
}

/// No old entry: a `src` value of [`carry_in_place`].
pub(crate) const NONE: u32 = u32::MAX;

/// Appends particle `i`'s half-list entries (the particles `j` of its cell after it and of the
/// 13 half-stencil cells within `r_i + r_j + skin`, in the grid's order) to `nl_j`, and where
/// each one's history is in the old list (or [`NONE`]) to `src`. The serial rebuild calls it
/// for every particle in turn; the parallel one per block of particles, then joins the blocks
/// in order: the same list.
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn half_neighbours_of(
    grid: &crate::grid::Grid,
    stencil: &mut crate::grid::Stencil,
    x: &[creep_law::Vec3],
    r: &[f64],
    id: &[u32],
    skin: f64,
    carry: &Carry,
    i: usize,
    nl_j: &mut Vec<u32>,
    src: &mut Vec<u32>,
) {
    let xi = x[i];
    let ri = r[i];
    let periodic = grid.is_periodic();
    let id_i = id[i];
    let (own, ranges) = grid.half_neighbour_ranges(i, stencil);
    for (a, b) in std::iter::once(own).chain(ranges.iter().copied()) {
        let (a, b) = (a as usize, b as usize);
        for ((j, &xj), &rj) in (a..b).zip(&x[a..b]).zip(&r[a..b]) {
            let d = if periodic {
                grid.min_image(xj - xi)
            } else {
                xj - xi
            };
            let cut = ri + rj + skin;
            if d.dot(d) < cut * cut {
                let id_j = id[j];
                nl_j.push(j as u32);
                src.push(
                    carry
                        .find(id_i.min(id_j), id_i.max(id_j))
                        .map_or(NONE, |k| k as u32),
                );
            }
        }
    }
}

/// Rearranges `v` in place so that afterwards `v[k]` is the old `v[src[k]]` (or `fill` where
/// `src[k]` is [`NONE`]) for every `k < src.len()`, and `v.len() == src.len()`. `src` must not
/// name an old entry twice (each history goes to at most one place) nor one beyond `v.len()`.
///
/// A partial permutation: positions whose old value nobody takes are free; from each free
/// position a chain fills it from its source, which is then free in turn, until a source is
/// [`NONE`] or lies beyond the new length; what is left are closed cycles, turned with one
/// temporary. Each entry is moved once (twice on a cycle's first), with no new array.
fn carry_in_place<X: Copy>(v: &mut Vec<X>, src: &[u32], fill: X) {
    let n_new = src.len();
    if v.len() < n_new {
        v.resize(n_new, fill);
    }
    // Who takes each old entry.
    let mut dst = vec![NONE; v.len()];
    for (k, &s) in src.iter().enumerate() {
        if s != NONE {
            debug_assert!(dst[s as usize] == NONE, "entry {s} carried twice");
            dst[s as usize] = k as u32;
        }
    }
    let mut done: Vec<bool> = src
        .iter()
        .enumerate()
        .map(|(k, &s)| s as usize == k)
        .collect();
    // Chains, from the free positions.
    for k0 in 0..n_new {
        if done[k0] || dst[k0] != NONE {
            continue;
        }
        let mut k = k0;
        loop {
            let s = src[k];
            done[k] = true;
            if s == NONE {
                v[k] = fill;
                break;
            }
            let s = s as usize;
            v[k] = v[s];
            // `s`'s old value has gone to `k`: `s` is free now.
            if s >= n_new {
                break;
            }
            k = s;
        }
    }
    // Cycles: every position left takes the value of another one left.
    for k0 in 0..n_new {
        if done[k0] {
            continue;
        }
        let first = v[k0];
        let mut k = k0;
        loop {
            done[k] = true;
            let s = src[k] as usize;
            if s == k0 {
                v[k] = first;
                break;
            }
            v[k] = v[s];
            k = s;
        }
    }
    v.truncate(n_new);
}

/// Shrinks `v`'s capacity to its length plus an eighth when it holds more than a quarter
/// over its length.
fn trim<X>(v: &mut Vec<X>) {
    let len = v.len();
    if v.capacity() > len + len / 4 {
        v.shrink_to(len + len / 8);
    }
}

/// `v[i] = old[order[i]]`.
fn permute<X: Copy>(v: &mut Vec<X>, order: &[u32]) {
    let old = std::mem::take(v);
    v.extend(order.iter().map(|&o| old[o as usize]));
}

/// Where the histories of the last list are, keyed by particle id (CSR), for the carry-over
/// at a rebuild: `(smaller id, partner id or wall, index in the old list)`.
#[derive(Default)]
pub(crate) struct Carry {
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
    #[inline]
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

#[cfg(test)]
mod tests {
    use super::{NONE, carry_in_place};

    /// The in-place carry-over equals building a new array, on random partial permutations
    /// (lists that grow, shrink, keep entries in place, drop and add entries).
    #[test]
    fn carry_in_place_equals_a_new_array() {
        let mut s: u64 = 12345;
        let mut rnd = |m: usize| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((s >> 33) as usize) % m.max(1)
        };
        for case in 0..2000 {
            let n_old = rnd(40);
            let n_new = rnd(40);
            let old: Vec<u64> = (0..n_old as u64).map(|k| 1000 + k).collect();
            // A random injective map from new positions to old entries, some NONE, some in
            // place.
            let mut pool: Vec<u32> = (0..n_old as u32).collect();
            for k in (1..pool.len()).rev() {
                pool.swap(k, rnd(k + 1));
            }
            let mut src = vec![NONE; n_new];
            for (k, slot) in src.iter_mut().enumerate() {
                match rnd(4) {
                    0 => {}
                    1 if k < n_old && pool.contains(&(k as u32)) => {
                        pool.retain(|&p| p != k as u32);
                        *slot = k as u32;
                    }
                    _ => {
                        if let Some(p) = pool.pop() {
                            *slot = p;
                        }
                    }
                }
            }
            let expected: Vec<u64> = src
                .iter()
                .map(|&s| if s == NONE { 7 } else { old[s as usize] })
                .collect();
            let mut v = old.clone();
            carry_in_place(&mut v, &src, 7);
            assert_eq!(v, expected, "case {case}: src {src:?}");
        }
    }
}
