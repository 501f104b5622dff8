//! `friction_drive`: a sphere driven at a fixed angular speed turns a second sphere pressed
//! onto it (its weight) against a brake torque. The output turns slower than the input by the
//! creepage: torque preserved, speed lost. Two identical drives side by side: creep-friction
//! (front) and Coulomb (back, Rapier's own rolling, the engine baseline the scene subtracts).
//! The live plot puts the measured point (Q/(mu P), normalised creepage xi G a^2/(mu P)) on
//! Kalker's curve `3/C11 [1 - (1 - Q/(mu P))^(1/3)]` (Kalker 2000; Kuhn 2011).
//!
//! The scene is creep-scenes' friction drive (`creep_scenes::friction_drive::DriveParams`:
//! R = 0.05 m, omega = 10 rad/s, dt = 1/240 s; the output's centre moves only along the line
//! of centres), as in `creep run friction-drive`.
//!
//! Keys: Up/Down raise/lower the brake torque (manual), A goes back to the automatic sweep,
//! M cycles the material (steel, glass, rubber), R restarts; and the shared keys.
//!
//! Run: `cargo run -p creep-bevy --features render --example friction_drive --ignore-rust-version --release`

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems
#![allow(clippy::needless_range_loop)] // lanes and twins indexed in parallel arrays

mod common;

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::{
    AngleMeter, DemoPlugin, OrbitCamera, PanelText, Plot, ResetRequested, Stepping, colours,
};
use creep_bevy::{CompliantSettings, CreepFriction, CreepMaterial, CreepSettings, Fidelity};
use creep_law::{PairMaterial, SteadyLaw, Surface, hertz};
use creep_scenes::friction_drive::DriveParams;
use creep_scenes::incline::G;

const USAGE: &str = "friction_drive: a driven sphere pair with a brake torque, creep vs Coulomb

usage: friction_drive [--material steel|glass|rubber] [common options]
  --material M   both spheres' material (default steel)
keys: Up/Down brake torque (manual), A automatic sweep, M material";

/// Distance between the two drives along z [m].
const TWIN: f32 = 0.25;
/// Window of the creepage measurement [s].
const WINDOW: f64 = 0.25;
/// Period of the automatic brake sweep, 0 to 0.95 mu P R and back [s].
const SWEEP: f64 = 16.0;

#[derive(Resource)]
struct Drive {
    params: DriveParams,
    material: usize,
    /// Brake torque as a share of mu P R [-]; `None`: the automatic sweep.
    manual: Option<f64>,
    /// The brake torque applied [N m].
    torque: f64,
    plot: Plot,
    image: Handle<Image>,
    caption: Entity,
    meshes: [Handle<Mesh>; 2],
    materials: [Handle<StandardMaterial>; 3],
    /// Measured points (Q/(mu P), normalised creepage).
    points: Vec<(f64, f64)>,
}

/// Which body of which drive.
#[derive(Component, Clone, Copy, PartialEq, Eq)]
struct Part {
    /// 0: creep drive, 1: Coulomb twin.
    twin: usize,
    output: bool,
}

#[derive(Component, Default)]
struct Meter(AngleMeter);

#[derive(Component)]
struct DriveEntity;

/// Angles over the last window: (time [s], [input, output] angle per twin [rad]).
#[derive(Resource, Default)]
struct History(VecDeque<(f64, [[f64; 2]; 2])>);

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--material"]);
    let mut material_index = 0;
    for (flag, value) in &own {
        match flag.as_str() {
            "--material" => material_index = common::material_arg(USAGE, value),
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    let params = DriveParams {
        material: common::material(material_index),
        ..DriveParams::default()
    };
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: friction drive",
            args,
            dt: params.dt as f32,
            steps_per_frame: 8,
            gravity: Vec3::new(0.0, -G as f32, 0.0),
            // The scene's solver (Rapier's own substeps), so that the demo is its scene.
            creep: CreepSettings::default().with_rapier_solver(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::new(0.1, 0.05, 0.5 * TWIN),
                yaw: 0.5,
                pitch: 0.3,
                distance: 0.75,
                up: Vec3::Y,
            },
            physics: true,
            many_objects: false,
        })
        .insert_resource(Start(params, material_index))
        .init_resource::<History>()
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (keys, reset, brake, measure).chain().after(common::StepSet),
        )
        .run();
}

#[derive(Resource)]
struct Start(DriveParams, usize);

fn setup(
    mut commands: Commands,
    start: Res<Start>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    mut reset: ResMut<ResetRequested>,
) {
    let plot = Plot::new(UVec2::new(420, 250), (0.0, 1.0), (0.0, 1.0));
    let (image, caption) = common::spawn_plot(&mut commands, &mut images, &plot, "", 6.0);
    let r = start.0.radius as f32;
    let mat = |c: Color| StandardMaterial {
        base_color: c,
        perceptual_roughness: 0.35,
        metallic: 0.4,
        ..default()
    };
    commands.insert_resource(Drive {
        params: start.0,
        material: start.1,
        manual: None,
        torque: 0.0,
        plot,
        image,
        caption,
        meshes: [
            meshes.add(Sphere::new(r).mesh().uv(32, 18)),
            meshes.add(Cuboid::new(0.9 * r, 0.12 * r, 0.3 * r)),
        ],
        materials: [
            materials.add(mat(Color::srgb(0.55, 0.57, 0.6))),
            materials.add(mat(Color::srgb_u8(255, 200, 40))),
            materials.add(mat(Color::srgb_u8(90, 150, 255))),
        ],
        points: Vec::new(),
    });
    reset.0 = true;
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut drive: ResMut<Drive>,
    mut reset: ResMut<ResetRequested>,
) {
    let share = drive.manual.unwrap_or(0.0);
    if input.just_pressed(KeyCode::ArrowUp) {
        drive.manual = Some((share + 0.05).min(0.95));
    }
    if input.just_pressed(KeyCode::ArrowDown) {
        drive.manual = Some((share - 0.05).max(0.0));
    }
    if input.just_pressed(KeyCode::KeyA) {
        drive.manual = None;
    }
    if input.just_pressed(KeyCode::KeyM) {
        drive.material = (drive.material + 1) % common::MATERIALS.len();
        drive.params.material = common::material(drive.material);
        reset.0 = true;
    }
}

/// Spawns the two drives: a kinematic driver spinning at +omega about z, and above it the
/// output sphere (dynamic, its centre free only along y), counter-rotating at -omega.
fn reset(
    mut commands: Commands,
    mut reset: ResMut<ResetRequested>,
    mut drive: ResMut<Drive>,
    mut stepping: ResMut<Stepping>,
    mut history: ResMut<History>,
    old: Query<Entity, With<DriveEntity>>,
) {
    if !reset.0 {
        return;
    }
    reset.0 = false;
    stepping.steps = 0;
    history.0.clear();
    drive.points.clear();
    for e in &old {
        commands.entity(e).despawn();
    }
    let p = drive.params;
    let r = p.radius as f32;
    let mu = p.material.friction() as f32;
    let omega = p.omega as f32;
    for twin in 0..2 {
        let fidelity = if twin == 0 {
            Fidelity::Creep
        } else {
            Fidelity::Coulomb
        };
        let m = CreepMaterial::new(p.material).with_fidelity(fidelity);
        // The creep drive in front (nearer the camera).
        let z = (1 - twin) as f32 * TWIN;
        let marker = |c: &mut ChildSpawnerCommands, colour: &Handle<StandardMaterial>| {
            c.spawn((
                Mesh3d(drive.meshes[1].clone()),
                MeshMaterial3d(colour.clone()),
                Transform::from_xyz(0.0, 0.55 * r, 0.9 * r),
            ));
        };
        let colour = drive.materials[1 + twin].clone();
        commands
            .spawn((
                RigidBody::KinematicVelocityBased,
                Transform::from_xyz(0.0, 0.0, z),
                Velocity::angular(Vec3::new(0.0, 0.0, omega)),
                Collider::ball(r),
                Friction::coefficient(mu),
                m,
                Mesh3d(drive.meshes[0].clone()),
                MeshMaterial3d(drive.materials[0].clone()),
                Part {
                    twin,
                    output: false,
                },
                Meter::default(),
                DriveEntity,
            ))
            .with_children(|c| marker(c, &colour));
        commands
            .spawn((
                RigidBody::Dynamic,
                Transform::from_xyz(0.0, 2.0 * r, z),
                Velocity::angular(Vec3::new(0.0, 0.0, -omega)),
                LockedAxes::TRANSLATION_LOCKED_X | LockedAxes::TRANSLATION_LOCKED_Z,
                Collider::ball(r),
                Friction::coefficient(mu),
                m,
                ExternalForce::default(),
                Sleeping::disabled(),
                Mesh3d(drive.meshes[0].clone()),
                MeshMaterial3d(colour.clone()),
                Part { twin, output: true },
                Meter::default(),
                DriveEntity,
            ))
            .with_children(|c| marker(c, &drive.materials[0]));
    }
}

/// The Coulomb limit of the output's contact, `mu P` with `P = m g + press` [N].
fn mu_p(p: &DriveParams) -> f64 {
    let m = p.material.density() * 4.0 / 3.0 * std::f64::consts::PI * p.radius.powi(3);
    p.material.friction() * (m * G + p.press)
}

/// Sets the brake torque (the automatic sweep: a triangle wave from 0 to 0.95 mu P R).
fn brake(
    mut drive: ResMut<Drive>,
    stepping: Res<Stepping>,
    mut outputs: Query<(&Part, &mut ExternalForce)>,
) {
    let share = drive.manual.unwrap_or_else(|| {
        let phase = (stepping.time() / SWEEP).fract();
        0.95 * (1.0 - (2.0 * phase - 1.0).abs())
    });
    drive.torque = share * mu_p(&drive.params) * drive.params.radius;
    for (part, mut f) in &mut outputs {
        if part.output {
            // The output counter-rotates (w_out = -w_in); the brake opposes it.
            f.torque = Vec3::new(0.0, 0.0, drive.torque as f32);
            f.force = Vec3::new(0.0, -drive.params.press as f32, 0.0);
        }
    }
}

fn measure(
    mut drive: ResMut<Drive>,
    stepping: Res<Stepping>,
    mut parts: Query<(Entity, &Part, &Transform, &mut Meter)>,
    mut history: ResMut<History>,
    mut panel: ResMut<PanelText>,
    mut images: ResMut<Assets<Image>>,
    mut captions: Query<&mut Text>,
    creep: Res<CreepFriction>,
    contexts: Query<(&RapierContextSimulation, &RapierContextColliders)>,
) {
    let t = stepping.time();
    let mut angles = [[0.0; 2]; 2];
    let mut creep_drive = Vec::new();
    for (entity, part, tf, mut meter) in &mut parts {
        if part.twin == 0 {
            creep_drive.push(entity);
        }
        meter.0.update(tf.rotation, Vec3::Z);
        // The output turns the other way: count its angle positive.
        angles[part.twin][usize::from(part.output)] = if part.output {
            -meter.0.angle
        } else {
            meter.0.angle
        };
    }
    if history.0.back().is_none_or(|h| h.0 < t) {
        history.0.push_back((t, angles));
    }
    while history.0.len() > 2 && t - history.0[1].0 >= WINDOW {
        history.0.pop_front();
    }
    // Creepage over the window, (R w_in - R w_out) / (R (w_in + w_out) / 2) (the scene's).
    let mut creepage = [f64::NAN; 2];
    if let (Some(a), Some(b)) = (history.0.front(), history.0.back())
        && b.0 - a.0 >= 0.5 * WINDOW
    {
        for twin in 0..2 {
            let d_in = b.1[twin][0] - a.1[twin][0];
            let d_out = b.1[twin][1] - a.1[twin][1];
            creepage[twin] = (d_in - d_out) / (0.5 * (d_in + d_out));
        }
    }
    let p = drive.params;
    let pair = PairMaterial::new(
        &p.material,
        &p.material,
        Surface::Sphere(p.radius),
        Surface::Sphere(p.radius),
    )
    .expect("valid materials");
    // The creep drive's contact, as the plugin reports it.
    let mut contact = None;
    if let Some((sim, colliders)) = contexts.iter().next() {
        contact = creep
            .creep_contacts(sim, colliders)
            .into_iter()
            .find(|c| creep_drive.contains(&c.collider1) && creep_drive.contains(&c.collider2));
    }
    let (pn, q) = contact.map_or((mu_p(&p) / p.material.friction(), 0.0), |c| {
        (f64::from(c.normal_force), f64::from(c.force.length()))
    });
    let mu = p.material.friction();
    let ratio = q / (mu * pn);
    let a = hertz::contact_radius(&pair, pn);
    // Normalised creepage xi G a^2 / (mu P): Kalker's curve is then material independent.
    let norm = pair.g * a * a / (mu * pn);
    let measured = creepage[0] - creepage[1];
    let expected = p.expected_creepage(pn, q).unwrap_or(f64::NAN);
    if measured.is_finite() && contact.is_some() && !stepping.paused {
        let pt = (ratio, measured * norm);
        if drive.points.last() != Some(&pt) {
            drive.points.push(pt);
        }
        if drive.points.len() > 4000 {
            drive.points.remove(0);
        }
    }
    let y_max = 3.0 / pair.c11 * 1.05;
    let mut plot = Plot::new(drive.plot.size, (0.0, 1.0), (0.0, y_max));
    let curve: Vec<(f64, f64)> = (0..=100)
        .map(|i| {
            let s = f64::from(i) / 100.0;
            (s, SteadyLaw::Kuhn { c11: pair.c11 }.creepage_n(s))
        })
        .collect();
    plot.polyline(&curve, colours::THEORY);
    // Kalker's linear theory, xi_n = s / C11, for reference.
    plot.line((0.0, 0.0), (1.0, 1.0 / pair.c11), colours::AXIS);
    let n = drive.points.len();
    for (i, &pt) in drive.points.iter().enumerate() {
        if i + 1 < n {
            plot.point(pt, 0, colours::CREEP);
        }
    }
    if let Some(&last) = drive.points.last() {
        plot.point(last, 4, colours::TORQUE);
    }
    if let Some(mut img) = images.get_mut(&drive.image) {
        plot.write(&mut img);
    }
    drive.plot = plot;
    if let Ok(mut c) = captions.get_mut(drive.caption) {
        c.0 = format!(
            "creepage xi G a^2/(mu P) [0-{y_max:.2}] vs Q/(mu P) [0-1]\n\
             white: Kalker 3/C11 [1-(1-Q/mu P)^(1/3)], grey: linear theory; red: now"
        );
    }
    let lag = |twin: usize| angles[twin][0] - angles[twin][1];
    panel.0 = format!(
        "friction drive: {} spheres R = {} m, omega_in = {} rad/s, mu = {}; front: creep, back: Coulomb\n\
         brake torque {:.4} N m = {:.2} mu P R ({}; Up/Down, A sweep, M material, R restart)\n\
         contact (creep drive): P {:.3} N, Q {:.4} N, Q/(mu P) {:.3}, a {:.3e} m\n\
         creepage: creep drive {:+.3e}, Coulomb twin (engine) {:+.3e}, difference {:+.3e}\n\
         Kalker F_ss(Q/mu P) = {:.3e} (measured/Kalker {:.3})\n\
         input minus output angle: creep {:.4} rad, Coulomb {:.4} rad, difference {:.4} rad after {:.1} rad",
        common::MATERIALS[drive.material],
        p.radius,
        p.omega,
        mu,
        drive.torque,
        drive.torque / (mu_p(&p) * p.radius),
        if drive.manual.is_some() {
            "manual"
        } else {
            "sweep"
        },
        pn,
        q,
        ratio,
        a,
        creepage[0],
        creepage[1],
        measured,
        expected,
        measured / expected,
        lag(0),
        lag(1),
        lag(0) - lag(1),
        angles[0][0],
    );
}
