//! The compliant (soft-sphere DEM) regime through Bevy steps the same physics as the Rapier-only
//! path: an oblique impact of a 10 mm glass sphere on a glass wall (restitution 0.9, mu 0.3,
//! dt = 0.2 of the Rayleigh time step, one solver iteration, no gravity), same trajectory within
//! 1e-6 m (the sphere's centre and a surface point) over the whole impact.

mod common;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::*;
use creep_bevy::{CreepFrictionPlugin, CreepMaterial, CreepSettings};
use creep_law::Material;
use creep_rapier::CreepWorld;
use rapier3d::prelude::{ColliderBuilder, RigidBodyBuilder, Vector};

const R: f32 = 0.01;
const E: f32 = 0.9;
const MU: f32 = 0.3;
const STEPS: usize = 300;

fn glass() -> CreepMaterial {
    CreepMaterial::compliant(Material::glass())
}

fn dt() -> f32 {
    let m = Material::glass();
    let t_r = creep_law::hertz::rayleigh_time_step(&m, f64::from(R));
    (0.2 * t_r) as f32
}

const Y0: f32 = R + 2e-5;
const V0: [f32; 3] = [0.3, -1.0, 0.0];

fn rapier_run() -> Vec<[Vec3; 2]> {
    let mut w = CreepWorld::new(dt(), CreepSettings::default()).unwrap();
    w.physics.gravity = Vector::ZERO;
    w.physics.integration_parameters.num_solver_iterations = 1;
    let m = glass();
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.05, 0.0)),
        ColliderBuilder::cuboid(1.0, 0.05, 1.0)
            .restitution(E)
            .friction(MU),
        Some(m.to_rapier()),
    );
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, Y0, 0.0))
            .linvel(Vector::new(V0[0], V0[1], V0[2])),
        ColliderBuilder::ball(R)
            .density(m.density())
            .restitution(E)
            .friction(MU),
        Some(m.to_rapier()),
    );
    (0..STEPS)
        .map(|_| {
            w.step().unwrap();
            let b = &w.physics.bodies[ball];
            let (t, q) = (b.translation(), *b.rotation());
            let t = Vec3::new(t.x, t.y, t.z);
            let q = Quat::from_xyzw(q.x, q.y, q.z, q.w);
            [t, t + q * Vec3::new(0.0, R, 0.0)]
        })
        .collect()
}

#[test]
fn compliant_impact_same_trajectory_as_rapier() {
    let rapier = rapier_run();

    let mut app = App::new();
    let params = IntegrationParameters {
        num_solver_iterations: 1,
        ..Default::default()
    };
    let init = RapierContextInitialization::InitializeDefaultRapierContext {
        integration_parameters: params,
        rapier_configuration: RapierConfiguration {
            gravity: Vec3::ZERO,
            physics_pipeline_active: false,
            ..RapierConfiguration::new(1.0)
        },
        broad_phase_optimization_strategy: BroadPhaseOptimizationStrategy::default(),
    };
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        creep_bevy::CreepRapierPlugin::default().with_custom_initialization(init),
        CreepFrictionPlugin::default(),
    ));
    app.insert_resource(TimestepMode::Fixed {
        dt: dt(),
        substeps: 1,
    });
    app.finish();
    app.cleanup();
    app.world_mut().spawn((
        RigidBody::Fixed,
        Transform::from_xyz(0.0, -0.05, 0.0),
        Collider::cuboid(1.0, 0.05, 1.0),
        Restitution::coefficient(E),
        Friction::coefficient(MU),
        glass(),
    ));
    app.update(); // the wall first, without physics (see `spawn_incline`)
    let ball = app
        .world_mut()
        .spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(0.0, Y0, 0.0),
            Velocity::linear(Vec3::from_array(V0)),
            Collider::ball(R),
            Restitution::coefficient(E),
            Friction::coefficient(MU),
            glass(),
        ))
        .id();
    set_physics_active(&mut app, true);

    let mut gap = 0f32;
    let mut touched = 0;
    for (i, r) in rapier.iter().enumerate() {
        app.update();
        let b = pose(&app, ball, R);
        gap = gap.max(b[0].distance(r[0])).max(b[1].distance(r[1]));
        touched += state(&app).compliant_counts().contacts;
        assert!(
            state(&app).warnings().is_empty(),
            "step {i}: {:?}",
            state(&app).warnings()
        );
    }
    let v = app.world().get::<Velocity>(ball).unwrap();
    println!(
        "compliant impact: {touched} contact steps, largest gap Bevy vs Rapier {gap:e} m, \
         rebound velocity {:?}, spin {:?}",
        v.linear, v.angular
    );
    assert!(
        touched > 20,
        "the sphere must hit the wall ({touched} contact steps)"
    );
    assert!(v.linear.y > 0.5, "it rebounds: {:?}", v.linear);
    assert!(v.angular.z < 0.0, "friction spins it: {:?}", v.angular);
    assert!(gap <= 1e-6, "gap {gap:e} m");
}
