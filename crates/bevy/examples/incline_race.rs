//! `incline_race`: three identical balls roll down parallel lanes of one incline — Coulomb
//! (Rapier's own rolling), creep-friction (Kuhn 2011) and a contact-torque rolling resistance
//! (Ai et al. 2011, type A) — with a live plot of each ball's slip `v - w R` against the
//! theory line.
//!
//! The scene is creep-scenes' incline (`creep_scenes::incline::InclineParams`: a 0.1 m ball,
//! mu = 0.5, a 20 degree incline made of a flat fixed cuboid with the gravity tilted by theta,
//! dt = 1/240 s), so this demo and `tests/incline.rs` / `creep run incline` are the same scene;
//! the camera's up is against the gravity, so the floor looks inclined.
//!
//! Keys: F cycles the middle lane's fidelity (Creep, Auto, Coulomb), M cycles the material
//! (steel, glass, rubber), R restarts; and the shared keys (see `common`).
//!
//! Run: `cargo run -p creep-bevy --features render --example incline_race --ignore-rust-version --release`
//! (`-- --screenshot out.png --frames 120` to render 120 frames, save a screenshot and exit).

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems
#![allow(clippy::needless_range_loop)] // lanes and twins indexed in parallel arrays

mod common;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::{
    AngleMeter, DemoPlugin, OrbitCamera, PanelText, Plot, ResetRequested, Stepping, colours,
};
use creep_bevy::{CompliantSettings, CreepFriction, CreepMaterial, CreepSettings, Fidelity};
use creep_law::Material;
use creep_law::rolling_torque::RollingModel;
use creep_scenes::incline::{G, InclineParams};

const USAGE: &str = "incline_race: Coulomb vs creep-friction vs rolling torque on one incline

usage: incline_race [--material steel|glass|rubber] [--mu-r 0.02] [common options]
  --material M   ball and incline material (default steel; mu = 0.5)
  --mu-r X       rolling friction coefficient of the third lane's type A torque (default 0.02)
keys: F cycles the middle lane's fidelity (Creep, Auto, Coulomb), M cycles the material";

/// Lanes' distance apart along z [m].
const LANE: f32 = 0.6;
/// Simulated seconds before the race restarts by itself [s].
const RACE_TIME: f64 = 4.0;
/// Window of the slip measurement [s] (finite differences of positions and rotations).
const WINDOW: f64 = 0.2;

/// The lane material: creep-law's `common::MATERIALS[index]` with mu = 0.5.
fn material(index: usize) -> Material {
    common::material(index)
        .with_friction(0.5)
        .expect("0.5 is a valid friction coefficient")
}

#[derive(Resource)]
struct Race {
    params: InclineParams,
    material: usize,
    mu_r: f64,
    fidelity: Fidelity,
    /// Raw slips, and the creep lane's slip relative to the Coulomb lane's.
    plots: [Plot; 2],
    images: [Handle<Image>; 2],
    captions: [Entity; 2],
    mesh: Handle<Mesh>,
    marker: Handle<Mesh>,
    lane_materials: [Handle<StandardMaterial>; 3],
    marker_material: Handle<StandardMaterial>,
    /// Per lane: the plotted points (rolling speed [m/s], slip velocity [m/s]).
    points: [Vec<(f64, f64)>; 3],
}

/// One ball and its history for the slip measurement.
#[derive(Component)]
struct Ball {
    lane: usize,
    /// (time [s], x [m], accumulated rotation about z [rad]).
    history: Vec<(f64, f64, f64)>,
    meter: AngleMeter,
}

#[derive(Component)]
struct RaceEntity;

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--material", "--mu-r"]);
    let mut material_index = 0;
    let mut mu_r = 0.02;
    for (flag, value) in &own {
        match flag.as_str() {
            "--material" => material_index = common::material_arg(USAGE, value),
            "--mu-r" => {
                mu_r = match value.parse::<f64>() {
                    Ok(v) if RollingModel::constant_torque(v).is_ok() && v < 0.1 => v,
                    _ => common::exit_with(
                        USAGE,
                        &format!("--mu-r `{value}`: expected a number in [0, 0.1)"),
                    ),
                }
            }
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    let params = InclineParams {
        material: material(material_index),
        ..InclineParams::default()
    };
    let gravity = Vec3::new(
        (G * params.theta.sin()) as f32,
        (-G * params.theta.cos()) as f32,
        0.0,
    );
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: incline race",
            args,
            dt: params.dt as f32,
            steps_per_frame: 8,
            gravity,
            // The scene's solver (Rapier's own substeps), so that the demo is its scene.
            creep: CreepSettings::default().with_rapier_solver(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::ZERO,
                yaw: 0.35,
                pitch: 0.45,
                distance: 3.2,
                up: -gravity.normalize(),
            },
            physics: true,
            many_objects: false,
        })
        .insert_resource(StartParams {
            params,
            material: material_index,
            mu_r,
        })
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (keys, reset, measure, draw_lanes)
                .chain()
                .after(common::StepSet),
        )
        .run();
}

#[derive(Resource)]
struct StartParams {
    params: InclineParams,
    material: usize,
    mu_r: f64,
}

fn setup(
    mut commands: Commands,
    start: Res<StartParams>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
    mut reset: ResMut<ResetRequested>,
) {
    let p = start.params;
    let plot = Plot::new(UVec2::new(360, 130), (0.0, 1.0), (-1.0, 1.0));
    let (image0, caption0) = common::spawn_plot(&mut commands, &mut images, &plot, "", 6.0);
    let (image1, caption1) = common::spawn_plot(&mut commands, &mut images, &plot, "", 180.0);
    let r = p.radius as f32;
    let lane_colour = |c: [u8; 4]| Color::srgb_u8(c[0], c[1], c[2]);
    let lane_materials = [colours::COULOMB, colours::CREEP, colours::TORQUE].map(|c| {
        materials.add(StandardMaterial {
            base_color: lane_colour(c),
            perceptual_roughness: 0.4,
            metallic: 0.3,
            ..default()
        })
    });
    commands.insert_resource(Race {
        params: p,
        material: start.material,
        mu_r: start.mu_r,
        fidelity: Fidelity::Creep,
        plots: [plot.clone(), plot],
        images: [image1, image0],
        captions: [caption1, caption0],
        mesh: meshes.add(Sphere::new(r).mesh().uv(32, 18)),
        marker: meshes.add(Sphere::new(0.25 * r).mesh().uv(12, 8)),
        lane_materials,
        marker_material: materials.add(StandardMaterial {
            base_color: Color::srgb(0.05, 0.05, 0.05),
            ..default()
        }),
        points: Default::default(),
    });
    // The incline: creep-scenes' fixed cuboid (2e4 x 1 x 20 m, top face at y = 0); drawn 60 m
    // long. Its fidelity is Creep so that each ball's own fidelity decides (a pair uses the
    // lower of the two).
    commands.spawn((
        RigidBody::Fixed,
        Transform::from_xyz(0.0, -0.5, 0.0),
        Collider::cuboid(1.0e4, 0.5, 10.0),
        Friction::coefficient(p.material.friction() as f32),
        CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(60.0, 0.02, 3.0 * LANE))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.35, 0.37, 0.40),
            perceptual_roughness: 0.9,
            ..default()
        })),
        Transform::from_xyz(29.0, -0.01, 0.0),
    ));
    reset.0 = true;
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut race: ResMut<Race>,
    mut reset: ResMut<ResetRequested>,
) {
    if input.just_pressed(KeyCode::KeyF) {
        race.fidelity = match race.fidelity {
            Fidelity::Creep => Fidelity::Auto,
            Fidelity::Auto => Fidelity::Coulomb,
            Fidelity::Coulomb => Fidelity::Creep,
        };
        reset.0 = true;
    }
    if input.just_pressed(KeyCode::KeyM) {
        race.material = (race.material + 1) % common::MATERIALS.len();
        race.params.material = material(race.material);
        reset.0 = true;
    }
}

/// The three lanes' creep materials: Coulomb, the chosen fidelity, Coulomb with a type A
/// rolling torque `mu_r R P` (Ai et al. 2011).
fn lane_material(race: &Race, lane: usize) -> CreepMaterial {
    let m = CreepMaterial::new(race.params.material);
    match lane {
        0 => m.with_fidelity(Fidelity::Coulomb),
        1 => m.with_fidelity(race.fidelity),
        _ => m.with_fidelity(Fidelity::Coulomb).with_rolling(
            RollingModel::constant_torque(race.mu_r).expect("mu_r checked when parsed"),
        ),
    }
}

fn reset(
    mut commands: Commands,
    mut reset: ResMut<ResetRequested>,
    mut race: ResMut<Race>,
    mut stepping: ResMut<Stepping>,
    old: Query<Entity, With<RaceEntity>>,
    mut floor: Query<(&mut CreepMaterial, &mut Friction), Without<Ball>>,
) {
    if !reset.0 && stepping.time() < RACE_TIME {
        return;
    }
    reset.0 = false;
    stepping.steps = 0;
    for e in &old {
        commands.entity(e).despawn();
    }
    for (mut m, mut f) in &mut floor {
        m.material = race.params.material;
        f.coefficient = race.params.material.friction() as f32;
    }
    let r = race.params.radius as f32;
    for lane in 0..3 {
        let z = (lane as f32 - 1.0) * LANE;
        commands
            .spawn((
                RigidBody::Dynamic,
                Transform::from_xyz(0.0, r, z),
                Collider::ball(r),
                Friction::coefficient(race.params.material.friction() as f32),
                lane_material(&race, lane),
                Sleeping::disabled(),
                Mesh3d(race.mesh.clone()),
                MeshMaterial3d(race.lane_materials[lane].clone()),
                Ball {
                    lane,
                    history: Vec::new(),
                    meter: AngleMeter::default(),
                },
                RaceEntity,
            ))
            .with_children(|c| {
                // A marker on the surface, to see the rotation.
                c.spawn((
                    Mesh3d(race.marker.clone()),
                    MeshMaterial3d(race.marker_material.clone()),
                    Transform::from_xyz(0.0, 0.0, 0.9 * r),
                ));
                c.spawn((
                    Mesh3d(race.marker.clone()),
                    MeshMaterial3d(race.marker_material.clone()),
                    Transform::from_xyz(0.0, 0.0, -0.9 * r),
                ));
                c.spawn((
                    Mesh3d(race.marker.clone()),
                    MeshMaterial3d(race.marker_material.clone()),
                    Transform::from_xyz(0.0, 0.9 * r, 0.0),
                ));
            });
    }
    race.points = Default::default();
}

/// The steady creepage of the ball on the incline at the closed-form loads of rolling without
/// slip (creep-scenes' `InclineParams::rolling_loads` and `expected_creepage`) [-].
fn kalker_creepage(p: &InclineParams) -> f64 {
    let (pn, q) = p.rolling_loads();
    p.expected_creepage(pn, q).unwrap_or(f64::NAN)
}

fn measure(
    mut race: ResMut<Race>,
    stepping: Res<Stepping>,
    mut balls: Query<(&Transform, &mut Ball)>,
    mut orbit: ResMut<OrbitCamera>,
    mut panel: ResMut<PanelText>,
    mut images: ResMut<Assets<Image>>,
    mut captions: Query<&mut Text>,
    creep: Res<CreepFriction>,
    contexts: Query<(&RapierContextSimulation, &RapierContextColliders)>,
) {
    let t = stepping.time();
    let p = race.params;
    let r = p.radius;
    let mut slips = [f64::NAN; 3];
    let mut speeds = [0.0; 3];
    let mut xs = [0.0; 3];
    let mut x_mean = 0.0;
    let n_balls = balls.iter().count().max(1) as f32;
    for (tf, mut ball) in &mut balls {
        ball.meter.update(tf.rotation, Vec3::Z);
        let x = f64::from(tf.translation.x);
        let angle = ball.meter.angle;
        if ball.history.last().is_none_or(|h| h.0 < t) {
            ball.history.push((t, x, angle));
        }
        x_mean += tf.translation.x / n_balls;
        xs[ball.lane] = x;
        // Slip velocity of the contact point, v_x + w_z R (the ball rolls towards +x with
        // w_z < 0), and the rolling speed, from positions and rotations over WINDOW.
        let now = *ball.history.last().expect("just pushed");
        if let Some(then) = ball.history.iter().rev().find(|h| now.0 - h.0 >= WINDOW) {
            let dt = now.0 - then.0;
            let dx = now.1 - then.1;
            let dtheta = now.2 - then.2;
            slips[ball.lane] = (dx + r * dtheta) / dt;
            speeds[ball.lane] = dx / dt;
        }
        ball.history.retain(|h| now.0 - h.0 < 2.0 * WINDOW);
    }
    // Look a little ahead of the balls, so that the plots (right) do not hide them.
    orbit.target = Vec3::new(x_mean + 0.7, 0.1, 0.0);
    let xi = kalker_creepage(&p);
    let lanes = ["Coulomb", fidelity_name(race.fidelity), "rolling torque"];
    let mut new_points = [(f64::NAN, f64::NAN); 3];
    for lane in 0..3 {
        if slips[lane].is_finite() && !stepping.paused {
            new_points[lane] = (speeds[lane], slips[lane]);
        }
    }
    for (lane, pt) in new_points.into_iter().enumerate() {
        if pt.0.is_finite() && race.points[lane].last() != Some(&pt) {
            race.points[lane].push(pt);
        }
    }
    // Plot 1: each ball's slip velocity [mm/s] against its rolling speed [m/s]; theory:
    // rigid rolling (0), and for the creep lane the engine's own slip (the Coulomb lane's,
    // fitted as a creepage) plus Kalker's creepage xi v.
    let v_max = common::nice_ceil(speeds.iter().cloned().fold(0.5, f64::max) * 1.1);
    let lane_colours = [colours::COULOMB, colours::CREEP, colours::TORQUE];
    let engine = engine_creepage(&race.points[0]);
    let mut y_max = 1e-4f64;
    for pts in &race.points {
        for &(_, s) in pts {
            y_max = y_max.max(1.2 * s.abs());
        }
    }
    let y_max = common::nice_ceil(y_max.max(1.2 * (engine + xi).abs() * v_max) * 1e3) * 1e-3;
    let mut plot = Plot::new(race.plots[0].size, (0.0, v_max), (-y_max, y_max));
    plot.line((0.0, 0.0), (v_max, 0.0), colours::THEORY);
    plot.line((0.0, 0.0), (v_max, (engine + xi) * v_max), colours::THEORY);
    for (lane, pts) in race.points.iter().enumerate() {
        plot.polyline(pts, lane_colours[lane]);
        if let Some(&last) = pts.last() {
            plot.point(last, 3, lane_colours[lane]);
        }
    }
    // Plot 2: the middle lane's slip minus the Coulomb lane's at the same time (same speed),
    // against Kalker's xi v: what creep-scenes' incline measures (creep run minus Coulomb run).
    let relative: Vec<(f64, f64)> = race.points[1]
        .iter()
        .zip(&race.points[0])
        .map(|(&(v, s), &(_, s0))| (v, s - s0))
        .collect();
    let y2 = relative
        .iter()
        .fold(1.3 * xi.abs() * v_max, |m, &(_, s)| m.max(1.2 * s.abs()));
    let y2 = common::nice_ceil(y2 * 1e3) * 1e-3;
    let mut plot2 = Plot::new(race.plots[1].size, (0.0, v_max), (-y2, y2));
    plot2.line((0.0, 0.0), (v_max, xi * v_max), colours::THEORY);
    plot2.polyline(&relative, colours::CREEP);
    if let Some(&last) = relative.last() {
        plot2.point(last, 3, colours::CREEP);
    }
    for (k, p) in [plot, plot2].into_iter().enumerate() {
        if let Some(mut img) = images.get_mut(&race.images[k]) {
            p.write(&mut img);
        }
        race.plots[k] = p;
    }
    let captions_text = [
        format!(
            "slip v - wR [+-{} mm/s] vs speed v [0-{v_max} m/s]; white: 0, engine + Kalker",
            y_max * 1e3
        ),
        format!(
            "middle lane's slip minus the Coulomb lane's [+-{} mm/s]\nwhite: Kalker xi v, xi = {xi:.3e}",
            y2 * 1e3
        ),
    ];
    for (k, text) in captions_text.into_iter().enumerate() {
        if let Ok(mut caption) = captions.get_mut(race.captions[k]) {
            caption.0 = text;
        }
    }
    // Panel.
    let a_rigid = 5.0 / 7.0 * G * p.theta.sin();
    let a_torque = 5.0 / 7.0 * G * (p.theta.sin() - race.mu_r * p.theta.cos());
    let mut s = format!(
        "incline race: {} ball R = {} m, mu = {}, theta = {:.0} deg; F fidelity, M material, R restart\n",
        common::MATERIALS[race.material],
        p.radius,
        p.material.friction(),
        p.theta.to_degrees()
    );
    for lane in 0..3 {
        let a = if t > 0.0 {
            2.0 * xs[lane] / (t * t)
        } else {
            0.0
        };
        let a_th = if lane == 2 { a_torque } else { a_rigid };
        s += &format!(
            "{:>14}: x {:6.3} m  v {:5.3} m/s  slip {:+.2e} m/s ({:+.2e} v)  a {:.4} (theory {:.4}) m/s^2\n",
            lanes[lane],
            xs[lane],
            speeds[lane],
            slips[lane],
            slips[lane] / speeds[lane],
            a,
            a_th
        );
    }
    let measured = slips[1] / speeds[1] - slips[0] / speeds[0];
    s += &format!(
        "creepage, middle lane minus Coulomb lane: {measured:+.3e}; Kalker F_ss(Q/mu P) = {xi:.3e}\n"
    );
    if let Some((sim, colliders)) = contexts.iter().next() {
        for c in creep.creep_contacts(sim, colliders) {
            if c.state != creep_bevy::ContactState::Stick {
                s += &format!(
                    "contact: P {:.2} N, |Q| {:.2} N, Q/(mu P) {:.3}, {:?}\n",
                    c.normal_force,
                    c.force.length(),
                    f64::from(c.force.length())
                        / (p.material.friction() * f64::from(c.normal_force)),
                    c.state
                );
            }
        }
    }
    let counts = creep.counts();
    s += &format!(
        "plugin: {} creep, {} rolling-torque contacts; creep power {:.2e} W",
        counts.creep, counts.rolling_torque, counts.creep_power
    );
    panel.0 = s;
}

/// The Coulomb lane's slip as a creepage: least squares through the origin, `sum(s v) /
/// sum(v^2)` [-].
fn engine_creepage(points: &[(f64, f64)]) -> f64 {
    let (sv, vv) = points
        .iter()
        .fold((0.0, 0.0), |(sv, vv), &(v, s)| (sv + s * v, vv + v * v));
    if vv > 0.0 { sv / vv } else { 0.0 }
}

fn fidelity_name(f: Fidelity) -> &'static str {
    match f {
        Fidelity::Creep => "creep",
        Fidelity::Auto => "auto",
        Fidelity::Coulomb => "Coulomb (F)",
    }
}

/// Cross lines on the lanes every 0.5 m around the balls, so that their motion shows.
fn draw_lanes(mut gizmos: Gizmos, orbit: Res<OrbitCamera>) {
    let x0 = (orbit.target.x / 0.5).floor() * 0.5;
    for i in -12..=12 {
        let x = x0 + i as f32 * 0.5;
        gizmos.line(
            Vec3::new(x, 0.002, -1.5 * LANE),
            Vec3::new(x, 0.002, 1.5 * LANE),
            Color::srgb(0.75, 0.75, 0.8),
        );
    }
    for k in 0..4 {
        let z = (k as f32 - 1.5) * LANE;
        gizmos.line(
            Vec3::new(x0 - 6.0, 0.002, z),
            Vec3::new(x0 + 6.0, 0.002, z),
            Color::srgb(0.75, 0.75, 0.8),
        );
    }
}
