//! What a user gets with the plugin's defaults and the documented recipe only, and what the
//! plugin says when a setup falls back to plain Rapier.

use creep_law::Material;
use creep_rapier::prelude::*;
use rapier3d::prelude::*;

const G: f64 = 9.81;

/// The documented recipe: `CreepWorld::new` with default settings, a steel floor and a 0.1 m
/// steel ball, both registered (`insert` with a material: the ball takes steel's density), their
/// friction the material's.
fn steel_world(dt: f32, settings: CreepSettings) -> (CreepWorld, CreepMaterial) {
    let mut w = CreepWorld::new(dt, settings).unwrap();
    let steel = CreepMaterial::new(Material::steel());
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1000.0, 0.5, 1000.0).friction(Material::steel().friction() as f32),
        Some(steel),
    );
    (w, steel)
}

fn ball(w: &mut CreepWorld, steel: CreepMaterial, x: f32, v: f32) -> RigidBodyHandle {
    let r = 0.1;
    w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(x, r, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -v / r)),
        ColliderBuilder::ball(r).friction(Material::steel().friction() as f32),
        Some(steel),
    )
    .0
}

fn energy(rb: &RigidBody) -> f64 {
    let v = f64::from(rb.linvel().length());
    let w = rb.angvel();
    let i = rb.mass_properties().local_mprops.principal_inertia();
    let m = f64::from(rb.mass());
    0.5 * m * v * v
        + 0.5 * f64::from(i.x * w.x * w.x + i.y * w.y * w.y + i.z * w.z * w.z)
        + m * G * f64::from(rb.translation().y)
}

/// Item: a 0.1 m steel ball launched rolling at 5 m/s at 1/60 s with nothing but the defaults
/// keeps 0.999 of its energy over 10 s and stays within 0.1 mm of the height of a twin at
/// rest (plain Rapier's four substeps: it floats 2.2 mm and loses 17 % in the first second).
#[test]
fn a_fast_ball_at_game_steps_keeps_its_energy_and_height_with_the_defaults() {
    let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default());
    let fast = ball(&mut w, steel, 0.0, 5.0);
    let rest = ball(&mut w, steel, -5.0, 0.0);
    // Let the resting twin settle into its contact first (it sets the rest height).
    let e0 = energy(&w.physics.bodies[fast]);
    let (mut worst_dy, mut warnings) = (0.0f64, Vec::new());
    for _ in 0..600 {
        let c = w.step().unwrap();
        warnings.extend(c.warnings);
        let y = f64::from(w.physics.bodies[fast].translation().y);
        let y_rest = f64::from(w.physics.bodies[rest].translation().y);
        worst_dy = worst_dy.max((y - y_rest).abs());
    }
    let kept = energy(&w.physics.bodies[fast]) / e0;
    let v = w.physics.bodies[fast].linvel().x;
    eprintln!("defaults: energy kept {kept:.6}, worst |y - y_rest| {worst_dy:.3e} m, v {v:.4} m/s");
    assert!((0.999..=1.0 + 1e-4).contains(&kept), "energy kept {kept}");
    assert!(worst_dy < 1e-4, "height off by {worst_dy} m");
    assert!(warnings.is_empty(), "{warnings:?}");
}

/// With Rapier's substeps kept (`SolverPreset::Rapier`) the same ball gets one warning naming
/// the setting, once.
#[test]
fn a_fast_ball_with_substeps_warns_once_naming_the_setting() {
    let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default().with_rapier_solver());
    assert_eq!(w.physics.integration_parameters.num_solver_iterations, 4);
    ball(&mut w, steel, 0.0, 5.0);
    ball(&mut w, steel, 3.0, 5.0);
    let mut warnings = Vec::new();
    for _ in 0..60 {
        warnings.extend(w.step().unwrap().warnings);
    }
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert!(matches!(
        warnings[0],
        CreepWarning::RotationGap { substeps: 4, .. }
    ));
    let text = warnings[0].to_string();
    eprintln!("{text}");
    assert!(text.contains("num_solver_iterations = 1"), "{text}");
    // A slow ball does not warn.
    let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default().with_rapier_solver());
    ball(&mut w, steel, 0.0, 0.5);
    for _ in 0..60 {
        assert!(w.step().unwrap().warnings.is_empty());
    }
}

/// An unregistered collider touching registered ones: one warning per collider (not per step
/// or contact), none with the opt-out; a world without any registered collider says so once.
#[test]
fn unregistered_colliders_are_warned_about_once_each() {
    for warn in [true, false] {
        let settings = CreepSettings {
            warn_unregistered: warn,
            ..CreepSettings::default()
        };
        let (mut w, steel) = steel_world(1.0 / 60.0, settings);
        for x in [0.0, 1.0] {
            // Unregistered balls rolling on the registered floor.
            w.insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(x, 0.1, 0.0))
                    .linvel(Vector::new(1.0, 0.0, 0.0)),
                ColliderBuilder::ball(0.1),
                None,
            );
        }
        ball(&mut w, steel, 3.0, 1.0);
        let mut warnings = Vec::new();
        for _ in 0..100 {
            warnings.extend(w.step().unwrap().warnings);
        }
        let n = warnings
            .iter()
            .filter(|w| matches!(w, CreepWarning::Unregistered { .. }))
            .count();
        assert_eq!(n, if warn { 2 } else { 0 }, "{warnings:?}");
        if warn {
            eprintln!("{}", warnings[0]);
        }
    }
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    w.physics.insert(
        RigidBodyBuilder::dynamic(),
        ColliderBuilder::ball(0.1).build(),
    );
    let first = w.step().unwrap().warnings;
    assert!(
        matches!(
            first[..],
            [CreepWarning::NothingRegistered { colliders: 1 }]
        ),
        "{first:?}"
    );
    eprintln!("{}", first[0]);
    assert!(w.step().unwrap().warnings.is_empty());
}

/// A NaN or negative friction on the unregistered partner of a registered collider is a typed
/// error, and no NaN reaches the bodies.
#[test]
fn bad_friction_of_an_unregistered_partner_is_a_typed_error() {
    for bad in [f32::NAN, -0.5] {
        let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default());
        let b = ball(&mut w, steel, 0.0, 1.0);
        // An unregistered block the ball runs into.
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(0.3, 0.1, 0.0)),
            ColliderBuilder::cuboid(0.1, 0.1, 0.1).friction(bad),
            None,
        );
        let mut error = None;
        for _ in 0..60 {
            if let Err(e) = w.step() {
                error = Some(e);
                break;
            }
        }
        assert!(
            matches!(error, Some(PluginError::Friction { .. })),
            "{bad}: {error:?}"
        );
        let rb = &w.physics.bodies[b];
        assert!(rb.linvel().is_finite() && rb.translation().is_finite());
    }
}

/// Bodies Rapier quarantines (their state went non-finite) are reported in the step's counts.
#[test]
fn quarantined_bodies_are_reported() {
    let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default());
    let b = ball(&mut w, steel, 0.0, 1.0);
    w.physics.bodies[b].set_linvel(Vector::new(f32::NAN, 0.0, 0.0), true);
    let c = w.step().unwrap();
    assert_eq!(c.quarantined_bodies, vec![b], "{c:?}");
    assert!(
        c.warnings
            .iter()
            .any(|x| matches!(x, CreepWarning::Quarantined { body } if *body == b))
    );
    eprintln!("{}", c.warnings[0]);
    assert!(w.step().unwrap().quarantined_bodies.is_empty());
}

/// With the spin cap lifted (one substep, a registered ball) a ball thrown at 1e4 m/s ends
/// with its rim speed within Rapier's linear speed cap.
#[test]
fn the_lifted_spin_cap_keeps_the_rim_speed_within_the_linear_cap() {
    let (mut w, steel) = steel_world(1.0 / 60.0, CreepSettings::default());
    let b = w
        .insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, 0.1, 0.0))
                .linvel(Vector::new(1.0e4, 0.0, 0.0)),
            ColliderBuilder::ball(0.1),
            Some(steel),
        )
        .0;
    let cap = w.physics.integration_parameters.max_linear_velocity();
    let mut worst = 0.0f32;
    for _ in 0..600 {
        w.step().unwrap();
        let rb = &w.physics.bodies[b];
        worst = worst.max(rb.angvel().length() * 0.1);
    }
    let rb = &w.physics.bodies[b];
    eprintln!(
        "v {} m/s, omega R {} m/s (worst {worst}), cap {cap}",
        rb.linvel().length(),
        rb.angvel().length() * 0.1
    );
    assert!(worst <= cap * 1.001, "omega R {worst} > {cap}");
}
