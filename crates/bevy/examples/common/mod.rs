//! Shared by the desktop demos (feature `render`): command-line options (`--screenshot`,
//! `--frames`), the window, an orbit camera, the on-screen panel, a live plot drawn into a
//! texture, the physics schedule (a fixed number of Rapier steps per frame, so that a run of N
//! frames is reproducible), frame timing and the keys every demo shares.
//!
//! Keys: Space pauses, `.` steps once while paused, `+`/`-` change the physics steps per frame,
//! R resets (the demo's own reset), Esc quits. Mouse: left drag orbits, wheel zooms.
#![allow(dead_code)] // each demo uses a part

use std::path::PathBuf;
use std::time::Instant;

use bevy::asset::RenderAssetUsages;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::input::mouse::{AccumulatedMouseMotion, AccumulatedMouseScroll};
use bevy::prelude::*;
use bevy::render::render_resource::{Extent3d, TextureDimension, TextureFormat};
use bevy::render::view::screenshot::{Screenshot, ScreenshotCaptured, save_to_disk};
use bevy::window::WindowResolution;
use bevy::winit::{UpdateMode, WinitSettings};
use bevy_rapier3d::prelude::*;
use creep_bevy::{
    CompliantSettings, CreepFrictionPlugin, CreepGizmos, CreepRapierPlugin, CreepSettings,
};

// ---------------------------------------------------------------------------------------------
// Command line
// ---------------------------------------------------------------------------------------------

/// The options every demo takes.
#[derive(Debug, Clone, Default)]
pub struct CommonArgs {
    /// Save a screenshot of the window here after `frames` frames, then exit.
    pub screenshot: Option<PathBuf>,
    /// Render this many frames, then exit (with `screenshot`: the frame it captures).
    pub frames: Option<u64>,
}

/// A command-line error: printed with the usage, exit code 2.
#[derive(Debug)]
pub struct ArgError(pub String);

/// The command-line arguments after the program name, split into the common options and the
/// rest (for the demo's own options, in order, as `(flag, value)` pairs). Every option takes
/// one value (`--flag value` or `--flag=value`).
pub fn parse_args(
    args: impl IntoIterator<Item = String>,
    own_flags: &[&str],
) -> Result<(CommonArgs, Vec<(String, String)>), ArgError> {
    let mut common = CommonArgs::default();
    let mut own = Vec::new();
    let mut it = args.into_iter();
    while let Some(arg) = it.next() {
        if arg == "--help" || arg == "-h" {
            return Err(ArgError(String::new()));
        }
        let (flag, inline) = match arg.split_once('=') {
            Some((f, v)) if f.starts_with("--") => (f.to_string(), Some(v.to_string())),
            _ => (arg.clone(), None),
        };
        if !flag.starts_with("--") {
            return Err(ArgError(format!("unexpected argument `{arg}`")));
        }
        let known = flag == "--screenshot" || flag == "--frames" || own_flags.contains(&&*flag);
        if !known {
            return Err(ArgError(format!("unknown option `{flag}`")));
        }
        let value = match inline {
            Some(v) => v,
            None => it
                .next()
                .ok_or_else(|| ArgError(format!("`{flag}` needs a value")))?,
        };
        match flag.as_str() {
            "--screenshot" => {
                let path = PathBuf::from(&value);
                let ext = path
                    .extension()
                    .and_then(|e| e.to_str())
                    .map(str::to_ascii_lowercase);
                if ext.as_deref() != Some("png") {
                    return Err(ArgError(format!(
                        "--screenshot `{value}`: the file name must end in .png"
                    )));
                }
                if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty())
                    && !dir.is_dir()
                {
                    return Err(ArgError(format!(
                        "--screenshot `{value}`: directory `{}` does not exist",
                        dir.display()
                    )));
                }
                common.screenshot = Some(path);
            }
            "--frames" => common.frames = Some(parse_count("--frames", &value, 1, 10_000_000)?),
            _ => own.push((flag, value)),
        }
    }
    if common.screenshot.is_some() && common.frames.is_none() {
        common.frames = Some(60);
    }
    Ok((common, own))
}

/// A whole number in `[lo, hi]`, or an error naming the option.
pub fn parse_count(flag: &str, value: &str, lo: u64, hi: u64) -> Result<u64, ArgError> {
    match value.parse::<u64>() {
        Ok(n) if (lo..=hi).contains(&n) => Ok(n),
        _ => Err(ArgError(format!(
            "{flag} `{value}`: expected a whole number in [{lo}, {hi}]"
        ))),
    }
}

/// Parses the process's arguments; on error prints it and `usage` and exits with code 2.
pub fn args_or_exit(usage: &str, own_flags: &[&str]) -> (CommonArgs, Vec<(String, String)>) {
    let parsed = parse_args(std::env::args().skip(1), own_flags);
    // The demos open an X11 window (the `render` feature enables winit's X11 backend only):
    // without a display winit would panic, so say what is missing instead.
    if cfg!(target_os = "linux") && parsed.is_ok() && std::env::var_os("DISPLAY").is_none() {
        eprintln!(
            "error: no X display (DISPLAY is not set). Headless: `Xvfb :99 &` and run with \
             DISPLAY=:99 XDG_RUNTIME_DIR=/tmp/xdg (see the README's \"Desktop demos\")"
        );
        std::process::exit(2);
    }
    match parsed {
        Ok(a) => a,
        Err(ArgError(msg)) if msg.is_empty() => {
            println!("{usage}\n{COMMON_USAGE}");
            std::process::exit(0);
        }
        Err(ArgError(msg)) => {
            eprintln!("error: {msg}\n\n{usage}\n{COMMON_USAGE}");
            std::process::exit(2);
        }
    }
}

/// Prints an error about a demo option and exits with code 2.
/// The materials the demos cycle through (`--material`, key M), by name.
pub const MATERIALS: [&str; 3] = ["steel", "glass", "rubber"];

/// creep-law's material `MATERIALS[index]` (G, nu, density of steel, glass, rubber).
pub fn material(index: usize) -> creep_law::Material {
    match index % MATERIALS.len() {
        0 => creep_law::Material::steel(),
        1 => creep_law::Material::glass(),
        _ => creep_law::Material::rubber(),
    }
}

/// The index in [`MATERIALS`] of a `--material` value, or exit 2 with the usage.
pub fn material_arg(usage: &str, value: &str) -> usize {
    MATERIALS
        .iter()
        .position(|m| m == &value)
        .unwrap_or_else(|| {
            exit_with(
                usage,
                &format!("--material `{value}`: expected steel, glass or rubber"),
            )
        })
}

pub fn exit_with(usage: &str, msg: &str) -> ! {
    eprintln!("error: {msg}\n\n{usage}\n{COMMON_USAGE}");
    std::process::exit(2);
}

/// Usage of the common options.
pub const COMMON_USAGE: &str = "common options:
  --screenshot FILE.png   save a screenshot after --frames frames (default 60), then exit
  --frames N              render N frames, then exit (prints the median frame time)
keys: Space pause, . one step while paused, +/- physics steps per frame, R reset, Esc quit;
mouse: left drag orbits the camera, wheel zooms";

// ---------------------------------------------------------------------------------------------
// App
// ---------------------------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------------------------
// Live plot: lines and points rasterised into a texture shown by a UI image
// ---------------------------------------------------------------------------------------------

/// A plot drawn on the CPU into an RGBA image each frame (simple and renderer-agnostic).
#[derive(Debug, Clone)]
pub struct Plot {
    /// Width and height [px].
    pub size: UVec2,
    /// x range (data units).
    pub x: (f64, f64),
    /// y range (data units).
    pub y: (f64, f64),
    pixels: Vec<u8>,
}

/// Plot colours.
pub mod colours {
    /// Background.
    pub const BG: [u8; 4] = [16, 18, 22, 220];
    /// Axes and grid.
    pub const AXIS: [u8; 4] = [110, 110, 120, 255];
    /// Grid.
    pub const GRID: [u8; 4] = [45, 48, 55, 255];
    /// Theory lines.
    pub const THEORY: [u8; 4] = [235, 235, 235, 255];
    /// Coulomb.
    pub const COULOMB: [u8; 4] = [90, 150, 255, 255];
    /// Creep.
    pub const CREEP: [u8; 4] = [255, 200, 40, 255];
    /// Rolling torque.
    pub const TORQUE: [u8; 4] = [240, 90, 90, 255];
    /// Something else.
    pub const OTHER: [u8; 4] = [110, 220, 120, 255];
}

impl Plot {
    /// An empty plot.
    pub fn new(size: UVec2, x: (f64, f64), y: (f64, f64)) -> Self {
        let mut p = Self {
            size,
            x,
            y,
            pixels: vec![0; (size.x * size.y * 4) as usize],
        };
        p.clear();
        p
    }
    /// Clears to the background and draws the axes (through 0 where in range) and a grid of
    /// `grid` divisions.
    pub fn clear(&mut self) {
        for px in self.pixels.chunks_exact_mut(4) {
            px.copy_from_slice(&colours::BG);
        }
        let n = 5;
        for i in 0..=n {
            let f = i as f64 / n as f64;
            let gx = self.x.0 + f * (self.x.1 - self.x.0);
            let gy = self.y.0 + f * (self.y.1 - self.y.0);
            self.line((gx, self.y.0), (gx, self.y.1), colours::GRID);
            self.line((self.x.0, gy), (self.x.1, gy), colours::GRID);
        }
        let x0 = 0f64.clamp(self.x.0, self.x.1);
        let y0 = 0f64.clamp(self.y.0, self.y.1);
        self.line((x0, self.y.0), (x0, self.y.1), colours::AXIS);
        self.line((self.x.0, y0), (self.x.1, y0), colours::AXIS);
    }
    fn to_px(&self, (x, y): (f64, f64)) -> (f64, f64) {
        let w = f64::from(self.size.x - 1);
        let h = f64::from(self.size.y - 1);
        (
            (x - self.x.0) / (self.x.1 - self.x.0) * w,
            h - (y - self.y.0) / (self.y.1 - self.y.0) * h,
        )
    }
    fn put(&mut self, x: i64, y: i64, c: [u8; 4]) {
        if x >= 0 && y >= 0 && (x as u32) < self.size.x && (y as u32) < self.size.y {
            let i = ((y as u32 * self.size.x + x as u32) * 4) as usize;
            self.pixels[i..i + 4].copy_from_slice(&c);
        }
    }
    /// A line between two data points (clipped to the image).
    pub fn line(&mut self, a: (f64, f64), b: (f64, f64), c: [u8; 4]) {
        let (pa, pb) = (self.to_px(a), self.to_px(b));
        if !(pa.0.is_finite() && pa.1.is_finite() && pb.0.is_finite() && pb.1.is_finite()) {
            return;
        }
        let lim = 4.0 * f64::from(self.size.x.max(self.size.y));
        let clamp = |v: f64| v.clamp(-lim, lim);
        let (x0, y0, x1, y1) = (clamp(pa.0), clamp(pa.1), clamp(pb.0), clamp(pb.1));
        let n = (x1 - x0).abs().max((y1 - y0).abs()).ceil().max(1.0) as i64;
        for i in 0..=n {
            let t = i as f64 / n as f64;
            let x = x0 + t * (x1 - x0);
            let y = y0 + t * (y1 - y0);
            self.put(x.round() as i64, y.round() as i64, c);
        }
    }
    /// A polyline through data points.
    pub fn polyline(&mut self, pts: &[(f64, f64)], c: [u8; 4]) {
        for w in pts.windows(2) {
            self.line(w[0], w[1], c);
        }
    }
    /// A filled square marker of half-width `r` pixels at a data point.
    pub fn point(&mut self, p: (f64, f64), r: i64, c: [u8; 4]) {
        let (x, y) = self.to_px(p);
        if !(x.is_finite() && y.is_finite()) {
            return;
        }
        let (x, y) = (x.round() as i64, y.round() as i64);
        for dy in -r..=r {
            for dx in -r..=r {
                self.put(x + dx, y + dy, c);
            }
        }
    }
    /// A new image of the plot's size.
    pub fn image(&self) -> Image {
        Image::new(
            Extent3d {
                width: self.size.x,
                height: self.size.y,
                depth_or_array_layers: 1,
            },
            TextureDimension::D2,
            self.pixels.clone(),
            TextureFormat::Rgba8UnormSrgb,
            RenderAssetUsages::default(),
        )
    }
    /// Copies the pixels into `image` (made by [`Plot::image`]).
    pub fn write(&self, image: &mut Image) {
        image.data = Some(self.pixels.clone());
    }
}

/// Spawns a plot image at the window's right edge, `bottom` pixels above the bottom, with a
/// caption above it (a UI text node, returned for updates); returns the image handle and the
/// caption entity.
pub fn spawn_plot(
    commands: &mut Commands,
    images: &mut Assets<Image>,
    plot: &Plot,
    caption: &str,
    bottom: f32,
) -> (Handle<Image>, Entity) {
    let handle = images.add(plot.image());
    let mut caption_entity = Entity::PLACEHOLDER;
    commands
        .spawn(Node {
            position_type: PositionType::Absolute,
            right: Val::Px(6.0),
            bottom: Val::Px(bottom),
            flex_direction: FlexDirection::Column,
            align_items: AlignItems::End,
            ..default()
        })
        .with_children(|p| {
            caption_entity = p
                .spawn((
                    Node {
                        padding: UiRect::all(Val::Px(4.0)),
                        ..default()
                    },
                    BackgroundColor(Color::srgba(0.0, 0.0, 0.0, 0.6)),
                    Text::new(caption),
                    TextFont::from_font_size(12.0),
                    TextColor(Color::srgb(0.9, 0.9, 0.9)),
                ))
                .id();
            p.spawn((
                Node {
                    width: Val::Px(plot.size.x as f32),
                    height: Val::Px(plot.size.y as f32),
                    ..default()
                },
                ImageNode::new(handle.clone()),
            ));
        });
    (handle, caption_entity)
}

/// `x` rounded to a "nice" value at or above it (1, 2 or 5 times a power of ten), for axes.
pub fn nice_ceil(x: f64) -> f64 {
    if !(x > 0.0) || !x.is_finite() {
        return 1.0;
    }
    let p = 10f64.powf(x.log10().floor());
    for m in [1.0, 2.0, 5.0, 10.0] {
        if m * p >= x {
            return m * p;
        }
    }
    10.0 * p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(v: &[&str]) -> Result<(CommonArgs, Vec<(String, String)>), ArgError> {
        parse_args(v.iter().map(|s| s.to_string()), &["--spheres"])
    }

    #[test]
    fn parses_and_refuses() {
        let (c, own) = args(&["--frames", "5", "--spheres=10"]).unwrap();
        assert_eq!(c.frames, Some(5));
        assert_eq!(own, vec![("--spheres".to_string(), "10".to_string())]);
        assert!(args(&["--frames", "x"]).is_err());
        assert!(args(&["--frames"]).is_err());
        assert!(args(&["--nope", "1"]).is_err());
        assert!(args(&["--screenshot", "a.jpg"]).is_err());
        assert!(args(&["--screenshot", "/no/such/dir/a.png"]).is_err());
        let (c, _) = args(&["--screenshot", "a.png"]).unwrap();
        assert_eq!(c.frames, Some(60));
    }
}

/// Accumulates a body's rotation about a fixed axis from its orientation increments [rad]
/// (creep-scenes' `RollingMeter` for Bevy's `Quat`: robust to the wrap-around of a
/// quaternion's angle).
#[derive(Debug, Clone, Copy, Default)]
pub struct AngleMeter {
    last: Option<Quat>,
    /// Accumulated angle about the axis [rad].
    pub angle: f64,
}

impl AngleMeter {
    /// Adds the rotation since the last call about `axis` (unit): `2 atan2(v . axis, w)` of
    /// the increment `q last^-1`.
    pub fn update(&mut self, rotation: Quat, axis: Vec3) {
        if let Some(last) = self.last {
            let dq = rotation * last.inverse();
            let v = Vec3::new(dq.x, dq.y, dq.z);
            self.angle += 2.0 * f64::from(v.dot(axis)).atan2(f64::from(dq.w));
        }
        self.last = Some(rotation);
    }
}
