//! The plugin's state: settings, per-contact records, per-step counts and warnings, in one
//! resource ([`CreepState`]).
//!
//! Avian's hooks get read-only ECS access and may be called from several threads, so the
//! records sit behind a mutex; without Avian's `parallel` feature the lock is never contended.
//! Records are indexed by Avian's stable [`ContactId`] (a dense index, reused by Avian once a
//! pair ends): no hashing per contact.

use std::sync::{Mutex, MutexGuard};

use avian3d::collision::contact_types::ContactId;
use bevy::prelude::*;
use creep_law::{CreepModel, Material, Vec3};

use creep_law::PairMaterial;
use creep_law::rigid::RigidPair;

/// The plugin's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepSettings {
    /// Saturated creep slip `F_ss(1) |v_roll|` \[m/s\] below which an [`crate::Fidelity::Auto`]
    /// contact is left to Coulomb (finite, `>= 0`).
    pub auto_tolerance: f64,
    /// The steady creep law (Kalker's `F_ss` for [`CreepModel::Kuhn`]).
    pub creep_model: CreepModel,
    /// Removes each creep ball's own rotation from the separation Avian's solver reads at
    /// every substep (crate `plugin`): a ball turned about its centre is the same ball, so the
    /// gap `R (1 - cos(w t))` the turned anchor opens is not there. Off by default: with it a
    /// freely rolling ball keeps its height, and Avian's soft contact can then hand it up to
    /// about 2e-6 of its energy (see the crate's guide page).
    pub rotation_gap_removal: bool,
}

impl Default for CreepSettings {
    fn default() -> Self {
        Self {
            auto_tolerance: 1e-7,
            creep_model: CreepModel::Kuhn,
            rotation_gap_removal: false,
        }
    }
}

impl CreepSettings {
    /// `Ok` if the settings are usable, else the reason.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.auto_tolerance >= 0.0 && self.auto_tolerance.is_finite()) {
            return Err(format!(
                "auto_tolerance = {} m/s: must be finite and >= 0",
                self.auto_tolerance
            ));
        }
        Ok(())
    }
}

/// What the hooks did in one physics step (each contact point counted once).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepCounts {
    /// Contacts given a creep slip target.
    pub creep: usize,
    /// Contacts left to Coulomb by the law: no load (a new contact), no rolling, a force within
    /// the solver's rounding, or (Auto) a creep slip below the tolerance.
    pub coulomb_auto: usize,
    /// Contacts left to Coulomb because a collider asked for [`crate::Fidelity::Coulomb`].
    pub coulomb_requested: usize,
    /// Contacts left to Coulomb by a bad setup (see [`CreepWarning`]).
    pub coulomb_setup: usize,
    /// Largest loop gain `K F'(q)` of the implicit solve \[-\].
    pub max_loop_gain: f64,
    /// Creep power `sum Q . tau` the targets ask for \[W\].
    pub creep_power: f64,
}

/// A bad setup the plugin met; the contact is solved with Avian's Coulomb friction and a Bevy
/// warning is logged once per collider and kind.
#[derive(Debug, Clone, PartialEq)]
pub enum CreepWarning {
    /// A collider touches a creep collider but has no [`crate::CreepMaterial`].
    MissingMaterial(Entity),
    /// A creep collider's shape is neither a ball nor flat (cuboid, half-space, triangle mesh,
    /// height field, convex hull): capsules, cylinders, cones and compounds are not modelled.
    UnsupportedShape(Entity),
    /// The pair's materials or radii are invalid for the contact law (the law's message).
    InvalidMaterial(Entity, String),
    /// The creep hooks are not Avian's narrow-phase hooks (install them with
    /// `PhysicsPlugins::default().with_collision_hooks::<CreepHooks>()`): every contact is
    /// Coulomb.
    HooksNotInstalled,
    /// A creep collider's `ActiveCollisionHooks` lacked `MODIFY_CONTACTS` (the flag was added).
    HookFlagAdded(Entity),
    /// The plugin's settings were invalid (the defaults are used).
    InvalidSettings(String),
}

impl std::fmt::Display for CreepWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::MissingMaterial(e) => write!(
                f,
                "collider {e} touches a creep collider without a CreepMaterial: Coulomb friction"
            ),
            Self::UnsupportedShape(e) => write!(
                f,
                "collider {e}: shape not modelled by creep-friction (balls and flat shapes are): Coulomb friction"
            ),
            Self::InvalidMaterial(e, why) => {
                write!(
                    f,
                    "collider {e}: invalid creep material ({why}): Coulomb friction"
                )
            }
            Self::HooksNotInstalled => write!(
                f,
                "CreepHooks are not Avian's collision hooks (all contacts Coulomb): use \
                 PhysicsPlugins::default().with_collision_hooks::<CreepHooks>()"
            ),
            Self::HookFlagAdded(e) => write!(
                f,
                "collider {e}: ActiveCollisionHooks lacked MODIFY_CONTACTS; added"
            ),
            Self::InvalidSettings(why) => {
                write!(f, "invalid creep settings ({why}): the defaults are used")
            }
        }
    }
}

/// One contact point's record (the first point of one manifold), kept between steps.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct PointRecord {
    /// Last step's normal force \[N\] (0 before the solver has run on it).
    pub p: f64,
    /// Last step's tangential force on collider 1's body \[N\].
    pub q_meas: Vec3,
    /// The target given last (q's surface relative to p's) \[m/s\].
    pub target: Vec3,
    /// The force the target was built from \[N\].
    pub q_used: Vec3,
    /// Spin creep's twisting moment on collider 2's body \[N m\] (applied after the step).
    pub moment: Vec3,
    /// The contact normal of the step (from collider 1 to collider 2).
    pub normal: Vec3,
    /// The step's normal impulse so far, summed over its substeps \[N s\].
    pub acc_normal: f64,
    /// The step's friction impulse on collider 2's body so far, summed over its substeps
    /// \[N s\].
    pub acc_tangent: Vec3,
}

/// One contact pair's record.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PairRecord {
    /// The pair's colliders (a reused `ContactId` is told apart by them).
    pub colliders: (Entity, Entity),
    /// Their bodies.
    pub bodies: (Option<Entity>, Option<Entity>),
    /// The materials and friction the law was built from.
    pub key: (Material, Material, f32, f32, f32),
    /// The contact's pair and the pair's constants, built once (`None`: invalid, Coulomb).
    pub law: Option<(PairMaterial, RigidPair)>,
    /// Per manifold, its first point.
    pub points: Vec<PointRecord>,
    /// Harvested in the step that just ran.
    pub harvested: bool,
}

/// Everything behind the lock.
#[derive(Debug, Default)]
pub(crate) struct Inner {
    pub settings: CreepSettings,
    pub records: Vec<Option<PairRecord>>,
    pub current: StepCounts,
    pub last_step: StepCounts,
    pub hook_calls: u64,
    pub steps: u64,
    pub warned: Vec<(Option<Entity>, u8)>,
    pub warnings: Vec<CreepWarning>,
    /// Per contact (indexed by `ContactId`) of a pair of creep colliders: the step it was last
    /// solved in and, per manifold, that step's friction frame `[t1, t2]` (the frame of the
    /// warm-start friction impulses Avian carries over as components).
    pub frames: Vec<(u64, Vec<[bevy::math::Vec3; 2]>)>,
    /// This step's contact points with a creep ball on a side, for the per-substep separation.
    pub gaps: Vec<GapPoint>,
}

/// A contact point whose separation the solver must read without a ball's own rotation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct GapPoint {
    /// Graph colour, constraint and point index in Avian's `ConstraintGraph`.
    pub at: (usize, usize, usize),
    /// Whether body 1's and body 2's colliders are balls.
    pub balls: (bool, bool),
    /// The point's `initial_separation` as Avian prepared it \[m\].
    pub base: f32,
}

impl Inner {
    /// Logs `w` once per (entity, kind).
    pub fn warn(&mut self, w: CreepWarning) {
        let key = match &w {
            CreepWarning::MissingMaterial(e) => (Some(*e), 0),
            CreepWarning::UnsupportedShape(e) => (Some(*e), 1),
            CreepWarning::InvalidMaterial(e, _) => (Some(*e), 2),
            CreepWarning::HooksNotInstalled => (None, 3),
            CreepWarning::HookFlagAdded(e) => (Some(*e), 4),
            CreepWarning::InvalidSettings(_) => (None, 5),
        };
        if self.warned.contains(&key) {
            return;
        }
        self.warned.push(key);
        warn!("creep-avian: {w}");
        self.warnings.push(w);
    }

    /// The record slot of `id`.
    pub fn slot(&mut self, id: ContactId) -> &mut Option<PairRecord> {
        let i = id.0 as usize;
        if i >= self.records.len() {
            self.records.resize(i + 1, None);
        }
        &mut self.records[i]
    }
}

/// What one creep contact holds after a step (for tests, examples and diagnostics).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactInfo {
    /// The two colliders (collider 1 is `p`, the normal points from it to collider 2).
    pub colliders: (Entity, Entity),
    /// Normal force \[N\] of the step.
    pub p: f64,
    /// Tangential force on collider 1's body \[N\] of the step.
    pub q_meas: Vec3,
    /// The creep slip target in force (collider 2's surface relative to collider 1's) \[m/s\].
    pub target: Vec3,
    /// The tangential force the target was built from \[N\].
    pub q_used: Vec3,
}

/// The plugin's resource: settings, per-contact records, the counts of the last step and the
/// warnings.
#[derive(Resource, Debug, Default)]
pub struct CreepState {
    pub(crate) inner: Mutex<Inner>,
}

impl CreepState {
    pub(crate) fn new(settings: CreepSettings) -> Self {
        Self {
            inner: Mutex::new(Inner {
                settings,
                ..Default::default()
            }),
        }
    }

    /// The lock (a poisoned lock is taken as it is: the records stay usable).
    pub(crate) fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The settings.
    pub fn settings(&self) -> CreepSettings {
        self.lock().settings
    }

    /// Sets the settings (invalid ones are refused with the reason).
    pub fn set_settings(&self, settings: CreepSettings) -> Result<(), String> {
        settings.validate()?;
        self.lock().settings = settings;
        Ok(())
    }

    /// What the hooks did in the last physics step.
    pub fn counts(&self) -> StepCounts {
        self.lock().last_step
    }

    /// Physics steps seen.
    pub fn steps(&self) -> u64 {
        self.lock().steps
    }

    /// The warnings logged so far (each once).
    pub fn warnings(&self) -> Vec<CreepWarning> {
        self.lock().warnings.clone()
    }

    /// The creep contacts after the last step (allocates: for tests and diagnostics).
    pub fn contacts(&self) -> Vec<ContactInfo> {
        let inner = self.lock();
        inner
            .records
            .iter()
            .flatten()
            .flat_map(|r| {
                r.points.iter().map(move |p| ContactInfo {
                    colliders: r.colliders,
                    p: p.p,
                    q_meas: p.q_meas,
                    target: p.target,
                    q_used: p.q_used,
                })
            })
            .collect()
    }
}
