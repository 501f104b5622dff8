//! What the rigid hook did in a step.

use creep_law::rigid::{CoulombReason, RigidCreep};
use rapier3d::prelude::*;

use crate::warning::CreepWarning;

/// What the plugin did in the last step.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct StepCounts {
    /// Contacts with a collider the registry does not know: left to Coulomb (each such
    /// collider touching a registered one is also named once in [`StepCounts::warnings`]).
    pub coulomb_unregistered: usize,
    /// Contacts with a shape the rigid regime does not model (not a ball, cuboid, half-space,
    /// triangle mesh, heightfield or convex polyhedron, nor a cylinder on one of the flat
    /// shapes (a wheel): capsules, cones, compounds, ...): Coulomb.
    pub coulomb_unsupported: usize,
    /// Contacts between two flat shapes (no ball on either side; Hertz's contact needs a
    /// curved side): Coulomb.
    pub coulomb_no_sphere: usize,
    /// Contacts whose pair asked for Coulomb.
    pub coulomb_requested: usize,
    /// `Auto` contacts whose creep bound was below the tolerance: Coulomb.
    pub coulomb_auto: usize,
    /// Contacts that took the creep-friction path.
    pub creep: usize,
    /// Contacts with a contact-torque rolling model.
    pub rolling_torque: usize,
    /// Ball contacts, among the above, of pairs whose contacts Rapier recycled this step
    /// (kept from the pair's last full update) and whose slip target the hook rewrote on the
    /// kept solver contacts. Nonzero only with the feature `rapier-patched`, whose engine
    /// recycles hooked pairs that opt in (`ActiveHooks::RECYCLE_MODIFIED_SOLVER_CONTACTS`).
    pub recycled: usize,
    /// Power dissipated by creep, `sum Q . v_disp` \[W\] (>= 0).
    pub creep_power: f64,
    /// Largest loop gain `g` of the Q -> slip -> Q feedback this step (see the module docs).
    pub max_loop_gain: f64,
    /// Registered colliders whose hook was on for this step, among those the step visited (the
    /// colliders of awake bodies; every registered collider on a full visit; set by
    /// [`crate::CreepPipeline`]).
    pub hooks_on: usize,
    /// Contacts of pairs whose two colliders are below the activation speed, in the one step
    /// before their hooks go off: left as plain Rapier contacts (their targets cleared, so that
    /// Rapier's contact recycling does not keep a stale creep target).
    pub quiet: usize,
    /// What the plugin reports once, first seen in this step ([`crate::CreepWarning`]: a fast
    /// ball or wheel with substeps, an unregistered collider touching a registered one, no
    /// registered collider, a quarantined body). Print them with `Display`.
    pub warnings: Vec<CreepWarning>,
    /// Bodies Rapier quarantined in this step (their state went non-finite; rapier3d's
    /// `PhysicsPipeline::quarantine`): disabled. Filled by [`crate::CreepPipeline::step`]; a
    /// host that runs Rapier's step itself passes Rapier's report to
    /// [`crate::CreepPipeline::report_quarantine`].
    pub quarantined_bodies: Vec<RigidBodyHandle>,
    /// Colliders Rapier quarantined in this step (non-finite geometry): disabled.
    pub quarantined_colliders: Vec<ColliderHandle>,
}

impl StepCounts {
    /// Adds another part's counts (the shards' of one step): sums, and the larger loop gain.
    pub(crate) fn add(&mut self, o: &StepCounts) {
        self.coulomb_unregistered += o.coulomb_unregistered;
        self.coulomb_unsupported += o.coulomb_unsupported;
        self.coulomb_no_sphere += o.coulomb_no_sphere;
        self.coulomb_requested += o.coulomb_requested;
        self.coulomb_auto += o.coulomb_auto;
        self.creep += o.creep;
        self.rolling_torque += o.rolling_torque;
        self.recycled += o.recycled;
        self.creep_power += o.creep_power;
        self.max_loop_gain = self.max_loop_gain.max(o.max_loop_gain);
        self.hooks_on += o.hooks_on;
        self.quiet += o.quiet;
    }

    /// Books the kernel's answer for `contacts` solver contacts (a ball's one, a wheel's
    /// manifold): creep with its power and loop gain, or Coulomb for its reason.
    pub(crate) fn book(&mut self, out: &RigidCreep, contacts: usize) {
        match out.coulomb {
            None => {
                self.max_loop_gain = self.max_loop_gain.max(out.loop_gain);
                self.creep += contacts;
                self.creep_power += out.power;
            }
            Some(CoulombReason::OutsideTable) => self.coulomb_unsupported += contacts,
            Some(_) => self.coulomb_auto += contacts,
        }
    }
}
