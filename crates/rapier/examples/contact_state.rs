//! Reading each contact's state after a step: stick, creep or slip, its normal and tangential
//! force, its creep slip velocity and the power it dissipates (`Q . v_disp`), from the plugin's
//! contact records (`world.hooks.records()`).
//!
//! Three steel balls on one 20 degree incline (mu = 0.5), each against its closed form:
//! * rolling: creeps, `Q = (2/7) m g sin(theta)`;
//! * rotation locked: sticks (no rolling, so no creep), `Q = m g sin(theta)`;
//! * launched with backspin: slides at the Coulomb limit, `|Q| = mu m g cos(theta)`.
//!
//! `cargo run --release -p creep-rapier --example contact_state`

use creep_rapier::prelude::*;
use rapier3d::prelude::*;

const THETA: f64 = 20.0 * std::f64::consts::PI / 180.0;
const MU: f64 = 0.5;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = CreepWorld::new(1.0 / 240.0, CreepSettings::default())?;
    world.physics.integration_parameters.num_solver_iterations = 1;
    let g = 9.81 * Vector::new(THETA.sin() as f32, -THETA.cos() as f32, 0.0);
    world.physics.gravity = g;
    let steel = CreepMaterial::new(Material::steel()).with_fidelity(Fidelity::Creep);
    let slope = RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0));
    world.insert(slope, ColliderBuilder::cuboid(100.0, 0.5, 10.0).friction(MU as f32), Some(steel));
    let ball = |z: f32| RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.1, z)).can_sleep(false);
    let mut add = |body: RigidBodyBuilder| {
        world.insert(body, ColliderBuilder::ball(0.1).friction(MU as f32), Some(steel)).0
    };
    let rolling = add(ball(-1.0));
    let locked = add(ball(0.0).lock_rotations());
    let backspin = add(ball(1.0).angvel(Vector::new(0.0, 0.0, 60.0)));
    let names = [(rolling, "rolling"), (locked, "locked"), (backspin, "backspin")];

    for step in 1..=120 {
        let counts = world.step()?;
        if step % 40 != 0 {
            continue;
        }
        println!("t = {:.3} s: {} creep contact(s), creep power {:.3e} W", step as f64 / 240.0,
            counts.creep, counts.creep_power);
        for (_, rec) in world.hooks.records() {
            // The slope is fixed: the ball is whichever body the record names.
            let Some(&(body, name)) = names.iter().find(|(h, _)| Some(*h) == rec.bodies.0 || Some(*h) == rec.bodies.1)
            else {
                continue;
            };
            let (q, slip) = (rec.q_used.length(), rec.target.length());
            let state = if slip == 0.0 {
                "stick"
            } else if q >= (1.0 - 1e-3) * MU * rec.p {
                "slip"
            } else {
                "creep"
            };
            let m = f64::from(world.physics.bodies[body].mass()) * 9.81;
            let expected = match name {
                "rolling" => 2.0 / 7.0 * m * THETA.sin(),
                "locked" => m * THETA.sin(),
                _ => MU * m * THETA.cos(),
            };
            println!(
                "  {name:8} {state:5}  P {:7.2} N (m g cos {:7.2})  |Q| {q:6.2} N (closed form {expected:6.2})  \
                 Q/(mu P) {:.3}  slip {slip:.2e} m/s  power {:.2e} W",
                rec.p, m * THETA.cos(), q / (MU * rec.p), rec.q_used.dot(rec.target).max(0.0)
            );
        }
    }
    Ok(())
}
