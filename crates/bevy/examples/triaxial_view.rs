//! `triaxial_view`: runs creep-scenes' drained triaxial test of the compliant regime at the
//! `--quick` size (343 spheres: generation, frictionless isotropic compaction with servo
//! walls, then the shear with Coulomb-Mindlin contacts and again with Kuhn's creep-friction
//! from the same packing) on a thread, and shows it as it runs: the spheres coloured by their
//! contacts (red: one at the Coulomb limit, yellow: one creeping, creep displacement >= 0.1 of
//! the sliding one, the scene's `CREEPING`; blue: touching; grey: none), the walls' inner box,
//! and a live plot of q/p against the axial strain for both shears. When the test ends the
//! recording replays in a loop.
//!
//! It is the same code as `creep triaxial --quick` (`creep_scenes::triaxial::{Specimen,
//! compact_observed, shear_observed}`), so the numbers in the panel are the test's.
//!
//! Keys: R replays from the start; and the shared keys (Space pauses the replay).
//!
//! Run: `cargo run -p creep-bevy --features render --example triaxial_view --ignore-rust-version --release`

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems
#![allow(clippy::needless_range_loop)] // lanes and twins indexed in parallel arrays

mod common;

use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::time::Duration;

use bevy::prelude::*;
use common::{
    DemoPlugin, OrbitCamera, PanelText, Plot, ResetRequested, RunArgs, Stepping, colours,
};
use creep_bevy::{CompliantSettings, CreepSettings};
use creep_scenes::triaxial::{
    CREEPING, Specimen, TriaxialParams, TriaxialRow, compact_observed, shear_observed,
};

const USAGE: &str = "triaxial_view: the compliant regime's triaxial test at a small size

usage: triaxial_view [--n-per-side N] [--every K] [common options]
  --n-per-side N   spheres per lattice side, 3 to 12 (default 7: the --quick size, 343 spheres)
  --every K        steps between two frames of the recording, 1 to 1000 (default 20)";

/// Drawn scale: world units per metre (the spheres are millimetres; Bevy's camera near plane
/// is 0.1 units).
const SCALE: f32 = 100.0;
/// Compaction steps allowed (the scene's `creep triaxial` uses the same order).
const MAX_COMPACTION_STEPS: usize = 200_000;

/// One frame of the recording.
struct Snapshot {
    phase: Phase,
    step: usize,
    /// Ball centres [m], radii [m] and contact state (0 touching, 1 creeping, 2 sliding,
    /// 3 none).
    balls: Vec<(Vec3, f32, u8)>,
    /// The walls' inner box, min and max corners [m].
    bounds: (Vec3, Vec3),
    /// The latest recorded row of the shear.
    row: Option<TriaxialRow>,
    contacts: usize,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Compaction,
    ShearCoulomb,
    ShearCreep,
}

impl Phase {
    fn name(self) -> &'static str {
        match self {
            Phase::Compaction => "isotropic compaction (frictionless, servo walls)",
            Phase::ShearCoulomb => "shear, Coulomb-Mindlin",
            Phase::ShearCreep => "shear, creep-friction (Kuhn 2011)",
        }
    }
}

/// What the thread sends.
enum Message {
    Snapshot(Box<Snapshot>),
    Done,
    Error(String),
}

#[derive(Resource)]
struct View {
    rx: Option<std::sync::Mutex<Receiver<Message>>>,
    recording: Vec<Snapshot>,
    /// Index of the snapshot shown.
    shown: usize,
    /// Live (following the run) or replaying.
    live: bool,
    error: Option<String>,
    params: TriaxialParams,
    balls: Vec<Entity>,
    mesh: Handle<Mesh>,
    colours: [Handle<StandardMaterial>; 4],
    plot: Plot,
    image: Handle<Image>,
    caption: Entity,
    /// (axial strain, q/p) per shear.
    curves: [Vec<(f64, f64)>; 2],
}

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--n-per-side", "--every"]);
    let mut params = TriaxialParams::quick();
    let mut every = 20usize;
    for (flag, value) in &own {
        match flag.as_str() {
            "--n-per-side" => {
                params.n_per_side = common::parse_count(flag, value, 3, 12)
                    .unwrap_or_else(|e| common::exit_with(USAGE, &e.0))
                    as usize
            }
            "--every" => {
                every = common::parse_count(flag, value, 1, 1000)
                    .unwrap_or_else(|e| common::exit_with(USAGE, &e.0))
                    as usize
            }
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    if let Err(e) = params.validate() {
        common::exit_with(USAGE, &e.to_string());
    }
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        if let Err(e) = run(params, every, &tx) {
            let _ = tx.send(Message::Error(e));
        }
    });
    let side =
        (params.n_per_side as f64 * 2.0 * params.radius * (1.0 + params.radius_spread) * 1.05)
            as f32
            * SCALE;
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: triaxial test (compliant regime)",
            args,
            dt: params.time_step() as f32,
            steps_per_frame: 1,
            gravity: Vec3::ZERO,
            creep: CreepSettings::default(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::splat(0.5 * side),
                yaw: 0.7,
                pitch: 0.35,
                distance: 2.6 * side,
                up: Vec3::Y,
            },
            physics: false,
            many_objects: false,
        })
        .insert_resource(Start(params, Some(std::sync::Mutex::new(rx))))
        .add_systems(Startup, setup)
        .add_systems(Update, (receive, show).chain())
        .run();
}

#[derive(Resource)]
struct Start(TriaxialParams, Option<std::sync::Mutex<Receiver<Message>>>);

/// The test, as `creep triaxial` runs it, with a snapshot every `every` steps.
fn run(
    params: TriaxialParams,
    every: usize,
    tx: &std::sync::mpsc::Sender<Message>,
) -> Result<(), String> {
    let send = |phase: Phase, step: usize, s: &Specimen, row: Option<&TriaxialRow>| {
        let _ = tx.send(Message::Snapshot(Box::new(snapshot(phase, step, s, row))));
    };
    let mut specimen = Specimen::generate(params).map_err(|e| e.to_string())?;
    send(Phase::Compaction, 0, &specimen, None);
    let mut step = 0usize;
    compact_observed(&mut specimen, MAX_COMPACTION_STEPS, &mut |_| {}, &mut |s| {
        step += 1;
        if step.is_multiple_of(every) {
            send(Phase::Compaction, step, s, None);
        }
    })
    .map_err(|e| e.to_string())?;
    for (phase, creep) in [(Phase::ShearCoulomb, false), (Phase::ShearCreep, true)] {
        let mut step = 0usize;
        let mut last_row = None;
        shear_observed(&specimen, creep, &mut |_| {}, &mut |s, row| {
            if let Some(r) = row {
                last_row = Some(*r);
            }
            if step.is_multiple_of(every) || row.is_some() {
                send(phase, step, s, last_row.as_ref());
            }
            step += 1;
        })
        .map_err(|e| e.to_string())?;
    }
    let _ = tx.send(Message::Done);
    Ok(())
}

/// The balls, their contact states and the walls' inner box, from the specimen's Rapier world.
fn snapshot(phase: Phase, step: usize, s: &Specimen, row: Option<&TriaxialRow>) -> Snapshot {
    let world = s.world();
    let colliders = &world.physics.colliders;
    // Contact state per ball: the worst of its ball-ball contacts (the walls are frictionless,
    // always "at the Coulomb limit"; the scene's contact shares leave them out too).
    let is_ball = |h| {
        colliders
            .get(h)
            .is_some_and(|c| c.shape().as_ball().is_some())
    };
    let mut state: std::collections::HashMap<_, u8> = Default::default();
    let mut contacts = 0;
    for (&(c1, c2), c) in world.compliant.contacts() {
        if !(c.overlap > 0.0) || !is_ball(c1) || !is_ball(c2) {
            continue;
        }
        contacts += 1;
        // The compaction is frictionless (mu = 0): every contact is "at the Coulomb limit"
        // there, so it is shown as touching.
        let k = if phase == Phase::Compaction {
            0
        } else if c.sliding {
            2
        } else if c.creep_ratio >= CREEPING {
            1
        } else {
            0
        };
        for h in [c1, c2] {
            let e = state.entry(h).or_insert(k);
            *e = (*e).max(k);
        }
    }
    let mut balls = Vec::with_capacity(s.len());
    let mut walls = Vec::new();
    for (h, co) in colliders.iter() {
        let t = co.translation();
        let p = Vec3::new(t.x, t.y, t.z);
        if let Some(ball) = co.shape().as_ball() {
            balls.push((p, ball.radius, state.get(&h).copied().unwrap_or(3)));
        } else if let Some(cuboid) = co.shape().as_cuboid() {
            let he = cuboid.half_extents;
            walls.push((p, Vec3::new(he.x, he.y, he.z)));
        }
    }
    let centre = balls.iter().map(|b| b.0).sum::<Vec3>() / balls.len().max(1) as f32;
    // Each wall's inner face: on the axis where the centre lies farthest outside its extent.
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for (p, he) in walls {
        let d = centre - p;
        let k = (0..3)
            .max_by(|&a, &b| (d[a].abs() - he[a]).total_cmp(&(d[b].abs() - he[b])))
            .unwrap_or(0);
        let face = p[k] + d[k].signum() * he[k];
        if d[k] > 0.0 {
            lo[k] = face;
        } else {
            hi[k] = face;
        }
    }
    Snapshot {
        phase,
        step,
        balls,
        bounds: (lo, hi),
        row: row.copied(),
        contacts,
    }
}

fn setup(
    mut commands: Commands,
    mut start: ResMut<Start>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut images: ResMut<Assets<Image>>,
) {
    let plot = Plot::new(UVec2::new(400, 230), (0.0, 0.1), (0.0, 1.5));
    let (image, caption) = common::spawn_plot(&mut commands, &mut images, &plot, "", 6.0);
    let colour = |r: f32, g: f32, b: f32| StandardMaterial {
        base_color: Color::srgb(r, g, b),
        perceptual_roughness: 0.5,
        ..default()
    };
    commands.insert_resource(View {
        rx: start.1.take(),
        recording: Vec::new(),
        shown: 0,
        live: true,
        error: None,
        params: start.0,
        balls: Vec::new(),
        mesh: meshes.add(Sphere::new(1.0).mesh().ico(2).expect("small subdivision")),
        colours: [
            materials.add(colour(0.2, 0.45, 1.0)),
            materials.add(colour(1.0, 0.8, 0.1)),
            materials.add(colour(1.0, 0.2, 0.2)),
            materials.add(colour(0.55, 0.55, 0.58)),
        ],
        plot,
        image,
        caption,
        curves: Default::default(),
    });
}

/// Takes the thread's snapshots: with `--frames` exactly one a frame (waiting for it, so a run
/// of N frames shows snapshot N on any machine), otherwise all that have arrived.
fn receive(mut view: ResMut<View>, args: Res<RunArgs>) {
    let Some(rx) = view.rx.take() else {
        return;
    };
    let deterministic = args.0.frames.is_some();
    let mut keep = true;
    {
        let rx = rx.lock().expect("receiver lock");
        loop {
            let msg = if deterministic {
                match rx.recv_timeout(Duration::from_secs(120)) {
                    Ok(m) => Some(m),
                    Err(RecvTimeoutError::Timeout) => {
                        view.error = Some("no snapshot from the test for 120 s".into());
                        None
                    }
                    Err(RecvTimeoutError::Disconnected) => {
                        keep = false;
                        None
                    }
                }
            } else {
                match rx.try_recv() {
                    Ok(m) => Some(m),
                    Err(std::sync::mpsc::TryRecvError::Empty) => None,
                    Err(std::sync::mpsc::TryRecvError::Disconnected) => {
                        keep = false;
                        None
                    }
                }
            };
            let Some(msg) = msg else { break };
            match msg {
                Message::Snapshot(s) => view.recording.push(*s),
                Message::Done => keep = false,
                Message::Error(e) => {
                    view.error = Some(e);
                    keep = false;
                }
            }
            if deterministic {
                break;
            }
        }
    }
    if keep {
        view.rx = Some(rx);
    }
}

fn show(
    mut commands: Commands,
    mut view: ResMut<View>,
    mut reset: ResMut<ResetRequested>,
    stepping: Res<Stepping>,
    mut balls: Query<(&mut Transform, &mut MeshMaterial3d<StandardMaterial>)>,
    mut gizmos: Gizmos,
    mut panel: ResMut<PanelText>,
    mut images: ResMut<Assets<Image>>,
    mut captions: Query<&mut Text>,
) {
    let n = view.recording.len();
    if n == 0 {
        panel.0 = match &view.error {
            Some(e) => format!("triaxial test failed: {e}"),
            None => "generating the packing ...".into(),
        };
        return;
    }
    let running = view.rx.is_some();
    if reset.0 {
        reset.0 = false;
        view.live = false;
        view.shown = 0;
    }
    if view.live {
        view.shown = n - 1;
        if !running {
            view.live = false;
        }
    } else if !stepping.paused {
        view.shown = if view.shown + 1 >= n {
            0
        } else {
            view.shown + 1
        };
    }
    let view = &mut *view;
    let snap = &view.recording[view.shown];
    if view.balls.is_empty() {
        view.balls = snap
            .balls
            .iter()
            .map(|_| {
                commands
                    .spawn((
                        Mesh3d(view.mesh.clone()),
                        MeshMaterial3d(view.colours[3].clone()),
                        Transform::default(),
                    ))
                    .id()
            })
            .collect();
    } else {
        for (&e, &(p, r, k)) in view.balls.iter().zip(&snap.balls) {
            if let Ok((mut t, mut m)) = balls.get_mut(e) {
                *t = Transform::from_translation(p * SCALE).with_scale(Vec3::splat(r * SCALE));
                if m.0 != view.colours[k as usize] {
                    m.0 = view.colours[k as usize].clone();
                }
            }
        }
    }
    let (lo, hi) = snap.bounds;
    if lo.x < hi.x && lo.y < hi.y && lo.z < hi.z {
        let c = 0.5 * (lo + hi) * SCALE;
        let size = (hi - lo) * SCALE;
        gizmos.cube(
            Transform::from_translation(c).with_scale(size),
            Color::srgb(0.8, 0.8, 0.85),
        );
    }
    // The curves up to the snapshot shown.
    for c in &mut view.curves {
        c.clear();
    }
    for s in &view.recording[..=view.shown] {
        let k = match s.phase {
            Phase::ShearCoulomb => 0,
            Phase::ShearCreep => 1,
            _ => continue,
        };
        if let Some(r) = s.row {
            let pt = (r.axial_strain, r.q_over_p);
            if view.curves[k].last() != Some(&pt) {
                view.curves[k].push(pt);
            }
        }
    }
    let x_max = view.params.axial_strain;
    let mut plot = Plot::new(view.plot.size, (0.0, x_max), (0.0, 1.5));
    plot.polyline(&view.curves[0], colours::COULOMB);
    plot.polyline(&view.curves[1], colours::CREEP);
    for (k, c) in view.curves.iter().enumerate() {
        if let Some(&last) = c.last() {
            plot.point(last, 3, [colours::COULOMB, colours::CREEP][k]);
        }
    }
    if let Some(mut img) = images.get_mut(&view.image) {
        plot.write(&mut img);
    }
    view.plot = plot;
    if let Ok(mut c) = captions.get_mut(view.caption) {
        c.0 = format!(
            "q/p [0-1.5] vs axial strain [0-{:.0} %]\nblue: Coulomb-Mindlin, yellow: creep-friction",
            x_max * 100.0
        );
    }
    let p = view.params;
    let mut s = format!(
        "triaxial test (compliant regime), {} spheres, p0 = {:.0} kPa, I = {:.0e}, dt = {:.3e} s\n\
         {} | {} step {} | snapshot {}/{}{}\n\
         spheres: red sliding contact, yellow creeping (>= {CREEPING} of the slip), blue touching, grey none; {} ball-ball contacts\n",
        snap.balls.len(),
        p.confining_pressure / 1e3,
        p.inertial_number,
        p.time_step(),
        if running {
            "running"
        } else {
            "replay (R restarts)"
        },
        snap.phase.name(),
        snap.step,
        view.shown + 1,
        n,
        if view.error.is_some() { " | ERROR" } else { "" },
        snap.contacts,
    );
    if let Some(r) = snap.row {
        s += &format!(
            "eps_a {:.2} %  eps_v {:+.3} %  q/p {:.3}  p {:.1} kPa  coordination {:.2}\n\
             contacts sliding {:.3}, rolling {:.3}, creeping {:.3}; solid fraction {:.4}",
            r.axial_strain * 100.0,
            r.volumetric_strain * 100.0,
            r.q_over_p,
            r.p / 1e3,
            r.coordination,
            r.share_sliding,
            r.share_rolling,
            r.share_creeping,
            r.solid_fraction
        );
    }
    if let Some(e) = &view.error {
        s += &format!("\nerror: {e}");
    }
    panel.0 = s;
}
