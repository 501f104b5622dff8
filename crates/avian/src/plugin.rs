//! [`CreepAvianPlugin`]: the resource, the hook flags and the per-step bookkeeping.

use avian3d::dynamics::solver::constraint_graph::ConstraintGraph;
use avian3d::dynamics::solver::schedule::SolverSystems;
use avian3d::prelude::*;
use bevy::prelude::*;
use creep_law::CreepModel;

use crate::hooks::{CreepHooks, v3};
use crate::material::CreepMaterial;
use crate::state::{CreepSettings, CreepState, CreepWarning};

/// Creep-friction for Avian. Install [`crate::CreepHooks`] as Avian's collision hooks, add this
/// plugin, and give colliders a [`CreepMaterial`]:
///
/// ```no_run
/// use avian3d::prelude::*;
/// use bevy::prelude::*;
/// use creep_avian::prelude::*;
/// App::new()
///     .add_plugins((MinimalPlugins, TransformPlugin))
///     .add_plugins((
///         PhysicsPlugins::default().with_collision_hooks::<CreepHooks>(),
///         CreepAvianPlugin::default(),
///     ))
///     .add_systems(Startup, |mut commands: Commands| {
///         commands.spawn((RigidBody::Dynamic, Collider::sphere(0.1), CreepMaterial::steel()));
///     })
///     .run();
/// ```
///
/// What it does:
/// - inserts [`CreepState`] (settings, records, counts, warnings);
/// - gives each `CreepMaterial` collider `ActiveCollisionHooks::MODIFY_CONTACTS` (a required
///   component; an existing `ActiveCollisionHooks` without the flag gets it, with a warning);
/// - after Avian's solver has stored its impulses, reads each creep contact's normal and
///   tangential impulses from Avian's contact constraints into the records (the hook runs
///   before Avian copies last step's impulses into the new manifolds, so it cannot read them
///   there), and closes the step's counts;
/// - warns (Bevy `warn!`, and [`CreepState::warnings`]) and leaves the contact to Coulomb,
///   never panics, on: a collider touching a creep collider without a material, a shape other
///   than a ball or a flat one, an invalid material, invalid settings, the creep hooks not
///   installed as Avian's narrow-phase hooks.
#[derive(Debug, Clone, Copy, Default)]
pub struct CreepAvianPlugin {
    settings: CreepSettings,
}

impl CreepAvianPlugin {
    /// The plugin with these settings (validated when the plugin is built: invalid settings
    /// draw a warning and the defaults are used).
    pub fn with_settings(mut self, settings: CreepSettings) -> Self {
        self.settings = settings;
        self
    }
    /// The saturated creep slip \[m/s\] below which `Fidelity::Auto` contacts stay Coulomb.
    pub fn with_auto_tolerance(mut self, tolerance: f64) -> Self {
        self.settings.auto_tolerance = tolerance;
        self
    }
    /// Offsets creep pairs' penetration by the mean rotation gap of the step's substeps
    /// ([`CreepSettings::rotation_gap_correction`]).
    pub fn with_rotation_gap_correction(mut self, on: bool) -> Self {
        self.settings.rotation_gap_correction = on;
        self
    }
    /// The steady creep law (Kalker's `F_ss` by default).
    pub fn with_creep_model(mut self, model: CreepModel) -> Self {
        self.settings.creep_model = model;
        self
    }
}

impl Plugin for CreepAvianPlugin {
    fn build(&self, app: &mut App) {
        let state = match self.settings.validate() {
            Ok(()) => CreepState::new(self.settings),
            Err(why) => {
                let state = CreepState::new(CreepSettings::default());
                state.lock().warn(CreepWarning::InvalidSettings(why));
                state
            }
        };
        app.insert_resource(state);
        app.register_required_components_with::<CreepMaterial, ActiveCollisionHooks>(|| {
            ActiveCollisionHooks::MODIFY_CONTACTS
        });
        app.add_systems(
            PhysicsSchedule,
            (
                (add_missing_hook_flags, begin_step).in_set(PhysicsStepSystems::First),
                harvest
                    .in_set(PhysicsStepSystems::Solver)
                    .after(SolverSystems::StoreContactImpulses),
            ),
        );
    }

    fn finish(&self, app: &mut App) {
        if !app.is_plugin_added::<NarrowPhasePlugin<Collider, CreepHooks>>() {
            if let Some(state) = app.world().get_resource::<CreepState>() {
                state.lock().warn(CreepWarning::HooksNotInstalled);
            }
        }
    }
}

/// Gives `MODIFY_CONTACTS` to creep colliders whose `ActiveCollisionHooks` lack it.
fn add_missing_hook_flags(
    mut commands: Commands,
    state: Res<CreepState>,
    query: Query<(Entity, &ActiveCollisionHooks), With<CreepMaterial>>,
) {
    for (e, flags) in &query {
        if !flags.contains(ActiveCollisionHooks::MODIFY_CONTACTS) {
            state.lock().warn(CreepWarning::HookFlagAdded(e));
            commands
                .entity(e)
                .insert(*flags | ActiveCollisionHooks::MODIFY_CONTACTS);
        }
    }
}

/// Starts a step's counts.
fn begin_step(state: Res<CreepState>) {
    let mut inner = state.lock();
    inner.counts = Default::default();
    inner.hook_calls = 0;
}

/// Copies each creep contact's impulses of the step from Avian's constraints into the records,
/// drops the records of pairs that generated no constraint, closes the counts.
fn harvest(
    graph: Res<ConstraintGraph>,
    state: Res<CreepState>,
    time: Res<Time>,
    substeps: Res<SubstepCount>,
) {
    let dt = time.delta_secs_f64();
    let mut inner = state.lock();
    inner.steps += 1;
    if dt > 0.0 {
        // Per-substep impulse to force: the last substep's accumulated impulses (normal and
        // friction) over the substep's time.
        let per_substep = f64::from(substeps.0.max(1)) / dt;
        for color in &graph.colors {
            for c in &color.contact_constraints {
                let Some(Some(rec)) = inner.records.get_mut(c.contact_id.0 as usize) else {
                    continue;
                };
                rec.harvested = true;
                let Some(prev) = rec.points.get_mut(c.manifold_index) else {
                    continue;
                };
                let Some(point) = c.points.first() else {
                    continue;
                };
                let n = c.normal;
                let t1 = c.tangent1;
                let t2 = t1.cross(n);
                let j = point
                    .tangent_part
                    .as_ref()
                    .map_or(Vec3::ZERO, |t| t.impulse.x * t1 + t.impulse.y * t2);
                // The solver applies +j to body 2 and -j to body 1.
                prev.q_meas = v3(-j) * per_substep;
                prev.p = f64::from(point.normal_part.impulse) * per_substep;
            }
        }
    }
    for slot in inner.records.iter_mut() {
        if let Some(rec) = slot {
            if rec.harvested {
                rec.harvested = false;
            } else {
                *slot = None;
            }
        }
    }
    inner.last = inner.counts;
}
