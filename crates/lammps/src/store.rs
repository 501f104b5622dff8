//! The pair style's hot path: contact histories kept as creep-law's own structs between
//! neighbour-list builds ([`HistoryStore`]), and one call per step that reads the host's atom
//! arrays, steps every touching pair in place and adds the forces and torques into the host's
//! arrays ([`compute_pairs`]).
//!
//! Why: the flat `[f64]` form of a history ([`ContactHistory::write`]/[`ContactHistory::read`])
//! is what LAMMPS stores per atom, sends to other ranks and writes to restart files, but it
//! only has to exist then (before atoms migrate, at the end of a run, for a restart). Between
//! neighbour-list builds the histories stay here, one [`ContactHistory`] per slot, and the
//! kernel steps them in place as creep-dem does: no per-contact conversion, no validation of a
//! history the kernel itself wrote, no 22-double contact record gathered by the host and no
//! per-contact output scattered back by it. The conversion to and from the flat form (with its
//! validation) happens in [`HistoryStore::load`] and [`HistoryStore::save`], once per
//! neighbour-list build. The law is the same function ([`pair_force`]), called on the same
//! values in the same order, so the results are bit-identical to [`Model::compute_at`]'s.

use creep_law::Vec3;
use creep_law::pair::{
    Cheap, ContactGeometry, ContactHistory, Exact, LANES, PairBody, PairForces, SphereForceLanes,
    SphereLanes, SpherePair, TangentialLaw, block_supports, pair_force,
};
use creep_law::{LawError, Surface};

use crate::model::{Model, ModelError, Tier};

/// Contact histories of one tier, one per slot, in creep-law's own form.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryStore {
    slots: Slots,
    /// The buffer [`HistoryStore::remap`] gathers into (then swapped with `slots`), kept
    /// empty between calls so that its capacity is reused: no allocation at a rebuild once
    /// the store has reached its size.
    spare: Slots,
}

#[derive(Debug, Clone, PartialEq)]
enum Slots {
    Exact(Vec<ContactHistory<Exact>>),
    Spring(Vec<ContactHistory<Cheap>>),
}

impl HistoryStore {
    /// An empty store for `tier`.
    pub fn new(tier: Tier) -> Self {
        let empty = || match tier {
            Tier::Exact => Slots::Exact(Vec::new()),
            Tier::Spring => Slots::Spring(Vec::new()),
        };
        Self {
            slots: empty(),
            spare: empty(),
        }
    }

    /// The tier of the histories.
    pub fn tier(&self) -> Tier {
        match self.slots {
            Slots::Exact(_) => Tier::Exact,
            Slots::Spring(_) => Tier::Spring,
        }
    }

    /// Number of slots.
    pub fn len(&self) -> usize {
        match &self.slots {
            Slots::Exact(v) => v.len(),
            Slots::Spring(v) => v.len(),
        }
    }

    /// Whether the store has no slots.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Replaces the contents with the histories of `flat` in their flat form
    /// ([`ContactHistory::write`]), [`Tier::history_len`] doubles each: slot `k` is
    /// `flat[k * stride ..][..stride]`. A corrupt history (non-finite, an invalid Mindlin
    /// memory) is an error naming its slot, and leaves the store empty.
    pub fn load(&mut self, flat: &[f64]) -> Result<(), ModelError> {
        fn load_tier<T: TangentialLaw>(
            v: &mut Vec<ContactHistory<T>>,
            flat: &[f64],
        ) -> Result<(), ModelError> {
            let stride = ContactHistory::<T>::LEN;
            v.clear();
            if !flat.len().is_multiple_of(stride) {
                return Err(ModelError::Stride {
                    got: flat.len() % stride,
                    want: stride,
                });
            }
            v.reserve(flat.len() / stride);
            for (index, row) in flat.chunks_exact(stride).enumerate() {
                match ContactHistory::<T>::read(row) {
                    Ok(h) => v.push(h),
                    Err(source) => {
                        v.clear();
                        return Err(ModelError::History { index, source });
                    }
                }
            }
            Ok(())
        }
        match &mut self.slots {
            Slots::Exact(v) => load_tier(v, flat),
            Slots::Spring(v) => load_tier(v, flat),
        }
    }

    /// Writes every slot's history in its flat form into `out[..len * stride]` (slot `k` at
    /// `k * stride`, stride [`Tier::history_len`]); `out` must hold at least that many.
    pub fn save(&self, out: &mut [f64]) -> Result<(), ModelError> {
        fn save_tier<T: TangentialLaw>(
            v: &[ContactHistory<T>],
            out: &mut [f64],
        ) -> Result<(), ModelError> {
            let stride = ContactHistory::<T>::LEN;
            let want = v.len() * stride;
            let Some(out) = out.get_mut(..want) else {
                return Err(ModelError::Output {
                    got: out.len() / stride,
                    want: v.len(),
                });
            };
            for (index, (h, row)) in v.iter().zip(out.chunks_exact_mut(stride)).enumerate() {
                h.write(row)
                    .map_err(|source| ModelError::History { index, source })?;
            }
            Ok(())
        }
        match &self.slots {
            Slots::Exact(v) => save_tier(v, out),
            Slots::Spring(v) => save_tier(v, out),
        }
    }

    /// Reorders the store after a neighbour-list build without the flat form: new slot `k`
    /// holds the history that was in slot `from[k]` (a slot may be taken more than once or
    /// not at all; the histories are copied as they are, bit for bit). An index outside the
    /// store is an error naming the first such `k`, and leaves the store unchanged.
    ///
    /// The host's alternative to [`HistoryStore::save`] then [`HistoryStore::load`] when the
    /// histories need not leave the process between two builds (one rank: no atom migrates),
    /// with the same result: [`ContactHistory::read`] of [`ContactHistory::write`] is the
    /// identity (test `remap_is_save_then_load`).
    pub fn remap(&mut self, from: &[i32]) -> Result<(), ModelError> {
        fn remap_tier<T: TangentialLaw>(
            v: &mut Vec<ContactHistory<T>>,
            spare: &mut Vec<ContactHistory<T>>,
            from: &[i32],
        ) -> Result<(), ModelError> {
            spare.clear();
            spare.reserve(from.len());
            let len = v.len();
            for (index, &s) in from.iter().enumerate() {
                let Some(h) = usize::try_from(s).ok().and_then(|s| v.get(s)) else {
                    spare.clear();
                    return Err(ModelError::Slot {
                        index,
                        slot: s,
                        len,
                    });
                };
                spare.push(*h);
            }
            std::mem::swap(v, spare);
            spare.clear();
            Ok(())
        }
        match (&mut self.slots, &mut self.spare) {
            (Slots::Exact(v), Slots::Exact(spare)) => remap_tier(v, spare, from),
            (Slots::Spring(v), Slots::Spring(spare)) => remap_tier(v, spare, from),
            // `new` makes both of one tier and nothing changes a tier afterwards.
            _ => Err(ModelError::MixedTiers),
        }
    }
}

/// One rank's per-atom arrays, as LAMMPS keeps them (owned atoms first, then ghosts; `nall`
/// entries each). SI units.
#[derive(Debug, Clone, Copy)]
pub struct Atoms<'a> {
    /// Centres (m).
    pub x: &'a [[f64; 3]],
    /// Velocities (m/s).
    pub v: &'a [[f64; 3]],
    /// Angular velocities (rad/s).
    pub omega: &'a [[f64; 3]],
    /// Radii (m).
    pub radius: &'a [f64],
    /// Masses (kg).
    pub mass: &'a [f64],
    /// Atom types, `1..=ntypes`.
    pub kind: &'a [i32],
}

/// Where the pair forces go: the owned atoms' force and torque (the first `nlocal` atoms; a
/// ghost receives nothing, as LAMMPS' pair styles do with `newton off`).
#[derive(Debug)]
pub struct Accumulators<'a> {
    /// Forces (N), added to.
    pub force: &'a mut [[f64; 3]],
    /// Torques (N m), added to.
    pub torque: &'a mut [[f64; 3]],
}

/// One touching pair of a step: atom `p` (the normal points from p to q; the LAMMPS shim puts
/// the lower tag first), atom `q`, and the store slot of its history.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PairIndex {
    /// Atom index of body p (>= 0).
    pub p: i32,
    /// Atom index of body q (>= 0).
    pub q: i32,
    /// History slot (>= 0; a slot at or beyond the store's length is a new, virgin contact).
    pub slot: i32,
}

/// Optional per-contact outputs of [`compute_pairs`].
#[derive(Debug, Default)]
pub struct PairOutputs<'a> {
    /// The force on p of each contact (N) (the host's virial), zero for a dropped contact.
    pub force_p: Option<&'a mut [[f64; 3]]>,
    /// 1 if the contact carries force, 0 if it was dropped (coincident centres, or found apart
    /// by the kernel): its history is virgin again.
    pub touching: Option<&'a mut [u8]>,
}

/// The model table of [`compute_pairs`]: `model_of(ti * (ntypes + 1) + tj)` is the model of
/// atom types `ti`, `tj` (`None`: no `pair_coeff`), as LAMMPS' `[ntypes + 1][ntypes + 1]`
/// arrays.
#[derive(Debug, Clone, Copy)]
pub struct ModelTable<F> {
    /// Number of atom types.
    pub ntypes: usize,
    /// The lookup.
    pub model_of: F,
}

/// Steps the touching pairs of one step by `dt` (s) with their histories in `store`, and adds
/// each contact's force and torques into `acc` (force on p and `-force` on q; torques about
/// each centre; owned atoms only, `index < acc.force.len()`), in the order of `pairs`. The
/// store first grows to `nslots` slots (new ones virgin). Returns the number of dropped
/// contacts (`touching == 0`).
///
/// Errors (the batch stops at the failing contact): a non-finite or negative `dt`; an atom index
/// outside the arrays, a slot outside `nslots`, an atom type outside `1..=ntypes` or without a
/// model, a model of another tier than the store's, a radius or mass not finite and > 0, an
/// output buffer shorter than the batch, a position, velocity or angular velocity that is not
/// finite, a force that comes out non-finite anyway, atom arrays of unequal lengths.
#[allow(clippy::too_many_arguments)]
pub fn compute_pairs<'a, F>(
    table: &ModelTable<F>,
    store: &mut HistoryStore,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    pairs: &[PairIndex],
    nslots: usize,
    dt: f64,
    outputs: PairOutputs<'_>,
) -> Result<usize, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    if !(dt.is_finite() && dt >= 0.0) {
        return Err(ModelError::TimeStep(dt));
    }
    check_arrays(atoms, acc)?;
    for buf in [
        outputs.force_p.as_ref().map(|b| b.len()),
        outputs.touching.as_ref().map(|b| b.len()),
    ]
    .into_iter()
    .flatten()
    {
        if buf < pairs.len() {
            return Err(ModelError::Output {
                got: buf,
                want: pairs.len(),
            });
        }
    }
    let tier = store.tier();
    match &mut store.slots {
        Slots::Exact(v) => {
            v.resize(nslots, ContactHistory::default());
            step_pairs(table, tier, v, atoms, acc, pairs, dt, outputs)
        }
        Slots::Spring(v) => {
            v.resize(nslots, ContactHistory::default());
            step_pairs(table, tier, v, atoms, acc, pairs, dt, outputs)
        }
    }
}

/// [`compute_pairs`] for one tier (monomorphised: the kernel is inlined into this loop).
#[allow(clippy::too_many_arguments)]
fn step_pairs<'a, T: TangentialLaw, F>(
    table: &ModelTable<F>,
    tier: Tier,
    hist: &mut [ContactHistory<T>],
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    pairs: &[PairIndex],
    dt: f64,
    mut outputs: PairOutputs<'_>,
) -> Result<usize, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    let nall = atoms.x.len();
    let nslots = hist.len();
    let stride = table.ntypes + 1;
    let atom = |k: usize, a: i32| -> Result<usize, ModelError> {
        usize::try_from(a)
            .ok()
            .filter(|&a| a < nall)
            .ok_or(ModelError::AtomIndex {
                index: k,
                atom: a,
                nall,
            })
    };
    let kind = |k: usize, a: usize| -> Result<usize, ModelError> {
        let t = atoms.kind[a];
        usize::try_from(t)
            .ok()
            .filter(|&t| (1..=table.ntypes).contains(&t))
            .ok_or(ModelError::AtomType {
                index: k,
                kind: t,
                ntypes: table.ntypes,
            })
    };
    // The per-contact checks of the models' tier and of the atoms' state, hoisted: when every
    // model of the table has the store's tier and every atom of the arrays is valid (one pass
    // over the atoms, cheaper than checking both atoms of every contact, ~3.5 contacts per
    // atom), the loop skips them; otherwise it checks each contact as before, so an error names
    // the first contact that meets a bad atom or model, and an invalid atom in no contact is
    // no error.
    let tiers_ok =
        (0..stride * stride).all(|k| (table.model_of)(k).is_none_or(|m| m.tier() == tier));
    let atoms_ok = atoms_valid(atoms);
    let mut dropped = 0;
    for (k, pr) in pairs.iter().enumerate() {
        let (p, q) = (atom(k, pr.p)?, atom(k, pr.q)?);
        let h = usize::try_from(pr.slot)
            .ok()
            .and_then(|s| hist.get_mut(s))
            .ok_or(ModelError::Slot {
                index: k,
                slot: pr.slot,
                len: nslots,
            })?;
        let m = (table.model_of)(kind(k, p)? * stride + kind(k, q)?)
            .ok_or(ModelError::MissingModel(k))?;
        if !tiers_ok && m.tier() != tier {
            return Err(ModelError::MixedTiers);
        }
        let f = step_contact(k, m, atoms, acc, p, q, h, dt, atoms_ok)?;
        if let Some(out) = outputs.force_p.as_deref_mut() {
            out[k] = [f.force_p.x, f.force_p.y, f.force_p.z];
        }
        if let Some(out) = outputs.touching.as_deref_mut() {
            out[k] = u8::from(f.touching);
        }
        dropped += usize::from(!f.touching);
    }
    Ok(dropped)
}

/// A half neighbour list as LAMMPS builds it for a pair style (`NeighList`: `ilist[..inum]`,
/// `numneigh`, `firstneigh`), as [`compute_list`] walks it.
pub trait HalfList {
    /// The atoms whose neighbours are listed (`ilist[..inum]`), in the list's order.
    fn atoms(&self) -> &[i32];
    /// The neighbours of atom `i` (`firstneigh[i][..numneigh[i]]`, LAMMPS' special-bond bits
    /// still in the top bits), or `None` when `i` lies outside the list's per-atom arrays.
    fn neighbours(&self, i: usize) -> Option<&[i32]>;
}

/// A [`HalfList`] in Rust vectors (tests, hosts without LAMMPS): `neighbours[i]` are atom
/// `i`'s neighbours.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct VecList {
    /// The atoms whose neighbours are listed.
    pub atoms: Vec<i32>,
    /// Per atom index, its neighbours (atoms not in `atoms` may have any).
    pub neighbours: Vec<Vec<i32>>,
}

impl HalfList for VecList {
    fn atoms(&self) -> &[i32] {
        &self.atoms
    }
    fn neighbours(&self, i: usize) -> Option<&[i32]> {
        self.neighbours.get(i).map(Vec::as_slice)
    }
}

/// The host's per-entry state of [`compute_list`], one value per neighbour-list entry in the
/// list's order (entry `e` of atom `ilist[ii]`'s `jj`-th neighbour is `e = sum of numneigh over
/// ilist[..ii] + jj`), kept between the steps of one neighbour-list build.
#[derive(Debug)]
pub struct ListEntries<'a> {
    /// The entry's history slot in the store, -1 for none (apart, or never touched since the
    /// build): written by [`compute_list`] (a new contact gets a new, virgin slot; a contact
    /// found apart or dropped gets -1).
    pub slot: &'a mut [i32],
    /// Nonzero where the neighbour is body p (the LAMMPS shim: the lower atom tag is body p,
    /// fixed per build), zero where the list's atom is.
    pub swap: &'a [u8],
}

/// One contact's force for the host's virial: atoms `p` and `q` and the force on p (N).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PairForce {
    /// Atom index of body p.
    pub p: i32,
    /// Atom index of body q.
    pub q: i32,
    /// Force on p (N) (`-force_p` on q); zero for a dropped contact.
    pub force_p: [f64; 3],
}

/// What [`compute_list`] counted.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ListCounts {
    /// Touching pairs of the step (centres closer than the sum of the radii).
    pub contacts: usize,
    /// Of those, the ones whose body p is an owned atom (summed over ranks: each contact once).
    pub owned_contacts: usize,
    /// Contacts the kernel dropped (coincident centres): their entries' slots are -1 again.
    pub dropped: usize,
    /// The store's slots after the step (the host's count for [`HistoryStore::save`]).
    pub nslots: usize,
}

/// The pair style's whole step in one pass over LAMMPS' half neighbour list: for every entry
/// `(i, j)` of `list` (`j` masked by `neighmask`, LAMMPS' `NEIGHMASK`), the pair is a contact
/// when the centres are closer than the sum of the radii; its history is the one in the
/// entry's slot ([`ListEntries::slot`]; a new contact takes a new, virgin slot at the store's
/// end, an entry found apart gets -1: its history is abandoned and the slot reclaimed at the
/// next build), body p is `j` where [`ListEntries::swap`] says so and `i` otherwise, and the
/// kernel ([`pair_force`], the same per-contact code as [`compute_pairs`]) steps it in place and
/// adds its force and torques into the owned atoms of `acc` in the list's order. With
/// `forces`, the contacts' forces on p for the host's virial (index = the contact's number in
/// the step; at least as many entries as the list has are needed).
///
/// This is [`compute_pairs`] with the host's neighbour loop folded in: no array of touching
/// pairs is built by the host and read back, and the results are the same bits (the same
/// contacts in the same order, the same kernel: test `list_path_is_bitwise_the_pairs_path`).
///
/// Errors (the step stops at the failing entry; `k` in a message is the contact's number in
/// the step): as [`compute_pairs`], and entries that do not match the list (their number, a
/// list atom outside the list's arrays, a neighbour outside the atom arrays, a slot outside
/// the store).
#[allow(clippy::too_many_arguments)]
pub fn compute_list<'a, F, L: HalfList>(
    table: &ModelTable<F>,
    store: &mut HistoryStore,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    list: &L,
    neighmask: i32,
    entries: ListEntries<'_>,
    dt: f64,
    forces: Option<&mut [PairForce]>,
) -> Result<ListCounts, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    if !(dt.is_finite() && dt >= 0.0) {
        return Err(ModelError::TimeStep(dt));
    }
    check_arrays(atoms, acc)?;
    // The entries must be the list's, one per (i, j): checked before anything is written.
    let mut total = 0usize;
    for &i in list.atoms() {
        let n = usize::try_from(i)
            .ok()
            .and_then(|i| list.neighbours(i))
            .ok_or(ModelError::ListAtom(i))?
            .len();
        total += n;
    }
    if entries.slot.len() != total || entries.swap.len() != total {
        return Err(ModelError::ListEntries {
            got: entries.slot.len().min(entries.swap.len()),
            want: total,
        });
    }
    if let Some(out) = forces.as_deref()
        && out.len() < total
    {
        return Err(ModelError::Output {
            got: out.len(),
            want: total,
        });
    }
    let tier = store.tier();
    match &mut store.slots {
        Slots::Exact(v) => list_pairs_dispatch(
            table, tier, v, atoms, acc, list, neighmask, entries, dt, forces,
        ),
        Slots::Spring(v) => list_pairs_dispatch(
            table, tier, v, atoms, acc, list, neighmask, entries, dt, forces,
        ),
    }
}

/// [`list_pairs`] in its AVX2 copy where [`wide_available`] says so, else as compiled for the
/// target's baseline.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn list_pairs_dispatch<'a, T: TangentialLaw, F, L: HalfList>(
    table: &ModelTable<F>,
    tier: Tier,
    hist: &mut Vec<ContactHistory<T>>,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    list: &L,
    neighmask: i32,
    entries: ListEntries<'_>,
    dt: f64,
    forces: Option<&mut [PairForce]>,
) -> Result<ListCounts, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    #[cfg(target_arch = "x86_64")]
    if wide_available()? {
        /// [`list_pairs`] compiled with AVX2 and FMA enabled (the loop, the kernels down to the
        /// exact tier's Mindlin memory update, and the spring tier's block of four contacts
        /// inline into it): four `f64` per vector instruction and three-operand forms, the
        /// same bits (Rust never contracts into fused multiply-adds; IEEE 754 operations round
        /// lane by lane).
        #[target_feature(enable = "avx2,fma")]
        #[allow(clippy::too_many_arguments)]
        fn wide<'a, T: TangentialLaw, F, L: HalfList>(
            table: &ModelTable<F>,
            tier: Tier,
            hist: &mut Vec<ContactHistory<T>>,
            atoms: &Atoms<'_>,
            acc: &mut Accumulators<'_>,
            list: &L,
            neighmask: i32,
            entries: ListEntries<'_>,
            dt: f64,
            forces: Option<&mut [PairForce]>,
        ) -> Result<ListCounts, ModelError>
        where
            F: Fn(usize) -> Option<&'a Model>,
        {
            list_pairs(
                table, tier, hist, atoms, acc, list, neighmask, entries, dt, forces,
            )
        }
        // SAFETY: `wide_available` found AVX2 and FMA on this CPU.
        #[allow(unsafe_code)]
        return unsafe {
            wide(
                table, tier, hist, atoms, acc, list, neighmask, entries, dt, forces,
            )
        };
    }
    list_pairs(
        table, tier, hist, atoms, acc, list, neighmask, entries, dt, forces,
    )
}

/// Whether the list loop runs its AVX2 copy: the CPU has AVX2 and FMA, and the
/// environment does not ask for the portable kernels (creep-dem's
/// [`creep_dem::KERNELS_ENV`], read once per process; a value other than `portable`, `avx2`,
/// `auto` or empty is an error).
#[cfg(target_arch = "x86_64")]
fn wide_available() -> Result<bool, ModelError> {
    match creep_dem::Kernels::detected() {
        Ok(k) => Ok(k.wide()),
        Err(e) => Err(ModelError::Kernels(e.to_string())),
    }
}

/// [`compute_list`] for one tier (monomorphised: the kernel is inlined into this loop, and
/// the loop into each compiled copy). A tier with a block kernel for a loop without a buffer
/// of outputs ([`TangentialLaw::HAS_BLOCK_LANES`]: the spring tier) with valid atoms runs
/// [`list_pairs_lanes`]; otherwise each contact goes through the one-contact kernel here.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn list_pairs<'a, T: TangentialLaw, F, L: HalfList>(
    table: &ModelTable<F>,
    tier: Tier,
    hist: &mut Vec<ContactHistory<T>>,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    list: &L,
    neighmask: i32,
    entries: ListEntries<'_>,
    dt: f64,
    mut forces: Option<&mut [PairForce]>,
) -> Result<ListCounts, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    let nall = atoms.x.len();
    let nlocal = acc.force.len();
    let ListEntries { slot, swap } = entries;
    // At most one new slot per entry: reserved once, so that no push below reallocates.
    hist.reserve(slot.len());
    let atoms_ok = atoms_valid(atoms);
    let mut models = TypeModels::new(table, tier, atoms);
    if T::HAS_BLOCK_LANES && atoms_ok {
        return list_pairs_lanes(
            &mut models,
            hist,
            atoms,
            acc,
            list,
            neighmask,
            slot,
            swap,
            dt,
            forces,
        );
    }
    let mut counts = ListCounts::default();
    let mut e0 = 0usize;
    for &ia in list.atoms() {
        // Checked by the caller: the atom is in the list's arrays.
        let i = usize::try_from(ia).map_err(|_| ModelError::ListAtom(ia))?;
        let neigh = list.neighbours(i).ok_or(ModelError::ListAtom(ia))?;
        let first = e0;
        e0 += neigh.len();
        if i >= nall {
            return Err(ModelError::AtomIndex {
                index: counts.contacts,
                atom: ia,
                nall,
            });
        }
        let xi = atoms.x[i];
        let ri = atoms.radius[i];
        for (e, &jraw) in (first..).zip(neigh) {
            let j = neighbour(jraw, neighmask, nall, counts.contacts)?;
            let xj = atoms.x[j];
            let (dx, dy, dz) = (xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]);
            let rsum = ri + atoms.radius[j];
            if dx * dx + dy * dy + dz * dz >= rsum * rsum {
                slot[e] = -1; // apart: the history is abandoned (its slot reclaimed at the next build)
                continue;
            }
            let k = counts.contacts;
            let si = slot_of(hist, &mut slot[e], k)?;
            let (p, q) = if swap[e] != 0 { (j, i) } else { (i, j) };
            counts.contacts += 1;
            counts.owned_contacts += usize::from(p < nlocal);
            let (m, _) = models.of(atoms, p, q, k)?;
            let f = step_contact(k, m, atoms, acc, p, q, &mut hist[si], dt, atoms_ok)?;
            finish_contact(&f, &mut slot[e], ids(p, q), k, &mut counts, &mut forces);
        }
    }
    counts.nslots = hist.len();
    Ok(counts)
}

/// The models of a step's contacts by their atoms' types, and whether the block kernel takes
/// each ([`block_supports`]): where every atom (owned and ghost) is of one type, that type
/// pair's model, looked up once; otherwise each contact's, checked (types within the table,
/// a model for the pair, the store's tier) when its pair of types differs from the contact
/// before's (the types of two atoms in contact rarely change from one entry to the next).
struct TypeModels<'t, 'a, F> {
    table: &'t ModelTable<F>,
    tier: Tier,
    /// Every model of the table is of the store's tier.
    tiers_ok: bool,
    /// Every atom is of one type, whose model is `last`'s.
    single: bool,
    /// The types of the last contact looked up, its model and whether the block takes it.
    last: Option<((i32, i32), &'a Model, bool)>,
}

impl<'t, 'a, F: Fn(usize) -> Option<&'a Model>> TypeModels<'t, 'a, F> {
    #[inline(always)]
    fn new(table: &'t ModelTable<F>, tier: Tier, atoms: &Atoms<'_>) -> Self {
        let stride = table.ntypes + 1;
        let tiers_ok =
            (0..stride * stride).all(|k| (table.model_of)(k).is_none_or(|m| m.tier() == tier));
        let t0 = atoms.kind.first().copied().unwrap_or(0);
        let last = usize::try_from(t0)
            .ok()
            .filter(|&t| (1..=table.ntypes).contains(&t))
            .filter(|_| atoms.kind.iter().fold(true, |ok, &t| ok & (t == t0)))
            .and_then(|t| (table.model_of)(t * stride + t))
            .filter(|m| m.tier() == tier)
            .map(|m| ((t0, t0), m, block_supports(m.constants())));
        Self {
            table,
            tier,
            tiers_ok,
            single: last.is_some(),
            last,
        }
    }

    /// The model of contact `k` between atoms `p` and `q`, and whether the block takes it.
    #[inline(always)]
    fn of(
        &mut self,
        atoms: &Atoms<'_>,
        p: usize,
        q: usize,
        k: usize,
    ) -> Result<(&'a Model, bool), ModelError> {
        if self.single
            && let Some((_, m, b)) = self.last
        {
            return Ok((m, b));
        }
        let types = (atoms.kind[p], atoms.kind[q]);
        if let Some((t, m, b)) = self.last
            && t == types
        {
            return Ok((m, b));
        }
        self.lookup(types, k)
    }

    /// [`TypeModels::of`] through the table, for the atoms' types `types`.
    #[inline(never)]
    fn lookup(&mut self, types: (i32, i32), k: usize) -> Result<(&'a Model, bool), ModelError> {
        let ntypes = self.table.ntypes;
        let kind = |t: i32| -> Result<usize, ModelError> {
            usize::try_from(t)
                .ok()
                .filter(|&t| (1..=ntypes).contains(&t))
                .ok_or(ModelError::AtomType {
                    index: k,
                    kind: t,
                    ntypes,
                })
        };
        let m = (self.table.model_of)(kind(types.0)? * (ntypes + 1) + kind(types.1)?)
            .ok_or(ModelError::MissingModel(k))?;
        if !self.tiers_ok && m.tier() != self.tier {
            return Err(ModelError::MixedTiers);
        }
        let b = block_supports(m.constants());
        self.last = Some((types, m, b));
        Ok((m, b))
    }
}

/// Entry `jraw`'s atom index (`neighmask` applied), below `nall` (`k`: the contacts so far,
/// for the error).
#[inline(always)]
fn neighbour(jraw: i32, neighmask: i32, nall: usize, k: usize) -> Result<usize, ModelError> {
    let jm = jraw & neighmask;
    usize::try_from(jm)
        .ok()
        .filter(|&j| j < nall)
        .ok_or(ModelError::AtomIndex {
            index: k,
            atom: jm,
            nall,
        })
}

/// The history slot of a touching entry whose slot is `s` (contact `k`): a new, virgin one at
/// the store's end where it has none (`*s < 0`), an error where it is outside the store.
#[inline(always)]
fn slot_of<T: TangentialLaw>(
    hist: &mut Vec<ContactHistory<T>>,
    s: &mut i32,
    k: usize,
) -> Result<usize, ModelError> {
    if *s < 0 {
        let new = i32::try_from(hist.len()).map_err(|_| ModelError::Slot {
            index: k,
            slot: -1,
            len: hist.len(),
        })?;
        hist.push(ContactHistory::default());
        *s = new;
    }
    let len = hist.len();
    usize::try_from(*s)
        .ok()
        .filter(|&s| s < len)
        .ok_or(ModelError::Slot {
            index: k,
            slot: *s,
            len,
        })
}

/// The atoms' ids of the pair (p, q) for the virial: below `nall`, which came from C as a
/// count of `i32` indices.
#[inline(always)]
fn ids(p: usize, q: usize) -> [i32; 2] {
    [p as i32, q as i32]
}

/// [`list_pairs`] with the block kernel ([`TangentialLaw::sphere_block_lanes`]), for valid
/// atoms: touching pairs with a history that is not virgin and constants the block takes wait
/// in a [`Lanes`] block of [`LANES`] contacts, which runs when full, or before any other
/// contact is stepped; each lane's outputs are read in place and added to the owned atoms as
/// they come. So every force is added in list order, and the results are the one-contact
/// kernel's bits (a lane the block leaves goes to it in its place). The histories are
/// stepped in their slots of the store.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn list_pairs_lanes<'a, T: TangentialLaw, F, L: HalfList>(
    models: &mut TypeModels<'_, 'a, F>,
    hist: &mut Vec<ContactHistory<T>>,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    list: &L,
    neighmask: i32,
    slot: &mut [i32],
    swap: &[u8],
    dt: f64,
    mut forces: Option<&mut [PairForce]>,
) -> Result<ListCounts, ModelError>
where
    F: Fn(usize) -> Option<&'a Model>,
{
    let nall = atoms.x.len();
    let nlocal = acc.force.len();
    // All of one length (`check_arrays`): sliced to it, so that an index below `nall` needs
    // no further check.
    let (x, r) = (&atoms.x[..nall], &atoms.radius[..nall]);
    let bodies = Bodies {
        v: &atoms.v[..nall],
        omega: &atoms.omega[..nall],
        mass: &atoms.mass[..nall],
    };
    let mut counts = ListCounts::default();
    let mut pend = Lanes::default();
    let mut out = SphereForceLanes::default();
    // Every atom of one type: its model and whether the block takes it, held here.
    let single = models
        .last
        .filter(|_| models.single)
        .map(|(_, m, b)| (m, b));
    let mut e0 = 0usize;
    for &ia in list.atoms() {
        // Checked by the caller: the atom is in the list's arrays.
        let i = usize::try_from(ia).map_err(|_| ModelError::ListAtom(ia))?;
        let neigh = list.neighbours(i).ok_or(ModelError::ListAtom(ia))?;
        let first = e0;
        e0 += neigh.len();
        if i >= nall {
            return Err(ModelError::AtomIndex {
                index: counts.contacts,
                atom: ia,
                nall,
            });
        }
        let (xi, ri) = (x[i], r[i]);
        for (e, &jraw) in (first..).zip(neigh) {
            let j = neighbour(jraw, neighmask, nall, counts.contacts)?;
            let (xj, rj) = (x[j], r[j]);
            let (dx, dy, dz) = (xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]);
            let rsum = ri + rj;
            if dx * dx + dy * dy + dz * dz >= rsum * rsum {
                slot[e] = -1; // apart: the history is abandoned (its slot reclaimed at the next build)
                continue;
            }
            let k = counts.contacts;
            counts.contacts += 1;
            let sw = swap[e] != 0;
            let (p, q) = if sw { (j, i) } else { (i, j) };
            counts.owned_contacts += usize::from(p < nlocal);
            let (m, block) = match single {
                Some(mb) => mb,
                None => models.of(atoms, p, q, k)?,
            };
            let s = slot[e];
            // A slot of the store (`s` >= 0 below its length) whose history is not virgin.
            let si = s as u32 as usize;
            if block && si < hist.len() && !hist[si].is_virgin() {
                if pend.len > 0 && pend.model.is_some_and(|pm| !std::ptr::eq(pm, m)) {
                    pend.flush(
                        hist,
                        atoms,
                        acc,
                        slot,
                        &mut counts,
                        &mut forces,
                        dt,
                        &mut out,
                    )?;
                }
                let (xp, xq, rp, rq) = if sw {
                    (xj, xi, rj, ri)
                } else {
                    (xi, xj, ri, rj)
                };
                if pend.push(m, &bodies, (k, e, si), p, q, xp, xq, rp, rq) {
                    pend.flush(
                        hist,
                        atoms,
                        acc,
                        slot,
                        &mut counts,
                        &mut forces,
                        dt,
                        &mut out,
                    )?;
                }
                continue;
            }
            if pend.len > 0 {
                pend.flush(
                    hist,
                    atoms,
                    acc,
                    slot,
                    &mut counts,
                    &mut forces,
                    dt,
                    &mut out,
                )?;
            }
            let si = slot_of(hist, &mut slot[e], k)?;
            let f = step_contact(k, m, atoms, acc, p, q, &mut hist[si], dt, true)?;
            finish_contact(&f, &mut slot[e], ids(p, q), k, &mut counts, &mut forces);
        }
    }
    if pend.len > 0 {
        pend.flush(
            hist,
            atoms,
            acc,
            slot,
            &mut counts,
            &mut forces,
            dt,
            &mut out,
        )?;
    }
    counts.nslots = hist.len();
    Ok(counts)
}

/// A stepped contact's bookkeeping: a dropped one (`touching` false) frees its slot (`s`) and
/// is counted; its force goes to the virial buffer when there is one (entry `k`, atoms `ids`).
#[inline(always)]
fn finish_contact(
    f: &PairForces,
    s: &mut i32,
    ids: [i32; 2],
    k: usize,
    counts: &mut ListCounts,
    forces: &mut Option<&mut [PairForce]>,
) {
    if !f.touching {
        *s = -1;
        counts.dropped += 1;
    }
    if let Some(out) = forces.as_deref_mut() {
        out[k] = PairForce {
            p: ids[0],
            q: ids[1],
            force_p: [f.force_p.x, f.force_p.y, f.force_p.z],
        };
    }
}

/// The atoms' velocities, angular velocities and masses, all of one length.
struct Bodies<'a> {
    v: &'a [[f64; 3]],
    omega: &'a [[f64; 3]],
    mass: &'a [f64],
}

/// Up to [`LANES`] touching contacts of one model waiting for the block kernel: per lane the
/// contact's index in the step, its list entry and its history's slot, its atoms (p, q), and
/// the bodies.
#[derive(Default)]
struct Lanes<'m> {
    len: usize,
    model: Option<&'m Model>,
    lanes: [(usize, usize, usize); LANES],
    atoms: [(usize, usize); LANES],
    pairs: SphereLanes,
}

impl<'m> Lanes<'m> {
    /// Adds the contact `(k, e, slot)` of atoms `p`, `q` (centres `xp`, `xq`, radii `rp`, `rq`
    /// as the distance test loaded them) with model `m` (the block's: the caller flushes first
    /// when it differs) as the next lane; whether the block is full.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn push(
        &mut self,
        m: &'m Model,
        b: &Bodies<'_>,
        lane: (usize, usize, usize),
        p: usize,
        q: usize,
        xp: [f64; 3],
        xq: [f64; 3],
        rp: f64,
        rq: f64,
    ) -> bool {
        // `len < LANES` here (a full block is flushed); the mask tells the compiler so.
        let l = self.len % LANES;
        self.pairs.set(
            l,
            &SpherePair {
                xp: v3(xp),
                xq: v3(xq),
                rp,
                rq,
                vp: v3(b.v[p]),
                vq: v3(b.v[q]),
                wp: v3(b.omega[p]),
                wq: v3(b.omega[q]),
                mp: b.mass[p],
                mq: b.mass[q],
            },
        );
        self.lanes[l] = lane;
        self.atoms[l] = (p, q);
        self.model = Some(m);
        self.len += 1;
        self.len == LANES
    }

    /// Steps the waiting contacts: the block kernel on their histories in the store (the
    /// unused lanes repeat the first and are not written), then in lane order each lane's
    /// forces into the accumulators (read in place from `out`) and its bookkeeping, or, for a
    /// lane the block leaves, the one-contact kernel ([`step_contact`]): the order and the
    /// bits of the one-contact loop.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn flush<T: TangentialLaw>(
        &mut self,
        hist: &mut [ContactHistory<T>],
        atoms: &Atoms<'_>,
        acc: &mut Accumulators<'_>,
        slot: &mut [i32],
        counts: &mut ListCounts,
        forces: &mut Option<&mut [PairForce]>,
        dt: f64,
        out: &mut SphereForceLanes,
    ) -> Result<(), ModelError> {
        let n = self.len;
        self.len = 0;
        let Some(m) = self.model else {
            return Ok(());
        };
        for l in n..LANES {
            self.pairs.copy_lane(0, l);
        }
        let idx = std::array::from_fn(|l| self.lanes[if l < n { l } else { 0 }].2);
        let mask = T::sphere_block_lanes(m.constants(), &self.pairs, hist, idx, n, dt, out);
        // `all_finite` of each lane's force and torques, lane by lane.
        let sum3 = |a: &[[f64; LANES]; 3]| -> [f64; LANES] {
            std::array::from_fn(|l| a[0][l] + a[1][l] + a[2][l])
        };
        let (sf, stp, stq) = (sum3(&out.force_p), sum3(&out.torque_p), sum3(&out.torque_q));
        let sum: [f64; LANES] = std::array::from_fn(|l| 0.0 + sf[l] + stp[l] + stq[l]);
        for l in 0..n.min(LANES) {
            let (k, e, s) = self.lanes[l];
            let (p, q) = self.atoms[l];
            if mask >> l & 1 == 0 {
                let f = step_contact(k, m, atoms, acc, p, q, &mut hist[s], dt, true)?;
                finish_contact(&f, &mut slot[e], ids(p, q), k, counts, forces);
                continue;
            }
            let v = |a: &[[f64; LANES]; 3]| Vec3::new(a[0][l], a[1][l], a[2][l]);
            let force_p = v(&out.force_p);
            #[allow(clippy::eq_op)] // `s - s` is 0 or NaN, as in `all_finite`
            if sum[l] - sum[l] != 0.0 {
                return Err(non_finite(k, force_p));
            }
            add_parts(acc, p, q, force_p, v(&out.torque_p), v(&out.torque_q));
            if let Some(o) = forces.as_deref_mut() {
                o[k] = PairForce {
                    p: p as i32,
                    q: q as i32,
                    force_p: [force_p.x, force_p.y, force_p.z],
                };
            }
        }
        Ok(())
    }
}

/// One contact of [`compute_pairs`] / [`compute_list`] (`k`: its index in the step, for the
/// errors): the atoms' checks when `atoms_ok` is false, the kernel on atoms `p` and `q` with
/// model `m` and history `h`, and the force and torques added into the owned atoms of `acc`.
/// Returns the kernel's forces (a dropped contact: `touching == false`, its history reset).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn step_contact<T: TangentialLaw>(
    k: usize,
    m: &Model,
    atoms: &Atoms<'_>,
    acc: &mut Accumulators<'_>,
    p: usize,
    q: usize,
    h: &mut ContactHistory<T>,
    dt: f64,
    atoms_ok: bool,
) -> Result<PairForces, ModelError> {
    let body = |a: usize| PairBody {
        position: v3(atoms.x[a]),
        velocity: v3(atoms.v[a]),
        angular_velocity: v3(atoms.omega[a]),
        surface: Surface::Sphere(atoms.radius[a]),
        mass: atoms.mass[a],
    };
    let (bp, bq) = (body(p), body(q));
    if !atoms_ok {
        check(k, atoms.radius[p], atoms.mass[p])?;
        check(k, atoms.radius[q], atoms.mass[q])?;
        let finite = |b: &PairBody| {
            b.position.is_finite() && b.velocity.is_finite() && b.angular_velocity.is_finite()
        };
        if !(finite(&bp) && finite(&bq)) {
            return Err(ModelError::AtomState { index: k });
        }
    }
    let f = match ContactGeometry::sphere_sphere(
        bp.position,
        atoms.radius[p],
        bq.position,
        atoms.radius[q],
    ) {
        Some(g) => pair_force(m.constants(), &bp, &bq, &g, h, dt),
        None => {
            // Coincident centres: no normal; the contact is dropped (as Model::step).
            *h = ContactHistory::default();
            Default::default()
        }
    };
    add_forces(k, acc, p, q, f.force_p, f.torque_p, f.torque_q)?;
    Ok(f)
}

/// Contact `k`'s force on p and torques on p and q added into the owned atoms of `acc`, after
/// the check that they are finite (an error otherwise, nothing added).
#[inline(always)]
fn add_forces(
    k: usize,
    acc: &mut Accumulators<'_>,
    p: usize,
    q: usize,
    force_p: Vec3,
    torque_p: Vec3,
    torque_q: Vec3,
) -> Result<(), ModelError> {
    if !all_finite(&[force_p, torque_p, torque_q]) {
        return Err(non_finite(k, force_p));
    }
    add_parts(acc, p, q, force_p, torque_p, torque_q);
    Ok(())
}

/// The error of contact `k` whose force on p (`force_p`) or torques are not finite.
#[cold]
fn non_finite(k: usize, force_p: Vec3) -> ModelError {
    ModelError::History {
        index: k,
        source: LawError::OutOfRange {
            name: "contact force (NaN or infinite history)",
            value: force_p.x,
            range: "finite",
        },
    }
}

/// A contact's force on p and torques on p and q added into the owned atoms of `acc`.
#[inline(always)]
fn add_parts(
    acc: &mut Accumulators<'_>,
    p: usize,
    q: usize,
    force_p: Vec3,
    torque_p: Vec3,
    torque_q: Vec3,
) {
    let nlocal = acc.force.len();
    if p < nlocal {
        add(&mut acc.force[p], force_p);
        add(&mut acc.torque[p], torque_p);
    }
    if q < nlocal {
        add(&mut acc.force[q], -force_p);
        add(&mut acc.torque[q], torque_q);
    }
}

/// The atom arrays all of one length, the accumulators of one length and no longer.
fn check_arrays(atoms: &Atoms<'_>, acc: &Accumulators<'_>) -> Result<(), ModelError> {
    let nall = atoms.x.len();
    if [
        atoms.v.len(),
        atoms.omega.len(),
        atoms.radius.len(),
        atoms.mass.len(),
        atoms.kind.len(),
    ]
    .iter()
    .any(|&l| l != nall)
        || acc.force.len() != acc.torque.len()
        || acc.force.len() > nall
    {
        return Err(ModelError::AtomArrays);
    }
    Ok(())
}

/// Whether every atom of the arrays passes the per-contact checks of [`compute_pairs`]: finite
/// position, velocity and angular velocity, radius and mass finite and > 0. Branch-free
/// accumulation over the arrays (no early exit: the common answer is yes).
#[allow(clippy::eq_op)] // `x - x` is the point: 0 or NaN
fn atoms_valid(atoms: &Atoms<'_>) -> bool {
    // `x - x` is 0 for a finite x and NaN otherwise; a sum of them is 0 iff all are finite,
    // whatever the order of the sum: eight sums side by side (one chain of dependent
    // additions was the check's latency, 2 % of the plugin's run), then theirs.
    let all_zero = |v: &[f64]| {
        let mut acc = [0.0f64; 8];
        let chunks = v.chunks_exact(8);
        let tail = chunks.remainder();
        for c in chunks {
            for (s, &x) in acc.iter_mut().zip(c) {
                *s += x - x;
            }
        }
        for (s, &x) in acc.iter_mut().zip(tail) {
            *s += x - x;
        }
        acc.iter().sum::<f64>() == 0.0
    };
    let positive = |v: &[f64]| v.iter().fold(true, |ok, &a| ok & (a > 0.0)) && all_zero(v);
    all_zero(atoms.x.as_flattened())
        && all_zero(atoms.v.as_flattened())
        && all_zero(atoms.omega.as_flattened())
        && positive(atoms.radius)
        && positive(atoms.mass)
}

/// Whether every component of `v` is finite and the components' sum does not overflow (every
/// component below ~1e307 in size: a force in N or a torque in N m that is not, is no
/// contact's), in the floating-point domain with one sum: `s - s` is 0 for a finite sum `s`
/// and NaN otherwise, and the sum is NaN or infinite when a component is (IEEE 754: `inf +
/// x`, `NaN + x`). LLVM lowers `is_finite` to integer tests of the bit pattern, a dozen
/// operations per vector; this is one addition per component.
#[inline(always)]
#[allow(clippy::eq_op)] // `s - s` is the point: 0 or NaN
fn all_finite(v: &[Vec3]) -> bool {
    let s = v.iter().fold(0.0, |acc, c| acc + (c.x + c.y + c.z));
    s - s == 0.0
}

#[inline(always)]
fn v3(a: [f64; 3]) -> Vec3 {
    Vec3::new(a[0], a[1], a[2])
}

#[inline(always)]
fn add(acc: &mut [f64; 3], f: Vec3) {
    acc[0] += f.x;
    acc[1] += f.y;
    acc[2] += f.z;
}

/// A sphere's radius and mass must be finite and > 0 (contact `k`).
#[inline(always)]
fn check(k: usize, radius: f64, mass: f64) -> Result<(), ModelError> {
    if radius.is_finite() && radius > 0.0 && mass.is_finite() && mass > 0.0 {
        Ok(())
    } else {
        Err(ModelError::Body {
            index: k,
            radius,
            mass,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_finite_flags_each_non_finite_component() {
        let ok = [
            Vec3::new(1e3, -2.0, 0.0),
            Vec3::new(-1e300, 1e300, 5.0),
            Vec3::ZERO,
        ];
        assert!(all_finite(&ok));
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            for k in 0..9 {
                let mut v = ok;
                let c = &mut v[k / 3];
                match k % 3 {
                    0 => c.x = bad,
                    1 => c.y = bad,
                    _ => c.z = bad,
                }
                assert!(!all_finite(&v), "{bad} at component {k} not flagged");
            }
        }
        // Opposite infinities sum to NaN: still flagged.
        assert!(!all_finite(&[Vec3::new(
            f64::INFINITY,
            f64::NEG_INFINITY,
            0.0
        )]));
    }
}
