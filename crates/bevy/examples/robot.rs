//! `robot`: creep-scenes' differential-drive robot (two driven crowned rubber wheels on
//! revolute motors and a caster ball, `creep_scenes::robot`) as bevy_rapier3d bodies, joints
//! and motors whose contacts the creep-friction plugin runs (`robot_entities`: the same
//! entities `tests/robot.rs` matches against the scene within 1 %), next to its Coulomb twin
//! (the same robot with `Fidelity::Coulomb` materials) on one floor, both driven with the same
//! motor targets, turning on the spot or on an arc.
//!
//! At each contact with the floor (gizmos): the floor's tangential force on the body (orange
//! arrow, 0.2 m per N), the slip velocity `v_disp` of the floor against the body (cyan arrow,
//! 20 m per m/s: creep slips are small), and the spin creepage `phi` (a magenta circle of
//! radius `|phi|` mm per 1/m, i.e. 10 mm at `phi = 10 /m`). The creep frame's axes are the
//! scene's (Kalker's `x` against the rolling direction, `y = n x x`, `n` down). The trails are
//! the axle midpoints' paths. The panel gives, per robot, the speed, the yaw rate and the arc
//! radius against the closed forms of a differential drive, each contact's creepages
//! (`xi`, `eta`, `phi`), forces and twisting moment (means over the last 0.5 s), and the energy
//! the contacts dissipated since the start (measured from the contact impulses, and as the
//! creep hook books it).
//!
//! Keys: 1 turn on the spot, 2 arc, 3 straight ahead, Up/Down rim speeds x 1.25 / 0.8,
//! R restarts both; and the shared keys (see `common`).
//!
//! Run: `cargo run -p creep-bevy --features render --example robot --ignore-rust-version --release`

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems

mod common;
mod robot_entities;

use std::collections::VecDeque;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::{DemoPlugin, OrbitCamera, PanelText, PhysicsStep, ResetRequested, Stepping};
use creep_bevy::prelude::*;
use creep_scenes::robot::{ContactSample, RobotParams, RobotSample, WheelSpeeds};
use robot_entities::{
    RobotEntities, RobotView, robot_parameters, set_speeds, spawn_floor, spawn_robot,
};

const USAGE: &str = "robot: a differential-drive robot with creep-friction and its Coulomb twin

usage: robot [--manoeuvre spot|arc|straight] [--speed V] [--left VL] [--right VR] [common options]
  --manoeuvre M   spot (rim speeds -V, +V), arc (VL, VR) or straight (V, V); default arc
  --speed V       rim speed of the turn on the spot and of the straight run [m/s] (default 0.1)
  --left VL       left rim speed of the arc [m/s] (default 0.1)
  --right VR      right rim speed of the arc [m/s] (default 0.15)
keys: 1 spot, 2 arc, 3 straight, Up/Down speeds x1.25 / x0.8, R restarts";

/// Drawn scale: world units per metre (Bevy's camera near plane is 0.1 units).
const SCALE: f32 = 10.0;
/// The twin starts this far along +x from the creep robot \[m\] (one world, one floor).
const TWIN_OFFSET: f32 = 1.3;
/// Arrow scales: tangential force \[m/N\], slip velocity \[m per m/s\], spin circle \[m per 1/m\].
const FORCE_SCALE: f32 = 0.2;
const SLIP_SCALE: f32 = 20.0;
const SPIN_SCALE: f32 = 1e-3;
/// Steps the panel's means run over (0.5 s at the scene's 1/240 s).
const MEAN_STEPS: usize = 120;
/// Trail points kept per robot.
const TRAIL: usize = 4000;

#[derive(Debug, Clone, Copy, PartialEq)]
enum Manoeuvre {
    Spot,
    Arc,
    Straight,
}

#[derive(Debug, Clone, Copy)]
struct Command {
    manoeuvre: Manoeuvre,
    speed: f64,
    left: f64,
    right: f64,
}

impl Command {
    fn speeds(&self) -> WheelSpeeds {
        match self.manoeuvre {
            Manoeuvre::Spot => WheelSpeeds::spot(self.speed),
            Manoeuvre::Arc => WheelSpeeds::arc(self.left, self.right),
            Manoeuvre::Straight => WheelSpeeds::arc(self.speed, self.speed),
        }
    }
    fn name(&self) -> &'static str {
        match self.manoeuvre {
            Manoeuvre::Spot => "turning on the spot",
            Manoeuvre::Arc => "arc",
            Manoeuvre::Straight => "straight ahead",
        }
    }
}

/// One robot and what the demo keeps of it.
struct Lane {
    robot: RobotEntities,
    fidelity: Fidelity,
    recent: VecDeque<RobotSample>,
    trail: VecDeque<Vec3>,
    /// Energy dissipated by the contacts since the start: measured, as the hook books it \[J\].
    dissipated: f64,
    hook_energy: f64,
    last: Option<RobotSample>,
    /// Drawn entities (meshes at the drawn scale): chassis, left wheel, right wheel, caster.
    parts: [Entity; 4],
}

#[derive(Resource)]
struct Scene {
    params: RobotParams,
    command: Command,
    lanes: Vec<Lane>,
    /// The floor's physics entity.
    floor: Entity,
    error: Option<String>,
    meshes: [Handle<Mesh>; 3],
    materials: [[Handle<StandardMaterial>; 2]; 2],
}

#[derive(Resource)]
struct Start(Command);

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--manoeuvre", "--speed", "--left", "--right"]);
    let mut command = Command {
        manoeuvre: Manoeuvre::Arc,
        speed: 0.1,
        left: 0.1,
        right: 0.15,
    };
    let speed = |flag: &str, value: &str| match value.parse::<f64>() {
        Ok(v) if v.is_finite() && v.abs() <= 1.0 => v,
        _ => common::exit_with(
            USAGE,
            &format!("{flag} `{value}`: expected a rim speed in [-1, 1] m/s"),
        ),
    };
    for (flag, value) in &own {
        match flag.as_str() {
            "--manoeuvre" => {
                command.manoeuvre = match value.as_str() {
                    "spot" => Manoeuvre::Spot,
                    "arc" => Manoeuvre::Arc,
                    "straight" => Manoeuvre::Straight,
                    _ => common::exit_with(
                        USAGE,
                        &format!("--manoeuvre `{value}`: expected spot, arc or straight"),
                    ),
                }
            }
            "--speed" => command.speed = speed(flag, value),
            "--left" => command.left = speed(flag, value),
            "--right" => command.right = speed(flag, value),
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    let params = RobotParams::default();
    if let Err(e) = params.validate().and_then(|()| params.crown()) {
        common::exit_with(USAGE, &e.to_string());
    }
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: a differential-drive robot and its Coulomb twin",
            args,
            dt: params.dt as f32,
            steps_per_frame: 2,
            gravity: Vec3::new(0.0, -9.81, 0.0),
            creep: CreepSettings::default(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::new(0.5 * TWIN_OFFSET, 0.0, -0.35) * SCALE,
                yaw: 0.0,
                pitch: 0.75,
                distance: 2.4 * SCALE,
                up: Vec3::Y,
            },
            physics: true,
            many_objects: false,
        })
        .insert_resource(Start(command))
        .add_systems(Startup, (robot_parameters(params), setup))
        .add_systems(
            Update,
            (
                (keys, respawn).chain().before(common::StepSet),
                draw.after(common::StepSet),
            ),
        )
        .add_systems(PhysicsStep, record.after(PhysicsSet::Writeback))
        .run();
}

fn setup(
    mut commands: Commands,
    start: Res<Start>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut reset: ResMut<ResetRequested>,
) {
    let p = RobotParams::default();
    let (r, lb) = (p.wheel_radius as f32, p.wheelbase as f32);
    let colour = |c: Color| StandardMaterial {
        base_color: c,
        perceptual_roughness: 0.6,
        ..default()
    };
    // Per lane (creep, twin): the chassis' and the wheels' materials.
    let materials_ = [
        [
            materials.add(colour(Color::srgb(0.95, 0.75, 0.15))),
            materials.add(colour(Color::srgb(0.15, 0.15, 0.17))),
        ],
        [
            materials.add(colour(Color::srgb(0.3, 0.55, 1.0))),
            materials.add(colour(Color::srgb(0.15, 0.15, 0.17))),
        ],
    ];
    // Meshes in drawn units: the chassis box, a wheel (Bevy's cylinder is about y), the ball.
    let meshes_ = [
        meshes.add(Cuboid::new(
            1.4 * lb * SCALE,
            0.8 * r * SCALE,
            0.8 * p.track as f32 * SCALE,
        )),
        meshes.add(Cylinder::new(r * SCALE, p.wheel_width as f32 * SCALE)),
        meshes.add(
            Sphere::new(p.caster_radius as f32 * SCALE)
                .mesh()
                .ico(3)
                .expect("small subdivision"),
        ),
    ];
    let floor = spawn_floor(&mut commands, &p, Fidelity::Creep);
    // The floor drawn: a dark plane.
    commands.spawn((
        Mesh3d(meshes.add(Plane3d::default().mesh().size(60.0, 60.0))),
        MeshMaterial3d(materials.add(colour(Color::srgb(0.22, 0.23, 0.26)))),
        Transform::from_xyz(0.0, -0.001, 0.0),
    ));
    commands.insert_resource(Scene {
        params: p,
        command: start.0,
        lanes: Vec::new(),
        floor,
        error: None,
        meshes: meshes_,
        materials: materials_,
    });
    reset.0 = true;
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    scene: Option<ResMut<Scene>>,
    mut joints: Query<&mut ImpulseJoint>,
) {
    let Some(mut scene) = scene else {
        return;
    };
    let before = scene.command;
    let c = &mut scene.command;
    if input.just_pressed(KeyCode::Digit1) {
        c.manoeuvre = Manoeuvre::Spot;
    }
    if input.just_pressed(KeyCode::Digit2) {
        c.manoeuvre = Manoeuvre::Arc;
    }
    if input.just_pressed(KeyCode::Digit3) {
        c.manoeuvre = Manoeuvre::Straight;
    }
    for (key, factor) in [(KeyCode::ArrowUp, 1.25), (KeyCode::ArrowDown, 0.8)] {
        if input.just_pressed(key) {
            c.speed *= factor;
            c.left *= factor;
            c.right *= factor;
        }
    }
    let changed = c.manoeuvre != before.manoeuvre || c.speed != before.speed;
    if changed {
        let speeds = scene.command.speeds();
        for lane in &scene.lanes {
            set_speeds(&mut joints, &lane.robot, speeds, &scene.params);
        }
    }
}

/// (Re)builds both robots at rest on the floor when R was pressed (before the frame's steps).
fn respawn(
    mut commands: Commands,
    scene: Option<ResMut<Scene>>,
    mut reset: ResMut<ResetRequested>,
    mut stepping: ResMut<Stepping>,
) {
    let Some(mut scene) = scene else {
        return;
    };
    let scene = &mut *scene;
    if !std::mem::take(&mut reset.0) {
        return;
    }
    for lane in scene.lanes.drain(..) {
        for e in lane.robot.bodies().into_iter().chain(lane.parts) {
            commands.entity(e).despawn();
        }
    }
    stepping.steps = 0;
    for (k, fidelity) in [Fidelity::Creep, Fidelity::Coulomb].into_iter().enumerate() {
        let origin = Vec3::new(k as f32 * TWIN_OFFSET, 0.0, 0.0);
        let robot = match spawn_robot(
            &mut commands,
            &scene.params,
            fidelity,
            scene.command.speeds(),
            scene.floor,
            origin,
        ) {
            Ok(r) => r,
            Err(e) => {
                scene.error = Some(e);
                return;
            }
        };
        let [chassis, wheel, ball] = scene.meshes.clone();
        let [body, tyre] = scene.materials[k].clone();
        let mut spawn = |mesh: Handle<Mesh>, material: Handle<StandardMaterial>| {
            commands
                .spawn((Mesh3d(mesh), MeshMaterial3d(material), Transform::default()))
                .id()
        };
        let parts = [
            spawn(chassis, body.clone()),
            spawn(wheel.clone(), tyre.clone()),
            spawn(wheel, tyre.clone()),
            spawn(ball, body),
        ];
        scene.lanes.push(Lane {
            robot,
            fidelity,
            recent: VecDeque::with_capacity(MEAN_STEPS + 1),
            trail: VecDeque::with_capacity(TRAIL),
            dissipated: 0.0,
            hook_energy: 0.0,
            last: None,
            parts,
        });
    }
}

/// After each Rapier step (in the physics schedule): each robot's sample, the scene's
/// measurement, and the energies, means and trails the panel shows.
fn record(view: RobotView, scene: Option<ResMut<Scene>>, stepping: Res<Stepping>) {
    let Some(mut scene) = scene else {
        return;
    };
    let params = scene.params;
    let dt = params.dt;
    // `Stepping::steps` counts the steps before this one.
    let t = (stepping.steps + 1) as f64 * dt;
    for lane in &mut scene.lanes {
        let Some(s) = view.sample(&lane.robot, &params, t, dt) else {
            continue;
        };
        lane.dissipated += s.power() * dt;
        lane.hook_energy += s.hook_creep_power * dt;
        if lane.recent.len() == MEAN_STEPS {
            lane.recent.pop_front();
        }
        lane.recent.push_back(s);
        let p = vec3(s.position);
        if lane.trail.back().is_none_or(|q| q.distance(p) > 1e-3) {
            if lane.trail.len() == TRAIL {
                lane.trail.pop_front();
            }
            lane.trail.push_back(p);
        }
        lane.last = Some(s);
    }
}

fn vec3(v: creep_law::Vec3) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// A body's Rapier pose, translation and velocity (`None` before it exists in Rapier).
fn body(set: &RapierRigidBodySet, e: Entity) -> Option<&rapier3d::prelude::RigidBody> {
    set.entity2body().get(&e).and_then(|h| set.bodies.get(*h))
}

/// Means of the recent samples of one contact: speed, creepages (mean slip / mean speed, as
/// the scene's summaries), forces, moment.
fn mean_contact(
    recent: &VecDeque<RobotSample>,
    pick: impl Fn(&RobotSample) -> ContactSample,
) -> [f64; 7] {
    let k = 1.0 / recent.len().max(1) as f64;
    let mut m = [0.0; 7];
    let mut slip = [0.0; 2];
    let mut twist = 0.0;
    for s in recent {
        let c = pick(s);
        m[0] += k * c.speed;
        slip[0] += k * c.slip[0];
        slip[1] += k * c.slip[1];
        twist += k * c.twist;
        m[4] += k * c.fx;
        m[5] += k * c.fy;
        m[6] += k * c.mz;
    }
    let inv_v = if m[0] > 0.0 { 1.0 / m[0] } else { 0.0 };
    m[1] = slip[0] * inv_v;
    m[2] = slip[1] * inv_v;
    m[3] = twist * inv_v;
    m
}

fn draw(
    scene: Option<Res<Scene>>,
    sets: Query<&RapierRigidBodySet, With<DefaultRapierContext>>,
    mut transforms: Query<&mut Transform>,
    mut gizmos: Gizmos,
    mut panel: ResMut<PanelText>,
) {
    let (Some(scene), Ok(rapier_bodies)) = (scene, sets.single()) else {
        return;
    };
    let p = &scene.params;
    let (r, lb) = (p.wheel_radius as f32, p.wheelbase as f32);
    let mut text = format!(
        "differential-drive robot (creep-scenes robot): crowned rubber wheels R = {:.0} mm (a/b = {}), track {:.2} m, caster ball {:.0} mm\n\
         {}: rim speeds left {:+.3}, right {:+.3} m/s (1 spot, 2 arc, 3 straight, Up/Down speed, R restart)\n\
         arrows: orange tangential force ({FORCE_SCALE} m/N), cyan slip velocity ({SLIP_SCALE} m per m/s); magenta circle: spin creepage (1 mm per 1/m)\n",
        1e3 * p.wheel_radius,
        p.contact_ratio,
        p.track,
        1e3 * p.caster_radius,
        scene.command.name(),
        scene.command.speeds().left,
        scene.command.speeds().right,
    );
    for (k, lane) in scene.lanes.iter().enumerate() {
        let robot = &lane.robot;
        let pose = |e: Entity| body(rapier_bodies, e).map(|b| (b.translation(), *b.rotation()));
        // Bodies.
        let Some((cp, cq)) = pose(robot.chassis) else {
            continue;
        };
        let chassis =
            Transform::from_translation((cp + cq * Vec3::new(-0.4 * lb, 0.0, 0.0)) * SCALE)
                .with_rotation(cq);
        let mut set = |e: Entity, t: Transform| {
            if let Ok(mut x) = transforms.get_mut(e) {
                *x = t;
            }
        };
        set(lane.parts[0], chassis);
        for i in 0..2 {
            if let Some((wp, wq)) = pose(robot.wheels[i]) {
                set(
                    lane.parts[1 + i],
                    Transform::from_translation(wp * SCALE)
                        .with_rotation(wq * Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
                );
            }
        }
        if let Some((bp, bq)) = pose(robot.caster) {
            set(
                lane.parts[3],
                Transform::from_translation(bp * SCALE).with_rotation(bq),
            );
        }
        // Trail.
        if lane.trail.len() > 1 {
            gizmos.linestrip(
                lane.trail.iter().map(|&q| q * SCALE),
                if k == 0 {
                    Color::srgb(0.95, 0.75, 0.15)
                } else {
                    Color::srgb(0.3, 0.55, 1.0)
                },
            );
        }
        // Contacts: under each body's centre; the creep frame rebuilt as the scene does it
        // (x against the rolling direction: the wheel's heading, the ball's velocity).
        let Some(s) = lane.last else { continue };
        let heading = cq * Vec3::X;
        let bodies = [
            (robot.wheels[0], r, Some(heading), s.wheels[0]),
            (robot.wheels[1], r, Some(heading), s.wheels[1]),
            (robot.caster, p.caster_radius as f32, None, s.caster),
        ];
        for (e, radius, heading, c) in bodies {
            if !(c.p > 0.0) {
                continue;
            }
            let Some(rb) = body(rapier_bodies, e) else {
                continue;
            };
            let (t, v) = (rb.translation(), rb.linvel());
            let centre = Vec3::new(t.x, t.y, t.z);
            let vel = Vec3::new(v.x, 0.0, v.z);
            let x = match heading {
                Some(hd) if hd.dot(vel) > 0.0 => -hd,
                Some(hd) => hd,
                None => -vel.normalize_or(-Vec3::X),
            };
            let n = Vec3::NEG_Y;
            let y = n.cross(x);
            let at = (centre - Vec3::Y * radius) * SCALE + Vec3::Y * 0.02;
            let force = vec3(c.force);
            let tangential = Vec3::new(force.x, 0.0, force.z);
            if tangential.length() > 0.0 {
                gizmos.arrow(
                    at,
                    at + tangential * FORCE_SCALE * SCALE,
                    Color::srgb(1.0, 0.5, 0.1),
                );
            }
            let slip = (x * c.slip[0] as f32 + y * c.slip[1] as f32) * SLIP_SCALE * SCALE;
            if slip.length() > 0.0 {
                gizmos.arrow(at, at + slip, Color::srgb(0.2, 0.9, 1.0));
            }
            let ring = (c.phi.abs() as f32 * SPIN_SCALE * SCALE).min(0.5 * SCALE);
            if ring > 0.0 {
                gizmos.circle(
                    Isometry3d::new(at, Quat::from_rotation_x(std::f32::consts::FRAC_PI_2)),
                    ring,
                    Color::srgb(1.0, 0.3, 0.9),
                );
            }
        }
        // Panel.
        let (vm, om) = lane
            .recent
            .iter()
            .fold((0.0, 0.0), |(a, b), s| (a + s.speed, b + s.yaw_rate));
        let kk = 1.0 / lane.recent.len().max(1) as f64;
        let (vm, om) = (vm * kk, om * kk);
        let rim = lane.recent.iter().fold([0.0; 2], |a, s| {
            [a[0] + kk * s.rim_speeds[0], a[1] + kk * s.rim_speeds[1]]
        });
        let (_, om_cf, r_cf) = WheelSpeeds::arc(rim[0], rim[1]).kinematics(p.track);
        let radius = if om != 0.0 { vm / om } else { f64::INFINITY };
        text += &format!(
            "{} ({}): V {:+.4} m/s, Omega {:+.4} rad/s (closed form {:+.4}), radius {:.3} m (closed form {:.3}); \
             dissipated {:.3e} J (hook books {:.3e} J)\n",
            match lane.fidelity {
                Fidelity::Creep => "creep-friction",
                _ => "Coulomb twin",
            },
            if k == 0 {
                "yellow, left"
            } else {
                "blue, right"
            },
            vm,
            om,
            om_cf,
            radius,
            r_cf,
            lane.dissipated,
            lane.hook_energy,
        );
        for (name, m) in [
            ("left wheel", mean_contact(&lane.recent, |s| s.wheels[0])),
            ("right wheel", mean_contact(&lane.recent, |s| s.wheels[1])),
            ("caster", mean_contact(&lane.recent, |s| s.caster)),
        ] {
            text += &format!(
                "  {name:<11} xi {:+.2e}  eta {:+.2e}  phi {:+.2e} 1/m  Fx {:+.3} N  Fy {:+.3} N  Mz {:+.2e} N m\n",
                m[1], m[2], m[3], m[4], m[5], m[6]
            );
        }
    }
    if let Some(e) = &scene.error {
        text += &format!("error: {e}\n");
    }
    panel.0 = text;
}
