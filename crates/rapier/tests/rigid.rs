//! Rigid-regime tests: the plugin in Rapier's own solver, against closed forms.

use creep_law::Material;
use creep_law::rolling_torque::RollingModel;
use creep_rapier::*;
use rapier3d::prelude::*;

const G: f64 = 9.81;

/// A 0.1 m steel ball on a steel plane with gravity tilted by `theta` (an incline of angle
/// theta, without the geometry of a tilted box). Returns the world and the ball.
fn incline(dt: f32, theta: f64, fidelity: Fidelity) -> (CreepWorld, RigidBodyHandle) {
    let mut w = CreepWorld::new(dt, CreepSettings::default()).unwrap();
    w.physics.gravity = Vector::new((G * theta.sin()) as f32, (-G * theta.cos()) as f32, 0.0);
    let steel =
        CreepMaterial::new(Material::steel().with_friction(0.5).unwrap()).with_fidelity(fidelity);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1000.0, 0.5, 10.0).friction(0.5),
        Some(steel),
    );
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.1, 0.0))
            .can_sleep(false),
        ColliderBuilder::ball(0.1).density(7850.0).friction(0.5),
        Some(steel),
    );
    (w, ball)
}

#[test]
fn anchor_drift_correction_stops_the_sinking() {
    let run = |correct: bool| {
        let settings = CreepSettings {
            anchor_drift_correction: correct,
            ..Default::default()
        };
        let (mut w, ball) = incline(1.0 / 60.0, 20f64.to_radians(), Fidelity::Coulomb);
        w.hooks = CreepHooks::new(w.hooks.registry().clone(), settings).unwrap();
        for _ in 0..60 {
            w.step().unwrap();
        }
        f64::from(w.physics.bodies[ball].translation().y) - 0.1
    };
    let (with, without) = (run(true), run(false));
    println!(
        "sinking after 1 s at 1/60 s: {without:.2e} m without, {with:.2e} m with the correction"
    );
    assert!(without < -2e-3, "{without}");
    assert!(with.abs() < 0.25 * without.abs(), "{with} vs {without}");
}

#[test]
fn constant_rolling_torque_stops_the_ball_at_the_closed_form_distance() {
    // Ai et al. (2011) type A, M = mu_r R P: a ball rolling without slip decelerates at
    // a = mu_r g R^2 m / (R^2 m + I) = (5/7) mu_r g, so it stops after 7 v0^2 / (10 mu_r g).
    let (mu_r, v0) = (0.02, 1.0);
    let mut w = CreepWorld::new(1.0 / 240.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel())
        .with_rolling(RollingModel::constant_torque(mu_r).unwrap());
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1000.0, 0.5, 10.0),
        Some(steel),
    );
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.1, 0.0))
            .linvel(Vector::new(v0, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -(v0 / 0.1)))
            .can_sleep(false),
        ColliderBuilder::ball(0.1).density(7850.0),
        Some(steel),
    );
    // Stops after v0 / ((5/7) mu_r g) = 7.3 s; run 9 s.
    for _ in 0..240 * 9 {
        w.step().unwrap();
    }
    let b = &w.physics.bodies[ball];
    let x = f64::from(b.translation().x);
    let expect = 7.0 * f64::from(v0).powi(2) / (10.0 * mu_r * G);
    println!("stopping distance {x:.4} m vs {expect:.4} m");
    assert!((x / expect - 1.0).abs() < 0.01, "{x} vs {expect}");
    assert!(
        f64::from(b.linvel().length()) < 1e-3,
        "still moving: {:?}",
        b.linvel()
    );
}

#[test]
fn unknown_colliders_fall_back_to_coulomb() {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel());
    w.insert(
        RigidBodyBuilder::fixed(),
        ColliderBuilder::cuboid(10.0, 0.1, 10.0),
        Some(steel),
    );
    // Opted in to the hook but not registered.
    let c = ColliderBuilder::ball(0.1).active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
    w.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.2, 0.0)),
        c,
        None,
    );
    // A capsule: not a shape creep-law models (Creep fidelity keeps its hook on at rest).
    w.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(1.0, 0.3, 0.0)),
        ColliderBuilder::capsule_y(0.1, 0.1),
        Some(steel.with_fidelity(Fidelity::Creep)),
    );
    let mut seen = StepCounts::default();
    for _ in 0..30 {
        let c = w.step().unwrap();
        seen.coulomb_unregistered += c.coulomb_unregistered;
        seen.coulomb_unsupported += c.coulomb_unsupported;
    }
    assert!(
        seen.coulomb_unregistered > 0 && seen.coulomb_unsupported > 0,
        "{seen:?}"
    );
}

#[test]
fn wrong_integration_parameters_are_a_clear_error() {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    w.physics.integration_parameters.friction_model = FrictionModel::Simplified;
    assert_eq!(w.step(), Err(PluginError::FrictionModel));
    let mut p = IntegrationParameters::default();
    configure_parameters(&mut p);
    assert_eq!(check_parameters(&p), Ok(()));
    p.contact_clustering = true;
    assert_eq!(check_parameters(&p), Err(PluginError::ContactClustering));
    p.contact_clustering = false;
    p.dt = f32::NAN;
    assert!(matches!(
        check_parameters(&p),
        Err(PluginError::TimeStep(_))
    ));
    let bad = CreepSettings {
        auto_tolerance: -1.0,
        ..Default::default()
    };
    assert!(CreepHooks::new(MaterialRegistry::new(), bad).is_err());
}

#[test]
fn contact_records_stay_bounded_over_a_million_create_destroy_cycles() {
    // Each cycle a new contact appears and the previous one ends: the sweep keeps memory flat.
    let mut store = ContactStore::default();
    let h = |i: u32| ColliderHandle::from_raw_parts(i, 0);
    for i in 0..1_000_000u32 {
        store.begin_step();
        store.touch(ContactKey {
            collider1: h(i),
            collider2: h(i + 1),
            feature1: i,
            feature2: 0,
        });
        store.sweep();
        assert!(store.len() <= 1);
    }
    store.begin_step();
    store.sweep();
    assert!(store.is_empty());
}

#[test]
fn records_are_dropped_when_a_body_is_removed() {
    let (mut w, ball) = incline(1.0 / 60.0, 0.3, Fidelity::Creep);
    for _ in 0..10 {
        w.step().unwrap();
    }
    assert_eq!(w.hooks.live_contacts(), 1);
    w.remove_body(ball);
    w.step().unwrap();
    assert_eq!(w.hooks.live_contacts(), 0);
}

#[test]
fn quiet_bodies_switch_their_hooks_off_and_moving_ones_on() {
    // A ball resting on a floor (Auto): below the activation speed its collider's hook is off,
    // so its contacts keep Rapier's recycling; pushed, it comes back on and creeps.
    let (mut w, ball) = incline(1.0 / 60.0, 0.0, Fidelity::Auto);
    for _ in 0..120 {
        w.step().unwrap();
    }
    assert_eq!(w.hooks.counts().hooks_on, 0);
    let collider = w.physics.bodies[ball].colliders()[0];
    assert!(
        !w.physics.colliders[collider]
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    );
    w.physics.bodies[ball].set_linvel(Vector::new(1.0, 0.0, 0.0), true);
    w.step().unwrap();
    assert_eq!(w.hooks.counts().hooks_on, 1);
    assert!(
        w.physics.colliders[collider]
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    );
    let bad = CreepSettings {
        activation_speed: f64::NAN,
        ..Default::default()
    };
    assert!(CreepHooks::new(MaterialRegistry::new(), bad).is_err());
}
