//! `wheel_in_sand`: a driven rigid wheel digging into a granular bed, the scene of
//! `creep run wheel-on-sand` (`creep_scenes::bed`, i.e. creep-bed's `wheel`: a creep-dem bed
//! in a slice periodic along the wheel's axis, the wheel a Rapier cylinder coupled both ways,
//! its spin and forward speed prescribed, its sinkage free) stepped on a thread one game step
//! at a time and drawn as it runs.
//!
//! The grains are one sphere mesh drawn with four materials (Bevy batches the identical
//! mesh + material pairs into instanced draws), coloured by the worst state of their grain and
//! wall contacts, read from creep-dem (`Dem::for_each_contact_force` at the engine's step, on
//! copies of the histories: the engine's state is not changed): red sliding (at the Coulomb
//! limit), yellow creeping (creep displacement at least `CREEPING` = 0.1 of the step's sliding
//! displacement, the triaxial scene's rule), blue sticking, grey no contact. The grains
//! touching the wheel get a white tick along the contact normal. The panel shows the sinkage,
//! the drawbar pull and the driving torque (the scene's definitions: `creep_bed::wheel`), also
//! as `z/R`, `DP/W` and `T/(W R)`, and the plot draws those three against time (means over the
//! last 20 game steps: the pull and the torque fluctuate with the grains' stick-slip).
//!
//! Keys: Up/Down slip +- 0.1 (drives again from the landed state), C switches the contact
//! model (creep-friction / Coulomb-Mindlin: lands the wheel again), R drives again; and the
//! shared keys (see `common`; `+`/`-` change the game steps per frame).
//!
//! Run: `cargo run -p creep-bevy --features render --example wheel_in_sand --ignore-rust-version --release`

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems

mod common;

use std::sync::Mutex;
use std::sync::mpsc::{Receiver, RecvTimeoutError, Sender, SyncSender, TryRecvError};
use std::time::Duration;

use bevy::prelude::*;
use common::{
    DemoPlugin, OrbitCamera, PanelText, Plot, ResetRequested, RunArgs, Stepping, colours,
};
use creep_bevy::{CompliantSettings, CreepSettings};
use creep_dem::Cheap;
use creep_law::CreepModel;
use creep_scenes::bed::{BedError, Driving, WheelOnSand, WheelRow, settle};
use creep_scenes::triaxial::CREEPING;

const USAGE: &str = "wheel_in_sand: a driven wheel digging into a granular bed (creep-dem + Rapier)

usage: wheel_in_sand [--grains N] [--slip S] [--contact creep|coulomb] [common options]
  --grains N       grains in the bed, 640 to 20000 (default 2000; the bed grows along the track)
  --slip S         slip ratio 1 - v/(w R), 0 to 0.9 (default 0.2)
  --contact M      contact model at the grain contacts: creep (Kuhn 2011, default) or coulomb
                   (Coulomb-Mindlin only)
keys: Up/Down slip +- 0.1, C switches the contact model, R drives again";

/// Drawn scale: world units per metre (the grains are millimetres; Bevy's camera near plane
/// is 0.1 units).
const SCALE: f32 = 20.0;
/// Game steps the panel's and the plot's means run over.
const MEAN_STEPS: usize = 20;
/// How long a frame with `--frames` waits for the simulation thread (settling a large bed in a
/// debug build takes minutes).
const WAIT: Duration = Duration::from_secs(1800);

/// What stays fixed during one drive.
#[derive(Debug, Clone, Copy)]
struct Info {
    grains: usize,
    slip: f64,
    creep: bool,
    /// Wheel radius \[m\], weight \[N\], spin \[rad/s\], forward speed \[m/s\].
    radius: f64,
    weight: f64,
    spin: f64,
    speed: f64,
    /// Track length and slice width \[m\], undisturbed surface level \[m\].
    footprint: (f64, f64),
    surface: f64,
    /// Game step \[s\] and the DEM steps in it.
    dt_rigid: f64,
    substeps: usize,
    /// Grain radius (largest) \[m\].
    grain_radius: f64,
}

/// One game step of a drive, as drawn.
struct Snapshot {
    epoch: u64,
    info: Info,
    /// Game steps since the drive started.
    step: usize,
    row: Option<WheelRow>,
    /// By grain id: centre \[m\], radius \[m\], state (0 none, 1 stick, 2 creep, 3 slip).
    grains: Vec<(Vec3, f32, u8)>,
    /// The wheel's centre \[m\] and rotation.
    wheel: (Vec3, Quat),
    /// Ids of the grains touching the wheel.
    touching: Vec<usize>,
    /// Grains by state (index as above).
    counts: [usize; 4],
}

/// What the simulation thread sends.
enum Message {
    Status(String),
    Frame(Box<Snapshot>),
    /// The drive reached the end of the track (epoch).
    Done(u64),
    Error(String),
}

/// What the app asks the simulation thread: drive at `slip` with `creep` (land again if the
/// contact model changed); snapshots carry `epoch` from then on.
#[derive(Debug, Clone, Copy)]
struct Command {
    slip: f64,
    creep: bool,
    epoch: u64,
}

#[derive(Resource)]
struct View {
    rx: Mutex<Receiver<Message>>,
    tx: Sender<Command>,
    /// The drive asked for (slip, creep) and its epoch.
    slip: f64,
    creep: bool,
    epoch: u64,
    snap: Option<Snapshot>,
    /// The rows of the current drive.
    rows: Vec<WheelRow>,
    done: bool,
    status: String,
    error: Option<String>,
    grains: Vec<Entity>,
    mesh: Handle<Mesh>,
    colours: [Handle<StandardMaterial>; 4],
    wheel: Option<Entity>,
    wheel_material: Handle<StandardMaterial>,
    plot: Plot,
    image: Handle<Image>,
    caption: Entity,
}

#[derive(Resource)]
struct Start {
    rx: Option<Mutex<Receiver<Message>>>,
    tx: Option<Sender<Command>>,
    slip: f64,
    creep: bool,
    camera_set: bool,
}

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--grains", "--slip", "--contact"]);
    let mut grains = 2000usize;
    let mut slip = 0.2f64;
    let mut creep = true;
    for (flag, value) in &own {
        match flag.as_str() {
            "--grains" => {
                grains = common::parse_count(flag, value, 640, 20_000)
                    .unwrap_or_else(|e| common::exit_with(USAGE, &e.0))
                    as usize
            }
            "--slip" => {
                slip = match value.parse::<f64>() {
                    Ok(s) if (0.0..=0.9).contains(&s) => s,
                    _ => common::exit_with(
                        USAGE,
                        &format!("--slip `{value}`: expected a slip ratio in [0, 0.9]"),
                    ),
                }
            }
            "--contact" => {
                creep = match value.as_str() {
                    "creep" => true,
                    "coulomb" => false,
                    _ => common::exit_with(
                        USAGE,
                        &format!("--contact `{value}`: expected creep or coulomb"),
                    ),
                }
            }
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    let spec = match scene(grains) {
        Ok(s) => s,
        Err(e) => common::exit_with(USAGE, &e.to_string()),
    };
    let dt_rigid = match spec.dt_rigid() {
        Ok(dt) => dt,
        Err(e) => common::exit_with(USAGE, &e.to_string()),
    };
    let (lx, _) = spec.bed.footprint();
    let (tx, rx) = std::sync::mpsc::sync_channel(2);
    let (ctx, crx) = std::sync::mpsc::channel();
    let first = Command {
        slip,
        creep,
        epoch: 0,
    };
    std::thread::spawn(move || {
        if let Err(e) = simulate(spec, first, &crx, &tx) {
            let _ = tx.send(Message::Error(e.to_string()));
        }
    });
    let x = (0.5 * lx) as f32 * SCALE;
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: a wheel in sand (creep-dem bed + Rapier wheel)",
            args,
            dt: dt_rigid as f32,
            steps_per_frame: 1,
            gravity: Vec3::ZERO,
            creep: CreepSettings::default(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::new(x, 0.02 * SCALE, 0.0),
                yaw: 0.45,
                pitch: 0.32,
                distance: 1.25 * lx as f32 * SCALE,
                up: Vec3::Y,
            },
            physics: false,
            many_objects: true,
        })
        .insert_resource(Start {
            rx: Some(Mutex::new(rx)),
            tx: Some(ctx),
            slip,
            creep,
            camera_set: false,
        })
        .add_systems(Startup, setup)
        .add_systems(Update, (keys, receive, show).chain().after(common::StepSet))
        .run();
}

/// The wheel scene at `grains` grains, driven as far as the track allows at slip 0.
fn scene(grains: usize) -> Result<WheelOnSand, BedError> {
    let mut s = WheelOnSand::with_grains(grains)?;
    let (lx, _) = s.bed.footprint();
    let per_step = s.spin * s.wheel_radius() * s.dt_rigid()?;
    let room = lx - s.start_x() - 1.5 * s.wheel_radius();
    s.drive_steps = ((room / per_step).floor() as usize).max(4);
    Ok(s)
}

/// The simulation thread: settles the bed once, lands the wheel per contact model, drives it
/// one game step at a time and sends a snapshot after each (the bounded channel paces it to
/// the frames); between steps it takes the app's commands.
fn simulate(
    spec: WheelOnSand,
    first: Command,
    commands: &Receiver<Command>,
    tx: &SyncSender<Message>,
) -> Result<(), BedError> {
    let status = |s: String| tx.send(Message::Status(s)).is_ok();
    let model = |creep: bool| creep.then_some(CreepModel::Kuhn);
    let name = |creep: bool| {
        if creep {
            "creep-friction"
        } else {
            "Coulomb-Mindlin"
        }
    };
    if !status(format!(
        "settling the bed (about {} grains) ...",
        spec.bed.counts.iter().product::<usize>()
    )) {
        return Ok(());
    }
    let settled = settle::<Cheap>(&spec)?;
    let mut cmd = first;
    loop {
        if !status(format!(
            "landing the wheel ({}): {} game steps at rest ...",
            name(cmd.creep),
            spec.sink_steps
        )) {
            return Ok(());
        }
        let landed = settled.land(model(cmd.creep))?;
        let creep = cmd.creep;
        // Drives from the landed state until the contact model changes.
        while cmd.creep == creep {
            let mut driving = landed.start(cmd.slip)?;
            let info = info(&driving, settled.grains());
            let epoch = cmd.epoch;
            if tx
                .send(Message::Frame(Box::new(snapshot(
                    &driving, None, epoch, info,
                ))))
                .is_err()
            {
                return Ok(());
            }
            let mut next = None;
            while next.is_none() {
                match commands.try_recv() {
                    Ok(c) => next = Some(c),
                    Err(TryRecvError::Disconnected) => return Ok(()),
                    Err(TryRecvError::Empty) => {}
                }
                if next.is_some() {
                    break;
                }
                if driving.steps() >= spec.drive_steps || driving.at_track_end() {
                    if tx.send(Message::Done(epoch)).is_err() {
                        return Ok(());
                    }
                    match commands.recv() {
                        Ok(c) => next = Some(c),
                        Err(_) => return Ok(()),
                    }
                    break;
                }
                let row = driving.step()?;
                let snap = snapshot(&driving, Some(row), epoch, info);
                if tx.send(Message::Frame(Box::new(snap))).is_err() {
                    return Ok(());
                }
            }
            // The latest command wins.
            let mut c = next.unwrap_or(cmd);
            while let Ok(later) = commands.try_recv() {
                c = later;
            }
            cmd = c;
        }
    }
}

fn info(d: &Driving<Cheap>, grains: usize) -> Info {
    let s = d.spec();
    Info {
        grains,
        slip: d.slip(),
        creep: d.creep().is_some(),
        radius: s.wheel_radius(),
        weight: d.weight(),
        spin: s.spin,
        speed: d.speed(),
        footprint: s.bed.footprint(),
        surface: d.surface(),
        dt_rigid: s.dt_rigid().unwrap_or(0.0),
        substeps: s.substeps,
        grain_radius: s.bed.radius,
    }
}

fn v3(v: creep_law::Vec3) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// The grains (by id) with their contact states, the wheel's pose and its contacts.
fn snapshot(d: &Driving<Cheap>, row: Option<WheelRow>, epoch: u64, info: Info) -> Snapshot {
    let dem = d.bed().dem();
    let n = dem.len();
    // State rank per grain id: 0 none, 1 stick, 2 creep, 3 slip; the worst of its contacts
    // with grains and walls (one more step of the kernel on copies of the histories).
    let mut rank = vec![0u8; n];
    dem.for_each_contact_force(dem.config().dt, |c| {
        let f = &c.forces;
        if !f.touching {
            return;
        }
        let k = if f.sliding {
            3
        } else if f.slide_length > 0.0 && f.creep_displacement.length() >= CREEPING * f.slide_length
        {
            2
        } else {
            1
        };
        for id in c.p.into_iter().chain(Some(c.q)) {
            if let Some(r) = rank.get_mut(id) {
                *r = (*r).max(k);
            }
        }
    });
    let mut grains = vec![(Vec3::ZERO, 0.0f32, 0u8); n];
    let mut counts = [0usize; 4];
    for ((x, r), &id) in dem.positions().iter().zip(dem.radii()).zip(dem.ids()) {
        let id = id as usize;
        if let (Some(g), Some(&k)) = (grains.get_mut(id), rank.get(id)) {
            *g = (v3(*x), *r as f32, k);
            counts[k as usize] += 1;
        }
    }
    let pose = d.wheel_pose();
    let (t, q) = (pose.translation, pose.rotation);
    Snapshot {
        epoch,
        info,
        step: d.steps(),
        row,
        grains,
        wheel: (
            Vec3::new(t.x, t.y, t.z),
            Quat::from_xyzw(q.x, q.y, q.z, q.w),
        ),
        touching: d.bed().boundaries().touching(0).collect(),
        counts,
    }
}

fn setup(
    mut commands: Commands,
    mut start: ResMut<Start>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let plot = Plot::new(UVec2::new(360, 200), (0.0, 1.0), (-1.0, 1.0));
    let (image, caption) = common::spawn_plot(&mut commands, &mut images, &plot, "", 6.0);
    let colour = |r: f32, g: f32, b: f32| StandardMaterial {
        base_color: Color::srgb(r, g, b),
        perceptual_roughness: 0.6,
        ..default()
    };
    let (Some(rx), Some(tx)) = (start.rx.take(), start.tx.take()) else {
        return;
    };
    commands.insert_resource(View {
        rx,
        tx,
        slip: start.slip,
        creep: start.creep,
        epoch: 0,
        snap: None,
        rows: Vec::new(),
        done: false,
        status: "starting ...".into(),
        error: None,
        grains: Vec::new(),
        mesh: meshes.add(Sphere::new(1.0).mesh().ico(1).expect("small subdivision")),
        colours: [
            materials.add(colour(0.55, 0.55, 0.58)),
            materials.add(colour(0.2, 0.45, 1.0)),
            materials.add(colour(1.0, 0.8, 0.1)),
            materials.add(colour(1.0, 0.2, 0.2)),
        ],
        wheel: None,
        wheel_material: materials.add(StandardMaterial {
            base_color: Color::srgba(0.75, 0.78, 0.82, 0.45),
            alpha_mode: AlphaMode::Blend,
            perceptual_roughness: 0.35,
            metallic: 0.3,
            ..default()
        }),
        plot,
        image,
        caption,
    });
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    view: Option<ResMut<View>>,
    mut reset: ResMut<ResetRequested>,
) {
    let Some(mut view) = view else {
        return;
    };
    let mut again = std::mem::take(&mut reset.0);
    if input.just_pressed(KeyCode::ArrowUp) {
        view.slip = ((view.slip * 10.0).round() + 1.0).min(9.0) / 10.0;
        again = true;
    }
    if input.just_pressed(KeyCode::ArrowDown) {
        view.slip = ((view.slip * 10.0).round() - 1.0).max(0.0) / 10.0;
        again = true;
    }
    if input.just_pressed(KeyCode::KeyC) {
        view.creep = !view.creep;
        again = true;
    }
    if again {
        view.epoch += 1;
        let cmd = Command {
            slip: view.slip,
            creep: view.creep,
            epoch: view.epoch,
        };
        if view.tx.send(cmd).is_err() && view.error.is_none() {
            view.error = Some("the simulation thread has stopped".into());
        }
    }
}

/// Takes the thread's snapshots: `steps_per_frame` game steps a frame (one while paused and
/// `.` was pressed); with `--frames` it waits for them, so that frame N shows the same game
/// step on any machine. Snapshots of an older drive are dropped; the first of a new drive is
/// taken at once.
fn receive(view: Option<ResMut<View>>, mut stepping: ResMut<Stepping>, args: Res<RunArgs>) {
    let Some(mut view) = view else {
        return;
    };
    let deterministic = args.0.frames.is_some();
    let mut budget = if stepping.paused {
        usize::from(stepping.single)
    } else {
        stepping.steps_per_frame as usize
    };
    stepping.single = false;
    let view = &mut *view;
    let rx = view.rx.lock().expect("receiver lock");
    loop {
        let current = view.snap.as_ref().is_some_and(|s| s.epoch == view.epoch);
        if current && (budget == 0 || view.done) {
            break;
        }
        let msg = if deterministic {
            match rx.recv_timeout(WAIT) {
                Ok(m) => m,
                Err(RecvTimeoutError::Timeout) => {
                    view.error = Some(format!("no game step from the bed for {WAIT:?}"));
                    break;
                }
                Err(RecvTimeoutError::Disconnected) => break,
            }
        } else {
            match rx.try_recv() {
                Ok(m) => m,
                Err(_) => break,
            }
        };
        match msg {
            Message::Status(s) => view.status = s,
            Message::Error(e) => {
                view.error = Some(e);
                break;
            }
            Message::Done(epoch) => {
                if epoch == view.epoch {
                    view.done = true;
                }
            }
            Message::Frame(s) if s.epoch != view.epoch => {}
            Message::Frame(s) => {
                if s.step == 0 {
                    view.rows.clear();
                    view.done = false;
                } else {
                    budget = budget.saturating_sub(1);
                }
                if let Some(r) = s.row {
                    view.rows.push(r);
                }
                stepping.steps = s.step as u64;
                view.snap = Some(*s);
            }
        }
    }
}

/// Means of the last [`MEAN_STEPS`] rows: sinkage, pull, torque.
fn recent_means(rows: &[WheelRow]) -> Option<(f64, f64, f64)> {
    let tail = &rows[rows.len().saturating_sub(MEAN_STEPS)..];
    if tail.is_empty() {
        return None;
    }
    let k = tail.len() as f64;
    let (z, p, t) = tail.iter().fold((0.0, 0.0, 0.0), |(z, p, t), r| {
        (z + r.sinkage, p + r.drawbar_pull, t + r.torque)
    });
    Some((z / k, p / k, t / k))
}

fn show(
    mut commands: Commands,
    view: Option<ResMut<View>>,
    mut start: ResMut<Start>,
    mut orbit: ResMut<OrbitCamera>,
    mut transforms: Query<(&mut Transform, &mut MeshMaterial3d<StandardMaterial>)>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut gizmos: Gizmos,
    mut panel: ResMut<PanelText>,
    mut images: ResMut<Assets<Image>>,
    mut captions: Query<&mut Text>,
) {
    let Some(mut view) = view else {
        return;
    };
    let view = &mut *view;
    let Some(snap) = view.snap.as_ref() else {
        panel.0 = match &view.error {
            Some(e) => format!("wheel in sand: error: {e}"),
            None => format!("wheel in sand: {}", view.status),
        };
        return;
    };
    let info = snap.info;
    let (lx, lz) = (info.footprint.0 as f32, info.footprint.1 as f32);
    if !start.camera_set {
        start.camera_set = true;
        orbit.target = Vec3::new(0.5 * lx, 0.55 * info.surface as f32, 0.5 * lz) * SCALE;
    }
    // Grains: spawned once (their number does not change), then moved and recoloured.
    if view.grains.len() != snap.grains.len() {
        for e in view.grains.drain(..) {
            commands.entity(e).despawn();
        }
        view.grains = snap
            .grains
            .iter()
            .map(|&(x, r, k)| {
                commands
                    .spawn((
                        Mesh3d(view.mesh.clone()),
                        MeshMaterial3d(view.colours[k as usize].clone()),
                        Transform::from_translation(x * SCALE).with_scale(Vec3::splat(r * SCALE)),
                    ))
                    .id()
            })
            .collect();
    } else {
        for (&e, &(x, r, k)) in view.grains.iter().zip(&snap.grains) {
            if let Ok((mut t, mut m)) = transforms.get_mut(e) {
                *t = Transform::from_translation(x * SCALE).with_scale(Vec3::splat(r * SCALE));
                if m.0 != view.colours[k as usize] {
                    m.0 = view.colours[k as usize].clone();
                }
            }
        }
    }
    // The wheel: a translucent cylinder (Bevy's is about y: turned about x onto the body's z).
    let rw = info.radius as f32;
    let half = 0.5 * lz + 2.0 * info.grain_radius as f32;
    let (centre, rot) = snap.wheel;
    let wheel_transform = Transform::from_translation(centre * SCALE)
        .with_rotation(rot * Quat::from_rotation_x(std::f32::consts::FRAC_PI_2));
    match view.wheel {
        None => {
            view.wheel = Some(
                commands
                    .spawn((
                        Mesh3d(meshes.add(Cylinder::new(rw * SCALE, 2.0 * half * SCALE))),
                        MeshMaterial3d(view.wheel_material.clone()),
                        wheel_transform,
                    ))
                    .id(),
            );
        }
        Some(e) => {
            if let Ok((mut t, _)) = transforms.get_mut(e) {
                *t = wheel_transform;
            }
        }
    }
    // Rims and spokes on both faces (they show the spin), the axle.
    let rim = Color::srgb(0.9, 0.92, 0.95);
    for side in [-1.0f32, 1.0] {
        let c = (centre + rot * Vec3::new(0.0, 0.0, side * half)) * SCALE;
        gizmos.circle(Isometry3d::new(c, rot), rw * SCALE, rim);
        for k in 0..6 {
            let a = k as f32 * std::f32::consts::PI / 3.0;
            let d = rot * Vec3::new(a.cos(), a.sin(), 0.0);
            gizmos.line(c, c + d * rw * SCALE, rim);
        }
    }
    gizmos.line(
        (centre - rot * Vec3::Z * half) * SCALE,
        (centre + rot * Vec3::Z * half) * SCALE,
        rim,
    );
    // The grains under the wheel: a tick from the grain's centre towards the axle (the
    // contact normal, nearly: the rim is flat at the contact).
    let white = Color::srgb(1.0, 1.0, 1.0);
    for &id in &snap.touching {
        if let Some(&(x, r, _)) = snap.grains.get(id) {
            let axle = centre + rot * Vec3::Z * (rot.inverse() * (x - centre)).z;
            let n = (axle - x).normalize_or_zero();
            gizmos.line(x * SCALE, (x + n * 1.6 * r) * SCALE, white);
        }
    }
    // The box: floor and end walls (lines), the undisturbed surface (dashed by segments).
    let edge = Color::srgb(0.6, 0.62, 0.66);
    let top = 1.6 * info.surface as f32;
    for z in [0.0, lz] {
        let p = |x: f32, y: f32| Vec3::new(x, y, z) * SCALE;
        gizmos.line(p(0.0, 0.0), p(lx, 0.0), edge);
        gizmos.line(p(0.0, 0.0), p(0.0, top), edge);
        gizmos.line(p(lx, 0.0), p(lx, top), edge);
        let s = info.surface as f32;
        let dash = 2.0 * info.grain_radius as f32;
        let mut x = 0.0;
        while x < lx {
            gizmos.line(
                p(x, s),
                p((x + dash).min(lx), s),
                Color::srgb(0.35, 0.9, 0.45),
            );
            x += 2.0 * dash;
        }
    }
    for x in [0.0, lx] {
        gizmos.line(
            Vec3::new(x, 0.0, 0.0) * SCALE,
            Vec3::new(x, 0.0, lz) * SCALE,
            edge,
        );
    }

    // The plot: z/R, DP/W and T/(W R) against time, means over the last MEAN_STEPS steps.
    let duration = (info.footprint.0 - 3.0 * info.radius) / info.speed.max(1e-9);
    let x_max = common::nice_ceil(duration.min(5.0));
    let mut plot = Plot::new(view.plot.size, (0.0, x_max), (-1.0, 1.0));
    let mut curves: [Vec<(f64, f64)>; 3] = Default::default();
    for k in 1..=view.rows.len() {
        if let Some((z, p, t)) = recent_means(&view.rows[..k]) {
            let time = view.rows[k - 1].t;
            curves[0].push((time, z / info.radius));
            curves[1].push((time, p / info.weight));
            curves[2].push((time, t / (info.weight * info.radius)));
        }
    }
    let cols = [colours::OTHER, colours::COULOMB, colours::CREEP];
    for (c, col) in curves.iter().zip(cols) {
        plot.polyline(c, col);
    }
    if let Some(mut img) = images.get_mut(&view.image) {
        plot.write(&mut img);
    }
    view.plot = plot;
    if let Ok(mut c) = captions.get_mut(view.caption) {
        c.0 = format!(
            "means over {MEAN_STEPS} game steps, [-1, 1] vs t [0-{x_max} s]\n\
             green z/R, blue DP/W, yellow T/(W R)"
        );
    }

    let model = if info.creep {
        "creep-friction (Kuhn 2011)"
    } else {
        "Coulomb-Mindlin only"
    };
    let mut s = format!(
        "wheel in sand: {} grains (r {:.1}-{:.1} mm), slice {:.1} mm wide (periodic), track {:.0} mm; \
         grain contacts: {model} (C)\n\
         wheel R = {:.0} mm, W = {:.2} N, spin {:.1} rad/s, slip {:.2} (Up/Down), v = {:.1} mm/s; \
         game step {:.3} ms = {} DEM steps\n",
        info.grains,
        0.8e3 * info.grain_radius,
        1e3 * info.grain_radius,
        1e3 * info.footprint.1,
        1e3 * info.footprint.0,
        1e3 * info.radius,
        info.weight,
        info.spin,
        info.slip,
        1e3 * info.speed,
        1e3 * info.dt_rigid,
        info.substeps,
    );
    if view.slip != info.slip || view.creep != info.creep {
        s += &format!(
            "switching to slip {:.1}, {} ...\n",
            view.slip,
            if view.creep { "creep" } else { "Coulomb" }
        );
    }
    match (snap.row, recent_means(&view.rows)) {
        (Some(r), Some((z, p, t))) => {
            s += &format!(
                "drive t = {:.3} s{}: sinkage {:.2} mm (z/R {:.3}), drawbar pull {:+.3} N (DP/W {:+.3}), \
                 torque {:.2e} N m (T/(W R) {:.3})\n  this step: sinkage {:.2} mm, pull {:+.3} N, torque {:.2e} N m\n",
                r.t,
                if view.done {
                    " (end of the track: R drives again)"
                } else {
                    ""
                },
                1e3 * z,
                z / info.radius,
                p,
                p / info.weight,
                t,
                t / (info.weight * info.radius),
                1e3 * r.sinkage,
                r.drawbar_pull,
                r.torque,
            );
        }
        _ => s += "landed, starting the drive\n",
    }
    let c = snap.counts;
    s += &format!(
        "grains: slip {} (red)  creep {} (yellow)  stick {} (blue)  none {} (grey); \
         {} touch the wheel (white ticks)",
        c[3],
        c[2],
        c[1],
        c[0],
        snap.touching.len()
    );
    if let Some(e) = &view.error {
        s += &format!("\nerror: {e}");
    }
    panel.0 = s;
}
