//! Gizmos (feature `gizmos`): each contact's creep slip and tangential force as lines from its
//! contact point, coloured by [`ContactState`]. Bevy's gizmo API collects the lines headless;
//! an app with a renderer (`bevy_gizmos_render`, the demos' `render` feature) shows them.

use bevy::prelude::*;
use bevy_rapier3d::prelude::{
    DefaultRapierContext, RapierContextColliders, RapierContextSimulation,
};

use crate::contacts::ContactState;
use crate::state::CreepFriction;

/// What the gizmos draw, and at which scale. Insert it (or use
/// [`crate::CreepFrictionPlugin::with_gizmos`]) to switch the gizmos on.
#[derive(Resource, Debug, Clone, Copy, PartialEq)]
pub struct CreepGizmos {
    /// Length drawn per unit of tangential force [m/N].
    pub force_scale: f32,
    /// Length drawn per unit of creep slip velocity [m/(m/s)] (creep slips are small: 1e-4 of
    /// the rolling speed for steel).
    pub slip_scale: f32,
    /// Colour of a sticking contact's force.
    pub stick: Color,
    /// Colour of a creeping contact's force.
    pub creep: Color,
    /// Colour of a sliding contact's force.
    pub slip: Color,
    /// Colour of the creep slip line.
    pub slip_line: Color,
}

impl Default for CreepGizmos {
    fn default() -> Self {
        Self {
            force_scale: 0.01,
            slip_scale: 100.0,
            stick: Color::srgb(0.2, 0.4, 1.0),
            creep: Color::srgb(1.0, 0.8, 0.1),
            slip: Color::srgb(1.0, 0.2, 0.2),
            slip_line: Color::srgb(0.2, 1.0, 0.4),
        }
    }
}

/// Draws the contacts of the served context (runs after the physics writeback).
pub fn draw_creep_gizmos(
    settings: Option<Res<CreepGizmos>>,
    state: Res<CreepFriction>,
    contexts: Query<(
        &RapierContextSimulation,
        &RapierContextColliders,
        Has<DefaultRapierContext>,
    )>,
    mut gizmos: Gizmos,
) {
    let Some(settings) = settings else {
        return;
    };
    let Some((sim, colliders, _)) = contexts.iter().find(|c| c.2).or_else(|| {
        (contexts.iter().count() == 1)
            .then(|| contexts.iter().next())
            .flatten()
    }) else {
        return;
    };
    for c in state.creep_contacts(sim, colliders) {
        let colour = match c.state {
            ContactState::Stick => settings.stick,
            ContactState::Creep => settings.creep,
            ContactState::Slip => settings.slip,
        };
        gizmos.line(c.point, c.point + c.force * settings.force_scale, colour);
        if c.slip != Vec3::ZERO {
            gizmos.line(
                c.point,
                c.point + c.slip * settings.slip_scale,
                settings.slip_line,
            );
        }
    }
}
