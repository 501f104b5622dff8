//! A Bevy app (MinimalPlugins, no window, no GPU) steps the same physics as the Rapier-only
//! path: the incline scene of creep-scenes (a 0.1 m steel ball on a 20 degree steel incline,
//! dt = 1/240 s), built the same way in both, gives the same trajectory within 1e-6 m over 600
//! steps, for each fidelity.

mod common;

use bevy::prelude::*;
use common::*;
use creep_bevy::{CreepFrictionPlugin, CreepMaterial, Fidelity};
use creep_law::rolling_torque::RollingModel;
use creep_rapier::StepCounts;
use creep_scenes::incline::InclineParams;

const STEPS: usize = 600;
const TOLERANCE: f32 = 1e-6;

/// The Rapier-only path: `CreepWorld` with the bodies of crates/scenes/src/incline.rs
/// (`run_one`), stepped `STEPS` times; the ball's pose and the plugin's counts after each step.
fn rapier_run(
    p: &InclineParams,
    mat: Option<creep_rapier::CreepMaterial>,
) -> Vec<([Vec3; 2], StepCounts)> {
    let (mut w, ball) = creep_scenes::incline::world(p, mat).expect("world");
    let r = p.radius as f32;
    (0..STEPS)
        .map(|_| {
            let counts = w.step().expect("step");
            let b = &w.physics.bodies[ball];
            let (t, q) = (b.translation(), *b.rotation());
            let t = Vec3::new(t.x, t.y, t.z);
            let q = Quat::from_xyzw(q.x, q.y, q.z, q.w);
            ([t, t + q * Vec3::new(0.0, r, 0.0)], counts)
        })
        .collect()
}

/// The Bevy path: the same bodies as entities, `CreepMaterial` on both colliders, and the
/// scene's solver (Rapier's own: `with_rapier_solver`).
fn bevy_run(p: &InclineParams, mat: Option<CreepMaterial>) -> Vec<([Vec3; 2], StepCounts)> {
    let mut app = app(
        p.dt as f32,
        incline_gravity(p),
        CreepFrictionPlugin::default().with_rapier_solver(),
    );
    let (_, ball) = spawn_incline(&mut app, p, mat, mat);
    (0..STEPS)
        .map(|_| {
            app.update();
            (
                pose(&app, ball, p.radius as f32),
                state(&app).counts().clone(),
            )
        })
        .collect()
}

/// Largest distance between the two runs' poses over all steps [m].
fn max_gap(a: &[([Vec3; 2], StepCounts)], b: &[([Vec3; 2], StepCounts)]) -> f32 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .flat_map(|((pa, _), (pb, _))| [pa[0].distance(pb[0]), pa[1].distance(pb[1])])
        .fold(0.0, f32::max)
}

fn compare(name: &str, mat: Option<CreepMaterial>) -> Vec<([Vec3; 2], StepCounts)> {
    let p = incline();
    let rapier = rapier_run(&p, mat.map(|m| m.to_rapier()));
    let bevy = bevy_run(&p, mat);
    let gap = max_gap(&rapier, &bevy);
    let travelled = bevy.last().unwrap().0[0].x;
    println!(
        "{name}: largest gap Bevy vs Rapier over {STEPS} steps = {gap:e} m (ball travelled {travelled:.4} m)"
    );
    assert!(gap <= TOLERANCE, "{name}: gap {gap:e} m > {TOLERANCE:e} m");
    // The same plugin decisions, step by step.
    for (i, ((_, cr), (_, cb))) in rapier.iter().zip(&bevy).enumerate() {
        if mat.is_some() {
            assert_eq!(cr, cb, "{name}: counts differ at step {i}");
        }
    }
    assert!(
        travelled > 5.0,
        "{name}: the ball must roll down ({travelled} m)"
    );
    bevy
}

#[test]
fn incline_creep_same_trajectory_as_rapier() {
    let creep = compare(
        "creep",
        Some(CreepMaterial::new(incline().material).with_fidelity(Fidelity::Creep)),
    );
    let last = &creep.last().unwrap().1;
    assert!(
        last.creep > 0,
        "the contact must take the creep path: {last:?}"
    );
    assert!(last.creep_power > 0.0, "creep dissipates power: {last:?}");

    // Creep is not a no-op: against a Coulomb run of the same scene the ball's surface point
    // ends elsewhere (the contact slips forward by ~3e-4 of the rolled distance).
    let coulomb = compare(
        "coulomb",
        Some(CreepMaterial::new(incline().material).with_fidelity(Fidelity::Coulomb)),
    );
    let (pc, pk) = (coulomb.last().unwrap().0, creep.last().unwrap().0);
    let apart = pc[1].distance(pk[1]);
    println!("surface point, creep vs Coulomb after {STEPS} steps: {apart:e} m");
    assert!(apart > 1e-4, "creep changes the rolling: {apart:e} m");
    let lc = &coulomb.last().unwrap().1;
    assert_eq!(lc.creep, 0);
    assert!(lc.coulomb_requested > 0);
}

#[test]
fn incline_auto_same_trajectory_as_rapier() {
    compare("auto", Some(CreepMaterial::new(incline().material)));
}

#[test]
fn incline_rolling_torque_same_trajectory_as_rapier() {
    let bevy = compare(
        "rolling torque",
        Some(
            CreepMaterial::new(incline().material)
                .with_fidelity(Fidelity::Coulomb)
                .with_rolling(RollingModel::ConstantTorque { mu_r: 0.01 }),
        ),
    );
    assert!(bevy.last().unwrap().1.rolling_torque > 0);
}

#[test]
fn incline_without_materials_is_plain_rapier() {
    compare("no material", None);
}

#[test]
fn creep_contacts_show_the_incline_contact() {
    let p = incline();
    let mut app = app(
        p.dt as f32,
        incline_gravity(&p),
        CreepFrictionPlugin::default(),
    );
    let mat = CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep);
    let (floor, ball) = spawn_incline(&mut app, &p, Some(mat), Some(mat));
    for _ in 0..240 {
        app.update();
    }
    let mut q = app.world_mut().query::<(
        &bevy_rapier3d::prelude::RapierContextSimulation,
        &bevy_rapier3d::prelude::RapierContextColliders,
    )>();
    let (sim, colliders) = q.single(app.world()).unwrap();
    let contacts = state(&app).creep_contacts(sim, colliders);
    assert_eq!(contacts.len(), 1, "{contacts:?}");
    let c = contacts[0];
    let ball_x = app.world().get::<Transform>(ball).unwrap().translation.x;
    println!("incline contact after 1 s: {c:?}");
    assert_eq!(c.state, creep_bevy::ContactState::Creep);
    assert!(
        [c.collider1, c.collider2].contains(&floor) && [c.collider1, c.collider2].contains(&ball)
    );
    // Under the ball, on the incline's surface (the narrow phase's point, from the start of the
    // last step: up to v dt = 1 cm behind the ball at 2.4 m/s).
    assert!(
        (c.point.x - ball_x).abs() < 0.02 && c.point.y.abs() < 1e-3,
        "{:?} vs {ball_x}",
        c.point
    );
    // Rolling without slip transmits Q = (2/7) m g sin(theta) at P = m g cos(theta) (the creep
    // changes this by ~3e-4).
    let m = p.material.density() * 4.0 / 3.0 * std::f64::consts::PI * p.radius.powi(3);
    let q_expect = 2.0 / 7.0 * m * creep_scenes::incline::G * p.theta.sin();
    let p_expect = m * creep_scenes::incline::G * p.theta.cos();
    assert!(
        (f64::from(c.force.length()) / q_expect - 1.0).abs() < 0.01,
        "{} vs {q_expect}",
        c.force.length()
    );
    assert!(
        (f64::from(c.normal_force) / p_expect - 1.0).abs() < 0.01,
        "{} vs {p_expect}",
        c.normal_force
    );
    // The creep slip is along the force the contact transmits to the ball (down the incline
    // is +x): ball is q if the floor is collider1.
    assert!(
        c.slip.length() > 0.0 && c.slip.x.abs() > 0.99 * c.slip.length(),
        "{:?}",
        c.slip
    );
}
