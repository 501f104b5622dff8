//! The plugin's resource: creep-rapier's hooks (materials, settings, per-contact state), the map
//! between Bevy entities and Rapier collider handles, the last step's counts, and the warnings
//! the plugin gave.

use std::collections::{HashMap, HashSet};
use std::fmt;

use bevy::prelude::*;
use creep_rapier::diagnostics::{ContactKey, ContactRecord};
use creep_rapier::{
    CompliantCounts, CompliantRegime, CompliantSettings, CreepHooks, CreepPipeline, CreepSettings,
    MaterialRegistry, PluginError, StepCounts,
};
use rapier3d::prelude::{ColliderHandle, ColliderSet};

/// Why the plugin warned. Each warning is given once: with Bevy's `warn!` when a log subscriber
/// listens (`LogPlugin`, part of `DefaultPlugins`), else on standard error (an app on
/// `MinimalPlugins` has no `LogPlugin`, and `warn!` alone would print nothing); the list is kept
/// in [`CreepFriction::warnings`] so that an app (or a test) can inspect it.
#[derive(Debug, Clone, PartialEq)]
pub enum CreepWarning {
    /// `CreepFrictionPlugin` was added a second time; the second one (and its configuration)
    /// is ignored.
    PluginAddedTwice,
    /// `RapierPhysicsPlugin::<CreepPhysicsHooks>` is not in the app (and the plugin was not told
    /// that custom hooks delegate to [`crate::CreepPhysicsHooks`]): Rapier never calls the creep
    /// hook and every contact stays Coulomb.
    HooksNotInstalled,
    /// A context's integration parameters did not suit the plugin (`FrictionModel::Coulomb`
    /// and no contact clustering are required); `configured` says whether the plugin set them
    /// (otherwise the context stays Coulomb).
    Parameters {
        /// The context entity.
        context: Entity,
        /// What was wrong.
        error: PluginError,
        /// Whether the plugin fixed it.
        configured: bool,
    },
    /// A collider without `CreepMaterial` touches one with it: that contact stays Coulomb.
    MissingMaterial {
        /// The collider entity without a material.
        entity: Entity,
    },
    /// `CreepMaterial` on an entity without a bevy_rapier3d `Collider`: nothing to do.
    NoCollider {
        /// The entity.
        entity: Entity,
    },
    /// `CreepMaterial` on a collider whose shape creep-rapier does not model
    /// ([`creep_rapier::supported_shape`], listed in [`creep_rapier::SUPPORTED_SHAPES`]): it
    /// stays Coulomb.
    UnsupportedShape {
        /// The collider entity.
        entity: Entity,
        /// Rapier's shape type.
        shape: String,
    },
    /// A crown (`CreepMaterial::with_crown`) on a collider that is not a cylinder: only wheels
    /// have one; it is ignored.
    CrownIgnored {
        /// The collider entity.
        entity: Entity,
        /// Rapier's shape type.
        shape: String,
    },
    /// A `CreepMaterial` creep-rapier refuses (a wheel's crown radius not finite and > 0): the
    /// collider stays Coulomb.
    InvalidMaterial {
        /// The collider entity.
        entity: Entity,
        /// What was wrong.
        error: PluginError,
    },
    /// `CreepMaterial` on a collider of another Rapier context than the one the plugin serves
    /// (the default context): it stays Coulomb.
    OtherContext {
        /// The collider entity.
        entity: Entity,
    },
    /// More than one Rapier step ran in one schedule run (`TimestepMode` with `substeps > 1`, or
    /// `Interpolated` catching up): the contact state and the rolling torque are updated once
    /// per run, not once per step, so creep is approximate. Use `substeps: 1` (and run the
    /// physics in `FixedUpdate` for a fixed rate).
    StepsPerRun {
        /// Steps in that run.
        steps: usize,
    },
    /// A registered ball or wheel turned more than creep-rapier's `ROTATION_GAP_TURN` in a
    /// step with more than one solver substep (the plugin's default is one,
    /// `SolverPreset::Rolling`; kept away by [`crate::CreepFrictionPlugin::with_rapier_solver`]
    /// or by changing `num_solver_iterations`): Rapier's rotation gap makes it float or sink
    /// and lose energy. Given once.
    RotationGap {
        /// The ball's or wheel's collider entity.
        entity: Option<Entity>,
        /// Its rim speed `|omega| R` \[m/s\].
        rim_speed: f64,
        /// Its turn in the step `|omega| dt` \[rad\].
        turn: f64,
        /// The solver substeps of the step.
        substeps: usize,
    },
    /// The context has colliders but none has a `CreepMaterial`: every contact is plain
    /// Rapier. Given once.
    NothingRegistered {
        /// Colliders in the context.
        colliders: usize,
    },
    /// Rapier quarantined a body whose state went non-finite (NaN or infinite): it is
    /// disabled.
    Quarantined {
        /// The body's entity.
        entity: Option<Entity>,
    },
    /// The plugin's settings were refused; the defaults are used.
    InvalidSettings {
        /// What was wrong.
        error: PluginError,
    },
    /// The plugin could not start a step (e.g. a zero or infinite time step): it stays Coulomb.
    Step {
        /// What was wrong.
        error: PluginError,
    },
}

impl fmt::Display for CreepWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PluginAddedTwice => write!(
                f,
                "creep-friction: CreepFrictionPlugin was added twice; the second one and its \
                 configuration are ignored"
            ),
            Self::HooksNotInstalled => write!(
                f,
                "creep-friction: RapierPhysicsPlugin::<CreepPhysicsHooks> is not in the app, so \
                 Rapier never calls the creep hook and every contact stays Coulomb (add it, or \
                 delegate from your own hooks to CreepPhysicsHooks and use \
                 CreepFrictionPlugin::with_custom_hooks())"
            ),
            Self::Parameters {
                context,
                error,
                configured,
            } => {
                if *configured {
                    write!(
                        f,
                        "creep-friction: context {context}: {error}; the plugin set \
                         FrictionModel::Coulomb and contact_clustering = false"
                    )
                } else {
                    write!(
                        f,
                        "creep-friction: context {context}: {error}; its contacts stay Coulomb"
                    )
                }
            }
            Self::MissingMaterial { entity } => write!(
                f,
                "creep-friction: collider {entity} has no CreepMaterial but touches one that \
                 has: those contacts stay Coulomb (give it a CreepMaterial, with \
                 Fidelity::Coulomb to keep it Coulomb and silence this)"
            ),
            Self::NoCollider { entity } => write!(
                f,
                "creep-friction: entity {entity} has a CreepMaterial but no Collider: ignored"
            ),
            Self::UnsupportedShape { entity, shape } => write!(
                f,
                "creep-friction: collider {entity} is a {shape}, which creep-friction does not \
                 model (it models {}): it stays Coulomb",
                creep_rapier::SUPPORTED_SHAPES
            ),
            Self::CrownIgnored { entity, shape } => write!(
                f,
                "creep-friction: collider {entity} is a {shape}: its CreepMaterial's crown is \
                 read for cylinders (wheels) only and is ignored"
            ),
            Self::InvalidMaterial { entity, error } => write!(
                f,
                "creep-friction: collider {entity}: {error}; it stays Coulomb"
            ),
            Self::OtherContext { entity } => write!(
                f,
                "creep-friction: collider {entity} belongs to another Rapier context than the \
                 default one the plugin serves: it stays Coulomb"
            ),
            Self::StepsPerRun { steps } => write!(
                f,
                "creep-friction: {steps} Rapier steps ran in one schedule run (substeps > 1 or \
                 Interpolated catching up); the plugin updates its state once per run, so \
                 creep is approximate: use TimestepMode::Fixed {{ substeps: 1, .. }}"
            ),
            Self::RotationGap {
                entity,
                rim_speed,
                turn,
                substeps,
            } => write!(
                f,
                "creep-friction: collider {} rolls at {rim_speed:.3} m/s ({turn:.3} rad a step) \
                 with num_solver_iterations = {substeps}: Rapier's rotation gap makes it float \
                 or sink and lose energy; use one substep (the plugin's default, \
                 SolverPreset::Rolling: drop CreepFrictionPlugin::with_rapier_solver(), or set \
                 RapierContextSimulation::integration_parameters.num_solver_iterations = 1)",
                name(*entity)
            ),
            Self::NothingRegistered { colliders } => write!(
                f,
                "creep-friction: none of the context's {colliders} colliders has a \
                 CreepMaterial: every contact is plain Rapier (give the colliders that should \
                 creep a CreepMaterial)"
            ),
            Self::Quarantined { entity } => write!(
                f,
                "creep-friction: Rapier quarantined body {}: its state went non-finite (NaN or \
                 infinite) and it is disabled (check its size, mass and speed)",
                name(*entity)
            ),
            Self::InvalidSettings { error } => write!(
                f,
                "creep-friction: invalid settings: {error}; the defaults are used"
            ),
            Self::Step { error } => {
                write!(
                    f,
                    "creep-friction: cannot step: {error}; contacts stay Coulomb"
                )
            }
        }
    }
}

/// An entity, or `?` for a Rapier object without one.
fn name(entity: Option<Entity>) -> String {
    entity.map_or_else(|| "?".to_string(), |e| e.to_string())
}

/// Gives a warning: Bevy's `warn!` when a `tracing` subscriber listens (Bevy's `LogPlugin`, in
/// `DefaultPlugins`, or one of the app's own), otherwise (`MinimalPlugins`, a test harness)
/// a line on standard error, `WARN creep-friction: ...`, where `warn!` would reach nobody.
pub(crate) fn emit(warning: &CreepWarning) {
    if log_listens() {
        warn!("{warning}");
    } else {
        eprintln!("WARN {warning}");
    }
}

/// Whether a `tracing` subscriber (global, or scoped to this thread) is installed.
fn log_listens() -> bool {
    use bevy::log::tracing::{dispatcher, subscriber::NoSubscriber};
    dispatcher::get_default(|d| !d.is::<NoSubscriber>())
}

/// How many "missing material" warnings are given before the plugin stops looking for more.
pub const MAX_MISSING_MATERIAL_WARNINGS: usize = 16;

/// The plugin's resource: creep-rapier's [`CreepHooks`] for the default Rapier context, with
/// the settings ([`CreepFriction::settings`]) and the last step's counts
/// ([`CreepFriction::counts`]: contacts by path, power dissipated by creep).
#[derive(Resource)]
pub struct CreepFriction {
    /// creep-rapier's step owner: the rigid hooks and the compliant (DEM) regime of the pairs
    /// with a [`creep_rapier::Regime::Compliant`] collider.
    pub(crate) pipeline: CreepPipeline,
    /// Registered collider -> its entity (guards against handles of another context).
    pub(crate) entities: HashMap<ColliderHandle, Entity>,
    /// Entity -> its registered collider.
    pub(crate) handles: HashMap<Entity, ColliderHandle>,
    /// Entities with a `CreepMaterial` whose collider does not exist yet.
    pub(crate) pending: HashSet<Entity>,
    /// Colliders whose material was removed: their hook flag is cleared before the next step.
    pub(crate) unhook: Vec<ColliderHandle>,
    /// Colliders that left the compliant regime: their solver groups (which creep-rapier sets
    /// to none for compliant colliders) are restored before the next step.
    pub(crate) restore_groups: Vec<(ColliderHandle, Entity)>,
    /// A step was started by the plugin and the hook may act.
    pub(crate) armed: bool,
    pub(crate) counts: StepCounts,
    pub(crate) steps: u64,
    pub(crate) warnings: Vec<CreepWarning>,
    pub(crate) warned: HashSet<WarnKey>,
    pub(crate) missing_warned: usize,
    pub(crate) configure_parameters: bool,
    /// The default context was created with the solver preset (through bevy_rapier3d's
    /// `RapierContextInitialization`).
    pub(crate) default_context_preset: bool,
    pub(crate) warn_missing_material: bool,
}

/// What a warning is about, to give each one once.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub(crate) enum WarnKey {
    Global(&'static str),
    Entity(&'static str, Entity),
}

impl CreepFriction {
    pub(crate) fn new(
        settings: CreepSettings,
        compliant: CompliantSettings,
        configure_parameters: bool,
        warn_missing_material: bool,
    ) -> Result<Self, PluginError> {
        Ok(Self {
            pipeline: CreepPipeline::from_parts(
                CreepHooks::new(MaterialRegistry::new(), settings)?,
                compliant,
            )?,
            entities: HashMap::new(),
            handles: HashMap::new(),
            pending: HashSet::new(),
            unhook: Vec::new(),
            restore_groups: Vec::new(),
            armed: false,
            counts: StepCounts::default(),
            steps: 0,
            warnings: Vec::new(),
            warned: HashSet::new(),
            missing_warned: 0,
            configure_parameters,
            default_context_preset: false,
            warn_missing_material,
        })
    }

    /// The plugin-wide settings (creep-rapier's [`CreepSettings`]).
    pub fn settings(&self) -> &CreepSettings {
        self.pipeline.hooks.settings()
    }

    /// Replaces the settings. The materials stay; the per-contact memory (last force and slip
    /// target of each contact) starts afresh. A refused setting is a typed error and changes
    /// nothing.
    pub fn set_settings(&mut self, settings: CreepSettings) -> Result<(), PluginError> {
        let registry = self.pipeline.hooks.registry().clone();
        self.pipeline.hooks = CreepHooks::new(registry, settings)?;
        Ok(())
    }

    /// The compliant regime (settings, per-contact state, energy totals).
    pub fn compliant(&self) -> &CompliantRegime {
        &self.pipeline.compliant
    }

    /// Replaces the compliant regime's settings (a refused setting is a typed error and changes
    /// nothing).
    pub fn set_compliant_settings(
        &mut self,
        settings: CompliantSettings,
    ) -> Result<(), PluginError> {
        self.pipeline.compliant.set_settings(settings)
    }

    /// What the compliant regime did in the last Rapier step (contacts, sliding, creeping,
    /// Rayleigh time step).
    pub fn compliant_counts(&self) -> CompliantCounts {
        self.pipeline.compliant.counts()
    }

    /// What the plugin did in the last Rapier step: contacts by path (Coulomb for each reason,
    /// creep, rolling torque), the power dissipated by creep `sum Q . v_disp` \[W\], the largest
    /// loop gain, and how many registered colliders had their hook on.
    pub fn counts(&self) -> &StepCounts {
        &self.counts
    }

    /// Number of Rapier steps the plugin has taken part in.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The warnings given so far, in order (each also given once with `warn!`, or on standard
    /// error when no log subscriber listens).
    pub fn warnings(&self) -> &[CreepWarning] {
        &self.warnings
    }

    /// The Rapier collider handle registered for a collider entity.
    pub fn collider_handle(&self, entity: Entity) -> Option<ColliderHandle> {
        self.handles.get(&entity).copied()
    }

    /// The collider entity registered for a Rapier collider handle.
    pub fn collider_entity(&self, handle: ColliderHandle) -> Option<Entity> {
        self.entities.get(&handle).copied()
    }

    /// Number of registered colliders.
    pub fn registered(&self) -> usize {
        self.handles.len()
    }

    /// The creep-rapier hooks (registry, settings, per-contact records).
    pub fn hooks(&self) -> &CreepHooks {
        &self.pipeline.hooks
    }

    /// Copies of the live per-contact records (force used, slip target, normal force, bodies;
    /// world frame, on collider 1; creep-rapier's [`ContactRecord`]).
    pub fn contacts(&self) -> Vec<(ContactKey, ContactRecord)> {
        self.pipeline.hooks.records()
    }

    /// Whether both colliders of a pair are this plugin's (not handles of another context that
    /// happen to be equal): a registered handle must carry its entity in `user_data`.
    pub(crate) fn owns(&self, colliders: &ColliderSet, handle: ColliderHandle) -> bool {
        match self.entities.get(&handle) {
            Some(e) => colliders
                .get(handle)
                .is_some_and(|c| c.user_data as u64 == e.to_bits()),
            None => true,
        }
    }

    /// Records and gives a warning that is given once by construction (creep-rapier's).
    pub(crate) fn give(&mut self, warning: CreepWarning) {
        emit(&warning);
        self.warnings.push(warning);
    }

    /// Records and gives a warning ([`emit`]), once per key.
    pub(crate) fn warn(&mut self, key: WarnKey, warning: CreepWarning) {
        if self.warned.insert(key) {
            emit(&warning);
            self.warnings.push(warning);
        }
    }
}
