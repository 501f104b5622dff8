//! Misuse gives a clear warning and a Coulomb fallback, never a panic: the plugin added twice, a
//! missing material, a non-sphere collider, the hooks not installed, unsuitable integration
//! parameters, several steps per run, a material without a collider, invalid settings.

mod common;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::*;
use creep_bevy::{
    CreepFriction, CreepFrictionPlugin, CreepMaterial, CreepSettings, CreepWarning, Fidelity,
};

fn creep_steel() -> CreepMaterial {
    CreepMaterial::new(incline().material).with_fidelity(Fidelity::Creep)
}

fn default_app() -> App {
    let p = incline();
    app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default(),
    )
}

fn run(app: &mut App, n: usize) {
    for _ in 0..n {
        app.update();
    }
}

fn has(app: &App, f: impl Fn(&CreepWarning) -> bool) -> bool {
    state(app).warnings().iter().any(f)
}

#[test]
fn plugin_added_twice_warns_and_still_works() {
    let p = incline();
    let mut app = app_unfinished(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default(),
    );
    app.add_plugins(CreepFrictionPlugin::default().with_settings(CreepSettings {
        activation_speed: 5.0,
        ..Default::default()
    }));
    app.finish();
    app.cleanup();
    spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 60);
    let s = state(&app);
    assert!(
        s.warnings().contains(&CreepWarning::PluginAddedTwice),
        "{:?}",
        s.warnings()
    );
    assert_eq!(s.warnings().len(), 1, "{:?}", s.warnings());
    // The first plugin's settings hold, and it runs once per step.
    assert_eq!(
        s.settings().activation_speed,
        CreepSettings::default().activation_speed
    );
    assert_eq!(s.steps(), 60);
    assert!(s.counts().creep > 0, "{:?}", s.counts());
}

#[test]
fn missing_material_warns_and_stays_coulomb() {
    let mut app = default_app();
    let p = incline();
    let (floor, ball) = spawn_incline(&mut app, &p, None, Some(creep_steel()));
    run(&mut app, 30);
    let s = state(&app);
    assert!(
        s.warnings()
            .contains(&CreepWarning::MissingMaterial { entity: floor }),
        "{:?}",
        s.warnings()
    );
    assert_eq!(s.warnings().len(), 1, "once only: {:?}", s.warnings());
    let c = s.counts();
    assert!(c.coulomb_unregistered > 0, "{c:?}");
    assert_eq!(c.creep, 0, "{c:?}");
    assert_eq!(s.collider_handle(floor), None);
    assert!(s.collider_handle(ball).is_some());

    // The fallback is Rapier's own Coulomb: the same trajectory as an app without materials.
    let mut plain = default_app();
    let (_, plain_ball) = spawn_incline(&mut plain, &p, None, None);
    run(&mut plain, 30);
    let r = p.radius as f32;
    let (a, b) = (pose(&app, ball, r), pose(&plain, plain_ball, r));
    assert!(
        a[0].distance(b[0]) <= 1e-6 && a[1].distance(b[1]) <= 1e-6,
        "{a:?} vs {b:?}"
    );
}

#[test]
fn missing_material_warning_can_be_silenced() {
    let p = incline();
    let mut app = app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default().warn_missing_material(false),
    );
    spawn_incline(&mut app, &p, None, Some(creep_steel()));
    run(&mut app, 10);
    assert!(
        state(&app).warnings().is_empty(),
        "{:?}",
        state(&app).warnings()
    );
    assert!(state(&app).counts().coulomb_unregistered > 0);
}

#[test]
fn non_sphere_collider_warns_and_stays_coulomb() {
    let mut app = default_app();
    let p = incline();
    let mu = p.material.friction() as f32;
    app.world_mut().spawn((
        RigidBody::Fixed,
        Transform::from_xyz(0.0, -0.5, 0.0),
        Collider::cuboid(1.0e4, 0.5, 10.0),
        Friction::coefficient(mu),
        creep_steel(),
    ));
    let capsule = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(0.0, 0.2, 0.0)
                .with_rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
            Collider::capsule_y(0.1, 0.1),
            Friction::coefficient(mu),
            Sleeping::disabled(),
            creep_steel(),
        ))
        .id();
    set_physics_active(&mut app, true);
    run(&mut app, 60);
    let s = state(&app);
    assert!(
        s.warnings().iter().any(|w| matches!(
            w,
            CreepWarning::UnsupportedShape { entity, shape } if *entity == capsule && shape.contains("Capsule")
        )),
        "{:?}",
        s.warnings()
    );
    let msg = s.warnings()[0].to_string();
    assert!(msg.contains("stays Coulomb"), "{msg}");
    let c = s.counts();
    assert!(c.coulomb_unsupported > 0, "{c:?}");
    assert_eq!(c.creep, 0, "{c:?}");
    // It rolled down the incline without any NaN.
    let t = app.world().get::<Transform>(capsule).unwrap().translation;
    assert!(t.is_finite() && t.x > 0.01, "{t:?}");
}

#[test]
fn hooks_not_installed_warns() {
    let p = incline();
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        RapierPhysicsPlugin::<NoUserData>::default(),
        CreepFrictionPlugin::default(),
    ));
    app.insert_resource(TimestepMode::Fixed {
        dt: p.dt as f32,
        substeps: 1,
    });
    app.finish();
    app.cleanup();
    spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 10);
    assert!(has(&app, |w| *w == CreepWarning::HooksNotInstalled));
    assert_eq!(state(&app).counts().creep, 0);

    // With hooks of one's own that delegate, the warning can be switched off.
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        RapierPhysicsPlugin::<NoUserData>::default(),
        CreepFrictionPlugin::default().with_custom_hooks(),
    ));
    app.finish();
    app.cleanup();
    run(&mut app, 2);
    assert!(state(&app).warnings().is_empty());
}

#[test]
fn unsuitable_parameters_are_set_with_a_warning() {
    let mut app = default_app();
    let p = incline();
    spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 5);
    assert!(
        state(&app).warnings().is_empty(),
        "{:?}",
        state(&app).warnings()
    );
    // Someone switches the friction model back to Rapier's default.
    let mut q = app.world_mut().query::<&mut RapierContextSimulation>();
    let mut sim = q.single_mut(app.world_mut()).unwrap();
    sim.integration_parameters.friction_model = FrictionModel::Simplified;
    run(&mut app, 5);
    assert!(has(&app, |w| matches!(
        w,
        CreepWarning::Parameters {
            configured: true,
            ..
        }
    )));
    let mut q = app.world_mut().query::<&RapierContextSimulation>();
    let sim = q.single(app.world()).unwrap();
    assert!(creep_rapier::check_parameters(&sim.integration_parameters).is_ok());
    assert!(state(&app).counts().creep > 0);
}

#[test]
fn unsuitable_parameters_without_configuring_stay_coulomb() {
    let p = incline();
    let mut app = app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default().without_configuring_parameters(),
    );
    spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 10);
    assert!(has(&app, |w| matches!(
        w,
        CreepWarning::Parameters {
            configured: false,
            ..
        }
    )));
    assert_eq!(state(&app).steps(), 0, "the plugin took part in no step");
    assert_eq!(state(&app).counts().creep, 0);
}

#[test]
fn several_steps_per_run_warn() {
    let mut app = default_app();
    app.insert_resource(TimestepMode::Fixed {
        dt: 1.0 / 120.0,
        substeps: 2,
    });
    let p = incline();
    spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 10);
    assert!(has(&app, |w| *w == CreepWarning::StepsPerRun { steps: 2 }));
}

#[test]
fn material_without_collider_warns() {
    let mut app = default_app();
    let e = app
        .world_mut()
        .spawn((Transform::default(), creep_steel()))
        .id();
    run(&mut app, 3);
    assert!(has(&app, |w| *w == CreepWarning::NoCollider { entity: e }));
}

#[test]
fn invalid_settings_are_refused() {
    let p = incline();
    let bad = CreepSettings {
        auto_tolerance: -1.0,
        ..Default::default()
    };
    let mut app = app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default().with_settings(bad),
    );
    run(&mut app, 1);
    assert!(has(&app, |w| matches!(
        w,
        CreepWarning::InvalidSettings { .. }
    )));
    assert_eq!(*state(&app).settings(), CreepSettings::default());
    let mut s = app.world_mut().resource_mut::<CreepFriction>();
    assert!(s.set_settings(bad).is_err());
    assert_eq!(*s.settings(), CreepSettings::default());
}

#[test]
fn material_sets_density_and_follows_the_component() {
    let mut app = default_app();
    let p = incline();
    let (floor, ball) = spawn_incline(&mut app, &p, Some(creep_steel()), Some(creep_steel()));
    run(&mut app, 2);
    let r = p.radius;
    let expected = p.material.density() * 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
    let mass = app.world().get::<ReadMassProperties>(ball).unwrap().mass;
    assert!(
        (f64::from(mass) - expected).abs() <= 1e-5 * expected,
        "{mass} vs {expected}"
    );
    assert_eq!(state(&app).registered(), 2);

    // Removing the material: the collider is forgotten and loses the creep hook.
    let handle = state(&app).collider_handle(ball).unwrap();
    app.world_mut().entity_mut(ball).remove::<CreepMaterial>();
    run(&mut app, 2);
    assert_eq!(state(&app).registered(), 1);
    assert_eq!(state(&app).collider_handle(ball), None);
    let mut q = app.world_mut().query::<&RapierContextColliders>();
    let colliders = q.single(app.world()).unwrap();
    let flags = colliders.colliders.get(handle).unwrap().active_hooks();
    assert!(!flags.contains(rapier3d::prelude::ActiveHooks::MODIFY_SOLVER_CONTACTS));
    // ... and the floor, now touching an unregistered ball, warns about it.
    run(&mut app, 2);
    assert!(has(&app, |w| *w
        == CreepWarning::MissingMaterial { entity: ball }));

    // Despawning a creep collider forgets it too.
    app.world_mut().despawn(floor);
    run(&mut app, 2);
    assert_eq!(state(&app).registered(), 0);
}

#[test]
fn compliant_regime_errors_warn_and_stay_coulomb() {
    // Compliant steel at dt = 1/240 s (far above the Rayleigh time step, ~1e-5 s for a 0.1 m
    // ball) and 4 solver iterations: creep-rapier refuses the step; the plugin warns and leaves
    // the contact to Rapier.
    let mut app = default_app();
    let p = incline();
    let m = CreepMaterial::compliant(p.material);
    let (_, ball) = spawn_incline(&mut app, &p, Some(m), Some(m));
    run(&mut app, 120);
    assert!(
        has(&app, |w| matches!(w, CreepWarning::Step { .. })),
        "{:?}",
        state(&app).warnings()
    );
    // Rapier's rigid contact held the ball on the incline, rolling down.
    let t = app.world().get::<Transform>(ball).unwrap().translation;
    assert!(
        t.is_finite() && (t.y - p.radius as f32).abs() < 1e-3 && t.x > 0.1,
        "{t:?}"
    );
}

/// Set in the child process of [`warnings_reach_stderr_without_log_plugin`].
const CHILD: &str = "CREEP_BEVY_WARNINGS_CHILD";

#[test]
fn warnings_reach_stderr_without_log_plugin() {
    if std::env::var_os(CHILD).is_some() {
        // The child: `MinimalPlugins` (no `LogPlugin`, no tracing subscriber) and a misuse.
        let mut app = default_app();
        app.world_mut().spawn((Transform::default(), creep_steel()));
        run(&mut app, 3);
        assert_eq!(state(&app).warnings().len(), 1);
        return;
    }
    // This test again, alone, in a child process whose output is not captured.
    let out = std::process::Command::new(std::env::current_exe().unwrap())
        .args([
            "--exact",
            "warnings_reach_stderr_without_log_plugin",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .output()
        .expect("the test binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let lines: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("WARN creep-friction:"))
        .collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(
        lines[0].contains("has a CreepMaterial but no Collider"),
        "{stderr}"
    );
}

/// A rubber floor (top face at y = 0) and a rubber cylinder on it as a wheel (axis along z,
/// rolling along x at 0.5 m/s), with `material`; returns the wheel.
fn spawn_wheel(app: &mut App, material: CreepMaterial) -> Entity {
    app.world_mut().spawn((
        RigidBody::Fixed,
        Transform::from_xyz(0.0, -0.5, 0.0),
        Collider::cuboid(100.0, 0.5, 10.0),
        Friction::coefficient(0.9),
        CreepMaterial::rubber().with_fidelity(Fidelity::Creep),
    ));
    let wheel = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(0.0, 0.05, 0.0),
            Sleeping::disabled(),
            Velocity {
                linear: Vec3::new(0.5, 0.0, 0.0),
                angular: Vec3::new(0.0, 0.0, -10.0),
            },
            // Only the rotation about the axle and the travel are free (no joint here).
            LockedAxes::ROTATION_LOCKED_X | LockedAxes::ROTATION_LOCKED_Y,
        ))
        .id();
    app.world_mut().spawn((
        Collider::cylinder(0.01, 0.05),
        Transform::from_rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
        Friction::coefficient(0.9),
        material,
        ChildOf(wheel),
    ));
    wheel
}

fn level_app() -> App {
    app(
        1.0 / 240.0,
        Vec3::new(0.0, -9.81, 0.0),
        CreepFrictionPlugin::default(),
    )
}

#[test]
fn a_cylinder_is_a_wheel_with_or_without_a_crown() {
    // On the incline (gravity tilted 20 degrees along x): the wheel rolls down, driven by its
    // contact's tangential force, and creeps.
    for crown in [None, Some(0.1)] {
        let mut app = default_app();
        let m = CreepMaterial::rubber().with_fidelity(Fidelity::Creep);
        spawn_wheel(&mut app, crown.map_or(m, |c| m.with_crown(c)));
        set_physics_active(&mut app, true);
        run(&mut app, 60);
        let s = state(&app);
        assert!(s.warnings().is_empty(), "{crown:?}: {:?}", s.warnings());
        let c = s.counts();
        assert!(c.creep > 0, "{crown:?}: {c:?}");
        assert_eq!(c.coulomb_unsupported, 0, "{crown:?}: {c:?}");
    }
}

#[test]
fn a_bad_crown_or_a_crown_on_a_ball_warns() {
    // A crown radius that is not > 0: that wheel alone stays Coulomb, the step goes on.
    let mut app = level_app();
    spawn_wheel(&mut app, CreepMaterial::rubber().with_crown(-1.0));
    set_physics_active(&mut app, true);
    run(&mut app, 30);
    let s = state(&app);
    assert!(
        has(&app, |w| matches!(w, CreepWarning::InvalidMaterial { .. })),
        "{:?}",
        s.warnings()
    );
    assert_eq!(s.warnings().len(), 1, "{:?}", s.warnings());
    assert_eq!(s.steps(), 30, "the plugin kept stepping");
    assert!(s.warnings()[0].to_string().contains("stays Coulomb"));

    // A crown on a ball is ignored, with a word.
    let mut app = default_app();
    let p = incline();
    let (_, ball) = spawn_incline(
        &mut app,
        &p,
        Some(creep_steel()),
        Some(creep_steel().with_crown(0.2)),
    );
    run(&mut app, 30);
    let s = state(&app);
    assert!(
        s.warnings().iter().any(|w| matches!(
            w,
            CreepWarning::CrownIgnored { entity, shape } if *entity == ball && shape.contains("Ball")
        )),
        "{:?}",
        s.warnings()
    );
    assert!(s.counts().creep > 0, "{:?}", s.counts());
}
