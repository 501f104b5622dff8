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
    // The rotation-gap correction is exact with one solver substep (Rapier then reads the gap
    // at the step's start and end only, which a constant and a rate follow exactly); with
    // Rapier's default four it is the gap's mean over the substeps.
    let run = |correct: bool, substeps: usize| {
        let settings = CreepSettings {
            anchor_drift_correction: correct,
            ..Default::default()
        };
        let (mut w, ball) = incline(1.0 / 60.0, 20f64.to_radians(), Fidelity::Coulomb);
        w.physics.integration_parameters.num_solver_iterations = substeps;
        *w.hooks_mut() = CreepHooks::new(w.hooks().registry().clone(), settings).unwrap();
        for _ in 0..60 {
            w.step().unwrap();
        }
        f64::from(w.physics.bodies[ball].translation().y) - 0.1
    };
    for substeps in [1, 4] {
        let (with, without) = (run(true, substeps), run(false, substeps));
        println!(
            "sinking after 1 s at 1/60 s, {substeps} substep(s): {without:.2e} m without, \
             {with:.2e} m with the correction"
        );
        if cfg!(feature = "rapier-patched") {
            // The patched Rapier reads no rotation gap on a ball: the ball stays at its
            // resting depth (7e-5 m overlap) at any substep count, and the plugin adds nothing.
            assert!(without.abs() < 1e-4, "{without}");
            assert_eq!(with, without);
        } else if substeps == 1 {
            // Rapier reads the gap at the end of the step only: plain sinking is smaller, and
            // the corrected ball stays at its resting depth (Rapier's 7e-5 m resting overlap).
            assert!(without < -2e-4, "{without}");
            assert!(
                with.abs() < 1e-4 && with.abs() < 0.5 * without.abs(),
                "{with} vs {without}"
            );
        } else {
            assert!(without < -2e-3, "{without}");
            assert!(with.abs() < 0.25 * without.abs(), "{with} vs {without}");
        }
    }
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
fn records_are_dropped_when_a_body_is_removed() {
    let (mut w, ball) = incline(1.0 / 60.0, 0.3, Fidelity::Creep);
    for _ in 0..10 {
        w.step().unwrap();
    }
    assert_eq!(w.hooks().live_contacts(), 1);
    w.remove_body(ball);
    w.step().unwrap();
    assert_eq!(w.hooks().live_contacts(), 0);
}

#[test]
fn quiet_bodies_switch_their_hooks_off_and_moving_ones_on() {
    // A ball resting on a floor (Auto): below the activation speed its collider's hook is off,
    // so its contacts keep Rapier's recycling; pushed, it comes back on and creeps.
    let (mut w, ball) = incline(1.0 / 60.0, 0.0, Fidelity::Auto);
    for _ in 0..120 {
        w.step().unwrap();
    }
    assert_eq!(w.hooks().counts().hooks_on, 0);
    let collider = w.physics.bodies[ball].colliders()[0];
    assert!(
        !w.physics.colliders[collider]
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    );
    w.physics.bodies[ball].set_linvel(Vector::new(1.0, 0.0, 0.0), true);
    w.step().unwrap();
    assert_eq!(w.hooks().counts().hooks_on, 1);
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

#[test]
fn stepping_around_the_pipeline_is_a_typed_error() {
    let (mut w, _) = incline(1.0 / 60.0, 0.0, Fidelity::Creep);
    w.step().unwrap();
    // Rapier stepped with the hooks but without the pipeline: the contacts are left to
    // Coulomb and the next step says so.
    let CreepWorld { physics, pipeline } = &mut w;
    physics.step_with_events(&pipeline.hooks, &());
    assert!(matches!(
        w.step(),
        Err(PluginError::HookOutsideStep { contacts }) if contacts > 0
    ));
    w.step().unwrap();
    // Finishing a step that was not prepared.
    assert_eq!(
        w.pipeline.finish_host_step(&mut w.physics.bodies),
        Err(PluginError::StepNotPrepared)
    );
    // Preparing twice.
    let p = &mut w.physics;
    let params = p.integration_parameters;
    let pl = &mut w.pipeline;
    pl.prepare_host_step(&params, &mut p.bodies, &mut p.colliders, &p.narrow_phase)
        .unwrap();
    assert_eq!(
        pl.prepare_host_step(&params, &mut p.bodies, &mut p.colliders, &p.narrow_phase),
        Err(PluginError::StepAlreadyPrepared)
    );
    pl.cancel_host_step(&mut p.bodies);
    w.step().unwrap();
}

#[test]
fn nan_or_negative_friction_is_a_typed_error() {
    for bad in [f32::NAN, -0.1, f32::INFINITY] {
        let (mut w, ball) = incline(1.0 / 60.0, 0.0, Fidelity::Creep);
        let c = w.physics.bodies[ball].colliders()[0];
        w.physics.colliders[c].set_friction(bad);
        assert!(
            matches!(w.step(), Err(PluginError::Friction { .. })),
            "{bad}"
        );
    }
}

#[test]
fn the_registry_follows_removals_through_rapiers_api() {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel());
    for _ in 0..2000 {
        let (b, _) = w.insert(
            RigidBodyBuilder::dynamic(),
            ColliderBuilder::ball(0.1),
            Some(steel),
        );
        let p = &mut w.physics;
        p.bodies.remove(
            b,
            &mut p.islands,
            &mut p.colliders,
            &mut p.impulse_joints,
            &mut p.multibody_joints,
            &mut p.soft_bodies,
            true,
        );
        w.step().unwrap();
    }
    assert_eq!(w.registry().len(), 0);
}

#[test]
fn the_material_density_sets_the_mass() {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel());
    let (b, _) = w.insert(
        RigidBodyBuilder::dynamic(),
        ColliderBuilder::ball(0.1),
        Some(steel),
    );
    let expected = Material::steel().density() * 4.0 / 3.0 * std::f64::consts::PI * 1e-3;
    let m = f64::from(w.physics.bodies[b].mass());
    assert!((m - expected).abs() < 1e-5 * expected, "{m} vs {expected}");
    // A collider with its own density keeps it.
    let (b, _) = w.insert(
        RigidBodyBuilder::dynamic(),
        ColliderBuilder::ball(0.1).density(1000.0),
        Some(steel),
    );
    let m = f64::from(w.physics.bodies[b].mass());
    assert!((m - 4.18879).abs() < 1e-4, "{m}");
}

#[test]
fn a_ball_creeps_on_a_trimesh_a_heightfield_and_a_convex_polyhedron() {
    let flat_grounds: Vec<ColliderBuilder> = vec![
        ColliderBuilder::trimesh(
            vec![
                Vector::new(-50.0, 0.0, -5.0),
                Vector::new(50.0, 0.0, -5.0),
                Vector::new(50.0, 0.0, 5.0),
                Vector::new(-50.0, 0.0, 5.0),
            ],
            vec![[0, 2, 1], [0, 3, 2]],
        )
        .unwrap(),
        ColliderBuilder::heightfield(
            rapier3d::geometry::Array2::repeat(3, 3, 0.0),
            Vector::new(100.0, 1.0, 10.0),
        ),
        ColliderBuilder::convex_hull(&[
            Vector::new(-50.0, -1.0, -5.0),
            Vector::new(50.0, -1.0, -5.0),
            Vector::new(50.0, -1.0, 5.0),
            Vector::new(-50.0, -1.0, 5.0),
            Vector::new(-50.0, 0.0, -5.0),
            Vector::new(50.0, 0.0, -5.0),
            Vector::new(50.0, 0.0, 5.0),
            Vector::new(-50.0, 0.0, 5.0),
        ])
        .unwrap(),
    ];
    for ground in flat_grounds {
        let mut w = CreepWorld::new(1.0 / 240.0, CreepSettings::default()).unwrap();
        let theta = 20f64.to_radians();
        w.physics.gravity = Vector::new((G * theta.sin()) as f32, (-G * theta.cos()) as f32, 0.0);
        let steel = CreepMaterial::new(Material::steel()).with_fidelity(Fidelity::Creep);
        w.insert(RigidBodyBuilder::fixed(), ground.friction(0.5), Some(steel));
        w.insert(
            RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.1, 0.0)),
            ColliderBuilder::ball(0.1).friction(0.5),
            Some(steel),
        );
        // A box on the same ground: two flat sides stay Coulomb, counted as such.
        w.insert(
            RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.1, 2.0)),
            ColliderBuilder::cuboid(0.1, 0.1, 0.1).friction(0.5),
            Some(steel),
        );
        let mut seen = StepCounts::default();
        for _ in 0..240 {
            let c = w.step().unwrap();
            seen.creep += c.creep;
            seen.coulomb_no_sphere += c.coulomb_no_sphere;
            seen.coulomb_unsupported += c.coulomb_unsupported;
            seen.creep_power += c.creep_power;
        }
        assert!(seen.creep > 200 && seen.creep_power > 0.0, "{seen:?}");
        assert!(seen.coulomb_no_sphere > 0, "{seen:?}");
        assert_eq!(seen.coulomb_unsupported, 0, "{seen:?}");
    }
}
