//! `incline_race`: two identical balls roll down parallel lanes of one incline in Avian, one
//! with creep-friction (yellow) and its Coulomb twin (blue, Avian's own friction), with the
//! law's figure on screen: the creep slip the creep ball measures (its slip less the twin's)
//! beside Kalker's steady creepage `F_ss(Q/(mu P))` at the force its contact transmits.
//!
//! The scene is `creep_avian::scenes::incline` (`InclineParams::default()`: a 0.1 m steel ball,
//! mu = 0.5, a 20 degree incline made of a flat static cuboid with the gravity tilted by theta,
//! dt = 1/240 s, Avian's 6 substeps, the plugin's rotation-gap removal on), so this demo and
//! `cargo run -p creep-avian --example incline` are the same scene; the camera's up is against
//! the gravity, so the floor looks inclined.
//!
//! Keys: F cycles the creep lane's fidelity (Creep, Auto, Coulomb), M cycles the material
//! (steel, glass, rubber), R restarts, Space pauses, +/- physics steps per frame, Esc quits.
//!
//! Run: `cargo run -p creep-avian --features render --example incline_race --ignore-rust-version`
//! (`-- --screenshot out.png --frames 60` renders 60 frames, saves a screenshot and exits).

use std::path::PathBuf;
use std::time::Duration;

use avian3d::prelude::*;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::math::DVec3;
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::window::WindowResolution;
use bevy::winit::{UpdateMode, WinitSettings};
use creep_avian::prelude::*;
use creep_avian::scenes::{DEFAULT_SUBSTEPS, G, InclineParams, RollingMeter, kalker_creepage};
use creep_law::{Material, Surface};

const USAGE: &str = "incline_race: creep-friction and Coulomb friction on one incline, in Avian

usage: incline_race [--material steel|glass|rubber] [--screenshot FILE.png] [--frames N]
  --material M          ball and incline material (default steel; mu = 0.5)
  --screenshot FILE.png save a screenshot after --frames frames (default 60), then exit
  --frames N            render N frames, then exit
keys: F cycles the creep lane's fidelity (Creep, Auto, Coulomb), M cycles the material,
      R restarts, Space pauses, +/- physics steps per frame, Esc quits";

/// The materials M cycles through.
const MATERIALS: [&str; 3] = ["steel", "glass", "rubber"];
/// Lanes' distance apart along z \[m\].
const LANE: f32 = 0.5;
/// Simulated seconds before the race restarts by itself \[s\].
const RACE_TIME: f64 = 3.0;
/// The slips are measured from this time on (the start's transient left out) \[s\].
const MEASURE_FROM: f64 = 0.25;
/// Lane colours: Coulomb twin, creep ball.
const LANE_COLOURS: [Color; 2] = [Color::srgb(0.35, 0.59, 1.0), Color::srgb(1.0, 0.78, 0.16)];
/// The bars' full width \[px\].
const BAR_WIDTH: f32 = 360.0;

/// The schedule holding Avian's physics: one run is one physics step of `dt`.
#[derive(ScheduleLabel, Debug, Clone, PartialEq, Eq, Hash)]
struct PhysicsStep;

/// The command line.
#[derive(Resource, Debug, Clone, Default)]
struct Args {
    material: usize,
    screenshot: Option<PathBuf>,
    frames: Option<u64>,
}

/// The command line, or the usage and exit code 2 (0 for `--help`).
fn args_or_exit() -> Args {
    fn fail(msg: &str) -> ! {
        eprintln!("error: {msg}\n\n{USAGE}");
        std::process::exit(2);
    }
    let mut args = Args::default();
    let mut it = std::env::args().skip(1);
    while let Some(arg) = it.next() {
        if arg == "--help" || arg == "-h" {
            println!("{USAGE}");
            std::process::exit(0);
        }
        let (flag, value) = match arg.split_once('=') {
            Some((f, v)) => (f.to_string(), v.to_string()),
            None => {
                let v = it
                    .next()
                    .unwrap_or_else(|| fail(&format!("`{arg}` needs a value")));
                (arg, v)
            }
        };
        match flag.as_str() {
            "--material" => {
                args.material = MATERIALS
                    .iter()
                    .position(|m| *m == value)
                    .unwrap_or_else(|| {
                        fail(&format!(
                            "--material `{value}`: expected steel, glass or rubber"
                        ))
                    });
            }
            "--frames" => match value.parse::<u64>() {
                Ok(n) if (1..=10_000_000).contains(&n) => args.frames = Some(n),
                _ => fail(&format!(
                    "--frames `{value}`: expected a whole number in [1, 10000000]"
                )),
            },
            "--screenshot" => {
                let path = PathBuf::from(&value);
                if path.extension().and_then(|e| e.to_str()) != Some("png") {
                    fail(&format!(
                        "--screenshot `{value}`: the file name must end in .png"
                    ));
                }
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
                    && !dir.is_dir()
                {
                    fail(&format!(
                        "--screenshot `{value}`: directory `{}` does not exist",
                        dir.display()
                    ));
                }
                args.screenshot = Some(path);
            }
            _ => fail(&format!("unknown option `{flag}`")),
        }
    }
    if args.screenshot.is_some() && args.frames.is_none() {
        args.frames = Some(60);
    }
    // The render feature enables winit's X11 backend only: without a display winit would
    // panic, so say what is missing instead.
    if cfg!(target_os = "linux") && std::env::var_os("DISPLAY").is_none() {
        eprintln!(
            "error: no X display (DISPLAY is not set). Headless: `Xvfb :99 &` and run with \
             DISPLAY=:99"
        );
        std::process::exit(2);
    }
    args
}

/// creep-law's material `MATERIALS[index]` with mu = 0.5.
fn material(index: usize) -> Material {
    let m = match index % MATERIALS.len() {
        0 => Material::steel(),
        1 => Material::glass(),
        _ => Material::rubber(),
    };
    m.with_friction(0.5)
        .expect("0.5 is a valid friction coefficient")
}

/// How the physics advances: `steps_per_frame` steps of `dt` each frame, not tied to the wall
/// clock (a run of N frames is the same physics on any machine).
#[derive(Resource, Debug, Clone, Copy)]
struct Stepping {
    steps_per_frame: u32,
    dt: Duration,
    paused: bool,
    /// Steps since the last restart.
    steps: u64,
    /// A restart asked for (R, F, M, or the race's end).
    restart: bool,
}

impl Stepping {
    /// Simulated time since the last restart \[s\].
    fn time(&self) -> f64 {
        self.steps as f64 * self.dt.as_secs_f64()
    }
}

/// The race: parameters, lane choice and what the lanes measured.
#[derive(Resource)]
struct Race {
    params: InclineParams,
    material: usize,
    fidelity: Fidelity,
    lanes: [Lane; 2],
    /// The creep contact's normal force and tangential force summed over the measured steps
    /// \[N\], and their count.
    p_sum: f64,
    q_sum: creep_law::Vec3,
    samples: usize,
    mesh: Handle<Mesh>,
    marker: Handle<Mesh>,
    lane_materials: [Handle<StandardMaterial>; 2],
    marker_material: Handle<StandardMaterial>,
}

/// One lane's ball and its measurement.
#[derive(Default, Clone, Copy)]
struct Lane {
    ball: Option<Entity>,
    x: f64,
    v: f64,
    meter: RollingMeter,
    /// Position and accumulated rotation at `MEASURE_FROM`.
    start: Option<(f64, f64)>,
}

impl Lane {
    /// Slip since `MEASURE_FROM`, `(dx + R dtheta) / dx` (the ball rolls towards +x turning
    /// about -z) \[-\].
    fn slip(&self, radius: f64) -> Option<f64> {
        let (x0, a0) = self.start?;
        let dx = self.x - x0;
        (dx > 1e-3).then(|| (dx + radius * (self.meter.angle - a0)) / dx)
    }
}

/// Marks what a restart despawns.
#[derive(Component)]
struct RaceEntity;

#[derive(Component)]
struct MainCamera;

#[derive(Component)]
struct PanelText;

/// Bar `k` of the figure: Kalker's creepage, the measured creep slip, the twin's slip.
#[derive(Component)]
struct Bar(usize);

#[derive(Component)]
struct BarValue(usize);

/// Frames rendered and whether the screenshot was asked for.
#[derive(Resource, Default)]
struct Frames {
    count: u64,
    screenshot_requested: bool,
}

fn main() {
    let args = args_or_exit();
    let params = InclineParams {
        material: material(args.material),
        ..InclineParams::default()
    };
    let gravity = Vec3::new(
        (G * params.theta.sin()) as f32,
        (-G * params.theta.cos()) as f32,
        0.0,
    );
    App::new()
        .add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: "creep-avian: incline race".into(),
                resolution: WindowResolution::new(960, 540),
                ..default()
            }),
            ..default()
        }))
        .add_plugins((
            PhysicsPlugins::new(PhysicsStep).with_collision_hooks::<CreepHooks>(),
            // As the crate's README advises: the balls' own rotation out of the separation
            // Avian's solver reads at each substep.
            CreepAvianPlugin::default().with_rotation_gap_removal(true),
        ))
        .insert_resource(SubstepCount(DEFAULT_SUBSTEPS))
        .insert_resource(Gravity(gravity))
        // Continuous frames even unfocused (Xvfb has no focus).
        .insert_resource(WinitSettings {
            focused_mode: UpdateMode::Continuous,
            unfocused_mode: UpdateMode::Continuous,
        })
        .insert_resource(ClearColor(Color::srgb(0.09, 0.10, 0.12)))
        .insert_resource(Stepping {
            steps_per_frame: 8,
            dt: Duration::from_secs_f64(params.dt),
            paused: false,
            steps: 0,
            restart: true,
        })
        .insert_resource(StartParams(params, args.material))
        .insert_resource(args)
        .init_resource::<Frames>()
        .add_systems(Startup, setup)
        .add_systems(
            Update,
            (
                keys,
                restart,
                run_physics,
                follow_camera,
                panel,
                draw_lanes,
                frames,
            )
                .chain(),
        )
        .run();
}

#[derive(Resource)]
struct StartParams(InclineParams, usize);

fn setup(
    mut commands: Commands,
    start: Res<StartParams>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
) {
    let p = start.0;
    let r = p.radius as f32;
    let lane_materials = LANE_COLOURS.map(|c| {
        materials.add(StandardMaterial {
            base_color: c,
            perceptual_roughness: 0.4,
            metallic: 0.3,
            ..default()
        })
    });
    commands.insert_resource(Race {
        params: p,
        material: start.1,
        fidelity: Fidelity::Creep,
        lanes: [Lane::default(); 2],
        p_sum: 0.0,
        q_sum: creep_law::Vec3::ZERO,
        samples: 0,
        mesh: meshes.add(Sphere::new(r).mesh().uv(32, 18)),
        marker: meshes.add(Sphere::new(0.25 * r).mesh().uv(12, 8)),
        lane_materials,
        marker_material: materials.add(StandardMaterial {
            base_color: Color::srgb(0.05, 0.05, 0.05),
            ..default()
        }),
    });
    // The incline: the scene's static cuboid (top face at y = 0), drawn 60 m long. Its fidelity
    // is Creep so that each ball's own fidelity decides (a pair takes the lower of the two).
    commands.spawn((
        RigidBody::Static,
        Collider::cuboid(2.0e3, 1.0, 20.0),
        Transform::from_xyz(0.0, -0.5, 0.0),
        Friction::new(p.material.friction() as f32),
        CreepMaterial::new(p.material).with_fidelity(Fidelity::Creep),
    ));
    commands.spawn((
        Mesh3d(meshes.add(Cuboid::new(60.0, 0.02, 2.0 * LANE + 0.4))),
        MeshMaterial3d(materials.add(StandardMaterial {
            base_color: Color::srgb(0.35, 0.37, 0.40),
            perceptual_roughness: 0.9,
            ..default()
        })),
        Transform::from_xyz(29.0, -0.01, 0.0),
    ));
    commands.spawn((Camera3d::default(), Transform::default(), MainCamera));
    commands.spawn((
        DirectionalLight {
            illuminance: 9_000.0,
            shadow_maps_enabled: false,
            ..default()
        },
        Transform::from_xyz(3.0, 8.0, 5.0).looking_at(Vec3::ZERO, Vec3::Y),
    ));
    commands.insert_resource(GlobalAmbientLight {
        brightness: 400.0,
        ..default()
    });
    // The panel (top left) and the figure (bottom right).
    commands.spawn((
        Node {
            position_type: PositionType::Absolute,
            top: Val::Px(6.0),
            left: Val::Px(6.0),
            padding: UiRect::all(Val::Px(6.0)),
            ..default()
        },
        BackgroundColor(Color::srgba(0.0, 0.0, 0.0, 0.6)),
        Text::new(""),
        TextFont::from_font_size(13.0),
        TextColor(Color::srgb(0.92, 0.92, 0.92)),
        PanelText,
    ));
    let labels = [
        ("Kalker F_ss(Q/mu P)", Color::srgb(0.92, 0.92, 0.92)),
        ("creep slip, measured", LANE_COLOURS[1]),
        ("Coulomb twin's slip", LANE_COLOURS[0]),
    ];
    commands
        .spawn((
            Node {
                position_type: PositionType::Absolute,
                bottom: Val::Px(6.0),
                right: Val::Px(6.0),
                padding: UiRect::all(Val::Px(8.0)),
                flex_direction: FlexDirection::Column,
                row_gap: Val::Px(4.0),
                ..default()
            },
            BackgroundColor(Color::srgba(0.0, 0.0, 0.0, 0.6)),
        ))
        .with_children(|c| {
            c.spawn((
                Text::new(
                    "the law's figure: creepage of the creep ball's contact\n\
                     (its slip less the Coulomb twin's) against Kalker's",
                ),
                TextFont::from_font_size(13.0),
                TextColor(Color::srgb(0.92, 0.92, 0.92)),
            ));
            for (k, (label, colour)) in labels.into_iter().enumerate() {
                c.spawn(Node {
                    flex_direction: FlexDirection::Row,
                    align_items: AlignItems::Center,
                    column_gap: Val::Px(6.0),
                    ..default()
                })
                .with_children(|row| {
                    row.spawn((
                        Node {
                            width: Val::Px(150.0),
                            ..default()
                        },
                        Text::new(label),
                        TextFont::from_font_size(13.0),
                        TextColor(colour),
                    ));
                    row.spawn((
                        Node {
                            width: Val::Px(BAR_WIDTH),
                            height: Val::Px(14.0),
                            ..default()
                        },
                        BackgroundColor(Color::srgba(1.0, 1.0, 1.0, 0.06)),
                    ))
                    .with_children(|track| {
                        track.spawn((
                            Node {
                                width: Val::Px(0.0),
                                height: Val::Percent(100.0),
                                ..default()
                            },
                            BackgroundColor(colour),
                            Bar(k),
                        ));
                    });
                    row.spawn((
                        Node {
                            width: Val::Px(80.0),
                            ..default()
                        },
                        Text::new(""),
                        TextFont::from_font_size(13.0),
                        TextColor(colour),
                        BarValue(k),
                    ));
                });
            }
        });
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut race: ResMut<Race>,
    mut stepping: ResMut<Stepping>,
    mut exit: MessageWriter<AppExit>,
) {
    if input.just_pressed(KeyCode::KeyF) {
        race.fidelity = match race.fidelity {
            Fidelity::Creep => Fidelity::Auto,
            Fidelity::Auto => Fidelity::Coulomb,
            Fidelity::Coulomb => Fidelity::Creep,
        };
        stepping.restart = true;
    }
    if input.just_pressed(KeyCode::KeyM) {
        race.material = (race.material + 1) % MATERIALS.len();
        race.params.material = material(race.material);
        stepping.restart = true;
    }
    if input.just_pressed(KeyCode::KeyR) {
        stepping.restart = true;
    }
    if input.just_pressed(KeyCode::Space) {
        stepping.paused = !stepping.paused;
    }
    if input.just_pressed(KeyCode::Equal) || input.just_pressed(KeyCode::NumpadAdd) {
        stepping.steps_per_frame = (stepping.steps_per_frame * 2).min(64);
    }
    if input.just_pressed(KeyCode::Minus) || input.just_pressed(KeyCode::NumpadSubtract) {
        stepping.steps_per_frame = (stepping.steps_per_frame / 2).max(1);
    }
    if input.just_pressed(KeyCode::Escape) {
        exit.write(AppExit::Success);
    }
}

/// Respawns the two balls at the top of their lanes (on R, F, M, or at the race's end).
fn restart(
    mut commands: Commands,
    mut race: ResMut<Race>,
    mut stepping: ResMut<Stepping>,
    old: Query<Entity, With<RaceEntity>>,
    mut floor: Query<(&mut CreepMaterial, &mut Friction), Without<RaceEntity>>,
) {
    if !stepping.restart && stepping.time() < RACE_TIME {
        return;
    }
    stepping.restart = false;
    stepping.steps = 0;
    for e in &old {
        commands.entity(e).despawn();
    }
    let p = race.params;
    for (mut m, mut f) in &mut floor {
        m.material = p.material;
        f.dynamic_coefficient = p.material.friction() as f32;
        f.static_coefficient = p.material.friction() as f32;
    }
    let r = p.radius as f32;
    for lane in 0..2 {
        let fidelity = if lane == 0 {
            Fidelity::Coulomb
        } else {
            race.fidelity
        };
        let ball = commands
            .spawn((
                RigidBody::Dynamic,
                Collider::sphere(r),
                ColliderDensity(p.material.density() as f32),
                Friction::new(p.material.friction() as f32),
                Transform::from_xyz(0.0, r, (lane as f32 - 0.5) * LANE),
                SleepingDisabled,
                CreepMaterial::new(p.material).with_fidelity(fidelity),
                Mesh3d(race.mesh.clone()),
                MeshMaterial3d(race.lane_materials[lane].clone()),
                RaceEntity,
            ))
            .with_children(|c| {
                // Markers on the surface, to see the rotation.
                for at in [
                    Vec3::new(0.0, 0.0, 0.9 * r),
                    Vec3::new(0.0, 0.0, -0.9 * r),
                    Vec3::new(0.0, 0.9 * r, 0.0),
                ] {
                    c.spawn((
                        Mesh3d(race.marker.clone()),
                        MeshMaterial3d(race.marker_material.clone()),
                        Transform::from_translation(at),
                    ));
                }
            })
            .id();
        race.lanes[lane] = Lane {
            ball: Some(ball),
            ..Lane::default()
        };
    }
    race.p_sum = 0.0;
    race.q_sum = creep_law::Vec3::ZERO;
    race.samples = 0;
}

/// Runs `steps_per_frame` physics steps of `dt` (Avian takes its step from the generic `Time`'s
/// delta), measuring the lanes after each.
fn run_physics(world: &mut World) {
    let s = *world.resource::<Stepping>();
    if s.paused {
        return;
    }
    let frame_clock = *world.resource::<Time>();
    let mut clock = Time::<()>::default();
    clock.advance_by(s.dt);
    for _ in 0..s.steps_per_frame {
        *world.resource_mut::<Time>() = clock;
        world.run_schedule(PhysicsStep);
        world.resource_mut::<Stepping>().steps += 1;
        measure(world);
    }
    *world.resource_mut::<Time>() = frame_clock;
}

/// Each lane's position, speed and rotation after a step, and the creep contact's loads.
fn measure(world: &mut World) {
    let t = world.resource::<Stepping>().time();
    let balls = world.resource::<Race>().lanes.map(|l| l.ball);
    let mut poses = [None; 2];
    for (k, ball) in balls.iter().enumerate() {
        let Some(e) = *ball else { continue };
        let (Some(pos), Some(rot), Some(v)) = (
            world.get::<Position>(e),
            world.get::<Rotation>(e),
            world.get::<LinearVelocity>(e),
        ) else {
            continue;
        };
        poses[k] = Some((f64::from(pos.0.x), rot.0, f64::from(v.0.x)));
    }
    let loads = balls[1].and_then(|creep_ball| {
        world
            .resource::<CreepState>()
            .contacts()
            .into_iter()
            .find(|c| c.colliders.0 == creep_ball || c.colliders.1 == creep_ball)
            .filter(|c| c.p > 0.0)
            .map(|c| (c.p, c.q_meas))
    });
    let mut race = world.resource_mut::<Race>();
    for (lane, pose) in race.lanes.iter_mut().zip(poses) {
        let Some((x, rot, v)) = pose else { continue };
        lane.meter.update(rot, DVec3::Z);
        lane.x = x;
        lane.v = v;
        if lane.start.is_none() && t >= MEASURE_FROM {
            lane.start = Some((x, lane.meter.angle));
        }
    }
    if t >= MEASURE_FROM
        && let Some((p, q)) = loads
    {
        race.p_sum += p;
        race.q_sum += q;
        race.samples += 1;
    }
}

/// The camera looks a little ahead of the balls, its up against the gravity.
fn follow_camera(
    race: Res<Race>,
    gravity: Res<Gravity>,
    mut camera: Query<&mut Transform, With<MainCamera>>,
) {
    let x = 0.5 * (race.lanes[0].x + race.lanes[1].x) as f32;
    let target = Vec3::new(x + 0.4, 0.1, 0.0);
    let up = -gravity.0.normalize_or(Vec3::NEG_Y);
    let (yaw, pitch, distance) = (0.35f32, 0.45f32, 2.6f32);
    let local = Vec3::new(
        pitch.cos() * yaw.sin(),
        pitch.sin(),
        pitch.cos() * yaw.cos(),
    );
    let eye = target + Quat::from_rotation_arc(Vec3::Y, up) * local * distance;
    for mut t in &mut camera {
        *t = Transform::from_translation(eye).looking_at(target, up);
    }
}

/// The panel's text and the figure's bars.
fn panel(
    race: Res<Race>,
    stepping: Res<Stepping>,
    state: Res<CreepState>,
    mut text: Query<&mut Text, With<PanelText>>,
    mut bars: Query<(&mut Node, &Bar)>,
    mut values: Query<(&mut Text, &BarValue), Without<PanelText>>,
) {
    let p = race.params;
    let r = p.radius;
    let t = stepping.time();
    let mu = p.material.friction();
    let slips = race.lanes.map(|l| l.slip(r));
    let measured = match slips {
        [Some(coulomb), Some(creep)] => Some(creep - coulomb),
        _ => None,
    };
    // Kalker's creepage at the transmitted force (mean over the measured steps), else at the
    // closed-form loads of rolling without slip.
    let (pn, q) = if race.samples > 0 {
        let n = race.samples as f64;
        (race.p_sum / n, race.q_sum.length() / n)
    } else {
        p.rolling_loads()
    };
    let kalker = kalker_creepage(&p.material, Surface::Plane, Surface::Sphere(r), pn, q).ok();
    let fmt = |x: Option<f64>| x.map_or("-".to_string(), |x| format!("{x:+.3e}"));
    let mut s = format!(
        "incline race in Avian: {} ball R = {r} m, mu = {mu}, theta = {:.0} deg, dt = 1/{:.0} s, \
         {DEFAULT_SUBSTEPS} substeps\n\
         t = {t:.2} s, {} steps/frame{}; F fidelity, M material, R restart, Space pause\n",
        MATERIALS[race.material],
        p.theta.to_degrees(),
        1.0 / p.dt,
        stepping.steps_per_frame,
        if stepping.paused { " (paused)" } else { "" },
    );
    let names = ["Coulomb twin", "creep ball"];
    let fidelities = [Fidelity::Coulomb, race.fidelity];
    for (k, l) in race.lanes.iter().enumerate() {
        s += &format!(
            "{:>12} ({:?}): x {:6.3} m  v {:5.3} m/s  slip {}\n",
            names[k],
            fidelities[k],
            l.x,
            l.v,
            fmt(slips[k]),
        );
    }
    s += &format!(
        "creep ball's contact: P {pn:.2} N, Q {q:.3} N, Q/(mu P) {:.3}\n",
        q / (mu * pn)
    );
    let diff = match (measured, kalker) {
        (Some(m), Some(k)) if k > 0.0 => format!("{:+.1} %", 100.0 * (m - k) / k),
        _ => "-".into(),
    };
    s += &format!(
        "creep slip {} vs Kalker F_ss(Q/mu P) {}: difference {diff}\n",
        fmt(measured),
        fmt(kalker)
    );
    let counts = state.counts();
    s += &format!(
        "plugin: {} creep contact(s), loop gain {:.2}, creep power {:.2e} W",
        counts.creep, counts.max_loop_gain, counts.creep_power
    );
    for mut t in &mut text {
        t.0 = s.clone();
    }
    // The figure: Kalker's creepage, the measured creep slip, the twin's own slip.
    let figures = [kalker, measured, slips[0]];
    let scale = figures.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs())) * 1.1;
    for (mut node, bar) in &mut bars {
        let w = match figures[bar.0] {
            Some(x) if scale > 0.0 => (x.abs() / scale) as f32 * BAR_WIDTH,
            _ => 0.0,
        };
        node.width = Val::Px(w);
    }
    for (mut text, v) in &mut values {
        text.0 = fmt(figures[v.0]);
    }
}

/// Cross lines on the incline every 0.5 m around the balls, so that their motion shows.
fn draw_lanes(mut gizmos: Gizmos, race: Res<Race>) {
    let x0 = (0.5 * (race.lanes[0].x + race.lanes[1].x) as f32 / 0.5).floor() * 0.5;
    let colour = Color::srgb(0.75, 0.75, 0.8);
    for i in -8..=12 {
        let x = x0 + i as f32 * 0.5;
        gizmos.line(
            Vec3::new(x, 0.002, -LANE - 0.2),
            Vec3::new(x, 0.002, LANE + 0.2),
            colour,
        );
    }
    for z in [-LANE - 0.2, 0.0, LANE + 0.2] {
        gizmos.line(
            Vec3::new(x0 - 4.0, 0.002, z),
            Vec3::new(x0 + 6.0, 0.002, z),
            colour,
        );
    }
}

/// After `--frames` frames: save the screenshot (`--screenshot`) and exit.
fn frames(mut commands: Commands, mut frames: ResMut<Frames>, args: Res<Args>) {
    frames.count += 1;
    let Some(n) = args.frames else { return };
    if frames.count < n || frames.screenshot_requested {
        return;
    }
    frames.screenshot_requested = true;
    match &args.screenshot {
        Some(path) => {
            let shown = path.display().to_string();
            commands
                .spawn(Screenshot::primary_window())
                .observe(save_to_disk(path.clone()))
                .observe(
                    move |_: On<ScreenshotCaptured>, mut exit: MessageWriter<AppExit>| {
                        println!("screenshot saved to {shown}");
                        exit.write(AppExit::Success);
                    },
                );
        }
        None => {
            commands.write_message(AppExit::Success);
        }
    }
}
