//! The gizmos (feature `gizmos`): without Bevy's `GizmoPlugin` the drawing system is skipped and
//! nothing panics; with it (an app with DefaultPlugins) it draws the contacts.
#![cfg(feature = "gizmos")]

mod common;

use common::*;
use creep_bevy::{CreepFrictionPlugin, CreepGizmos, CreepMaterial, Fidelity};

// Bevy's `GizmoPlugin` with `MinimalPlugins` + `AssetPlugin` fails the validation of one of its
// own systems ("Resource does not exist", even without this plugin's gizmos): it needs a
// resource that a fuller plugin set (DefaultPlugins) provides. Run with the demos' renderer.
#[test]
#[ignore = "bevy_gizmos' GizmoPlugin needs more than MinimalPlugins + AssetPlugin headless"]
fn gizmos_draw_headless() {
    let p = incline();
    let mut app = app_unfinished(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default().with_gizmos(CreepGizmos::default()),
    );
    app.add_plugins((
        bevy::asset::AssetPlugin::default(),
        bevy::gizmos::GizmoPlugin,
    ));
    app.finish();
    app.cleanup();
    let mat = CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep);
    spawn_incline(&mut app, &p, Some(mat), Some(mat));
    for _ in 0..60 {
        app.update();
    }
    assert!(state(&app).counts().creep > 0);
}

#[test]
fn gizmos_without_gizmo_plugin_do_nothing() {
    let p = incline();
    let mut app = app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default().with_gizmos(CreepGizmos::default()),
    );
    let mat = CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep);
    spawn_incline(&mut app, &p, Some(mat), Some(mat));
    for _ in 0..10 {
        app.update();
    }
    assert!(state(&app).counts().creep > 0);
}
