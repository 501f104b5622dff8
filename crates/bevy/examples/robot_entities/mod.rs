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
//! The measurement ([`RobotView::sample`]) is the scene's, term for term (frames, signs and
//! formulas in `creep_scenes::robot`'s module docs).
#![allow(dead_code)] // the demo and the test each use part of it

use std::f32::consts::FRAC_PI_2;

use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use creep_bevy::prelude::*;
use creep_law::Surface;
use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_rapier::ContactRecord;
use creep_scenes::robot::{
    ContactMean, ContactSample, PGS_ITERATIONS, RobotParams, RobotSample, RobotSummary, WheelSpeeds,
};
use rapier3d::prelude::{ColliderHandle, NEW_CONTACT_BIT, RigidBodyHandle};

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

/// A robot's Rapier handles.
struct Handles {
    chassis: RigidBodyHandle,
    wheels: [RigidBodyHandle; 2],
    wheel_colliders: [ColliderHandle; 2],
    caster: RigidBodyHandle,
    caster_collider: ColliderHandle,
    floor: RigidBodyHandle,
    floor_collider: ColliderHandle,
}

impl RobotView<'_, '_> {
    /// The robot's state and contacts after the last step (the scene's `Robot::step` sample,
    /// `hook_creep_power` included), at time `t` \[s\] with time step `dt` \[s\]; `None` before
    /// its bodies exist in Rapier.
    pub fn sample(&self, robot: &RobotEntities, t: f64, dt: f64) -> Option<RobotSample> {
        let (sim, colliders, set) = self.contexts.single().ok()?;
        let body = |e: Entity| set.entity2body().get(&e).copied();
        let collider = |e: Entity| colliders.entity2collider().get(&e).copied();
        let h = Handles {
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
        let bodies = &set.bodies;
        let ch = bodies.get(h.chassis)?;
        let rot = *ch.rotation();
        let heading = v3(rot * Vec3::X);
        let axle = v3(rot * Vec3::Z);
        let w_ch = v3(ch.angvel());
        let r = f64::from(
            colliders
                .colliders
                .get(h.wheel_colliders[0])?
                .shape()
                .as_cylinder()?
                .radius,
        );
        let mut rim = [0.0; 2];
        let mut wheels = [ContactSample::default(); 2];
        let ctx = Ctx {
            sim,
            colliders,
            set,
            creep: &self.creep,
            floor: h.floor,
            floor_collider: h.floor_collider,
            dt,
        };
        for i in 0..2 {
            let wb = bodies.get(h.wheels[i])?;
            rim[i] = -r * (v3(wb.angvel()) - w_ch).dot(axle);
            // The wheel's angular velocity as its joint holds it (the scene's sample).
            let w_joint = w_ch + axle * (v3(wb.angvel()) - w_ch).dot(axle);
            wheels[i] = ctx.contact(
                h.wheels[i],
                h.wheel_colliders[i],
                r,
                Some((heading, w_joint)),
            );
        }
        let rc = f64::from(
            colliders
                .colliders
                .get(h.caster_collider)?
                .shape()
                .as_ball()?
                .radius,
        );
        let caster = ctx.contact(h.caster, h.caster_collider, rc, None);
        let kinetic_energy = [h.chassis, h.wheels[0], h.wheels[1], h.caster]
            .iter()
            .filter_map(|b| bodies.get(*b))
            .map(|b| f64::from(b.kinetic_energy()))
            .sum();
        let hx = rot * Vec3::X;
        Some(RobotSample {
            t,
            position: v3(ch.translation()),
            // A turn to the left (about +y) takes x towards -z.
            yaw: f64::from(-hx.z).atan2(f64::from(hx.x)),
            speed: v3(ch.linvel()).dot(heading),
            yaw_rate: w_ch.y,
            rim_speeds: rim,
            wheels,
            caster,
            hook_creep_power: self.creep.counts().creep_power,
            kinetic_energy,
        })
    }
}

/// The Rapier sets and the plugin's records a contact sample reads.
struct Ctx<'a> {
    sim: &'a RapierContextSimulation,
    colliders: &'a RapierContextColliders,
    set: &'a RapierRigidBodySet,
    creep: &'a CreepFriction,
    floor: RigidBodyHandle,
    floor_collider: ColliderHandle,
    dt: f64,
}

impl Ctx<'_> {
    /// One body's contact with the floor: the scene's `Robot::contact`, term for term.
    fn contact(
        &self,
        body: RigidBodyHandle,
        collider: ColliderHandle,
        radius: f64,
        wheel: Option<(creep_law::Vec3, creep_law::Vec3)>,
    ) -> ContactSample {
        let heading = wheel.map(|(h, _)| h);
        let (Some(rb), Some(fl)) = (self.set.bodies.get(body), self.set.bodies.get(self.floor))
        else {
            return ContactSample::default();
        };
        let centre = v3(rb.translation());
        let n = creep_law::Vec3::new(0.0, -1.0, 0.0);
        // Rapier rolls a body about the point midway between the surfaces: `R - delta/2`
        // below the centre, `delta` the overlap of the last step.
        let overlap = self.overlap(collider);
        let point = centre + n * (radius - 0.5 * overlap);
        let p_motion = BodyMotion {
            position: centre,
            velocity: v3(rb.linvel()),
            angular_velocity: wheel.map_or(v3(rb.angvel()), |(_, w)| w),
            surface: Surface::Sphere(radius),
        };
        let q_motion = BodyMotion {
            position: v3(fl.translation()),
            velocity: v3(fl.linvel()),
            angular_velocity: v3(fl.angvel()),
            surface: Surface::Plane,
        };
        let rates = contact_rates(&p_motion, &q_motion, point, n);
        let x = match heading {
            Some(h) => {
                if h.dot(rates.v_roll) > 0.0 {
                    -h
                } else {
                    h
                }
            }
            None => rates
                .v_roll
                .try_normalize()
                .map_or(creep_law::Vec3::new(-1.0, 0.0, 0.0), |v| -v),
        };
        let y = n.cross(x);
        let speed = rates.v_roll.dot(x).abs();
        let (p, force) = self.impulses(collider);
        let v_disp = (q_motion.velocity_at(point) - p_motion.velocity_at(point)).reject(n);
        let power = force.dot(v_disp);
        let (mut mz, mut hook_power, mut target) = (0.0, 0.0, creep_law::Vec3::ZERO);
        for rec in self.pair_records(collider) {
            let (on_body, sign) = if rec.bodies.0 == Some(body) {
                (-rec.spin_torque, 1.0)
            } else {
                (rec.spin_torque, -1.0)
            };
            mz += on_body.dot(n);
            hook_power += rec.q_used.dot(rec.target).max(0.0);
            target += rec.target * sign;
        }
        let spin_power = mz * (q_motion.angular_velocity - p_motion.angular_velocity).dot(n);
        hook_power += spin_power.max(0.0);
        let inv_v = if speed > 0.0 { 1.0 / speed } else { 0.0 };
        ContactSample {
            p,
            force,
            fx: force.dot(x),
            fy: force.dot(y),
            mz,
            speed,
            xi: rates.v_disp.dot(x) * inv_v,
            eta: rates.v_disp.dot(y) * inv_v,
            phi: rates.w_twist * inv_v,
            slip: [rates.v_disp.dot(x), rates.v_disp.dot(y)],
            twist: rates.w_twist,
            target: [target.dot(x), target.dot(y)],
            power: power + spin_power,
            hook_power,
        }
    }

    /// The mean overlap \[m\] (>= 0) of a collider's solver contacts with the floor, read from
    /// the solver contacts' own distances. (The scene reads the manifold point each solver
    /// contact names; a wheel's patch contact names a point elsewhere on the cylinder, whose
    /// distance the narrow phase can leave far off: in one step of the turn on the spot here it
    /// read 0.46 m, a 0.45 m/s slip that step.)
    fn overlap(&self, collider: ColliderHandle) -> f64 {
        let Some(pair) = self
            .sim
            .narrow_phase
            .contact_pair(collider, self.floor_collider)
        else {
            return 0.0;
        };
        let (mut sum, mut count) = (0.0, 0.0);
        for m in pair.manifolds() {
            for sc in &m.data.solver_contacts {
                sum += f64::from(-sc.dist).max(0.0);
                count += 1.0;
            }
        }
        if count > 0.0 { sum / count } else { 0.0 }
    }

    /// Normal force and the floor's tangential force on the body \[N\] over the solver contacts
    /// of the last step (Rapier's impulses over `dt`).
    fn impulses(&self, collider: ColliderHandle) -> (f64, creep_law::Vec3) {
        let Some(pair) = self
            .sim
            .narrow_phase
            .contact_pair(collider, self.floor_collider)
        else {
            return (0.0, creep_law::Vec3::ZERO);
        };
        let sign = if pair.collider1 == collider {
            1.0
        } else {
            -1.0
        };
        let (mut p, mut q) = (0.0, creep_law::Vec3::ZERO);
        for m in pair.manifolds() {
            let (t1, t2) = creep_rapier::solver_tangents(v3(m.data.normal));
            for sc in &m.data.solver_contacts {
                let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
                let Some(pt) = m.points.get(cid) else {
                    continue;
                };
                p += f64::from(pt.data.impulse) / self.dt;
                let ti = pt.data.tangent_impulse;
                q += (t1 * f64::from(ti.x) + t2 * f64::from(ti.y)) * (sign / self.dt);
            }
        }
        (p, q)
    }

    /// The plugin's contact records of a collider's pair with the floor (either order).
    fn pair_records(&self, a: ColliderHandle) -> Vec<ContactRecord> {
        let b = self.floor_collider;
        self.creep
            .contacts()
            .into_iter()
            .filter(|(k, _)| {
                (k.collider1 == a && k.collider2 == b) || (k.collider1 == b && k.collider2 == a)
            })
            .map(|(_, r)| r)
            .collect()
    }
}

fn v3(v: Vec3) -> creep_law::Vec3 {
    creep_law::Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// A run's means over the second half of `samples` (the scene's `robot::run` summary).
pub fn summarize(samples: &[RobotSample], params: &RobotParams) -> RobotSummary {
    let half = &samples[samples.len() / 2..];
    let k = 1.0 / half.len().max(1) as f64;
    let mut s = RobotSummary::default();
    for x in half {
        s.rim_speeds[0] += k * x.rim_speeds[0];
        s.rim_speeds[1] += k * x.rim_speeds[1];
        s.speed += k * x.speed;
        s.yaw_rate += k * x.yaw_rate;
        add(&mut s.wheels[0], &x.wheels[0], k);
        add(&mut s.wheels[1], &x.wheels[1], k);
        add(&mut s.caster, &x.caster, k);
        s.dissipated += x.power() * params.dt;
        s.hook_energy += x.hook_creep_power * params.dt;
    }
    s.window = half.len() as f64 * params.dt;
    for m in s.wheels.iter_mut() {
        finish(m);
    }
    finish(&mut s.caster);
    let mean = WheelSpeeds::arc(s.rim_speeds[0], s.rim_speeds[1]);
    let (_, omega, radius) = mean.kinematics(params.track);
    s.yaw_rate_closed_form = omega;
    s.radius_closed_form = radius;
    s.radius = if s.yaw_rate != 0.0 {
        s.speed / s.yaw_rate
    } else {
        f64::INFINITY
    };
    s
}

fn add(m: &mut ContactMean, s: &ContactSample, k: f64) {
    m.p += k * s.p;
    m.fx += k * s.fx;
    m.fy += k * s.fy;
    m.mz += k * s.mz;
    m.speed += k * s.speed;
    m.slip[0] += k * s.slip[0];
    m.slip[1] += k * s.slip[1];
    m.twist += k * s.twist;
    m.law_creepage[0] += k * s.target[0];
    m.law_creepage[1] += k * s.target[1];
    m.power += k * s.power;
    m.hook_power += k * s.hook_power;
}

/// Creepages as the mean slip over the mean speed (the scene's `ContactMean`).
fn finish(m: &mut ContactMean) {
    let inv_v = if m.speed > 0.0 { 1.0 / m.speed } else { 0.0 };
    m.xi = m.slip[0] * inv_v;
    m.eta = m.slip[1] * inv_v;
    m.phi = m.twist * inv_v;
    m.law_creepage = [m.law_creepage[0] * inv_v, m.law_creepage[1] * inv_v];
}
