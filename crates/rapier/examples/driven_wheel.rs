//! A rubber wheel (a Rapier cylinder, line contact) on a revolute joint to a chassis rolls at
//! 0.1 m/s, driven by a torque `T` on the wheel and held back at the chassis by `T/R`, so the
//! floor's traction is `Q = T/R`. The wheel turns faster than it travels by the creepage of
//! Carter's line contact (Carter 1926; Johnson 1985, §8.2):
//! `xi = mu (a/R) (1 - sqrt(1 - Q/(mu P)))`, with the contact's half-width
//! `a = sqrt(4 P R / (pi E* w))` on a wheel of width `w`. Each drive runs with creep and with
//! Coulomb; the difference is compared with Carter.
//!
//! The wheel is built as the guide's recipe says, with the plugin's defaults and nothing else:
//! a cylinder on its own body turned so its axis is the axle, a revolute joint to the chassis
//! (whose rotations are locked here, standing in for the rest of a vehicle), the floor first.
//!
//! `cargo run --release -p creep-rapier --example driven_wheel`

use creep_law::{Material, PairMaterial, Surface};
use creep_rapier::prelude::*;
use rapier3d::prelude::*;

const R: f64 = 0.05;
const WIDTH: f64 = 0.04;
const SPEED: f32 = 0.1;
const DT: f32 = 1.0 / 240.0;
const STEPS: usize = 240;

/// Means over the second half: the creepage at the contact [-], and the traction `Q` and
/// normal force `P` the contact carried (the plugin's record; 0 for Coulomb) [N].
fn run(rubber: Material, share: f64, fidelity: Fidelity) -> Result<(f64, f64, f64), PluginError> {
    let mut world = CreepWorld::new(DT, CreepSettings::default())?;
    let mat = CreepMaterial::new(rubber).with_fidelity(fidelity);
    let mu = rubber.friction() as f32;
    let floor = RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0));
    world.insert(
        floor,
        ColliderBuilder::cuboid(1e3, 0.5, 1e3).friction(mu),
        Some(mat),
    );
    let (r, v) = (R as f32, SPEED);
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, r, 0.0))
        .linvel(Vector::new(v, 0.0, 0.0))
        .angvel(Vector::new(0.0, 0.0, -v / r));
    let tyre = ColliderBuilder::cylinder(0.5 * WIDTH as f32, r)
        .rotation(Vector::new(std::f32::consts::FRAC_PI_2, 0.0, 0.0)) // axis along the axle, z
        .density(rubber.density() as f32)
        .friction(mu);
    let (wheel, _) = world.insert(body, tyre, Some(mat));
    let chassis = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, r, 0.0))
        .linvel(Vector::new(v, 0.0, 0.0))
        .lock_rotations();
    let (chassis, _) = world.insert(chassis, ColliderBuilder::cuboid(0.02, 0.01, 0.01), None);
    let axle = RevoluteJointBuilder::new(Vector::Z).contacts_enabled(false);
    world
        .physics
        .impulse_joints
        .insert(chassis, wheel, axle, true);
    let mass = f64::from(world.physics.bodies[wheel].mass() + world.physics.bodies[chassis].mass());
    let torque = share * rubber.friction() * mass * 9.81 * R;
    world.physics.bodies[wheel].add_torque(Vector::new(0.0, 0.0, -torque as f32), true);
    world.physics.bodies[chassis].add_force(Vector::new((-torque / R) as f32, 0.0, 0.0), true);
    let (mut xi, mut q, mut p, mut n) = (0.0, 0.0, 0.0, 0.0);
    for i in 0..STEPS {
        world.step()?;
        let b = &world.physics.bodies[wheel];
        if i >= STEPS / 2 {
            // The tyre's surface velocity at the floor (y = 0) along the travel, over Kuhn &
            // Bagi's rolling speed `v - u/2` (the floor is at rest).
            let v = f64::from(b.linvel().x);
            let u = v + f64::from(b.angvel().z) * f64::from(b.translation().y);
            (xi, n) = (xi - u / (v - 0.5 * u), n + 1.0);
            for (_, rec) in world.hooks().records() {
                (q, p) = (q + rec.q_used.length(), p + rec.p);
            }
        }
    }
    Ok((xi / n, q / n, p / n))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let rubber = Material::new(1.0e6, 0.5, 0.9, 1100.0)?; // G [Pa], nu, mu, rho [kg/m^3]
    let pair = PairMaterial::new(&rubber, &rubber, Surface::Sphere(R), Surface::Plane)?;
    let mu = rubber.friction();
    println!("Q/(mu P)  creepage (creep - Coulomb)  Carter  error [% of mu P]  Coulomb's own slip");
    let mut worst: f64 = 0.0;
    for share in [0.2, 0.5, 0.7, 0.9] {
        let (xi_creep, q, p) = run(rubber, share, Fidelity::Creep)?;
        let (xi_coulomb, _, _) = run(rubber, share, Fidelity::Coulomb)?;
        let a = (4.0 * p * R / (std::f64::consts::PI * pair.e_star * WIDTH)).sqrt();
        let (xi, ratio) = (xi_creep - xi_coulomb, q / (mu * p));
        let carter = mu * a / R * (1.0 - (1.0 - ratio).sqrt());
        // Carter's force at the measured creepage, against the force the contact carried.
        let force = 1.0 - (1.0 - (xi / (mu * a / R)).min(1.0)).powi(2);
        worst = worst.max((force - ratio).abs());
        println!(
            "{ratio:8.3}  {xi:26.4e}  {carter:.4e}  {:+18.3}  {xi_coulomb:.1e}",
            100.0 * (force - ratio)
        );
    }
    println!("largest error: {:.3} % of mu P", 100.0 * worst);
    assert!(worst < 0.02, "within 2 % of mu P");
    Ok(())
}
