//! A 0.1 m steel ball rolls freely at 10 m/s on a level half-space at a game step of 1/60 s for
//! 10 s. Nothing loads the contact tangentially, so any energy lost or gained and any sinking
//! is the engine's error. Three runs:
//!
//! * plain Rapier (its default four solver substeps): Rapier caps each body's spin at 45
//!   degrees per step, so the ball (which needs 95 degrees per step) slides and loses energy;
//! * the plugin at four substeps: the spin cap stays and the rotation-gap correction is a mean
//!   over the substeps, so the ball hops and sinks by millimetres;
//! * the plugin at **one** substep (`num_solver_iterations = 1`, the default of `CreepWorld::new`
//!   and `configure_parameters`): the correction is exact and the cap is lifted for registered
//!   balls (`CreepSettings::lift_rotation_cap`).
//!
//! The four-substep runs opt out of the default with `CreepSettings::with_rapier_solver()`; the
//! plugin then warns once that the ball rolls too fast for Rapier's substeps.
//!
//! `cargo run --release -p creep-rapier --example rolling_ball`

use creep_rapier::prelude::*;
use rapier3d::prelude::*;

const R: f32 = 0.1;
const DT: f32 = 1.0 / 60.0;

/// A world with the ground and a ball at height `y` moving at `v` and rolling about the point
/// midway through the overlap (where Rapier's solve rolls it); registered with the plugin when
/// `plugin`.
fn world(
    substeps: usize,
    plugin: bool,
    y: f32,
    v: f32,
) -> Result<(CreepWorld, RigidBodyHandle), PluginError> {
    // The plugin's default is one solver substep; Rapier's own four are the named opt-out.
    let settings = match substeps {
        1 => CreepSettings::default(),
        _ => CreepSettings::default().with_rapier_solver(),
    };
    let mut world = CreepWorld::new(DT, settings)?;
    world.physics.integration_parameters.num_solver_iterations = substeps;
    let steel = Material::steel();
    let mat = plugin.then(|| CreepMaterial::new(steel).with_fidelity(Fidelity::Creep));
    let mu = steel.friction() as f32;
    let ground = ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y));
    world.insert(RigidBodyBuilder::fixed(), ground.friction(mu), mat);
    let arm = R - 0.5 * (R - y.min(R));
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, y, 0.0))
        .linvel(Vector::new(v, 0.0, 0.0))
        .angvel(Vector::new(0.0, 0.0, -v / arm))
        .can_sleep(false);
    let ball = ColliderBuilder::ball(R)
        .density(steel.density() as f32)
        .friction(mu);
    let (ball, _) = world.insert(body, ball, mat);
    Ok((world, ball))
}

fn step(world: &mut CreepWorld, plugin: bool) -> Result<(), PluginError> {
    if plugin {
        for warning in world.step()?.warnings {
            println!("  the plugin warns: {warning}"); // each warning is given once
        }
    } else {
        world.physics.step(); // Rapier alone, no hooks
    }
    Ok(())
}

fn energy(world: &CreepWorld, ball: RigidBodyHandle, rest: f32) -> f64 {
    let b = &world.physics.bodies[ball];
    let i = f64::from(b.mass_properties().local_mprops.principal_inertia().z);
    let (v, w) = (
        f64::from(b.linvel().length()),
        f64::from(b.angvel().length()),
    );
    let m = f64::from(b.mass());
    0.5 * m * v * v + 0.5 * i * w * w + m * 9.81 * f64::from(b.translation().y - rest)
}

/// Energy lost over 10 s [fraction of E0], largest rise and sink of the centre [m].
fn run(substeps: usize, plugin: bool) -> Result<(f64, f32, f32), PluginError> {
    let (mut w, ball) = world(substeps, plugin, R, 0.0)?;
    for _ in 0..120 {
        step(&mut w, plugin)?; // the resting height of the centre on this ground
    }
    let rest = w.physics.bodies[ball].translation().y;
    let (mut w, ball) = world(substeps, plugin, rest, 10.0)?;
    let e0 = energy(&w, ball, rest);
    let (mut rise, mut sink) = (0.0f32, 0.0f32);
    for _ in 0..600 {
        step(&mut w, plugin)?;
        let y = w.physics.bodies[ball].translation().y - rest;
        (rise, sink) = (rise.max(y), sink.max(-y));
    }
    Ok(((e0 - energy(&w, ball, rest)) / e0, rise, sink))
}

fn main() -> Result<(), PluginError> {
    println!(
        "10 m/s steel ball, 1/60 s, 10 s on a half-space: energy lost, largest rise, largest sink"
    );
    let mut one = (0.0, 0.0, 0.0);
    for (name, substeps, plugin) in [
        ("plain Rapier, 4 substeps", 4, false),
        ("plugin,       4 substeps", 4, true),
        ("plugin,       1 substep ", 1, true),
    ] {
        let (loss, rise, sink) = run(substeps, plugin)?;
        println!(
            "{name}: lost {loss:+.2e} of E0, rise {:.3} mm, sink {:.4} mm",
            1e3 * rise,
            1e3 * sink
        );
        one = (loss, rise, sink);
    }
    let (loss, _, sink) = one;
    assert!(loss.abs() < 1e-3 && sink < 1e-4, "one substep rolls right");
    Ok(())
}
