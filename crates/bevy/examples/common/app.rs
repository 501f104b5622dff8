//! The demo app: the window, the fixed physics schedule (a set number of Rapier steps per
//! frame), the orbit camera, the on-screen panel, frame timing and the shared keys.

use std::time::Instant;

use bevy::ecs::schedule::ScheduleLabel;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::window::WindowResolution;
use bevy::winit::{UpdateMode, WinitSettings};
use bevy_rapier3d::prelude::*;
use creep_bevy::{
    CompliantSettings, CreepFrictionPlugin, CreepGizmos, CreepRapierPlugin, CreepSettings,
};

use super::*;

/// The schedule that holds bevy_rapier3d's and the creep plugin's systems: one run is one
/// Rapier step (the plugin needs that), run [`Stepping::steps_per_frame`] times a frame.
#[derive(ScheduleLabel, Debug, Clone, PartialEq, Eq, Hash)]
pub struct PhysicsStep;

/// How the physics advances: `steps_per_frame` Rapier steps of `dt` each frame (not tied to
/// the wall clock: a run of N frames is the same physics on any machine).
#[derive(Resource, Debug, Clone, Copy)]
pub struct Stepping {
    /// Rapier steps per rendered frame.
    pub steps_per_frame: u32,
    /// Time step [s].
    pub dt: f32,
    /// Paused (Space).
    pub paused: bool,
    /// One step requested while paused (`.`).
    pub single: bool,
    /// Rapier steps taken since the last reset.
    pub steps: u64,
}

impl Stepping {
    /// Simulated time since the last reset [s].
    pub fn time(&self) -> f64 {
        self.steps as f64 * f64::from(self.dt)
    }
}

/// The set of the system that runs the physics steps of a frame: a demo's measuring systems
/// run `.after(StepSet)`, so that the time and the poses they read belong together.
#[derive(SystemSet, Debug, Clone, PartialEq, Eq, Hash)]
pub struct StepSet;

/// Set by R; the demo resets its scene and clears it.
#[derive(Resource, Debug, Default)]
pub struct ResetRequested(pub bool);

/// The demo's window, camera target, physics and shared systems.
pub struct DemoPlugin {
    /// Window title.
    pub title: &'static str,
    /// Common options.
    pub args: CommonArgs,
    /// Time step [s].
    pub dt: f32,
    /// Initial steps per frame.
    pub steps_per_frame: u32,
    /// Gravity [m/s^2].
    pub gravity: Vec3,
    /// The creep plugin's settings (rigid regime).
    pub creep: CreepSettings,
    /// The creep plugin's settings (compliant regime).
    pub compliant: CompliantSettings,
    /// Draw the contacts' forces and creep slips with the plugin's gizmos.
    pub gizmos: bool,
    /// Orbit camera: target, yaw [rad], pitch [rad], distance [m].
    pub camera: OrbitCamera,
    /// Whether the demo steps a bevy_rapier3d world (false: it shows a world stepped
    /// elsewhere, e.g. creep-scenes' triaxial test on a thread).
    pub physics: bool,
    /// Thousands of objects: render without MSAA and with a depth prepass (halves the frame
    /// time of `pour_and_pack` under a software renderer).
    pub many_objects: bool,
}

/// How the camera renders.
#[derive(Resource, Debug, Clone, Copy)]
struct ViewOptions {
    many_objects: bool,
}

impl Plugin for DemoPlugin {
    fn build(&self, app: &mut App) {
        app.add_plugins(DefaultPlugins.set(WindowPlugin {
            primary_window: Some(Window {
                title: self.title.into(),
                resolution: WindowResolution::new(960, 540),
                ..default()
            }),
            ..default()
        }))
        // Continuous frames even unfocused (Xvfb has no focus).
        .insert_resource(WinitSettings {
            focused_mode: UpdateMode::Continuous,
            unfocused_mode: UpdateMode::Continuous,
        })
        .insert_resource(ClearColor(Color::srgb(0.09, 0.10, 0.12)));

        if self.physics {
            let init = RapierContextInitialization::InitializeDefaultRapierContext {
                integration_parameters: IntegrationParameters::default(),
                rapier_configuration: RapierConfiguration {
                    gravity: self.gravity,
                    ..RapierConfiguration::new(1.0)
                },
                broad_phase_optimization_strategy: BroadPhaseOptimizationStrategy::default(),
            };
            app.add_plugins((
                CreepRapierPlugin::default()
                    .with_custom_initialization(init)
                    .in_schedule(PhysicsStep),
                {
                    let p = CreepFrictionPlugin::default()
                        .with_settings(self.creep)
                        .with_compliant_settings(self.compliant)
                        .in_schedule(PhysicsStep);
                    if self.gizmos {
                        p.with_gizmos(CreepGizmos::default())
                    } else {
                        p
                    }
                },
            ))
            .insert_resource(TimestepMode::Fixed {
                dt: self.dt,
                substeps: 1,
            });
        }
        app.insert_resource(Stepping {
            steps_per_frame: self.steps_per_frame,
            dt: self.dt,
            paused: false,
            single: false,
            steps: 0,
        })
        .insert_resource(RunArgs(self.args.clone()))
        .insert_resource(ViewOptions {
            many_objects: self.many_objects,
        })
        .insert_resource(FrameStats::default())
        .init_resource::<ResetRequested>()
        .init_resource::<PanelText>()
        .insert_resource(self.camera)
        .add_systems(Startup, setup_common)
        .add_systems(
            Update,
            (
                keys,
                run_physics.after(keys).in_set(StepSet),
                orbit_camera,
                update_panel,
                frame_stats,
            ),
        );
    }
}

/// The common options, as a resource.
#[derive(Resource, Debug, Clone)]
pub struct RunArgs(pub CommonArgs);

/// The panel's text, written by the demo each frame (the shared part, frame time and steps, is
/// prepended).
#[derive(Resource, Debug, Default)]
pub struct PanelText(pub String);

#[derive(Component)]
struct PanelNode;

/// Frame times (wall clock between frames) for the live display and the median on exit.
#[derive(Resource, Debug, Default)]
pub struct FrameStats {
    /// Frames rendered.
    pub frames: u64,
    last: Option<Instant>,
    /// Frame times after the warm-up [s].
    pub times: Vec<f64>,
    /// Smoothed frame time [s].
    pub smoothed: f64,
    /// Wall-clock time of the physics steps of each frame after the warm-up [s].
    pub physics: Vec<f64>,
    /// Smoothed physics time per frame [s].
    pub physics_smoothed: f64,
    screenshot_requested: bool,
}

/// Frames not counted in the median (shader compilation, first uploads).
pub const WARM_UP_FRAMES: u64 = 20;

impl FrameStats {
    /// Median of the frame times after the warm-up [s].
    pub fn median(&self) -> Option<f64> {
        if self.times.is_empty() {
            return None;
        }
        let mut t = self.times.clone();
        t.sort_by(f64::total_cmp);
        Some(t[t.len() / 2])
    }
    /// The line printed on exit.
    pub fn report(&self) -> String {
        match self.median() {
            Some(m) => {
                let mut t = self.times.clone();
                t.sort_by(f64::total_cmp);
                let p = |q: f64| t[((t.len() - 1) as f64 * q).round() as usize] * 1e3;
                let mut ph = self.physics.clone();
                ph.sort_by(f64::total_cmp);
                let physics = if ph.is_empty() {
                    String::new()
                } else {
                    format!("; physics median {:.1} ms a frame", ph[ph.len() / 2] * 1e3)
                };
                format!(
                    "frame time: median {:.1} ms over {} frames after {} warm-up frames (p10 {:.1} ms, p90 {:.1} ms){physics}",
                    m * 1e3,
                    t.len(),
                    WARM_UP_FRAMES,
                    p(0.1),
                    p(0.9)
                )
            }
            None => format!(
                "frame time: fewer than {} frames, no median",
                WARM_UP_FRAMES + 1
            ),
        }
    }
}

/// The orbit camera (a resource: the one camera of the demo).
#[derive(Resource, Debug, Clone, Copy)]
pub struct OrbitCamera {
    /// Point looked at [m].
    pub target: Vec3,
    /// Angle about the vertical axis [rad].
    pub yaw: f32,
    /// Elevation [rad].
    pub pitch: f32,
    /// Distance from the target [m].
    pub distance: f32,
    /// The screen's up direction (unit; `Vec3::Y` unless the scene tilts its gravity, as the
    /// incline does: then up is against gravity, and the floor looks inclined).
    pub up: Vec3,
}

impl OrbitCamera {
    /// The camera's transform.
    pub fn transform(&self) -> Transform {
        let local = Vec3::new(
            self.pitch.cos() * self.yaw.sin(),
            self.pitch.sin(),
            self.pitch.cos() * self.yaw.cos(),
        );
        let dir = Quat::from_rotation_arc(Vec3::Y, self.up) * local;
        Transform::from_translation(self.target + dir * self.distance)
            .looking_at(self.target, self.up)
    }
}

#[derive(Component)]
struct MainCamera;

fn setup_common(mut commands: Commands, orbit: Res<OrbitCamera>, options: Res<ViewOptions>) {
    let mut camera = commands.spawn((Camera3d::default(), orbit.transform(), MainCamera));
    if options.many_objects {
        // Thousands of small overlapping objects: a CPU renderer (llvmpipe) is fill-bound,
        // so no 4x MSAA and a depth prepass (each pixel shaded once).
        camera.insert((
            bevy::render::view::Msaa::Off,
            bevy::core_pipeline::prepass::DepthPrepass,
        ));
    }
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
        PanelNode,
    ));
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut stepping: ResMut<Stepping>,
    mut reset: ResMut<ResetRequested>,
    mut exit: MessageWriter<AppExit>,
) {
    if input.just_pressed(KeyCode::Space) {
        stepping.paused = !stepping.paused;
    }
    if input.just_pressed(KeyCode::Period) {
        stepping.single = true;
    }
    if input.just_pressed(KeyCode::Equal) || input.just_pressed(KeyCode::NumpadAdd) {
        stepping.steps_per_frame = (stepping.steps_per_frame * 2).min(256);
    }
    if input.just_pressed(KeyCode::Minus) || input.just_pressed(KeyCode::NumpadSubtract) {
        stepping.steps_per_frame = (stepping.steps_per_frame / 2).max(1);
    }
    if input.just_pressed(KeyCode::KeyR) {
        reset.0 = true;
    }
    if input.just_pressed(KeyCode::Escape) {
        exit.write(AppExit::Success);
    }
}

/// Runs [`PhysicsStep`] `steps_per_frame` times (once when `.` was pressed while paused).
fn run_physics(world: &mut World) {
    if !world.contains_resource::<TimestepMode>() {
        return; // no bevy_rapier3d world (`DemoPlugin::physics` false)
    }
    let s = *world.resource::<Stepping>();
    let n = if s.paused {
        u32::from(s.single)
    } else {
        s.steps_per_frame
    };
    world.resource_mut::<Stepping>().single = false;
    let start = Instant::now();
    for _ in 0..n {
        world.run_schedule(PhysicsStep);
        world.resource_mut::<Stepping>().steps += 1;
    }
    let elapsed = start.elapsed().as_secs_f64();
    let mut stats = world.resource_mut::<FrameStats>();
    stats.physics_smoothed = if stats.physics_smoothed == 0.0 {
        elapsed
    } else {
        0.9 * stats.physics_smoothed + 0.1 * elapsed
    };
    if stats.frames > WARM_UP_FRAMES {
        stats.physics.push(elapsed);
    }
}

fn orbit_camera(
    buttons: Res<ButtonInput<MouseButton>>,
    motion: Res<AccumulatedMouseMotion>,
    scroll: Res<AccumulatedMouseScroll>,
    mut orbit: ResMut<OrbitCamera>,
    mut camera: Query<&mut Transform, With<MainCamera>>,
) {
    if buttons.pressed(MouseButton::Left) && motion.delta != Vec2::ZERO {
        orbit.yaw -= motion.delta.x * 0.005;
        orbit.pitch = (orbit.pitch + motion.delta.y * 0.005).clamp(-1.5, 1.5);
    }
    if scroll.delta.y != 0.0 {
        orbit.distance = (orbit.distance * (1.0 - 0.1 * scroll.delta.y.signum())).max(0.01);
    }
    if orbit.is_changed() {
        for mut t in &mut camera {
            *t = orbit.transform();
        }
    }
}

fn update_panel(
    panel: Res<PanelText>,
    stats: Res<FrameStats>,
    stepping: Res<Stepping>,
    physics: Option<Res<TimestepMode>>,
    mut text: Query<&mut Text, With<PanelNode>>,
) {
    let head = if physics.is_none() {
        format!("frame {:.1} ms\n", stats.smoothed * 1e3)
    } else {
        format!(
            "frame {:.1} ms (physics {:.1} ms) | t = {:.3} s | {} step(s)/frame of {:.2} ms{}\n",
            stats.smoothed * 1e3,
            stats.physics_smoothed * 1e3,
            stepping.time(),
            stepping.steps_per_frame,
            stepping.dt * 1e3,
            if stepping.paused { " | PAUSED" } else { "" }
        )
    };
    for mut t in &mut text {
        t.0 = format!("{head}{}", panel.0);
    }
}

fn frame_stats(
    mut commands: Commands,
    mut stats: ResMut<FrameStats>,
    args: Res<RunArgs>,
    mut exit: MessageWriter<AppExit>,
) {
    let now = Instant::now();
    if let Some(last) = stats.last {
        let dt = (now - last).as_secs_f64();
        stats.smoothed = if stats.smoothed == 0.0 {
            dt
        } else {
            0.9 * stats.smoothed + 0.1 * dt
        };
        if stats.frames > WARM_UP_FRAMES {
            stats.times.push(dt);
        }
    }
    stats.last = Some(now);
    stats.frames += 1;
    let Some(frames) = args.0.frames else {
        return;
    };
    if stats.frames < frames {
        return;
    }
    match &args.0.screenshot {
        Some(path) if !stats.screenshot_requested => {
            stats.screenshot_requested = true;
            let shown = path.display().to_string();
            commands
                .spawn(Screenshot::primary_window())
                .observe(save_to_disk(path.clone()))
                .observe(
                    move |_: On<ScreenshotCaptured>,
                          stats: Res<FrameStats>,
                          mut exit: MessageWriter<AppExit>| {
                        println!("screenshot saved to {shown}");
                        println!("{}", stats.report());
                        exit.write(AppExit::Success);
                    },
                );
        }
        Some(_) => {} // waiting for the capture
        None => {
            println!("{}", stats.report());
            exit.write(AppExit::Success);
        }
    }
}
