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

impl ContactKey {
    /// A total order of keys (collider indices and generations, then features): the order in
    /// which the hooks apply the contacts' moments when several threads filled the store.
    pub fn order(&self) -> (u32, u32, u32, u32, u32, u32) {
        let (i1, g1) = self.collider1.into_raw_parts();
        let (i2, g2) = self.collider2.into_raw_parts();
        (i1, g1, i2, g2, self.feature1, self.feature2)
    }
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
    /// Twisting moment on body 2 about the normal computed this step by the 3-D creep law
    /// [N m] (spin creep, `creep_law::rigid`; `-spin_torque` on body 1).
    pub spin_torque: Vec3,
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

/// The summed load of coincident contacts: a ball on an edge or vertex shared by triangles
/// of a mesh (or cells of a heightfield) gets one contact from each, at one point along one
/// normal, and the solver splits the load between them arbitrarily. The rigid hook solves
/// such a group as one contact, from the group's load: every member gets the same slip
/// target and books its share of the group's power and moment (module `rigid::ball`).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct CoincidentLoad {
    /// The members' normal impulses of the last solve, summed \[N s\].
    pub(crate) normal_impulse: f64,
    /// Their friction impulses on body 1, summed \[N s\] (world).
    pub(crate) tangent_impulse: Vec3,
    /// Their last slip targets, weighted by their shares of the normal impulse \[m/s\].
    pub(crate) target: Vec3,
}

impl ContactRecord {
    /// Keeps the rigid kernel's answer for this step: the force and target (the next step's
    /// `last_target`) and the twisting moment to apply after the step (zero when the contact
    /// was left to Coulomb).
    pub(crate) fn set_creep(&mut self, out: &creep_law::rigid::RigidCreep) {
        self.q_used = out.force;
        self.target = out.target;
        self.spin_torque = out.moment;
    }
}

/// A fast, non-cryptographic hasher for [`ContactKey`]s (the multiply-rotate scheme of
/// rustc's FxHash): the keys are small integers, so SipHash's flood resistance buys nothing
/// and costs a sizable part of the hook's time.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct KeyHasher(u64);

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
pub(crate) struct ContactStore {
    pub(crate) records: KeyMap<ContactRecord>,
    pub(crate) generation: u64,
    /// The ball contacts of this step whose partner is a triangle mesh or heightfield (their
    /// contacts may coincide) and their points \[m\] (world), in the order the hook saw them:
    /// grouped before the next step (`CreepHooks::gather_coincident`).
    pub(crate) on_meshes: Vec<(ContactKey, Vec3)>,
    /// The loads of the groups found in the last solve, by member (empty without meshes).
    pub(crate) coincident: KeyMap<CoincidentLoad>,
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
    #[cfg(any(test, feature = "parallel"))]
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
    #[cfg(test)]
    /// Whether there are no records.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }
    /// Iterates over the live records.
    pub fn iter(&self) -> impl Iterator<Item = (&ContactKey, &ContactRecord)> {
        self.records.iter()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_records_stay_bounded_over_a_million_create_destroy_cycles() {
        // Each cycle a new contact appears and the previous one ends: the sweep keeps memory flat.
        let mut store = ContactStore::default();
        let h = |i: u32| ColliderHandle::from_raw_parts(i, 0);
        for i in 0..1_000_000u32 {
            store.begin_step();
            store.touch(ContactKey {
                collider1: h(i),
                collider2: h(i + 1),
                feature1: i,
                feature2: 0,
            });
            store.sweep();
            assert!(store.len() <= 1);
        }
        store.begin_step();
        store.sweep();
        assert!(store.is_empty());
    }
}
