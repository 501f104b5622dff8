//! A steel ball rolls down a 20 degree incline, once with Rapier's Coulomb friction and once
//! with creep-friction. Both roll at the closed form `a = (5/7) g sin(theta)`; with creep the
//! contact also slips forward by Kalker's steady creepage `F_ss(Q/(mu P))` per metre rolled
//! (Kalker 2000; Kuhn 2011), dissipating energy that Coulomb's law does not.
//!
//! `cargo run --release -p creep-rapier --example incline`

use creep_law::{PairMaterial, Surface, hertz, kalker};
use creep_rapier::prelude::*;
use rapier3d::math::Rotation;
use rapier3d::prelude::*;

const G: f64 = 9.81;
const THETA: f64 = 20.0 * std::f64::consts::PI / 180.0;
const R: f64 = 0.1;
const DT: f64 = 1.0 / 240.0;
const STEPS: usize = 240;

/// Angle [rad] the body turned about `axis` between two orientations.
fn turned(from: Rotation, to: Rotation, axis: Vector) -> f64 {
    let d = to * from.inverse();
    2.0 * f64::from(Vector::new(d.x, d.y, d.z).dot(axis)).atan2(f64::from(d.w))
}

struct Run {
    acceleration: f64,
    slip: f64,
    q: f64,
    p: f64,
    dissipated: f64,
}

fn run(fidelity: Fidelity) -> Result<Run, PluginError> {
    let steel = Material::steel().with_friction(0.5)?;
    let mu = steel.friction() as f32;
    let mut world = CreepWorld::new(DT as f32, CreepSettings::default())?;
    world.physics.gravity = Vector::new((G * THETA.sin()) as f32, (-G * THETA.cos()) as f32, 0.0);
    let mat = CreepMaterial::new(steel).with_fidelity(fidelity);
    let ground = RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0));
    world.insert(
        ground,
        ColliderBuilder::cuboid(1.0e3, 0.5, 10.0).friction(mu),
        Some(mat),
    );
    let ball = RigidBodyBuilder::dynamic().translation(Vector::new(0.0, R as f32, 0.0));
    let (ball, _) = world.insert(
        ball,
        ColliderBuilder::ball(R as f32).friction(mu),
        Some(mat),
    );
    let (mut x0, mut angle) = (0.0, 0.0);
    let (mut q, mut p, mut n, mut dissipated) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..STEPS {
        let rot = *world.physics.bodies[ball].rotation();
        let counts = world.step()?;
        dissipated += counts.creep_power * DT;
        let b = &world.physics.bodies[ball];
        if i == STEPS / 2 {
            (x0, angle) = (f64::from(b.translation().x), 0.0);
        } else if i > STEPS / 2 {
            angle += turned(rot, *b.rotation(), Vector::Z);
            for (_, rec) in world.hooks().records() {
                (q, p, n) = (q + rec.q_used.length(), p + rec.p, n + 1.0);
            }
        }
    }
    let b = &world.physics.bodies[ball];
    let dx = f64::from(b.translation().x) - x0;
    Ok(Run {
        acceleration: f64::from(b.linvel().x) / (STEPS as f64 * DT),
        slip: (dx + angle * R) / dx, // the ball turns clockwise (negative about z) rolling along +x
        q: q / n.max(1.0),
        p: p / n.max(1.0),
        dissipated,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let coulomb = run(Fidelity::Coulomb)?;
    let creep = run(Fidelity::Creep)?;
    let steel = Material::steel().with_friction(0.5)?;
    let pair = PairMaterial::new(&steel, &steel, Surface::Plane, Surface::Sphere(R))?;
    let mu_p = steel.friction() * creep.p;
    let a = hertz::contact_radius(&pair, creep.p);
    let kalker = kalker::steady_creepage(creep.q / mu_p, mu_p, pair.g, a, pair.c11);
    let measured = creep.slip - coulomb.slip;
    println!(
        "acceleration: Coulomb {:.4} m/s^2, creep {:.4} m/s^2, (5/7) g sin(theta) {:.4} m/s^2",
        coulomb.acceleration,
        creep.acceleration,
        5.0 / 7.0 * G * THETA.sin()
    );
    println!(
        "contact: P = {:.2} N, Q = {:.3} N, Q/(mu P) = {:.3}, Hertz radius a = {:.3e} m",
        creep.p,
        creep.q,
        creep.q / mu_p,
        a
    );
    println!(
        "creep slip (creep run - Coulomb run): {measured:.4e}, Kalker's F_ss: {kalker:.4e} ({:+.2} %)",
        100.0 * (measured / kalker - 1.0)
    );
    println!("Rapier's own slip in the Coulomb run: {:.2e}", coulomb.slip);
    println!(
        "energy dissipated by creep over 1 s: {:.3e} J (Coulomb: {:.1e} J)",
        creep.dissipated, coulomb.dissipated
    );
    assert!((measured / kalker - 1.0).abs() < 0.05 && creep.dissipated > 0.0);
    Ok(())
}
