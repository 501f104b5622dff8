//! Your own Rapier loop with creep-friction: Rapier's `PhysicsPipeline` and the sets you already
//! have, plus a `CreepPipeline` that owns the hooks and steps through `CreepPipeline::step`.
//! What `CreepWorld` does for you, done by hand:
//!
//! 1. `configure_parameters` sets the integration parameters the plugin needs (Coulomb friction
//!    model, no contact clustering; a step with others is a typed error) and the solver that
//!    rolling needs (one substep, four Gauss-Seidel iterations; `configure_parameters_for` with
//!    `SolverPreset::Rapier` keeps Rapier's);
//! 2. each collider that should creep is registered with its `CreepMaterial`; its mass comes
//!    from the collider's density, so give it the material's density;
//! 3. `CreepPipeline::step` takes what `PhysicsPipeline::step` takes, but the hooks.
//!
//! A steel ball rolls down a 20 degree incline; it must accelerate at `(5/7) g sin(theta)`.
//!
//! `cargo run --release -p creep-rapier --example own_loop`

use creep_rapier::prelude::*;
use rapier3d::prelude::*;

fn main() -> Result<(), PluginError> {
    let (theta, g, r) = (20f32.to_radians(), 9.81f32, 0.1f32);
    let gravity = Vector::new(g * theta.sin(), -g * theta.cos(), 0.0);
    let mut params = IntegrationParameters {
        dt: 1.0 / 240.0,
        ..Default::default()
    };
    configure_parameters(&mut params);
    let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    let (mut islands, mut broad_phase, mut narrow_phase) = (
        IslandManager::new(),
        BroadPhaseBvh::new(),
        NarrowPhase::new(),
    );
    let (mut impulse_joints, mut multibody_joints) =
        (ImpulseJointSet::new(), MultibodyJointSet::new());
    let (mut soft_bodies, mut ccd_solver) = (SoftBodySet::new(), CCDSolver::new());
    let mut physics_pipeline = PhysicsPipeline::new();

    let steel = Material::steel().with_friction(0.5)?;
    let mat = CreepMaterial::new(steel).with_fidelity(Fidelity::Creep);
    let mut creep = CreepPipeline::new(CreepSettings::default())?;
    let ground = bodies.insert(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    let floor = ColliderBuilder::cuboid(100.0, 0.5, 10.0).friction(0.5);
    let floor = colliders.insert_with_parent(floor, ground, &mut bodies);
    creep.registry_mut().insert(floor, mat);
    let ball = bodies.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, r, 0.0)));
    let ball_collider = ColliderBuilder::ball(r)
        .friction(0.5)
        .density(steel.density() as f32); // Rapier's default density is 1 kg/m^3
    let ball_collider = colliders.insert_with_parent(ball_collider, ball, &mut bodies);
    creep.registry_mut().insert(ball_collider, mat);

    let (steps, mut energy, mut last) = (240, 0.0, StepCounts::default());
    for _ in 0..steps {
        last = creep.step(RapierStep {
            pipeline: &mut physics_pipeline,
            gravity,
            params: &params,
            islands: &mut islands,
            broad_phase: &mut broad_phase,
            narrow_phase: &mut narrow_phase,
            bodies: &mut bodies,
            colliders: &mut colliders,
            impulse_joints: &mut impulse_joints,
            multibody_joints: &mut multibody_joints,
            soft_bodies: &mut soft_bodies,
            ccd_solver: &mut ccd_solver,
            events: &(),
        })?;
        energy += last.creep_power * f64::from(params.dt);
    }
    let b = &bodies[ball];
    let expected_mass = steel.density() * 4.0 / 3.0 * std::f64::consts::PI * f64::from(r).powi(3);
    let acceleration = b.linvel().x / (steps as f32 * params.dt);
    let closed_form = 5.0 / 7.0 * g * theta.sin();
    println!(
        "ball mass {:.3} kg (rho 4/3 pi R^3 = {expected_mass:.3} kg)",
        b.mass()
    );
    println!("acceleration {acceleration:.4} m/s^2, (5/7) g sin(theta) = {closed_form:.4} m/s^2");
    println!(
        "last step: {} contact(s) on the creep path, {} hook(s) on, creep power {:.3e} W",
        last.creep, last.hooks_on, last.creep_power
    );
    println!("energy dissipated by creep in 1 s: {energy:.3e} J");
    assert!(last.creep == 1 && (acceleration / closed_form - 1.0).abs() < 2e-3);
    Ok(())
}
