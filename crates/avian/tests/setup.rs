//! Bad setup is a Bevy warning and Coulomb friction, never a panic.

use avian3d::prelude::*;
use bevy::prelude::*;
use creep_avian::prelude::*;
use creep_avian::scenes::{Run, headless_app, step};

fn ball_on_floor(app: &mut App, floor: impl Bundle, ball: impl Bundle) {
    app.world_mut().spawn((
        RigidBody::Static,
        Position(Vec3::new(0.0, -0.5, 0.0)),
        floor,
    ));
    app.world_mut().spawn((
        RigidBody::Dynamic,
        Position(Vec3::new(0.0, 0.1, 0.0)),
        LinearVelocity(Vec3::new(1.0, 0.0, 0.0)),
        ball,
    ));
    for _ in 0..30 {
        step(app);
    }
}

fn warnings(app: &App) -> Vec<CreepWarning> {
    app.world().resource::<CreepState>().warnings()
}

#[test]
fn a_collider_without_material_is_coulomb_with_a_warning() {
    let mut app = headless_app(
        1.0 / 60.0,
        6,
        Vec3::new(0.0, -9.81, 0.0),
        Run::Plugin(Fidelity::Creep),
    );
    ball_on_floor(
        &mut app,
        Collider::cuboid(10.0, 1.0, 10.0),
        (Collider::sphere(0.1), CreepMaterial::steel()),
    );
    let w = warnings(&app);
    assert!(
        matches!(w.as_slice(), [CreepWarning::MissingMaterial(_)]),
        "{w:?}"
    );
    let c = app.world().resource::<CreepState>().counts();
    assert_eq!((c.creep, c.coulomb_setup), (0, 1), "{c:?}");
}

#[test]
fn an_unsupported_shape_is_coulomb_with_a_warning() {
    let mut app = headless_app(
        1.0 / 60.0,
        6,
        Vec3::new(0.0, -9.81, 0.0),
        Run::Plugin(Fidelity::Creep),
    );
    ball_on_floor(
        &mut app,
        (Collider::cuboid(10.0, 1.0, 10.0), CreepMaterial::steel()),
        (Collider::capsule(0.1, 0.2), CreepMaterial::steel()),
    );
    let w = warnings(&app);
    assert!(
        matches!(w.as_slice(), [CreepWarning::UnsupportedShape(_)]),
        "{w:?}"
    );
}

#[test]
fn a_supported_pair_creeps_without_warnings() {
    let mut app = headless_app(
        1.0 / 60.0,
        6,
        Vec3::new(0.0, -9.81, 0.0),
        Run::Plugin(Fidelity::Creep),
    );
    ball_on_floor(
        &mut app,
        (Collider::cuboid(10.0, 1.0, 10.0), CreepMaterial::steel()),
        (
            Collider::sphere(0.1),
            CreepMaterial::steel().with_fidelity(Fidelity::Creep),
        ),
    );
    assert!(warnings(&app).is_empty(), "{:?}", warnings(&app));
    assert_eq!(
        app.world().resource::<CreepState>().counts().coulomb_setup,
        0
    );
}

#[test]
fn hooks_not_installed_and_invalid_settings_warn() {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin));
    app.add_plugins((
        PhysicsPlugins::default(),
        CreepAvianPlugin::default().with_auto_tolerance(f64::NAN),
    ));
    app.finish();
    app.cleanup();
    app.update();
    let state = app.world().resource::<CreepState>();
    let w = state.warnings();
    assert!(w.contains(&CreepWarning::HooksNotInstalled), "{w:?}");
    assert!(
        w.iter()
            .any(|w| matches!(w, CreepWarning::InvalidSettings(_))),
        "{w:?}"
    );
    assert_eq!(state.settings(), CreepSettings::default());
    assert!(
        state
            .set_settings(CreepSettings {
                auto_tolerance: -1.0,
                ..Default::default()
            })
            .is_err()
    );
}
