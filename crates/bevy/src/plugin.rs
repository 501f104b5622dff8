//! `CreepFrictionPlugin` and its systems, which wrap bevy_rapier3d's step with creep-rapier's
//! step owner ([`creep_rapier::CreepPipeline`]): `prepare_host_step` before
//! `PhysicsSet::StepSimulation`, `finish_host_step` after it (before `PhysicsSet::Writeback`,
//! so the contact-torque impulses reach the `Velocity` and `Transform` written back).

use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;
use bevy_rapier3d::plugin::TimestepMode;
use bevy_rapier3d::prelude::{
    Collider, ColliderMassProperties, DefaultRapierContext, PhysicsSet, RapierConfiguration,
    RapierContextColliders, RapierContextEntityLink, RapierContextInitialization,
    RapierContextSimulation, RapierRigidBodySet, SimulationMode, SolverGroups,
};
use creep_rapier::{
    CompliantSettings, CreepSettings, Fidelity, PluginError, Regime, RollingResistance,
    SolverPreset, configure_parameters_for, supported_shape,
};
use rapier3d::prelude::{ActiveHooks, IntegrationParameters};

use crate::hooks::CreepRapierPlugin;
use crate::material::CreepMaterial;
use crate::state::{CreepFriction, CreepWarning, MAX_MISSING_MATERIAL_WARNINGS, WarnKey};

/// Creep-friction for bevy_rapier3d. Add it next to `RapierPhysicsPlugin::<CreepPhysicsHooks>`
/// (in the same schedule: `PostUpdate` by default, see [`CreepFrictionPlugin::in_schedule`]),
/// and give colliders a [`CreepMaterial`]:
///
/// ```no_run
/// use bevy::prelude::*;
/// use bevy_rapier3d::prelude::*;
/// use creep_bevy::prelude::*;
/// App::new()
///     .add_plugins((MinimalPlugins, TransformPlugin))
///     .add_plugins((CreepRapierPlugin::default(), CreepFrictionPlugin::default()))
///     .insert_resource(TimestepMode::Fixed { dt: 1.0 / 60.0, substeps: 1 })
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn((RigidBody::Dynamic, Collider::ball(0.1), CreepMaterial::steel()));
///     })
///     .run();
/// ```
///
/// What it does:
/// - sets one solver substep on each new context (`CreepSettings::solver`,
///   [`SolverPreset::Rolling`]: what rolling balls and wheels need at game time steps), unless
///   [`CreepFrictionPlugin::with_rapier_solver`];
/// - sets the integration parameters creep-rapier needs (`FrictionModel::Coulomb`, no contact
///   clustering) on the default context at start, and checks them before every step
///   ([`creep_rapier::check_parameters`]); a context that does not suit is set
///   ([`creep_rapier::configure_parameters`]) with a warning, or, with
///   [`CreepFrictionPlugin::without_configuring_parameters`], left Coulomb with a warning;
/// - registers each `CreepMaterial` collider in creep-rapier's `MaterialRegistry` under its
///   Rapier `ColliderHandle` (kept in step with the component: added, changed, removed,
///   despawned) and gives it `ColliderMassProperties::Density(rho)` unless it has its own;
/// - before each step: `CreepPipeline::prepare_host_step` (parameters, activation, compliant
///   forces); after it: `finish_host_step` (rolling torques, contact sweep) and the counts in
///   [`CreepFriction`];
/// - warns (Bevy `warn!` or standard error, and [`CreepFriction::warnings`]; see
///   [`CreepWarning`]) and falls back to Coulomb, never panics, on: the plugin added twice, the
///   creep hooks not installed, a collider touching a creep collider without a material, a
///   shape creep-rapier does not model ([`creep_rapier::supported_shape`]), an invalid material
///   (a wheel's crown), a collider of another context, several Rapier steps per schedule run.
///
/// It serves one Rapier context: the one with `DefaultRapierContext` (or the only one).
pub struct CreepFrictionPlugin {
    #[cfg(feature = "gizmos")]
    gizmos: Option<crate::gizmos::CreepGizmos>,
    settings: CreepSettings,
    compliant: CompliantSettings,
    schedule: Interned<dyn ScheduleLabel>,
    custom_hooks: bool,
    configure_parameters: bool,
    warn_missing_material: bool,
}

impl Default for CreepFrictionPlugin {
    fn default() -> Self {
        Self {
            #[cfg(feature = "gizmos")]
            gizmos: None,
            settings: CreepSettings::default(),
            compliant: CompliantSettings::default(),
            schedule: PostUpdate.intern(),
            custom_hooks: false,
            configure_parameters: true,
            warn_missing_material: true,
        }
    }
}

impl CreepFrictionPlugin {
    /// The plugin with creep-rapier settings (validated when the plugin is built; invalid
    /// settings draw a warning and the defaults are used).
    pub fn with_settings(mut self, settings: CreepSettings) -> Self {
        self.settings = settings;
        self
    }
    /// The plugin with compliant-regime settings (for colliders in [`Regime::Compliant`];
    /// validated when the plugin is built: invalid settings draw a warning and the defaults are
    /// used).
    pub fn with_compliant_settings(mut self, settings: CompliantSettings) -> Self {
        self.compliant = settings;
        self
    }
    /// Draws each contact's creep slip and tangential force with Bevy's gizmos (feature
    /// `gizmos`; shown by an app with a renderer).
    #[cfg(feature = "gizmos")]
    pub fn with_gizmos(mut self, gizmos: crate::gizmos::CreepGizmos) -> Self {
        self.gizmos = Some(gizmos);
        self
    }
    /// Runs the plugin's systems in `schedule`: it must be the schedule of
    /// `RapierPhysicsPlugin` (`PostUpdate` by default, `FixedUpdate` with its
    /// `in_fixed_schedule()`).
    pub fn in_schedule(mut self, schedule: impl ScheduleLabel) -> Self {
        self.schedule = schedule.intern();
        self
    }
    /// Runs the plugin's systems in `FixedUpdate` (with `RapierPhysicsPlugin::in_fixed_schedule`).
    pub fn in_fixed_schedule(self) -> Self {
        self.in_schedule(FixedUpdate)
    }
    /// Your own physics hooks delegate to [`crate::CreepPhysicsHooks`]: do not warn that
    /// `RapierPhysicsPlugin::<CreepPhysicsHooks>` is missing.
    pub fn with_custom_hooks(mut self) -> Self {
        self.custom_hooks = true;
        self
    }
    /// Do not change a context's integration parameters: a context that does not suit stays
    /// Coulomb (with a warning).
    pub fn without_configuring_parameters(mut self) -> Self {
        self.configure_parameters = false;
        self
    }
    /// Keep the solver iterations a context is created with (Rapier's defaults: four substeps,
    /// one Gauss-Seidel iteration each) instead of the plugin's default,
    /// [`SolverPreset::Rolling`] (one substep, [`creep_rapier::ROLLING_PGS_ITERATIONS`]
    /// iterations in it): for scenes that need Rapier's substeps (tall stacks, long joint
    /// chains). The same as `CreepSettings::solver = SolverPreset::Rapier` in
    /// [`CreepFrictionPlugin::with_settings`]. With more than one substep a fast-rolling ball or
    /// wheel floats and slides (a 0.1 m steel ball rolling at 5 m/s at 1/60 s floats 2.2 mm and
    /// loses 17 % of its energy in a second); the plugin says so once
    /// ([`CreepWarning::RotationGap`]).
    pub fn with_rapier_solver(mut self) -> Self {
        self.settings.solver = SolverPreset::Rapier;
        self
    }
    /// Whether to warn about colliders without a material touching creep colliders (default
    /// true; at most [`MAX_MISSING_MATERIAL_WARNINGS`] of them).
    pub fn warn_missing_material(mut self, warn: bool) -> Self {
        self.warn_missing_material = warn;
        self
    }
}

/// Marks that the plugin was built once.
#[derive(Resource)]
struct CreepFrictionBuilt;

impl Plugin for CreepFrictionPlugin {
    fn build(&self, app: &mut App) {
        if app.world().contains_resource::<CreepFrictionBuilt>() {
            // Bevy refuses a unique plugin twice with a panic; this one is not unique so that
            // the second registration is a warning instead.
            if let Some(mut state) = app.world_mut().get_resource_mut::<CreepFriction>() {
                state.warn(WarnKey::Global("twice"), CreepWarning::PluginAddedTwice);
            } else {
                crate::state::emit(&CreepWarning::PluginAddedTwice);
            }
            return;
        }
        app.insert_resource(CreepFrictionBuilt);
        let mut warning = None;
        let state = match CreepFriction::new(
            self.settings,
            self.compliant,
            self.configure_parameters,
            self.warn_missing_material,
        ) {
            Ok(s) => s,
            Err(error) => {
                warning = Some(CreepWarning::InvalidSettings { error });
                CreepFriction::new(
                    CreepSettings::default(),
                    CompliantSettings::default(),
                    self.configure_parameters,
                    self.warn_missing_material,
                )
                .expect("the default settings are valid")
            }
        };
        app.insert_resource(state);
        if let Some(w) = warning {
            app.world_mut()
                .resource_mut::<CreepFriction>()
                .warn(WarnKey::Global("settings"), w);
        }
        app.add_systems(
            self.schedule,
            (
                apply_density.before(PhysicsSet::SyncBackend),
                (configure_new_contexts, sync_materials, pre_step)
                    .chain()
                    .after(PhysicsSet::SyncBackend)
                    .before(PhysicsSet::StepSimulation),
                post_step
                    .after(PhysicsSet::StepSimulation)
                    .before(PhysicsSet::Writeback),
            ),
        );
        #[cfg(feature = "gizmos")]
        {
            if let Some(g) = self.gizmos {
                app.insert_resource(g);
            }
            app.add_systems(
                self.schedule,
                crate::gizmos::draw_creep_gizmos
                    .after(PhysicsSet::Writeback)
                    .run_if(resource_exists::<crate::gizmos::CreepGizmos>)
                    .run_if(resource_exists::<bevy::gizmos::config::GizmoConfigStore>),
            );
        }
    }

    fn finish(&self, app: &mut App) {
        // Called once per added instance; only the first one acts.
        let Some(state) = app.world().get_resource::<CreepFriction>() else {
            return;
        };
        if state.steps > 0 || state.warned.contains(&WarnKey::Global("finished")) {
            return;
        }
        let (configure, solver) = (state.configure_parameters, state.settings().solver);
        let mut preset_set = false;
        if configure
            && let Some(mut init) = app
                .world_mut()
                .get_resource_mut::<RapierContextInitialization>()
            && let RapierContextInitialization::InitializeDefaultRapierContext {
                integration_parameters,
                ..
            } = &mut *init
        {
            // The default context is created from this (in `PreStartup`): with the plugin's
            // solver preset, which a `Startup` system may still change.
            configure_parameters_for(integration_parameters, solver);
            preset_set = true;
        }
        let hooks_installed = app.is_plugin_added::<CreepRapierPlugin>();
        let mut state = app.world_mut().resource_mut::<CreepFriction>();
        state.default_context_preset = preset_set;
        state.warned.insert(WarnKey::Global("finished"));
        if !hooks_installed && !self.custom_hooks {
            state.warn(WarnKey::Global("hooks"), CreepWarning::HooksNotInstalled);
        }
    }

    fn is_unique(&self) -> bool {
        false
    }
}

/// The context the plugin serves: the default one, else the only one.
fn served_context<'a>(contexts: impl Iterator<Item = (Entity, bool)> + 'a) -> Option<Entity> {
    let mut only = None;
    let mut count = 0;
    for (e, is_default) in contexts {
        if is_default {
            return Some(e);
        }
        only = Some(e);
        count += 1;
    }
    if count == 1 { only } else { None }
}

/// Sets the integration parameters of every new context before its first step
/// ([`creep_rapier::configure_parameters_for`]): what creep-rapier requires
/// (`FrictionModel::Coulomb`, no contact clustering; a later change draws a warning in
/// [`pre_step`]) and the solver preset of the plugin's settings (`CreepSettings::solver`):
/// by default [`SolverPreset::Rolling`], one solver substep with
/// [`creep_rapier::ROLLING_PGS_ITERATIONS`] Gauss-Seidel iterations, what rolling balls and
/// wheels need at game steps (creep-rapier's `SolverPreset` docs: Rapier's four substeps make
/// a fast-rolling ball float and slide); [`CreepFrictionPlugin::with_rapier_solver`] keeps
/// the context's own. The default context got the preset at its creation, from
/// bevy_rapier3d's `RapierContextInitialization` (in [`CreepFrictionPlugin`]'s `finish`), so
/// that a `Startup` system's changes hold; parameters changed later are kept too.
fn configure_new_contexts(
    state: Res<CreepFriction>,
    mut contexts: Query<
        (
            Entity,
            &mut RapierContextSimulation,
            Has<DefaultRapierContext>,
        ),
        Added<RapierContextSimulation>,
    >,
) {
    if !state.configure_parameters {
        return;
    }
    for (entity, mut sim, is_default) in &mut contexts {
        let preset = if is_default && state.default_context_preset {
            SolverPreset::Rapier // the preset is set already; keep what Startup changed
        } else {
            state.settings().solver
        };
        configure_parameters_for(&mut sim.integration_parameters, preset);
        debug!("creep-friction: context {entity}: integration parameters set ({preset:?})");
    }
}

/// Gives new `CreepMaterial` colliders their density (unless they have their own mass
/// properties), before bevy_rapier3d creates their Rapier colliders.
fn apply_density(
    mut commands: Commands,
    new: Query<(Entity, &CreepMaterial), (Added<CreepMaterial>, Without<ColliderMassProperties>)>,
) {
    for (entity, mat) in &new {
        commands
            .entity(entity)
            .try_insert(ColliderMassProperties::Density(mat.density()));
    }
}

/// Keeps the registry in step with the `CreepMaterial` components.
fn sync_materials(
    mut state: ResMut<CreepFriction>,
    contexts: Query<(Entity, &RapierContextColliders, Has<DefaultRapierContext>)>,
    changed: Query<
        (Entity, &CreepMaterial),
        Or<(
            Changed<CreepMaterial>,
            Changed<Collider>,
            Added<RapierContextEntityLink>,
        )>,
    >,
    materials: Query<&CreepMaterial>,
    without_collider: Query<Entity, (Added<CreepMaterial>, Without<Collider>)>,
    links: Query<&RapierContextEntityLink>,
) {
    let state = &mut *state;
    let Some(ctx) = served_context(contexts.iter().map(|(e, _, d)| (e, d))) else {
        return;
    };
    let Ok((_, colliders, _)) = contexts.get(ctx) else {
        return;
    };
    for entity in &without_collider {
        state.warn(
            WarnKey::Entity("no-collider", entity),
            CreepWarning::NoCollider { entity },
        );
    }
    // Forget the colliders whose material was removed (they lose the creep hook) or that are
    // gone from the context (despawned, or their `Collider` removed). A check of every
    // registered collider rather than `RemovedComponents`, which a schedule that does not run
    // every frame (`FixedUpdate`) can miss.
    let gone: Vec<(Entity, _, bool)> = state
        .handles
        .iter()
        .filter_map(|(e, h)| {
            let alive = colliders
                .colliders
                .get(*h)
                .is_some_and(|c| c.user_data as u64 == e.to_bits());
            let has_material = materials.contains(*e);
            (!alive || !has_material).then_some((*e, *h, alive))
        })
        .collect();
    for (entity, handle, alive) in gone {
        state.handles.remove(&entity);
        state.entities.remove(&handle);
        state.pipeline.hooks.registry_mut().remove(handle);
        if alive {
            state.unhook.push(handle);
            state.restore_groups.push((handle, entity));
        } else if materials.contains(entity) {
            state.pending.insert(entity);
        }
    }
    state.pending.retain(|e| materials.contains(*e));
    // New or changed materials and shapes, and the ones still waiting for their collider.
    let mut todo: Vec<Entity> = changed.iter().map(|(e, _)| e).collect();
    todo.extend(state.pending.drain());
    todo.sort_unstable();
    todo.dedup();
    for entity in todo {
        let Ok(mat) = materials.get(entity) else {
            continue;
        };
        let Some(&handle) = colliders.entity2collider().get(&entity) else {
            match links.get(entity) {
                Ok(link) if link.0 != ctx => state.warn(
                    WarnKey::Entity("context", entity),
                    CreepWarning::OtherContext { entity },
                ),
                _ => {
                    // Its collider is not created yet (or it has none, warned above).
                    state.pending.insert(entity);
                }
            }
            continue;
        };
        let Some(collider) = colliders.colliders.get(handle) else {
            state.pending.insert(entity);
            continue;
        };
        let mut m = mat.to_rapier();
        let shape_name = || format!("{:?}", collider.shape().shape_type());
        match supported_shape(collider) {
            None => {
                state.warn(
                    WarnKey::Entity("shape", entity),
                    CreepWarning::UnsupportedShape {
                        entity,
                        shape: shape_name(),
                    },
                );
                m.regime = Regime::Rigid(Fidelity::Coulomb);
                m.rolling = RollingResistance::None;
                m.crown = None;
            }
            Some(shape) if m.crown.is_some() && !shape.is_wheel() => {
                state.warn(
                    WarnKey::Entity("crown", entity),
                    CreepWarning::CrownIgnored {
                        entity,
                        shape: shape_name(),
                    },
                );
                m.crown = None;
            }
            Some(_) => {}
        }
        if let Err(error) = m.validate() {
            // Registered as it is, the material would stop every step (creep-rapier refuses
            // it before the step): this collider alone stays Coulomb.
            state.warn(
                WarnKey::Entity("invalid-material", entity),
                CreepWarning::InvalidMaterial { entity, error },
            );
            m.regime = Regime::Rigid(Fidelity::Coulomb);
            m.rolling = RollingResistance::None;
            m.crown = None;
        }
        if let Some(old) = state.handles.insert(entity, handle)
            && old != handle
        {
            state.entities.remove(&old);
            state.pipeline.hooks.registry_mut().remove(old);
        }
        if !m.is_compliant()
            && state
                .pipeline
                .hooks
                .registry()
                .get(handle)
                .is_some_and(|old| old.is_compliant())
        {
            state.restore_groups.push((handle, entity));
        }
        state.entities.insert(handle, entity);
        state.pipeline.hooks.registry_mut().insert(handle, m);
    }
}

/// Gives a collider its solver groups back: its entity's `SolverGroups`, or Rapier's default.
fn restore_solver_groups(
    colliders: &mut rapier3d::prelude::ColliderSet,
    handle: rapier3d::prelude::ColliderHandle,
    entity: Entity,
    groups: &Query<&SolverGroups>,
) {
    let wanted: rapier3d::prelude::InteractionGroups =
        groups.get(entity).map(|g| (*g).into()).unwrap_or_default();
    if let Some(co) = colliders.get(handle)
        && co.solver_groups() != wanted
        && let Some(co) = colliders.get_mut(handle)
    {
        co.set_solver_groups(wanted);
    }
}

/// The time step bevy_rapier3d's `step_simulation` is about to take (the same arithmetic), or
/// `None` if it will not step.
fn step_dt(mode: Option<&TimestepMode>, time: &Time, params: &IntegrationParameters) -> f32 {
    match mode.copied() {
        Some(TimestepMode::Fixed { dt, substeps }) => dt / (substeps as f32),
        Some(TimestepMode::Variable {
            max_dt,
            time_scale,
            substeps,
        }) => (time.delta_secs() * time_scale).min(max_dt) / (substeps as f32),
        Some(TimestepMode::Interpolated {
            dt,
            time_scale,
            substeps,
        }) => dt / (substeps as f32) * time_scale,
        None => params.dt,
    }
}

/// Before the step: checks (and sets) the integration parameters, then
/// `CreepPipeline::prepare_host_step`.
fn pre_step(
    mut state: ResMut<CreepFriction>,
    mode: Option<Res<TimestepMode>>,
    time: Res<Time>,
    mut contexts: Query<(
        Entity,
        &mut RapierContextSimulation,
        &mut RapierContextColliders,
        &mut RapierRigidBodySet,
        &RapierConfiguration,
        Has<DefaultRapierContext>,
    )>,
    solver_groups: Query<&SolverGroups>,
) {
    let state = &mut *state;
    state.armed = false;
    let Some(ctx) = served_context(contexts.iter().map(|c| (c.0, c.5))) else {
        return;
    };
    let Ok((_, mut sim, mut colliders, mut bodies, config, _)) = contexts.get_mut(ctx) else {
        return;
    };
    // Colliders whose material was removed lose the creep hook.
    for handle in std::mem::take(&mut state.unhook) {
        if let Some(co) = colliders.colliders.get(handle)
            && co
                .active_hooks()
                .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
            && let Some(co) = colliders.colliders.get_mut(handle)
        {
            co.set_active_hooks(co.active_hooks() - ActiveHooks::MODIFY_SOLVER_CONTACTS);
        }
    }
    // Colliders that left the compliant regime get their solver groups back (the entity's
    // `SolverGroups`, or Rapier's default).
    for (handle, entity) in std::mem::take(&mut state.restore_groups) {
        restore_solver_groups(&mut colliders.colliders, handle, entity, &solver_groups);
    }
    if !config.physics_pipeline_active || config.simulation_mode != SimulationMode::Full {
        return;
    }
    if let Err(error) = creep_rapier::check_parameters(&sim.integration_parameters) {
        let time_step = matches!(error, PluginError::TimeStep(_));
        if state.configure_parameters && !time_step {
            // What the plugin requires only: the solver's iterations stay the user's.
            configure_parameters_for(&mut sim.integration_parameters, SolverPreset::Rapier);
        }
        if !time_step {
            let configured = state.configure_parameters;
            state.warn(
                WarnKey::Entity("parameters", ctx),
                CreepWarning::Parameters {
                    context: ctx,
                    error,
                    configured,
                },
            );
            if !configured {
                return;
            }
        }
    }
    let mut params = sim.integration_parameters;
    params.dt = step_dt(mode.as_deref(), &time, &params);
    if !(params.dt > 0.0) {
        return; // bevy_rapier3d takes no step this run
    }
    if state.pipeline.hooks.is_step_prepared() {
        // The last prepared step was never finished (its post-step found no context): undo it.
        state.pipeline.cancel_host_step(&mut bodies.bodies);
    }
    // With the island manager: the preparation visits the colliders of awake bodies only
    // (as `CreepWorld::step`), so that a settled scene whose bodies sleep costs what it costs
    // plain Rapier.
    if let Err(error) = state.pipeline.prepare_host_step_with_islands(
        &params,
        &sim.islands,
        &mut bodies.bodies,
        &mut colliders.colliders,
        &sim.narrow_phase,
    ) {
        // Not armed: the hook leaves every contact to Rapier (Coulomb), compliant pairs
        // included: they get their solver groups back for this step (the pipeline takes them
        // out of the solve again before the next).
        let compliant: Vec<_> = state
            .pipeline
            .registry()
            .iter()
            .filter(|(_, m)| m.is_compliant())
            .filter_map(|(h, _)| state.entities.get(h).map(|e| (*h, *e)))
            .collect();
        for (handle, entity) in compliant {
            restore_solver_groups(&mut colliders.colliders, handle, entity, &solver_groups);
        }
        state.warn(WarnKey::Global("step"), CreepWarning::Step { error });
        return;
    }
    state.armed = true;
}

/// After the step: `CreepPipeline::finish_host_step` (compliant user forces restored,
/// contact-torque impulses, sweep), the counts, the warnings about colliders without materials
/// and about several steps per run.
fn post_step(
    mut state: ResMut<CreepFriction>,
    mut contexts: Query<(
        Entity,
        &RapierContextSimulation,
        &RapierContextColliders,
        &mut RapierRigidBodySet,
        Has<DefaultRapierContext>,
    )>,
) {
    let state = &mut *state;
    if !std::mem::take(&mut state.armed) {
        return;
    }
    let Some(ctx) = served_context(contexts.iter().map(|c| (c.0, c.4))) else {
        return;
    };
    let Ok((_, sim, colliders, mut bodies, _)) = contexts.get_mut(ctx) else {
        return;
    };
    let steps = sim.step_stats().num_steps;
    state.pipeline.report_quarantine(sim.pipeline.quarantine());
    if steps == 0 {
        // No step ran (Interpolated mode ahead of real time): undo the preparation.
        state.pipeline.cancel_host_step(&mut bodies.bodies);
        return;
    }
    if steps > 1 {
        state.warn(
            WarnKey::Global("steps"),
            CreepWarning::StepsPerRun { steps },
        );
    }
    match state.pipeline.finish_host_step(&mut bodies.bodies) {
        Ok(counts) => state.counts = counts,
        Err(error) => {
            state.warn(WarnKey::Global("step"), CreepWarning::Step { error });
            return;
        }
    }
    // creep-rapier's own warnings (each given once there), with entities for handles. Its
    // `Unregistered` is this plugin's `MissingMaterial` (below), which names the entity.
    let entity_of_collider = |h| {
        colliders
            .colliders
            .get(h)
            .and_then(|c| Entity::try_from_bits(c.user_data as u64))
    };
    for w in state.counts.warnings.clone() {
        let warning = match w {
            creep_rapier::CreepWarning::RotationGap {
                collider,
                rim_speed,
                turn,
                substeps,
            } => CreepWarning::RotationGap {
                entity: entity_of_collider(collider),
                rim_speed,
                turn,
                substeps,
            },
            creep_rapier::CreepWarning::NothingRegistered { colliders } => {
                CreepWarning::NothingRegistered { colliders }
            }
            creep_rapier::CreepWarning::Quarantined { body } => CreepWarning::Quarantined {
                entity: bodies
                    .bodies
                    .get(body)
                    .and_then(|b| Entity::try_from_bits(b.user_data as u64)),
            },
            creep_rapier::CreepWarning::Unregistered { .. } => continue,
        };
        state.give(warning);
    }
    state.steps += 1;

    // Look for the colliders without material (all contact pairs: at the first occurrence,
    // then every 64th step, to bound the cost in large scenes).
    if state.counts.coulomb_unregistered > 0
        && state.warn_missing_material
        && state.missing_warned < MAX_MISSING_MATERIAL_WARNINGS
        && (state.missing_warned == 0 || state.steps.is_multiple_of(64))
    {
        let mut missing = Vec::new();
        for pair in sim.narrow_phase.contact_pairs() {
            if !pair.has_any_active_contact() {
                continue;
            }
            let (r1, r2) = (
                state.entities.contains_key(&pair.collider1),
                state.entities.contains_key(&pair.collider2),
            );
            if r1 == r2 {
                continue;
            }
            let other = if r1 { pair.collider2 } else { pair.collider1 };
            if let Some(entity) = colliders
                .colliders
                .get(other)
                .and_then(|c| Entity::try_from_bits(c.user_data as u64))
            {
                missing.push(entity);
            }
        }
        for entity in missing {
            if state.missing_warned >= MAX_MISSING_MATERIAL_WARNINGS {
                break;
            }
            let key = WarnKey::Entity("material", entity);
            if !state.warned.contains(&key) {
                state.missing_warned += 1;
                state.warn(key, CreepWarning::MissingMaterial { entity });
            }
        }
    }
}
