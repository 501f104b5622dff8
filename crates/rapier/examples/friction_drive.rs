//! A friction drive: a steel sphere spun at 10 rad/s turns a second one resting on it against a
//! brake torque `T`. In steady state the contact carries `Q = T/R` and the output turns slower
//! than the input by Kalker's creepage `xi = F_ss(Q/(mu P))` (Kalker 2000; Kuhn 2011): torque
//! preserved, speed lost. Each brake torque runs twice, with creep and with Coulomb (whose own
//! slip is Rapier's, not creep), and the difference is compared with Kalker's curve.
//!
//! `cargo run --release -p creep-rapier --example friction_drive`

use creep_law::{PairMaterial, Surface, hertz, kalker};
use creep_rapier::prelude::*;
use rapier3d::math::Rotation;
use rapier3d::prelude::*;

const R: f64 = 0.05;
const OMEGA: f64 = 10.0;
const DT: f64 = 1.0 / 240.0;
const STEPS: usize = 480;

fn turned(from: Rotation, to: Rotation) -> f64 {
    let d = to * from.inverse();
    2.0 * f64::from(d.z).atan2(f64::from(d.w))
}

/// Creepage `(w_in - w_out) / mean` over the second half, and the contact's mean Q and P [N].
fn run(torque: f64, fidelity: Fidelity) -> Result<(f64, f64, f64), PluginError> {
    let steel = Material::steel();
    let mu = steel.friction() as f32;
    let mut world = CreepWorld::new(DT as f32, CreepSettings::default())?;
    let mat = CreepMaterial::new(steel).with_fidelity(fidelity);
    let r = R as f32;
    let input =
        RigidBodyBuilder::kinematic_velocity_based().angvel(Vector::new(0.0, 0.0, OMEGA as f32));
    let (input, _) = world.insert(input, ColliderBuilder::ball(r).friction(mu), Some(mat));
    let output = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, 2.0 * r, 0.0))
        .enabled_translations(false, true, false)
        .angvel(Vector::new(0.0, 0.0, -OMEGA as f32))
        .can_sleep(false);
    let (output, _) = world.insert(output, ColliderBuilder::ball(r).friction(mu), Some(mat));
    world.physics.bodies[output].add_torque(Vector::new(0.0, 0.0, torque as f32), true); // the brake
    let (mut a_in, mut a_out, mut q, mut p, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for i in 0..STEPS {
        let (r_in, r_out) = (
            *world.physics.bodies[input].rotation(),
            *world.physics.bodies[output].rotation(),
        );
        world.step()?;
        if i >= STEPS / 2 {
            a_in += turned(r_in, *world.physics.bodies[input].rotation());
            a_out -= turned(r_out, *world.physics.bodies[output].rotation());
            for (_, rec) in world.hooks().records() {
                (q, p, n) = (q + rec.q_used.length(), p + rec.p, n + 1.0);
            }
        }
    }
    Ok((
        (a_in - a_out) / (0.5 * (a_in + a_out)),
        q / n.max(1.0),
        p / n.max(1.0),
    ))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let steel = Material::steel();
    let pair = PairMaterial::new(&steel, &steel, Surface::Sphere(R), Surface::Sphere(R))?;
    let mass = steel.density() * 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let mu_p_weight = steel.friction() * mass * 9.81;
    println!("Q/(mu P)  creepage (creep - Coulomb)  Kalker F_ss  error  Coulomb's own slip");
    let mut worst: f64 = 0.0;
    for share in [0.1, 0.3, 0.5, 0.7, 0.9] {
        let torque = share * mu_p_weight * R;
        let (xi_creep, q, p) = run(torque, Fidelity::Creep)?;
        let (xi_coulomb, _, _) = run(torque, Fidelity::Coulomb)?;
        let mu_p = steel.friction() * p;
        let a = hertz::contact_radius(&pair, p);
        let expected = kalker::steady_creepage(q / mu_p, mu_p, pair.g, a, pair.c11);
        let measured = xi_creep - xi_coulomb;
        let error = measured / expected - 1.0;
        worst = worst.max(error.abs());
        println!(
            "{:8.3}  {measured:26.4e}  {expected:11.4e}  {:+5.2} %  {xi_coulomb:.1e}",
            q / mu_p,
            100.0 * error
        );
    }
    println!(
        "largest error against Kalker's curve: {:.2} %",
        100.0 * worst
    );
    assert!(worst < 0.05);
    Ok(())
}
