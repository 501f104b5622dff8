//! Per-contact state of the rigid regime, kept across steps: records keyed by a stable contact
//! identity, and the fast hasher of the plugin's maps.

use std::collections::HashMap;

use creep_law::Vec3;
use creep_law::rolling_torque::RollingState;
use rapier3d::prelude::{ColliderHandle, RigidBodyHandle};

/// Stable identity of one contact point across steps: the collider pair and the two shape
/// features (Rapier may re-order a manifold's points; the features do not change).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ContactKey {
    /// Collider 1 of the pair.
    pub collider1: ColliderHandle,
    /// Collider 2 of the pair.
    pub collider2: ColliderHandle,
    /// Feature of collider 1.
    pub feature1: u32,
    /// Feature of collider 2.
    pub feature2: u32,
}

/// Per-contact state that persists across steps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactRecord {
    /// The relaxed friction force used for the slip target, world frame, on body 1 \[N\].
    pub q_used: Vec3,
    /// Contact-torque rolling state (EPSD spring).
    pub rolling: RollingState,
    /// Torque on body 2 computed this step by the rolling model [N m] (`-torque` on body 1).
    pub torque: Vec3,
    /// Bodies of the contact, for applying the torque.
    pub bodies: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    /// Normal force of the previous step, total normal impulse / dt \[N\].
    pub p: f64,
    /// Creep slip target set in the last step [m/s] (world frame).
    pub target: Vec3,
    /// Contact normal of the last step (the basis of its friction impulse).
    pub normal: Vec3,
    /// Step in which the record was last seen.
    pub(crate) generation: u64,
}

/// A fast, non-cryptographic hasher for [`ContactKey`]s (the multiply-rotate scheme of
/// rustc's FxHash): the keys are small integers, so SipHash's flood resistance buys nothing
/// and costs a sizable part of the hook's time.
#[derive(Debug, Clone, Copy, Default)]
pub struct KeyHasher(u64);

impl std::hash::Hasher for KeyHasher {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut buf = [0u8; 8];
            buf[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(buf));
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
}

/// A hash map with [`KeyHasher`] (handles and contact keys are small integers: SipHash's
/// protection against adversarial keys is not needed, its cost is).
pub(crate) type FastMap<K, V> = HashMap<K, V, std::hash::BuildHasherDefault<KeyHasher>>;

type KeyMap<V> = FastMap<ContactKey, V>;

/// Contact records keyed by [`ContactKey`], swept of the contacts not seen in a step.
#[derive(Debug, Clone, Default)]
pub struct ContactStore {
    pub(crate) records: KeyMap<ContactRecord>,
    pub(crate) generation: u64,
}

impl ContactStore {
    /// The record of a contact, created if new, marked as seen in this step.
    pub fn touch(&mut self, key: ContactKey) -> &mut ContactRecord {
        let generation = self.generation;
        let r = self.records.entry(key).or_default();
        r.generation = generation;
        r
    }
    /// Starts a new step.
    pub fn begin_step(&mut self) {
        self.generation += 1;
    }
    /// Drops the records not seen in the current step (pair separated, collider or body
    /// removed, island asleep). Returns how many were dropped.
    pub fn sweep(&mut self) -> usize {
        let before = self.records.len();
        let g = self.generation;
        self.records.retain(|_, r| r.generation == g);
        before - self.records.len()
    }
    /// Number of live records.
    pub fn len(&self) -> usize {
        self.records.len()
    }
    /// Whether there are no records.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }
    /// Iterates over the live records.
    pub fn iter(&self) -> impl Iterator<Item = (&ContactKey, &ContactRecord)> {
        self.records.iter()
    }
}

/// Solver contacts of one manifold (rapier3d 0.36, 3-D: `MAX_MANIFOLD_POINTS`).
pub(crate) const MAX_POINTS: usize = 4;

/// Per-pair constants of a manifold, computed once per pair and kept while the inputs they come
/// from (the two materials, the two surfaces, the combined friction) are unchanged.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairCache {
    pub(crate) key: (
        creep_law::Material,
        creep_law::Material,
        Surface,
        Surface,
        f64,
    ),
    pub(crate) pair: creep_law::PairMaterial,
    pub(crate) law: creep_law::steady_law::SteadyLaw,
}

/// The rigid regime's state of one contact manifold: its collider pair, the records of its
/// solver contacts (with their features, the contacts' identity across steps), the per-pair
/// constants, and what it added to the step's counts.
#[derive(Debug, Clone, Default)]
pub(crate) struct ManifoldSlot {
    /// The collider pair that owns the slot (`None`: free).
    pub(crate) owner: Option<(ColliderHandle, ColliderHandle)>,
    /// Step in which the slot was last touched.
    pub(crate) seen: u64,
    /// Number of live records.
    pub(crate) n: usize,
    /// Features and records of the live contacts.
    pub(crate) contacts: [(u32, u32, ContactRecord); MAX_POINTS],
    /// Per-pair constants.
    pub(crate) cache: Option<PairCache>,
    /// Creep power of this manifold in the step it was last touched \[W\].
    pub(crate) creep_power: f64,
    /// Largest loop gain of this manifold in that step.
    pub(crate) max_loop_gain: f64,
}

use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use creep_law::Surface;

/// Manifold records addressed by the manifold's `user_data` (slot index + 1), without hashing
/// and without a global lock: each slot has its own `Mutex`, which only the thread processing
/// that manifold takes (Rapier processes a pair once per step), so it is never contended. A
/// manifold the hook has not seen takes a free slot (an atomic cursor into the free list built
/// at the end of the previous step; past its end, an overflow list behind a lock, merged at
/// the end of the step). A slot is checked against its collider pair and the step that last
/// touched it, so a stale `user_data` never reads another manifold's records.
#[derive(Debug, Default)]
pub(crate) struct ManifoldSlab {
    pub(crate) slots: Vec<Mutex<ManifoldSlot>>,
    free: Vec<u32>,
    cursor: AtomicUsize,
    overflow: Mutex<Vec<ManifoldSlot>>,
    pub(crate) generation: u64,
}

/// Free slots kept ready at the start of a step, at least.
const MIN_FREE: usize = 256;

impl ManifoldSlab {
    /// Starts a step.
    pub(crate) fn begin_step(&mut self) {
        self.generation += 1;
        *self.cursor.get_mut() = 0;
    }

    /// The slot of a manifold with `user_data`, validated or newly taken; `f` runs on it with
    /// the value `user_data` must hold afterwards.
    pub(crate) fn with_slot<R>(
        &self,
        user_data: u32,
        owner: (ColliderHandle, ColliderHandle),
        f: impl FnOnce(&mut ManifoldSlot, bool) -> R,
    ) -> (R, u32) {
        let g = self.generation;
        if let Some(m) = (user_data as usize)
            .checked_sub(1)
            .and_then(|i| self.slots.get(i))
        {
            let mut s = m.lock().unwrap_or_else(|e| e.into_inner());
            if s.owner == Some(owner) && s.seen != g {
                s.seen = g;
                return (f(&mut s, false), user_data);
            }
        }
        let k = self.cursor.fetch_add(1, Ordering::Relaxed);
        if let Some(&i) = self.free.get(k) {
            let mut s = self.slots[i as usize]
                .lock()
                .unwrap_or_else(|e| e.into_inner());
            *s = ManifoldSlot {
                owner: Some(owner),
                seen: g,
                ..ManifoldSlot::default()
            };
            return (f(&mut s, true), i + 1);
        }
        let mut over = self.overflow.lock().unwrap_or_else(|e| e.into_inner());
        over.push(ManifoldSlot {
            owner: Some(owner),
            seen: g,
            ..ManifoldSlot::default()
        });
        let i = self.slots.len() + over.len() - 1;
        let last = over.len() - 1;
        (f(&mut over[last], true), i as u32 + 1)
    }

    /// Ends a step: merges the overflow, frees the slots not touched in the step (their
    /// contacts ended, or their pair was not processed with the hook), rebuilds the free list
    /// and keeps at least as many free slots as the step took plus a margin.
    pub(crate) fn end_step(&mut self) {
        let taken = *self.cursor.get_mut();
        let over = std::mem::take(self.overflow.get_mut().unwrap_or_else(|e| e.into_inner()));
        self.slots.extend(over.into_iter().map(Mutex::new));
        let g = self.generation;
        self.free.clear();
        for (i, m) in self.slots.iter_mut().enumerate() {
            let s = m.get_mut().unwrap_or_else(|e| e.into_inner());
            if s.owner.is_some() && s.seen != g {
                *s = ManifoldSlot::default();
            }
            if s.owner.is_none() {
                self.free.push(i as u32);
            }
        }
        let want = (2 * taken).max(MIN_FREE).max(self.slots.len() / 8);
        while self.free.len() < want {
            self.free.push(self.slots.len() as u32);
            self.slots.push(Mutex::new(ManifoldSlot::default()));
        }
        *self.cursor.get_mut() = 0;
    }

    /// The live slots (after `end_step`, those of the last step).
    pub(crate) fn live(&self) -> impl Iterator<Item = std::sync::MutexGuard<'_, ManifoldSlot>> {
        self.slots
            .iter()
            .map(|m| m.lock().unwrap_or_else(|e| e.into_inner()))
            .filter(|s| s.owner.is_some())
    }

    /// Mutable access to the live slots.
    pub(crate) fn live_mut(&mut self) -> impl Iterator<Item = &mut ManifoldSlot> {
        self.slots
            .iter_mut()
            .map(|m| m.get_mut().unwrap_or_else(|e| e.into_inner()))
            .filter(|s| s.owner.is_some())
    }
}
