//! creep-scenes' differential-drive robot (`creep_scenes::robot`: a chassis, two crowned rubber
//! wheels on revolute joints with velocity motors, a caster ball on a spherical joint, on a
//! flat rubber floor) as bevy_rapier3d entities, its contacts run by the creep-friction plugin:
//! what the `robot` demo shows and `tests/robot.rs` checks against the scene's own `Robot`.
//! No renderer here: the demo adds its meshes to the entities' drawn copies.
//!
//! The recipe, from the scene:
//! - a wheel is a `RigidBody::Dynamic` entity whose `Collider::cylinder` sits on a child entity
//!   turned onto the axle (Rapier's cylinder stands on its local `y`; the axle is the chassis'
//!   `z`), with `Friction`, a `CreepMaterial` with the wheel's crown
//!   (`CreepMaterial::with_crown`), held to the chassis by an `ImpulseJoint` with a
//!   `RevoluteJointBuilder` about `z` (contacts between the two off) and driven by its velocity
//!   motor (`set_motor_velocity(JointAxis::AngX, -v/R, factor)` for a rim speed `v` forward);
//! - the integration parameters: the plugin's one solver substep, 16 Gauss-Seidel iterations
//!   in it (`num_internal_pgs_iterations`: two motors, a ball joint and three contacts are
//!   coupled) and the wheel's radius as `length_unit` (Rapier's allowed overlap is 1e-3 length
//!   units: a rolling-radius error below the creepages), set by [`robot_parameters`];
//! - the caster ball on a spherical joint; bodies that never sleep (`Sleeping::disabled`).
//!
//! The measurement ([`RobotView::sample`]) is the scene's own (`creep_scenes::robot::RobotProbe`
//! over this context's sets; frames, signs and formulas in `creep_scenes::robot`'s module docs),
//! and a run's means are `creep_scenes::robot::summarize`.
#![allow(dead_code)] // the demo and the test each use part of it

use std::f32::consts::FRAC_PI_2;

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use creep_bevy::prelude::*;
use creep_scenes::robot::{
    PGS_ITERATIONS, RobotHandles, RobotParams, RobotProbe, RobotSample, WheelSpeeds,
};

/// The robot's entities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotEntities {
    /// The chassis body (its origin: the axle midpoint).
    pub chassis: Entity,
    /// The wheel bodies (left, right), each with its revolute joint to the chassis.
    pub wheels: [Entity; 2],
    /// The wheels' collider entities (children of the wheel bodies).
    pub wheel_colliders: [Entity; 2],
    /// The caster ball (body and collider), with its spherical joint to the chassis.
    pub caster: Entity,
    /// The floor (fixed body and collider).
    pub floor: Entity,
}

impl RobotEntities {
    /// The entities to despawn to remove the robot (its children go with them).
    pub fn bodies(&self) -> [Entity; 4] {
        [self.chassis, self.wheels[0], self.wheels[1], self.caster]
    }
}

/// Sets the robot's integration parameters on every Rapier context (module docs), before its
/// first step: a `Startup` system (the default context is created in `PreStartup`).
pub fn robot_parameters(params: RobotParams) -> impl FnMut(Query<&mut RapierContextSimulation>) {
    move |mut contexts| {
        for mut sim in &mut contexts {
            let ip = &mut sim.integration_parameters;
            ip.num_internal_pgs_iterations = PGS_ITERATIONS;
            ip.length_unit = params.wheel_radius as f32;
        }
    }
}

/// Spawns the floor: a fixed 2 km square slab of the robot's material, top face at `y = 0`.
pub fn spawn_floor(commands: &mut Commands, params: &RobotParams, fidelity: Fidelity) -> Entity {
    commands
        .spawn((
            RigidBody::Fixed,
            Transform::from_xyz(0.0, -0.5, 0.0),
            Collider::cuboid(1.0e3, 0.5, 1.0e3),
            Friction::coefficient(params.material.friction() as f32),
            CreepMaterial::new(params.material).with_fidelity(fidelity),
        ))
        .id()
}

/// The revolute joint of a wheel at `anchor` (chassis frame), its motor at rim speed `v`.
fn wheel_joint(chassis: Entity, anchor: Vec3, v: f64, params: &RobotParams) -> ImpulseJoint {
    let mut joint = RevoluteJointBuilder::new(Vec3::Z)
        .local_anchor1(anchor)
        .local_anchor2(Vec3::ZERO)
        .contacts_enabled(false)
        .build();
    // Forward rolling turns the wheel about -z relative to the chassis.
    joint.set_motor_velocity(
        (-v / params.wheel_radius) as f32,
        params.motor_factor as f32,
    );
    ImpulseJoint::new(chassis, joint)
}

/// Spawns the robot at rest on the floor `floor`, its axle midpoint above `origin` (on the
/// floor), heading along world `x`, its motors at `speeds`; `fidelity` for the wheels and the
/// caster. The scene's `Robot::new` with its `set_speeds`, as entities: [`spawn_chassis`],
/// [`spawn_wheel`] (left, right), [`spawn_caster`].
pub fn spawn_robot(
    commands: &mut Commands,
    params: &RobotParams,
    fidelity: Fidelity,
    speeds: WheelSpeeds,
    floor: Entity,
    origin: Vec3,
) -> Result<RobotEntities, String> {
    params.validate().map_err(|e| e.to_string())?;
    let chassis = spawn_chassis(commands, params, origin);
    let (l, lc) = spawn_wheel(commands, params, fidelity, chassis, 0, speeds.left, origin)?;
    let (r, rc) = spawn_wheel(commands, params, fidelity, chassis, 1, speeds.right, origin)?;
    let caster = spawn_caster(commands, params, fidelity, chassis, origin);
    Ok(RobotEntities {
        chassis,
        wheels: [l, r],
        wheel_colliders: [lc, rc],
        caster,
        floor,
    })
}

/// The chassis: a body whose origin is the axle midpoint (at the wheels' centre height, above
/// `origin`), its box (a child collider of the chassis' density) centred 0.4 wheelbase behind it.
pub fn spawn_chassis(commands: &mut Commands, params: &RobotParams, origin: Vec3) -> Entity {
    let r = params.wheel_radius as f32;
    let lb = params.wheelbase as f32;
    let (hx, hy, hz) = (0.7 * lb, 0.4 * r, 0.4 * params.track as f32);
    let volume = 8.0 * f64::from(hx * hy * hz);
    let chassis = commands
        .spawn((
            RigidBody::Dynamic,
            Transform::from_translation(origin + Vec3::new(0.0, r, 0.0)),
            Sleeping::disabled(),
        ))
        .id();
    commands.spawn((
        Collider::cuboid(hx, hy, hz),
        Transform::from_xyz(-0.4 * lb, 0.0, 0.0),
        ColliderMassProperties::Density((params.chassis_mass / volume) as f32),
        ChildOf(chassis),
    ));
    chassis
}

/// Wheel `i` (0 left at `z = -track/2`, 1 right), its revolute joint to `chassis` with its
/// motor at rim speed `v` \[m/s\]: the wheel body and its collider (a child entity).
pub fn spawn_wheel(
    commands: &mut Commands,
    params: &RobotParams,
    fidelity: Fidelity,
    chassis: Entity,
    i: usize,
    v: f64,
    origin: Vec3,
) -> Result<(Entity, Entity), String> {
    let crown = params.crown().map_err(|e| e.to_string())?;
    let material = CreepMaterial::new(params.material)
        .with_fidelity(fidelity)
        .with_crown(crown);
    let r = params.wheel_radius as f32;
    let side = if i == 0 { -1.0 } else { 1.0 };
    let z = side * 0.5 * params.track as f32;
    let wheel = commands
        .spawn((
            RigidBody::Dynamic,
            Transform::from_translation(origin + Vec3::new(0.0, r, z)),
            Sleeping::disabled(),
            wheel_joint(chassis, Vec3::new(0.0, 0.0, z), v, params),
        ))
        .id();
    // Rapier's cylinder has its axis along local y: turned onto the body's z.
    let collider = commands
        .spawn((
            Collider::cylinder(0.5 * params.wheel_width as f32, r),
            Transform::from_rotation(Quat::from_rotation_x(FRAC_PI_2)),
            Friction::coefficient(params.material.friction() as f32),
            material,
            ChildOf(wheel),
        ))
        .id();
    Ok((wheel, collider))
}

/// The caster ball (body and collider) on a spherical joint to `chassis`, one wheelbase behind
/// the axle.
pub fn spawn_caster(
    commands: &mut Commands,
    params: &RobotParams,
    fidelity: Fidelity,
    chassis: Entity,
    origin: Vec3,
) -> Entity {
    let (r, lb) = (params.wheel_radius as f32, params.wheelbase as f32);
    let rc = params.caster_radius as f32;
    let joint = SphericalJointBuilder::new()
        .local_anchor1(Vec3::new(-lb, rc - r, 0.0))
        .local_anchor2(Vec3::ZERO)
        .contacts_enabled(false);
    commands
        .spawn((
            RigidBody::Dynamic,
            Transform::from_translation(origin + Vec3::new(-lb, rc, 0.0)),
            Sleeping::disabled(),
            Collider::ball(rc),
            Friction::coefficient(params.material.friction() as f32),
            CreepMaterial::new(params.material).with_fidelity(fidelity),
            ImpulseJoint::new(chassis, joint),
        ))
        .id()
}

/// Sets the motors' target rim speeds \[m/s\] (the scene's `Robot::set_speeds`).
pub fn set_speeds(
    joints: &mut Query<&mut ImpulseJoint>,
    robot: &RobotEntities,
    speeds: WheelSpeeds,
    params: &RobotParams,
) {
    for (wheel, v) in robot.wheels.iter().zip([speeds.left, speeds.right]) {
        if let Ok(mut j) = joints.get_mut(*wheel) {
            j.data.as_mut().set_motor_velocity(
                JointAxis::AngX,
                (-v / params.wheel_radius) as f32,
                params.motor_factor as f32,
            );
        }
    }
}

/// What [`RobotView::sample`] reads: the served Rapier context and the plugin's resource.
#[derive(SystemParam)]
pub struct RobotView<'w, 's> {
    contexts: Query<
        'w,
        's,
        (
            &'static RapierContextSimulation,
            &'static RapierContextColliders,
            &'static RapierRigidBodySet,
        ),
        With<DefaultRapierContext>,
    >,
    creep: Res<'w, CreepFriction>,
}

impl RobotView<'_, '_> {
    /// The robot's state and contacts after the last step (the scene's `Robot::step` sample,
    /// `hook_creep_power` included), at time `t` \[s\] with time step `dt` \[s\], for the robot
    /// spawned with `params`: the scene's measurement (`creep_scenes::robot::RobotProbe`) over
    /// the default context's sets and the plugin's records. `None` before its bodies exist in
    /// Rapier.
    pub fn sample(
        &self,
        robot: &RobotEntities,
        params: &RobotParams,
        t: f64,
        dt: f64,
    ) -> Option<RobotSample> {
        let (sim, colliders, set) = self.contexts.single().ok()?;
        let body = |e: Entity| set.entity2body().get(&e).copied();
        let collider = |e: Entity| colliders.entity2collider().get(&e).copied();
        let handles = RobotHandles {
            chassis: body(robot.chassis)?,
            wheels: [body(robot.wheels[0])?, body(robot.wheels[1])?],
            wheel_colliders: [
                collider(robot.wheel_colliders[0])?,
                collider(robot.wheel_colliders[1])?,
            ],
            caster: body(robot.caster)?,
            caster_collider: collider(robot.caster)?,
            floor: body(robot.floor)?,
            floor_collider: collider(robot.floor)?,
        };
        let records = self.creep.contacts();
        RobotProbe {
            bodies: &set.bodies,
            narrow_phase: &sim.narrow_phase,
            records: &records,
            handles,
            params,
        }
        .sample(t, dt, self.creep.counts().creep_power)
    }
}
