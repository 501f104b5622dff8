//! The quick start of creep-bevy's README, line for line (`tests/quick_start.rs` checks that the
//! README shows these lines and runs them headless: the ball keeps 0.999 of its energy over
//! 10 s and its height within 0.1 mm). `cargo run -p creep-bevy --example quick_start
//! --ignore-rust-version` runs it without a window (this crate's Bevy has no renderer unless
//! the `render` feature is on); in a game of your own, add your camera, lights and meshes.

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use creep_bevy::prelude::*;

fn main() {
    App::new()
        .add_plugins((DefaultPlugins, physics))
        .add_systems(Startup, scene)
        .run();
}

/// bevy_rapier3d with the creep hooks, creep-friction (one solver substep, its default), and
/// one Rapier step of 1/60 s per frame.
pub fn physics(app: &mut App) {
    app.add_plugins((CreepRapierPlugin::default(), CreepFrictionPlugin::default()))
        .insert_resource(TimestepMode::Fixed {
            dt: 1.0 / 60.0,
            substeps: 1,
        });
}

/// A steel floor (its top face at y = 0) and a steel ball of radius 0.1 m launched rolling
/// at 5 m/s (its spin is 5 m/s over the radius). mu comes from `Friction`.
pub fn scene(mut commands: Commands) {
    commands.spawn((
        RigidBody::Fixed,
        Collider::cuboid(100.0, 0.5, 100.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
        Friction::coefficient(0.5),
        CreepMaterial::steel(),
    ));
    commands.spawn((
        RigidBody::Dynamic,
        Collider::ball(0.1),
        Transform::from_xyz(-40.0, 0.1, 0.0),
        Friction::coefficient(0.5),
        CreepMaterial::steel(),
        Velocity {
            linear: Vec3::new(5.0, 0.0, 0.0),
            angular: Vec3::new(0.0, 0.0, -50.0),
        },
    ));
}
