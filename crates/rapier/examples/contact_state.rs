//! Reading each contact after a step: its state (stick, creep or slip) and creep slip velocity
//! from the plugin's records (`world.hooks.records()`), its normal and friction force from
//! Rapier's impulses, and the power it dissipates by creep (`Q . v_disp`).
//!
//! Three steel balls on one 20 degree incline (mu = 0.5), each against its closed form:
//! * rolling: creeps, `Q = (2/7) m g sin(theta)`;
//! * rotation locked: sticks (no rolling, so no creep), `Q = m g sin(theta)`;
//! * launched with backspin: slides at the Coulomb limit, `Q = mu m g cos(theta)`, until it
//!   rolls, and then creeps like the first.
//!
//! `cargo run --release -p creep-rapier --example contact_state`

use creep_law::Vec3;
use creep_rapier::diagnostics::solver_tangents;
use creep_rapier::prelude::*;
use rapier3d::prelude::*;

const THETA: f64 = 20.0 * std::f64::consts::PI / 180.0;
const MU: f64 = 0.5;
const DT: f64 = 1.0 / 240.0;

/// Normal and friction force [N] of the last step between two colliders, from Rapier's impulses
/// at the points its solver used (in Rapier's tangent basis, `solver_tangents`).
fn forces(world: &CreepWorld, c1: ColliderHandle, c2: ColliderHandle) -> (f64, f64) {
    let Some(pair) = world.physics.narrow_phase.contact_pair(c1, c2) else {
        return (0.0, 0.0);
    };
    let (mut p, mut q) = (0.0, Vec3::ZERO);
    for m in pair.manifolds() {
        let n = m.data.normal;
        let (t1, t2) = solver_tangents(Vec3::new(n.x.into(), n.y.into(), n.z.into()));
        for sc in &m.data.solver_contacts {
            if let Some(pt) = m.points.get((sc.contact_id[0] & !NEW_CONTACT_BIT) as usize) {
                p += f64::from(pt.data.impulse);
                let ti = pt.data.tangent_impulse;
                q += t1 * f64::from(ti.x) + t2 * f64::from(ti.y);
            }
        }
    }
    (p / DT, q.length() / DT)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = CreepWorld::new(DT as f32, CreepSettings::default())?;
    world.physics.gravity = 9.81 * Vector::new(THETA.sin() as f32, -THETA.cos() as f32, 0.0);
    let steel = CreepMaterial::new(Material::steel()).with_fidelity(Fidelity::Creep);
    let slope = RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0));
    let floor = ColliderBuilder::cuboid(100.0, 0.5, 10.0).friction(MU as f32);
    world.insert(slope, floor, Some(steel));
    let ball = |z: f32| {
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.1, z))
            .can_sleep(false)
    };
    let mut add = |name, body: RigidBodyBuilder| {
        let ball = ColliderBuilder::ball(0.1).friction(MU as f32);
        let (b, _) = world.insert(body, ball, Some(steel));
        (b, name)
    };
    let balls = [
        add("rolling", ball(-1.0)),
        add("locked", ball(0.0).lock_rotations()),
        add("backspin", ball(1.0).angvel(Vector::new(0.0, 0.0, 60.0))),
    ];
    for step in 1..=120 {
        let counts = world.step()?;
        if step % 40 != 0 {
            continue;
        }
        println!(
            "t = {:.3} s: {} creep contact(s), creep power {:.3e} W",
            step as f64 * DT,
            counts.creep,
            counts.creep_power
        );
        for (key, rec) in world.hooks().records() {
            let Some(&(body, name)) = balls
                .iter()
                .find(|(b, _)| rec.bodies.1 == Some(*b) || rec.bodies.0 == Some(*b))
            else {
                continue;
            };
            let (p, q) = forces(&world, key.collider1, key.collider2);
            let slip = rec.target.length();
            let mg = f64::from(world.physics.bodies[body].mass()) * 9.81;
            let (state, closed_form) = if slip == 0.0 {
                ("stick", mg * THETA.sin())
            } else if rec.q_used.length() >= (1.0 - 1e-3) * MU * rec.p {
                ("slip", MU * mg * THETA.cos())
            } else {
                ("creep", 2.0 / 7.0 * mg * THETA.sin())
            };
            println!(
                "  {name:8} {state:5}  P {p:6.1} N (m g cos {:6.1})  Q {q:6.2} N (closed form {closed_form:6.2})  \
                 slip {slip:.2e} m/s  power {:.2e} W",
                mg * THETA.cos(),
                rec.q_used.dot(rec.target).max(0.0)
            );
        }
    }
    Ok(())
}
