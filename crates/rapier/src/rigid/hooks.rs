//! The rigid hooks' state and their step: preparation (parameters, colliders visited, hook
//! activation, spin cap), the moments after the step, the counts and records.

use std::sync::Mutex;
use std::sync::atomic::AtomicUsize;

use creep_law::Vec3;
use creep_law::rigid::{LawCache, RigidPairCache};
use rapier3d::prelude::*;

use super::counts::StepCounts;
use super::crowns::Crowns;
use super::settings::{CreepSettings, check_parameters};
use crate::error::PluginError;
use crate::registry::{CreepMaterial, Fidelity, MaterialRegistry, Regime, RollingResistance};
use crate::rolling::apply_rolling_impulse;
use crate::store::{ContactKey, ContactRecord, ContactStore};
use crate::warning::{CreepWarning, ROTATION_GAP_TURN, WarnedSet};

/// One shard of the hooks' mutable state: the records and counts of the collider pairs that
/// hash to it, and its own copies of the caches (`creep_law::rigid::RigidPairCache`).
#[derive(Default)]
pub(super) struct Shard {
    pub(super) store: ContactStore,
    pub(super) counts: StepCounts,
    /// Unregistered colliders seen touching a registered one (and the registered one), not
    /// yet reported by this shard.
    pub(super) unregistered: Vec<(ColliderHandle, ColliderHandle)>,
    /// The unregistered colliders this shard has reported.
    pub(super) unregistered_seen: WarnedSet,
    /// A collider of a pair the hook saw with a NaN, infinite or negative friction.
    pub(super) bad_friction: Option<(ColliderHandle, f32)>,
    /// The 3-D creep laws by contact shape (the wheel path's).
    pub(super) laws: LawCache,
    /// The wheels' axle tracks and elliptic Hertz cache (module `crowns`).
    pub(super) crowns: Crowns,
    /// The per-pair constants.
    pub(super) pairs: RigidPairCache,
}

/// Number of shards of the hooks' state. With feature `parallel` Rapier calls the hook for
/// different pairs on several threads at once; each call locks only the shard of its collider
/// pair, never a global lock, so calls on different shards never wait for each other (two
/// given calls meet on one shard with probability 1/64). Without it there is one thread and one
/// shard: one uncontended lock per manifold, and the records in one map.
const SHARDS: usize = if cfg!(feature = "parallel") { 64 } else { 1 };

/// The shard of a collider pair (a multiplicative hash of the two indices; the pair's order
/// is Rapier's, fixed for the pair's lifetime).
#[cfg(feature = "parallel")]
#[inline]
pub(super) fn shard_of(c1: ColliderHandle, c2: ColliderHandle) -> usize {
    let (i1, i2) = (c1.into_raw_parts().0, c2.into_raw_parts().0);
    let h = ((u64::from(i1) << 32) | u64::from(i2)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    // The top 6 bits: one of the 64 shards.
    (h >> 58) as usize
}

/// The shard of a collider pair: the only one without feature `parallel`.
#[cfg(not(feature = "parallel"))]
#[inline]
pub(super) fn shard_of(_: ColliderHandle, _: ColliderHandle) -> usize {
    0
}

/// The mark of a collider in its clearing step (see [`CreepHooks::update_activation`]): kept on
/// the collider itself, not in the hooks, so that a copied world (`clone_physics` with fresh
/// hooks) steps exactly as the original. `FILTER_INTERSECTION_PAIR` is used because it does
/// nothing for a non-sensor pair and the hooks keep Rapier's default for sensors.
const CLEARING_MARK: ActiveHooks = ActiveHooks::FILTER_INTERSECTION_PAIR;

/// The flag by which a collider's pairs keep Rapier's contact recycling with the hook on
/// (feature `rapier-patched`: `ActiveHooks::RECYCLE_MODIFIED_SOLVER_CONTACTS`, whose engine then
/// calls `modify_recycled_solver_contacts` on recycled steps); none without the feature.
#[cfg(feature = "rapier-patched")]
const RECYCLE: ActiveHooks = ActiveHooks::RECYCLE_MODIFIED_SOLVER_CONTACTS;
/// (Without the feature `rapier-patched`, crates.io's Rapier has no such flag.)
#[cfg(not(feature = "rapier-patched"))]
const RECYCLE: ActiveHooks = ActiveHooks::empty();

/// The flag by which a ball collider's manifolds without solver contacts skip the hook on full
/// updates (feature `rapier-patched`: `ActiveHooks::SKIP_EMPTY_SOLVER_CONTACTS`); none without
/// the feature. The hook has nothing to do on such a manifold unless a wheel (a cylinder) is on
/// it, and a ball's pair never takes the wheel path, whose other side is flat (module
/// `dispatch`). The engine still calls the hook there if the other collider's hook is on
/// without the flag.
#[cfg(feature = "rapier-patched")]
const SKIP_EMPTY: ActiveHooks = ActiveHooks::SKIP_EMPTY_SOLVER_CONTACTS;
/// (Without the feature `rapier-patched`, crates.io's Rapier has no such flag.)
#[cfg(not(feature = "rapier-patched"))]
const SKIP_EMPTY: ActiveHooks = ActiveHooks::empty();

/// The flags a registered collider whose hook is on may add to `MODIFY_SOLVER_CONTACTS`:
/// [`RECYCLE`] ([`recycle_opt_in`]) and [`SKIP_EMPTY`] (a ball).
const OPT_INS: ActiveHooks = RECYCLE.union(SKIP_EMPTY);

/// [`SKIP_EMPTY`] for a ball collider, else nothing.
fn skip_empty_opt_in(co: &Collider) -> ActiveHooks {
    if !SKIP_EMPTY.is_empty() && co.shape().shape_type() == rapier3d::parry::shape::ShapeType::Ball
    {
        SKIP_EMPTY
    } else {
        ActiveHooks::empty()
    }
}

/// Speed \[m/s\] (`|v| + |w| r`, as for [`CreepSettings::activation_speed`]) below which an
/// active collider opts in to recycling ([`recycle_opt_in`]). A recycled contact keeps the
/// lever arms of its pair's last full update, and Rapier's friction position bias reads the
/// bodies' motion since then as a tangential offset: on a rolling contact that is a spurious
/// slip (the friction drive's Coulomb run, 0.05 m steel spheres turning at 10 rad/s, 1/240 s:
/// 2.9e-4 recycled against 6e-7 fully updated each step, above the creepage of steel at low
/// load, 1e-4). Below this speed a pair drifts at most 1.7 mm in a 1/60 s step.
const RECYCLE_SPEED: f32 = 0.1;

/// The recycling opt-in of a registered collider whose hook is on ([`RECYCLE`]): a collider
/// of `Auto` or `Creep` fidelity whose body moves slower than [`RECYCLE_SPEED`], and not a
/// wheel (a cylinder), whose rotation-gap correction (`dist`, crate module `gap`) must follow
/// each step's spin and cannot be rewritten on a recycled contact. A ball's recycled contacts
/// get this step's slip target (the hook's recycled path); on the patched engine no other
/// shape's contacts carry anything that changes from step to step. (A `Coulomb` collider's
/// contacts get nothing from the hook: it keeps Rapier's full updates while its hook is on.)
fn recycle_opt_in(co: &Collider, mat: &CreepMaterial, bodies: &RigidBodySet) -> ActiveHooks {
    if RECYCLE.is_empty()
        || !matches!(mat.regime, Regime::Rigid(Fidelity::Auto | Fidelity::Creep))
        || matches!(
            crate::shape::supported_shape(co),
            Some(crate::SupportedShape::Wheel { .. })
        )
    {
        return ActiveHooks::empty();
    }
    let slow = co.parent().and_then(|h| bodies.get(h)).is_none_or(|rb| {
        let r = co.shape().compute_local_bounding_sphere().radius;
        rb.linvel().length() + rb.angvel().length() * r < RECYCLE_SPEED
    });
    if slow { RECYCLE } else { ActiveHooks::empty() }
}

/// Whether a collider's hook is in its clearing step or off (below the activation speed); a
/// collider no longer in the set counts as quiet.
pub(super) fn quiet_collider(co: Option<&Collider>) -> bool {
    co.is_none_or(|co| {
        let f = co.active_hooks();
        !f.contains(ActiveHooks::MODIFY_SOLVER_CONTACTS) || f.contains(CLEARING_MARK)
    })
}

/// The creep-friction physics hooks (rigid regime). Rapier calls them inside a step that a
/// [`crate::CreepPipeline`] prepared (through [`crate::CreepPipeline::step`],
/// [`crate::CreepWorld::step`] or the host pair); given to Rapier otherwise they leave every
/// contact to Coulomb and the next step returns [`PluginError::HookOutsideStep`].
pub struct CreepHooks {
    pub(super) registry: MaterialRegistry,
    pub(super) settings: CreepSettings,
    pub(super) dt: f64,
    pub(super) substeps: usize,
    /// Rapier's prediction distance of the step \[m\] (`IntegrationParameters::prediction_distance`;
    /// the wheel path keeps a patch contact by Rapier's own rule, module `wheel`).
    pub(super) prediction: f64,
    /// Whether the step owner has prepared the current step (dt, substeps, counts, store).
    pub(super) prepared: bool,
    /// Contacts the hook saw while no step was prepared (left to Rapier), reported as
    /// [`PluginError::HookOutsideStep`] by the next step.
    pub(super) outside: AtomicUsize,
    /// The mutable state, sharded by collider pair ([`SHARDS`]).
    pub(super) shards: Box<[Mutex<Shard>]>,
    /// Registered colliders whose hook is on this step (`update_activation`).
    hooks_on: usize,
    /// Scratch list of the records with a moment to apply (`end_step`, feature `parallel`:
    /// applied in key order so that the bodies' sums do not depend on the threads).
    #[cfg(feature = "parallel")]
    moments: Vec<(ContactKey, ContactRecord)>,
    /// The warnings of this step (`StepCounts::warnings`).
    warnings: Vec<CreepWarning>,
    /// Colliders warned about as unregistered.
    warned_unregistered: WarnedSet,
    /// Whether the rotation-gap warning was given.
    warned_gap: bool,
    /// Whether the nothing-registered warning was given.
    warned_nothing: bool,
    /// What Rapier quarantined in this step.
    quarantined: (Vec<RigidBodyHandle>, Vec<ColliderHandle>),
    /// Rapier's linear speed cap of the step \[m/s\] (`max_linear_velocity`).
    max_linvel: f64,
    /// Steps until the next scan of the contact pairs for unregistered colliders.
    scan_countdown: u32,
    /// The registered colliders the step's preparation visits ([`CreepHooks::select_colliders`]).
    selected: Vec<ColliderHandle>,
    /// Steps until the next preparation that visits every registered collider.
    full_countdown: u32,
    /// Whether the registry may have changed since the last full visit (`registry_mut`).
    registry_dirty: bool,
    /// Colliders in the world at the last full visit.
    last_collider_count: usize,
}

/// Steps between two preparations that visit every registered collider (the others visit the
/// colliders of awake bodies only, [`CreepHooks::select_colliders`]): what only such a visit
/// finds is a registered collider of a fixed body whose friction was made invalid since, which
/// the hook also refuses as soon as a moving registered body touches it.
const FULL_PASS_STEPS: u32 = 600;

/// Steps between two scans of the narrow phase's contact pairs for unregistered colliders
/// touching registered ones ([`CreepHooks::scan_unregistered`]; a pair whose hook runs is seen
/// at once).
const UNREGISTERED_SCAN_STEPS: u32 = 32;

impl CreepHooks {
    /// Hooks with the given materials and settings.
    pub fn new(registry: MaterialRegistry, settings: CreepSettings) -> Result<Self, PluginError> {
        settings.validate()?;
        Ok(Self {
            registry,
            settings,
            dt: 1.0 / 60.0,
            substeps: 4,
            prediction: 0.002,
            prepared: false,
            outside: AtomicUsize::new(0),
            shards: (0..SHARDS).map(|_| Mutex::new(Shard::default())).collect(),
            hooks_on: 0,
            #[cfg(feature = "parallel")]
            moments: Vec::new(),
            warnings: Vec::new(),
            warned_unregistered: WarnedSet::default(),
            warned_gap: false,
            warned_nothing: false,
            quarantined: (Vec::new(), Vec::new()),
            max_linvel: f64::MAX,
            scan_countdown: 0,
            selected: Vec::new(),
            full_countdown: 0,
            registry_dirty: true,
            last_collider_count: 0,
        })
    }

    /// The material registry.
    pub fn registry(&self) -> &MaterialRegistry {
        &self.registry
    }
    /// The material registry, to add or remove colliders.
    pub fn registry_mut(&mut self) -> &mut MaterialRegistry {
        self.registry_dirty = true;
        &mut self.registry
    }

    /// Chooses the registered colliders the step's preparation visits (friction check, spin
    /// cap, hook activation), so that a settled world whose bodies sleep costs no more than in
    /// plain Rapier: the colliders of the bodies `islands` has awake (a sleeping body's flags
    /// stay as they were when it fell asleep, when it was below the activation speed), and
    /// every registered collider (after forgetting those Rapier no longer has) on the first
    /// step, after any change through [`CreepHooks::registry_mut`], when the number of
    /// colliders changed, every [`FULL_PASS_STEPS`] steps, or without `islands`.
    pub(crate) fn select_colliders(
        &mut self,
        islands: Option<&IslandManager>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let mut selected = std::mem::take(&mut self.selected);
        selected.clear();
        let full = match islands {
            None => true,
            Some(_) => {
                self.registry_dirty
                    || self.full_countdown == 0
                    || colliders.len() != self.last_collider_count
            }
        };
        match islands {
            Some(islands) if !full => {
                self.full_countdown -= 1;
                for b in islands.active_bodies() {
                    if let Some(rb) = bodies.get(b) {
                        selected.extend(
                            rb.colliders()
                                .iter()
                                .filter(|&&c| self.registry.get(c).is_some()),
                        );
                    }
                }
            }
            _ => {
                self.full_countdown = FULL_PASS_STEPS - 1;
                self.registry_dirty = false;
                self.last_collider_count = colliders.len();
                self.registry.retain(|handle, _| colliders.contains(handle));
                selected.extend(self.registry.iter().map(|(h, _)| *h));
            }
        }
        self.selected = selected;
    }

    /// The registered colliders selected for this step ([`CreepHooks::select_colliders`]).
    pub(crate) fn selected(&self) -> &[ColliderHandle] {
        &self.selected
    }
    /// The settings.
    pub fn settings(&self) -> &CreepSettings {
        &self.settings
    }

    /// Gives a registered cylinder collider (a wheel) a crown radius `crown` \[m\] (finite
    /// and positive), or none (`None`: a line contact, Carter's law): sets its material's
    /// [`crate::CreepMaterial::crown`] (as [`crate::CreepMaterial::with_crown`] does before
    /// registration). A crowned wheel's contact is Hertz's ellipse with the curvature sums
    /// `1/R` and `1/crown` (crate module `wheel`). A bad radius is [`PluginError::Setting`], an
    /// unregistered collider [`PluginError::NotRegistered`].
    pub fn set_wheel_crown(
        &mut self,
        collider: ColliderHandle,
        crown: Option<f64>,
    ) -> Result<(), PluginError> {
        let Some(m) = self.registry.get_mut(collider) else {
            return Err(PluginError::NotRegistered {
                collider: crate::registry::handle_name(collider),
            });
        };
        let candidate = CreepMaterial { crown, ..*m };
        candidate.validate()?;
        *m = candidate;
        Ok(())
    }

    /// Prepares a step with its parameters (checks them). Called by [`crate::CreepPipeline`]
    /// only: a step the hooks see without it is [`PluginError::HookOutsideStep`].
    pub(crate) fn begin_step(&mut self, params: &IntegrationParameters) -> Result<(), PluginError> {
        let outside = std::mem::take(self.outside.get_mut());
        if outside > 0 {
            return Err(PluginError::HookOutsideStep { contacts: outside });
        }
        if self.prepared {
            return Err(PluginError::StepAlreadyPrepared);
        }
        check_parameters(params)?;
        self.prepared = true;
        self.dt = f64::from(params.dt);
        self.substeps = params.num_solver_iterations.max(1);
        self.prediction = f64::from(params.prediction_distance());
        self.max_linvel = f64::from(params.max_linear_velocity());
        self.warnings.clear();
        self.quarantined.0.clear();
        self.quarantined.1.clear();
        for shard in self.shards.iter_mut() {
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            shard.store.begin_step();
            shard.counts = StepCounts::default();
        }
        self.hooks_on = 0;
        Ok(())
    }

    /// Before each step (after `begin_step`), with the world's bodies and
    /// colliders: switches `ActiveHooks::MODIFY_SOLVER_CONTACTS` on for the registered colliders
    /// whose body moves faster than [`CreepSettings::activation_speed`] (always for `Creep`
    /// colliders) and off for the others, so that quiet contacts keep Rapier's contact recycling.
    /// A collider that becomes quiet keeps its flag for one clearing step ([`CLEARING_MARK`]): a
    /// recycled pair keeps the solver contacts of its last full update, `tangent_velocity` and
    /// `dist` included, so switching the flag off right away would leave the last creep target
    /// and gap correction in force for as long as Rapier recycles the pair.
    /// Returns how many are on. Unregistered colliders are left as they are.
    pub(crate) fn update_activation(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
    ) -> usize {
        let v_act = self.settings.activation_speed;
        let mut on_count = 0;
        if self.registry.is_empty() && !colliders.is_empty() && !self.warned_nothing {
            self.warned_nothing = true;
            self.warnings.push(CreepWarning::NothingRegistered {
                colliders: colliders.len(),
            });
        }
        let check_gap = self.substeps > 1 && !self.warned_gap;
        for &handle in &self.selected {
            let Some(mat) = self.registry.get(handle) else {
                continue;
            };
            // Read first: `ColliderSet::get_mut` marks a collider as modified, which makes Rapier
            // re-process it (a large cost if done for every collider every step).
            let Some(co) = colliders.get(handle) else {
                continue;
            };
            if check_gap && !self.warned_gap {
                // With substeps, a ball or wheel turning fast reads Rapier's rotation gap
                // (crate module `gap`): say so once, naming the setting.
                let radius = match crate::shape::supported_shape(co) {
                    Some(crate::SupportedShape::Ball { radius })
                    | Some(crate::SupportedShape::Wheel { radius, .. }) => Some(radius),
                    _ => None,
                };
                if let Some(radius) = radius
                    && let Some(rb) = co.parent().and_then(|h| bodies.get(h))
                    && rb.is_dynamic()
                {
                    let w = f64::from(rb.angvel().length());
                    let turn = w * self.dt;
                    if turn > ROTATION_GAP_TURN {
                        self.warned_gap = true;
                        self.warnings.push(CreepWarning::RotationGap {
                            collider: handle,
                            rim_speed: w * radius,
                            turn,
                            substeps: self.substeps,
                        });
                    }
                }
            }
            if mat.is_compliant() {
                // Out of Rapier's contact solve altogether (no solver contacts, no hook), so its
                // pairs keep Rapier's contact recycling: the compliant regime needs only the
                // narrow phase's pair list, and computes the geometry itself.
                let flags = co.active_hooks() - ActiveHooks::MODIFY_SOLVER_CONTACTS - OPT_INS;
                if (flags != co.active_hooks() || co.solver_groups() != InteractionGroups::none())
                    && let Some(co) = colliders.get_mut(handle)
                {
                    co.set_active_hooks(flags);
                    co.set_solver_groups(InteractionGroups::none());
                }
                continue;
            }
            let moving = mat.regime.fidelity() == Some(Fidelity::Creep)
                || matches!(mat.rolling, RollingResistance::Torque(_))
                || v_act == 0.0
                || co.parent().and_then(|h| bodies.get(h)).is_some_and(|rb| {
                    let r = co.shape().compute_local_bounding_sphere().radius;
                    rb.linvel().length() + rb.angvel().length() * r > v_act as f32
                });
            let flags = co.active_hooks();
            // Active (flag on) -> clearing (flag on, marked: pairs of two quiet colliders are
            // left as Rapier built them) -> off (flag off: recycled clean). With the feature
            // `rapier-patched`, an active collider may opt in to recycling ([`RECYCLE`],
            // [`recycle_opt_in`]) and a ball skips the hook on manifolds without solver
            // contacts ([`SKIP_EMPTY`]); the clearing mark still keeps its pairs from being
            // recycled. (Both flags change only with `MODIFY_SOLVER_CONTACTS` or the speed
            // that decides recycling, so the colliders written here are those written without
            // them.)
            let modify = ActiveHooks::MODIFY_SOLVER_CONTACTS;
            let wanted = if moving {
                let opt_in = recycle_opt_in(co, mat, bodies) | skip_empty_opt_in(co);
                (flags | modify | opt_in) - CLEARING_MARK - (OPT_INS - opt_in)
            } else if flags.contains(modify) && !flags.contains(CLEARING_MARK) {
                flags | CLEARING_MARK
            } else {
                flags - modify - OPT_INS - CLEARING_MARK
            };
            let on = wanted.contains(modify);
            if wanted != flags
                && let Some(co) = colliders.get_mut(handle)
            {
                co.set_active_hooks(wanted);
            }
            on_count += usize::from(on);
        }
        self.hooks_on = on_count;
        on_count
    }

    /// Call after each step: applies the contact-torque rolling resistance computed in the step
    /// (as angular impulses `M dt`, capped so that they never reverse the relative rolling) and
    /// drops the records of contacts that ended.
    pub(crate) fn end_step(&mut self, bodies: &mut RigidBodySet) -> Result<(), PluginError> {
        if !std::mem::take(&mut self.prepared) {
            return Err(PluginError::StepNotPrepared);
        }
        // The shards' reports: unregistered colliders (once each), a bad friction.
        let mut bad_friction = None;
        for shard in self.shards.iter_mut() {
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            bad_friction = bad_friction.or(shard.bad_friction.take());
            for (collider, touching) in shard.unregistered.drain(..) {
                if self.warned_unregistered.insert(collider) {
                    self.warnings
                        .push(CreepWarning::Unregistered { collider, touching });
                }
            }
        }
        let dt = self.dt;
        let has_moment =
            |rec: &ContactRecord| rec.torque != Vec3::ZERO || rec.spin_torque != Vec3::ZERO;
        #[cfg(feature = "parallel")]
        {
            // Several threads filled the shards' maps in no fixed order, and the capped
            // impulses of one body do not commute in f32: apply them in key order.
            self.moments.clear();
            for shard in self.shards.iter_mut() {
                let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
                let g = shard.store.generation;
                self.moments.extend(
                    shard
                        .store
                        .records
                        .iter()
                        .filter(|(_, r)| r.generation == g && has_moment(r))
                        .map(|(k, r)| (*k, *r)),
                );
                shard.store.sweep();
            }
            self.moments.sort_unstable_by_key(|(k, _)| k.order());
            for (_, rec) in &self.moments {
                apply_rolling_impulse(bodies, rec, dt);
            }
        }
        #[cfg(not(feature = "parallel"))]
        for shard in self.shards.iter_mut() {
            // One pass: the moments of this step's contacts applied, the ended ones dropped.
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            let g = shard.store.generation;
            shard.store.records.retain(|_, rec| {
                let live = rec.generation == g;
                if live && has_moment(rec) {
                    apply_rolling_impulse(bodies, rec, dt);
                }
                live
            });
        }
        match bad_friction {
            Some((collider, value)) => crate::registry::check_friction(collider, value),
            None => Ok(()),
        }
    }

    /// Every [`UNREGISTERED_SCAN_STEPS`] steps (with [`CreepSettings::warn_unregistered`]):
    /// warns once about each unregistered collider in contact with a registered one. The hook
    /// sees such pairs only while the registered collider's hook is on; this scan also finds
    /// them against a resting or fixed registered collider (a floor), at the cost of one pass
    /// over the contact pairs every few steps while some collider (of `colliders` in the
    /// world) is not registered.
    pub(crate) fn scan_unregistered(&mut self, narrow_phase: &NarrowPhase, colliders: usize) {
        // Nothing to find when every collider is registered (or none is).
        if !self.settings.warn_unregistered
            || self.registry.is_empty()
            || colliders <= self.registry.len()
        {
            return;
        }
        if self.scan_countdown > 0 {
            self.scan_countdown -= 1;
            return;
        }
        self.scan_countdown = UNREGISTERED_SCAN_STEPS - 1;
        for pair in narrow_phase.contact_pairs() {
            let (c1, c2) = (pair.collider1, pair.collider2);
            let (known, stranger) = match (self.registry.get(c1), self.registry.get(c2)) {
                (Some(_), None) => (c1, c2),
                (None, Some(_)) => (c2, c1),
                _ => continue,
            };
            if pair.has_any_active_contact() && self.warned_unregistered.insert(stranger) {
                self.warnings.push(CreepWarning::Unregistered {
                    collider: stranger,
                    touching: known,
                });
            }
        }
    }

    /// Groups the coincident ball contacts on triangle meshes and heightfields of the last
    /// step (`crate::store::CoincidentLoad`), before the next: for each pair whose ball
    /// contacts the hook listed (`ContactStore::on_meshes`), the contacts at one point (within
    /// `1e-6 m + 1e-6 |c|`) along one normal (within 1.4 mrad) get the group's summed normal
    /// and friction impulses of the last solve, read from the narrow phase, and its
    /// share-weighted last target. Costs nothing in a scene without such pairs.
    ///
    /// Only with more than one solver substep (those of the last step): there the solver's
    /// split between coincident contacts changes from substep to substep and their own
    /// targets work against each other (a rubber ball at 2 m/s on a mesh edge, 1/30 s, four
    /// substeps: 3.9e-4 of E0 gained, plain Rapier 2.6e-5; grouped, 2.6e-5). With one substep
    /// the split holds and the full matrix is the same either way within its noise (worst mesh
    /// gain 2.0e-5 both), so the contacts stay apart there.
    pub(crate) fn gather_coincident(&mut self, narrow_phase: &NarrowPhase) {
        let grouping = self.substeps > 1;
        for shard in self.shards.iter_mut() {
            let shard = shard.get_mut().unwrap_or_else(|e| e.into_inner());
            let store = &mut shard.store;
            // Last step's groups were taken by their members' hook calls; a member not seen
            // again leaves its entry here.
            if !store.coincident.is_empty() {
                store.coincident.clear();
            }
            let listed = std::mem::take(&mut store.on_meshes);
            if grouping {
                // A pair's contacts were listed one after the other (one call per manifold,
                // the pair's manifolds in one pass).
                for run in listed.chunk_by(|a, b| {
                    (a.0.collider1, a.0.collider2) == (b.0.collider1, b.0.collider2)
                }) {
                    if run.len() >= 2
                        && let Some(pair) =
                            narrow_phase.contact_pair(run[0].0.collider1, run[0].0.collider2)
                    {
                        group_coincident(run, pair, store);
                    }
                }
            }
            let mut listed = listed;
            listed.clear();
            store.on_meshes = listed;
        }
    }

    /// Records what Rapier quarantined in the step (rapier3d's `PhysicsPipeline::quarantine`):
    /// in [`StepCounts::quarantined_bodies`] and `quarantined_colliders`, each body also as a
    /// [`CreepWarning::Quarantined`].
    pub(crate) fn report_quarantine(&mut self, q: &rapier3d::pipeline::Quarantine) {
        for &body in q.bodies() {
            self.quarantined.0.push(body);
            self.warnings.push(CreepWarning::Quarantined { body });
        }
        self.quarantined.1.extend_from_slice(q.colliders());
    }

    /// Whether a step is prepared and not yet finished.
    pub fn is_step_prepared(&self) -> bool {
        self.prepared
    }

    /// Abandons a prepared step (its host did not step): the counts of the step stay, no
    /// rolling torque is applied, no record is swept.
    pub(crate) fn abandon_step(&mut self) {
        self.prepared = false;
    }

    /// Lifts Rapier's angular speed cap (45 degrees per step, `RigidBody::set_allow_fast_rotation`)
    /// on the dynamic bodies of registered ball colliders: the cap exists for the swept volume of
    /// rotating shapes in CCD, which a ball's rotation does not change, and it makes a ball
    /// rolling faster than `(pi/4) R / dt` slide (0.1 m at 1/60 s: 4.7 m/s) and lose most of its
    /// energy. Only bodies whose flag must change are touched.
    pub(crate) fn lift_rotation_cap(&self, bodies: &mut RigidBodySet, colliders: &ColliderSet) {
        // Only with one substep, where the rotation-gap correction is exact: with Rapier's
        // substeps a ball spinning past the cap (100 rad/s at 1/60 s in the hard-case matrix)
        // gains 4.0e-6 of E0 per step against its Coulomb twin (the mean correction's error).
        // The patched Rapier (feature `rapier-patched`) caps no ball centred at its centre of
        // mass by itself.
        if !self.settings.lift_rotation_cap
            || self.substeps != 1
            || cfg!(feature = "rapier-patched")
        {
            return;
        }
        for &handle in &self.selected {
            let Some(mat) = self.registry.get(handle) else {
                continue;
            };
            if mat.is_compliant() {
                continue;
            }
            let Some(co) = colliders.get(handle) else {
                continue;
            };
            if co.shape().as_ball().is_none() {
                continue;
            }
            let Some(parent) = co.parent() else { continue };
            let Some(rb) = bodies.get(parent).filter(|rb| rb.is_dynamic()) else {
                continue;
            };
            // Rapier caps every body's linear speed (`max_linear_velocity`, 400 m/s per length
            // unit) but no lifted spin: a ball at that cap keeps the spin cap too, so that its
            // rim speed `|omega| R` never runs past the linear cap (friction spins a lifted
            // ball only towards `|v|/R`).
            let radius = f64::from(co.shape().as_ball().map_or(0.0, |b| b.radius));
            let cap = 0.99 * self.max_linvel;
            let lift = f64::from(rb.linvel().length()) < cap
                && f64::from(rb.angvel().length()) * radius < cap;
            if rb.is_fast_rotation_allowed() != lift
                && let Some(rb) = bodies.get_mut(parent)
            {
                rb.set_allow_fast_rotation(lift);
            }
        }
    }

    /// What the plugin did in the last step.
    /// (The shards' counts summed in shard order; with feature `parallel` and several threads
    /// `creep_power` is summed in the threads' order within a shard, so it may differ from one
    /// run to another in its last bits; the physics does not.)
    pub fn counts(&self) -> StepCounts {
        let mut c = StepCounts {
            hooks_on: self.hooks_on,
            warnings: self.warnings.clone(),
            quarantined_bodies: self.quarantined.0.clone(),
            quarantined_colliders: self.quarantined.1.clone(),
            ..StepCounts::default()
        };
        for shard in self.shards.iter() {
            c.add(&shard.lock().unwrap_or_else(|e| e.into_inner()).counts);
        }
        c
    }

    /// Number of live per-contact records.
    pub fn live_contacts(&self) -> usize {
        self.shards
            .iter()
            .map(|s| s.lock().unwrap_or_else(|e| e.into_inner()).store.len())
            .sum()
    }

    /// Copies of all live contact records.
    pub fn records(&self) -> Vec<(ContactKey, ContactRecord)> {
        let mut all = Vec::new();
        for shard in self.shards.iter() {
            let shard = shard.lock().unwrap_or_else(|e| e.into_inner());
            all.extend(shard.store.iter().map(|(k, r)| (*k, *r)));
        }
        all
    }

    /// A copy of the record of one contact, if live.
    pub fn record(&self, key: &ContactKey) -> Option<ContactRecord> {
        let shard = self.shards[shard_of(key.collider1, key.collider2)]
            .lock()
            .unwrap_or_else(|e| e.into_inner());
        shard.store.records.get(key).copied()
    }
}

/// The coincident groups among one pair's listed contacts (`run`: key and point, all of one
/// collider pair; [`CreepHooks::gather_coincident`]): each member's last solved impulses from
/// the pair's manifold points (in the solver's tangent basis of the member's normal), the
/// groups by point and normal, their loads in `store.coincident` by member.
fn group_coincident(run: &[(ContactKey, Vec3)], pair: &ContactPair, store: &mut ContactStore) {
    use crate::store::CoincidentLoad;
    /// Members of one pair's run considered (a ball touches at most a few triangles).
    const MAX: usize = 16;
    if pair.collider1 != run[0].0.collider1 || run.len() > MAX {
        return;
    }
    // Per member: normal impulse, friction impulse on body 1 (world), normal, last target.
    let mut members: [Option<(f64, Vec3, Vec3, Vec3)>; MAX] = [None; MAX];
    for m in pair.manifolds() {
        let subshapes = (m.subshape1, m.subshape2);
        for pt in &m.points {
            let features = super::ball::contact_features((pt.fid1.0, pt.fid2.0), subshapes, true);
            let Some(i) = run
                .iter()
                .position(|(k, _)| (k.feature1, k.feature2) == features)
            else {
                continue;
            };
            let Some(rec) = store.records.get(&run[i].0) else {
                continue;
            };
            let (t1, t2) = crate::convert::solver_tangents(rec.normal);
            let ti = pt.data.tangent_impulse;
            members[i] = Some((
                f64::from(pt.data.impulse),
                t1 * f64::from(ti.x) + t2 * f64::from(ti.y),
                rec.normal,
                rec.target,
            ));
        }
    }
    let mut grouped = [false; MAX];
    for i in 0..run.len() {
        let (Some((_, _, ni, _)), false) = (members[i], grouped[i]) else {
            continue;
        };
        let ci = run[i].1;
        let tol = 1e-6 * (1.0 + ci.length());
        let mut group = [0usize; MAX];
        let mut k = 0;
        for j in i..run.len() {
            if let Some((_, _, nj, _)) = members[j]
                && !grouped[j]
                && (run[j].1 - ci).length() <= tol
                && ni.dot(nj) >= 1.0 - 1e-6
            {
                group[k] = j;
                k += 1;
            }
        }
        if k < 2 {
            continue;
        }
        let mut load = CoincidentLoad::default();
        for &j in &group[..k] {
            let (p, q, _, _) = members[j].unwrap_or_default();
            load.normal_impulse += p;
            load.tangent_impulse += q;
            grouped[j] = true;
        }
        if !(load.normal_impulse > 0.0) {
            continue;
        }
        for &j in &group[..k] {
            let (p, _, _, target) = members[j].unwrap_or_default();
            load.target += target * (p / load.normal_impulse);
        }
        for &j in &group[..k] {
            store.coincident.insert(run[j].0, load);
        }
    }
}
