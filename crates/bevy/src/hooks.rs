//! The physics-hooks `SystemParam` that bevy_rapier3d gives to Rapier: it delegates to
//! creep-rapier's [`creep_rapier::CreepHooks`] held in the [`crate::CreepFriction`] resource.

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier3d::pipeline::{BevyPhysicsHooks, ContactModificationContextView};
use bevy_rapier3d::prelude::RapierPhysicsPlugin;
use rapier3d::pipeline::{ContactModificationContext, PhysicsHooks};

use crate::state::CreepFriction;

/// bevy_rapier3d's physics hooks with creep-friction: give it to `RapierPhysicsPlugin`
/// (`RapierPhysicsPlugin::<CreepPhysicsHooks>::default()`, or [`CreepRapierPlugin`]).
///
/// With hooks of your own, put a `CreepPhysicsHooks<'w>` field in your `SystemParam`, call
/// [`CreepPhysicsHooks::modify_solver_contacts_raw`] from your `modify_solver_contacts`, and
/// add the plugin with [`crate::CreepFrictionPlugin::with_custom_hooks`].
///
/// Without the [`crate::CreepFrictionPlugin`] (no [`CreepFriction`] resource) it does nothing.
#[derive(SystemParam)]
pub struct CreepPhysicsHooks<'w> {
    state: Option<Res<'w, CreepFriction>>,
}

/// bevy_rapier3d's physics plugin with the creep hooks.
pub type CreepRapierPlugin = RapierPhysicsPlugin<CreepPhysicsHooks<'static>>;

impl CreepPhysicsHooks<'_> {
    /// Rapier's `modify_solver_contacts` with creep-friction, on the raw Rapier context (what
    /// `ContactModificationContextView::raw` holds). Acts only inside a step the plugin started
    /// (its systems run around bevy_rapier3d's `PhysicsSet::StepSimulation`) and only on
    /// colliders of the context it serves.
    pub fn modify_solver_contacts_raw(&self, context: &mut ContactModificationContext) {
        let Some(state) = self.state.as_deref() else {
            return;
        };
        if !state.armed
            || !state.owns(context.colliders, context.collider1)
            || !state.owns(context.colliders, context.collider2)
        {
            return;
        }
        state.pipeline.hooks.modify_solver_contacts(context);
    }
}

impl BevyPhysicsHooks for CreepPhysicsHooks<'_> {
    fn modify_solver_contacts(&self, context: ContactModificationContextView) {
        self.modify_solver_contacts_raw(context.raw);
    }
}
