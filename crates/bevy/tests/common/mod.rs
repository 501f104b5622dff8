//! Shared by the headless tests: a Bevy app with `MinimalPlugins` (no window, no GPU),
//! bevy_rapier3d with the creep hooks, and the incline scene of creep-scenes built the same way
//! in Bevy and in plain Rapier.
#![allow(dead_code)]

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use creep_bevy::{CreepFriction, CreepFrictionPlugin, CreepMaterial, CreepRapierPlugin};
use creep_scenes::incline::{G, InclineParams};

/// The incline scene's parameters (crates/scenes/src/incline.rs defaults: a 0.1 m steel ball,
/// mu = 0.5, on a 20 degree steel incline, dt = 1/240 s).
pub fn incline() -> InclineParams {
    InclineParams::default()
}

/// The incline's gravity, tilted by theta (as in the scene) [m/s^2].
pub fn incline_gravity(p: &InclineParams) -> Vec3 {
    Vec3::new((G * p.theta.sin()) as f32, (-G * p.theta.cos()) as f32, 0.0)
}

/// A headless app stepping bevy_rapier3d at a fixed `dt` (one Rapier step per `update`), with
/// `gravity`, the creep hooks, and `plugin`; its physics is paused until
/// [`set_physics_active`] (which [`spawn_incline`] calls).
pub fn app(dt: f32, gravity: Vec3, plugin: CreepFrictionPlugin) -> App {
    let mut app = app_unfinished(dt, gravity, plugin);
    // `App::run` does this; a test that calls `update` itself must.
    app.finish();
    app.cleanup();
    app
}

/// [`app`] before `finish` (to add more plugins).
pub fn app_unfinished(dt: f32, gravity: Vec3, plugin: CreepFrictionPlugin) -> App {
    let mut app = App::new();
    let init = RapierContextInitialization::InitializeDefaultRapierContext {
        integration_parameters: IntegrationParameters::default(),
        // Paused until a scene is spawned (see `spawn_incline`).
        rapier_configuration: RapierConfiguration {
            gravity,
            physics_pipeline_active: false,
            ..RapierConfiguration::new(1.0)
        },
        broad_phase_optimization_strategy: BroadPhaseOptimizationStrategy::default(),
    };
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        CreepRapierPlugin::default().with_custom_initialization(init),
        plugin,
    ));
    app.insert_resource(TimestepMode::Fixed { dt, substeps: 1 });
    app
}

/// Spawns the incline (a fixed 2e4 x 1 x 20 m cuboid, top face at y = 0) with `floor`, and the
/// ball (radius R, resting on it) with `ball`; returns the two entities. Runs one frame without
/// physics (the incline's) and leaves the physics running.
pub fn spawn_incline(
    app: &mut App,
    p: &InclineParams,
    floor: Option<CreepMaterial>,
    ball: Option<CreepMaterial>,
) -> (Entity, Entity) {
    let mu = p.material.friction() as f32;
    let r = p.radius as f32;
    let mut f = app.world_mut().spawn((
        RigidBody::Fixed,
        Transform::from_xyz(0.0, -0.5, 0.0),
        Collider::cuboid(1.0e4, 0.5, 10.0),
        Friction::coefficient(mu),
    ));
    if let Some(m) = floor {
        f.insert(m);
    }
    let floor = f.id();
    // Rapier numbers colliders in the order bevy_rapier3d creates them, which follows Bevy's
    // query order (by archetype), not the spawn order. The pair order decides which body is
    // Rapier's collider1, hence the rounding of every step: create the incline first, in a
    // frame without physics, as the Rapier-only scene does.
    app.update();
    set_physics_active(app, true);
    let mut b = app.world_mut().spawn((
        RigidBody::Dynamic,
        Transform::from_xyz(0.0, r, 0.0),
        Collider::ball(r),
        Friction::coefficient(mu),
        Sleeping::disabled(),
    ));
    match ball {
        Some(m) => {
            b.insert(m);
        }
        None => {
            b.insert(ColliderMassProperties::Density(p.material.density() as f32));
        }
    }
    (floor, b.id())
}

/// Pauses or resumes the Rapier pipeline of the (only) context (running the first frame,
/// which creates the context, if it has not run).
pub fn set_physics_active(app: &mut App, active: bool) {
    let mut q = app.world_mut().query::<&mut RapierConfiguration>();
    if q.iter(app.world()).next().is_none() {
        app.update(); // the context is created in the first frame
    }
    for mut c in q.iter_mut(app.world_mut()) {
        c.physics_pipeline_active = active;
    }
}

/// A body's pose as the Bevy app sees it: its centre and the point of its surface that started
/// at the top (centre + rotation * (0, R, 0)) [m], so that rotation errors show in metres.
pub fn pose(app: &App, ball: Entity, r: f32) -> [Vec3; 2] {
    let t = app.world().get::<Transform>(ball).expect("ball transform");
    [
        t.translation,
        t.translation + t.rotation * Vec3::new(0.0, r, 0.0),
    ]
}

/// The plugin's resource.
pub fn state(app: &App) -> &CreepFriction {
    app.world().resource::<CreepFriction>()
}
