//! `pour_and_pack`: a few thousand steel spheres poured into a box, settling into a packing,
//! each coloured by the state of its contacts in the creep plugin (rigid regime, `Auto`
//! fidelity): blue stick, yellow creep, red slip (gross sliding at the Coulomb limit), grey
//! none (free flight, or quiet: the plugin switches its hook off for bodies slower than
//! `activation_speed`, and Rapier's Coulomb contact holds them). The panel shows the frame
//! time, the plugin's counts and the creep power.
//!
//! The demo prints the median frame time when it exits (`--frames N`, or Esc).
//!
//! Keys: F cycles the spheres' fidelity (Auto, Creep, Coulomb), R pours again; and the shared
//! keys (see `common`).
//!
//! Run: `cargo run -p creep-bevy --features render --example pour_and_pack --ignore-rust-version --release -- --spheres 2000`

#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::too_many_arguments)] // Bevy systems
#![allow(clippy::needless_range_loop)] // lanes and twins indexed in parallel arrays

mod common;

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use common::{DemoPlugin, OrbitCamera, PanelText, ResetRequested, Stepping};
use creep_bevy::{
    CompliantSettings, ContactState, CreepFriction, CreepMaterial, CreepSettings, Fidelity,
};
use creep_law::Material;

const USAGE: &str = "pour_and_pack: spheres poured into a box, coloured by contact state

usage: pour_and_pack [--spheres N] [--dt S] [common options]
  --spheres N    number of spheres, 1 to 20000 (default 2000)
  --dt S         time step [s], 1e-4 to 0.02 (default 1/120); one step per frame
keys: F cycles the spheres' fidelity (Auto, Creep, Coulomb), R pours again";

/// Mean sphere radius [m] (five radii from -10 % to +10 %, so that the packing does not
/// crystallise).
const RADIUS: f32 = 0.025;
/// Inner width of the box [m].
const BOX: f32 = 0.8;
/// Friction coefficient of spheres and box [-].
const MU: f32 = 0.5;

#[derive(Resource)]
struct Pour {
    n: usize,
    fidelity: Fidelity,
    /// One mesh per radius.
    meshes: [Handle<Mesh>; 5],
    /// Stick, creep, slip, none.
    colours: [Handle<StandardMaterial>; 4],
}

#[derive(Component)]
struct Grain;

fn main() {
    let (args, own) = common::args_or_exit(USAGE, &["--spheres", "--dt"]);
    let mut n = 2000usize;
    let mut dt = 1.0 / 120.0f32;
    for (flag, value) in &own {
        match flag.as_str() {
            "--spheres" => {
                n = common::parse_count("--spheres", value, 1, 20_000)
                    .unwrap_or_else(|e| common::exit_with(USAGE, &e.0)) as usize
            }
            "--dt" => {
                dt = match value.parse::<f32>() {
                    Ok(v) if (1e-4..=0.02).contains(&v) => v,
                    _ => common::exit_with(
                        USAGE,
                        &format!("--dt `{value}`: expected a time step in [1e-4, 0.02] s"),
                    ),
                }
            }
            _ => unreachable!("only the declared flags reach here"),
        }
    }
    App::new()
        .add_plugins(DemoPlugin {
            title: "creep-friction: pour and pack",
            args,
            dt,
            steps_per_frame: 1,
            gravity: Vec3::new(0.0, -9.81, 0.0),
            // The scene's solver (Rapier's own substeps), so that the demo is its scene.
            creep: CreepSettings::default().with_rapier_solver(),
            compliant: CompliantSettings::default(),
            gizmos: false,
            camera: OrbitCamera {
                target: Vec3::new(0.0, 0.45, 0.0),
                yaw: 0.6,
                pitch: 0.55,
                distance: 2.6,
                up: Vec3::Y,
            },
            physics: true,
            many_objects: true,
        })
        .insert_resource(PourStart(n))
        .add_systems(Startup, setup)
        .add_systems(Update, (keys, reset, colour).chain().after(common::StepSet))
        .run();
}

#[derive(Resource)]
struct PourStart(usize);

/// The k-th of the five radii [m].
fn radius(k: usize) -> f32 {
    RADIUS * (0.9 + 0.05 * k as f32)
}

fn setup(
    mut commands: Commands,
    start: Res<PourStart>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut materials: ResMut<Assets<StandardMaterial>>,
    mut reset: ResMut<ResetRequested>,
) {
    let steel = CreepMaterial::new(Material::steel()).with_fidelity(Fidelity::Creep);
    let colour = |r: f32, g: f32, b: f32| StandardMaterial {
        base_color: Color::srgb(r, g, b),
        perceptual_roughness: 0.5,
        ..default()
    };
    let colours = [
        materials.add(colour(0.2, 0.45, 1.0)),
        materials.add(colour(1.0, 0.8, 0.1)),
        materials.add(colour(1.0, 0.2, 0.2)),
        materials.add(colour(0.55, 0.55, 0.58)),
    ];
    commands.insert_resource(Pour {
        n: start.0,
        fidelity: Fidelity::Auto,
        meshes: std::array::from_fn(|k| {
            meshes.add(
                Sphere::new(radius(k))
                    .mesh()
                    .ico(1)
                    .expect("small subdivision"),
            )
        }),
        colours,
    });
    // The box: a floor and four walls (fixed cuboids, steel, fidelity Creep so that the
    // spheres' own fidelity decides). Walls drawn translucent.
    let half = BOX / 2.0;
    let t = 0.05;
    let h = 0.6;
    let wall_material = materials.add(StandardMaterial {
        base_color: Color::srgba(0.7, 0.75, 0.8, 0.18),
        alpha_mode: AlphaMode::Blend,
        ..default()
    });
    let floor_material = materials.add(colour(0.3, 0.32, 0.35));
    let walls = [
        (
            Vec3::new(0.0, -t, 0.0),
            Vec3::new(half + 2.0 * t, t, half + 2.0 * t),
            true,
        ),
        (
            Vec3::new(half + t, h, 0.0),
            Vec3::new(t, h, half + 2.0 * t),
            false,
        ),
        (
            Vec3::new(-half - t, h, 0.0),
            Vec3::new(t, h, half + 2.0 * t),
            false,
        ),
        (Vec3::new(0.0, h, half + t), Vec3::new(half, h, t), false),
        (Vec3::new(0.0, h, -half - t), Vec3::new(half, h, t), false),
    ];
    for (centre, he, floor) in walls {
        commands.spawn((
            RigidBody::Fixed,
            Transform::from_translation(centre),
            Collider::cuboid(he.x, he.y, he.z),
            Friction::coefficient(MU),
            steel,
            Mesh3d(meshes.add(Cuboid::new(2.0 * he.x, 2.0 * he.y, 2.0 * he.z))),
            MeshMaterial3d(if floor {
                floor_material.clone()
            } else {
                wall_material.clone()
            }),
        ));
    }
    reset.0 = true;
}

fn keys(
    input: Res<ButtonInput<KeyCode>>,
    mut pour: ResMut<Pour>,
    mut grains: Query<&mut CreepMaterial, With<Grain>>,
) {
    if input.just_pressed(KeyCode::KeyF) {
        pour.fidelity = match pour.fidelity {
            Fidelity::Auto => Fidelity::Creep,
            Fidelity::Creep => Fidelity::Coulomb,
            Fidelity::Coulomb => Fidelity::Auto,
        };
        for mut m in &mut grains {
            *m = m.with_fidelity(pour.fidelity);
        }
    }
}

/// A small deterministic generator (SplitMix64), so that every run pours the same spheres.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_f32(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Pours: the spheres start on a jittered lattice in a column above the box (all of them at
/// once, so that a frame-time measurement sees all N), with small random velocities.
fn reset(
    mut commands: Commands,
    mut reset: ResMut<ResetRequested>,
    pour: Res<Pour>,
    mut stepping: ResMut<Stepping>,
    old: Query<Entity, With<Grain>>,
) {
    if !reset.0 {
        return;
    }
    reset.0 = false;
    stepping.steps = 0;
    for e in &old {
        commands.entity(e).despawn();
    }
    let mut rng = SplitMix64(2011);
    let spacing = 2.0 * RADIUS * 1.1 * 1.15;
    let per_side = ((0.8 * BOX) / spacing).floor().max(1.0) as usize;
    let material = CreepMaterial::new(Material::steel()).with_fidelity(pour.fidelity);
    for i in 0..pour.n {
        let layer = i / (per_side * per_side);
        let k = i % (per_side * per_side);
        let (a, b) = (k / per_side, k % per_side);
        let jitter = |rng: &mut SplitMix64| (rng.next_f32() - 0.5) * 0.1 * spacing;
        let x = (a as f32 - 0.5 * (per_side - 1) as f32) * spacing + jitter(&mut rng);
        let z = (b as f32 - 0.5 * (per_side - 1) as f32) * spacing + jitter(&mut rng);
        let y = 0.6 + layer as f32 * spacing + jitter(&mut rng);
        let size = ((rng.next_f32() * 5.0) as usize).min(4);
        let v = Vec3::new(rng.next_f32() - 0.5, 0.0, rng.next_f32() - 0.5) * 0.2;
        commands.spawn((
            RigidBody::Dynamic,
            Transform::from_xyz(x, y, z),
            Collider::ball(radius(size)),
            Velocity::linear(v),
            Friction::coefficient(MU),
            material,
            Mesh3d(pour.meshes[size].clone()),
            MeshMaterial3d(pour.colours[3].clone()),
            Grain,
        ));
    }
}

/// Colours each sphere by the "worst" state of its contacts (slip > creep > stick > none).
fn colour(
    pour: Res<Pour>,
    creep: Res<CreepFriction>,
    contexts: Query<(&RapierContextSimulation, &RapierContextColliders)>,
    mut grains: Query<(Entity, &mut MeshMaterial3d<StandardMaterial>), With<Grain>>,
    mut panel: ResMut<PanelText>,
    stepping: Res<Stepping>,
) {
    let Some((sim, colliders)) = contexts.iter().next() else {
        return;
    };
    let contacts = creep.creep_contacts(sim, colliders);
    let mut worst: bevy::platform::collections::HashMap<Entity, u8> = Default::default();
    let rank = |s: ContactState| match s {
        ContactState::Stick => 0u8,
        ContactState::Creep => 1,
        ContactState::Slip => 2,
    };
    let mut by_state = [0usize; 3];
    for c in &contacts {
        let k = rank(c.state);
        by_state[k as usize] += 1;
        for e in [c.collider1, c.collider2] {
            let w = worst.entry(e).or_insert(k);
            *w = (*w).max(k);
        }
    }
    let mut spheres = [0usize; 4];
    for (e, mut m) in &mut grains {
        let k = worst.get(&e).map_or(3, |&k| k as usize);
        spheres[k] += 1;
        if m.0 != pour.colours[k] {
            m.0 = pour.colours[k].clone();
        }
    }
    let counts = creep.counts();
    let fidelity = match pour.fidelity {
        Fidelity::Auto => "Auto",
        Fidelity::Creep => "Creep",
        Fidelity::Coulomb => "Coulomb",
    };
    panel.0 = format!(
        "pour and pack: {} steel spheres (R = {} mm +-10 %, mu = {MU}), fidelity {fidelity} (F); R pours again\n\
         spheres: stick {} (blue)  creep {} (yellow)  slip {} (red)  none/quiet {} (grey)\n\
         plugin contacts: stick {}  creep {}  slip {}; Coulomb (auto off) {}; hooks on {}\n\
         creep power {:.3e} W; largest loop gain {:.2}; t = {:.2} s",
        pour.n,
        RADIUS * 1e3,
        spheres[0],
        spheres[1],
        spheres[2],
        spheres[3],
        by_state[0],
        by_state[1],
        by_state[2],
        counts.coulomb_auto,
        counts.hooks_on,
        counts.creep_power,
        counts.max_loop_gain,
        stepping.time()
    );
}
