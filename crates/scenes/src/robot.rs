//! A differential-drive robot: a chassis, two driven crowned rubber wheels
//! on revolute joints with velocity motors, and a caster ball on a spherical joint, on a flat
//! rubber floor; it turns on the spot or drives an arc, with creep-friction or as a Coulomb twin.
//!
//! # Frames and signs
//!
//! World `y` up. The chassis' forward direction is its local `x`, its axle its local `z`, so its
//! right side is `+z` (forward × up); the left wheel sits at `z = -track/2`, the right one at
//! `+track/2`, both at `x = 0` of the chassis (the axle line), the caster ball at
//! `x = -wheelbase`. A wheel's **rim speed** `v_i = -R (w_wheel - w_chassis) . e_axle` \[m/s\]
//! (positive forward) is what its motor sets; the chassis' **yaw rate** `Omega = w . y`
//! (positive: turning left).
//!
//! Each contact is measured in the frame of `creep_law::rigid` (Kalker 1967; Kalker
//! 1990, §1.2) with the rolling body as p and the floor as q (`n` from p to q, downwards):
//! Kuhn & Bagi's rolling velocity `v_roll` at the point Rapier rolls the body about (under its
//! centre, midway between the surfaces: `R - delta/2` below it, `delta` the overlap),
//! `x` along the wheel's heading against the rolling (`x = -v_roll/|v_roll|` for the ball),
//! `y = n × x`, and with `V = |v_roll . x|`: longitudinal creepage `xi = v_disp . x / V`,
//! lateral `eta = v_disp . y / V`, spin `phi = (w_q - w_p) . n / V` \[1/m\] (`v_disp` the floor's
//! surface velocity less the body's).
//!
//! # Closed forms (rigid kinematics of the differential drive; Siegwart, Nourbakhsh &
//! Scaramuzza 2011, *Introduction to Autonomous Mobile Robots*, §3.2)
//!
//! Without slip the axle's midpoint moves at `V = (v_r + v_l)/2` and the chassis turns at
//! `Omega = (v_r - v_l)/b` (`b` the track), on an arc of radius `R = V/Omega =
//! (b/2)(v_r + v_l)/(v_r - v_l)`; turning on the spot (`v_l = -v_r`) a wheel rolls at `v_r` on
//! a circle of radius `b/2`, so its spin creepage is `phi = Omega/V = 2/b` and its lateral
//! creepage zero (its contact moves along its heading). On an arc each wheel spins with
//! `phi_i = Omega/v_i = 1/R_i`, `R_i = R ± b/2`: the spin's lateral forces (Kalker's `C23`) of
//! the two wheels differ and, with the centripetal force, ask for lateral creep. Creep makes
//! the wheels' ground speeds differ from their rim speeds by their longitudinal creepages, so
//! the measured radius differs from the closed form by about `xi/((v_r - v_l)/(v_r + v_l))`.
//!
//! # Energy
//!
//! A contact dissipates `Q . v_disp + M_z w_twist` (`Q` the floor's force on the body, from
//! Rapier's contact impulses; `M_z` the creep law's twisting moment on the body, which the
//! plugin applies after the step, read from its contact record): the **measured** dissipation.
//! The rigid hook books its own estimate, `q_used . target + M_z w_twist` per creep contact
//! (`StepCounts::creep_power`): in a steady creep run the two agree up to the engine's own slip
//! (measured -6.6 % turning on the spot, +0.3 % on the arc). The measured lateral creepage
//! `eta` reads about `-Omega dt` more than the motion: a wheel's velocity after a step is
//! tangent to its circle at the step's start (Rapier's symplectic Euler: velocities from the
//! start-of-step geometry, then positions), while the sample's axes have turned with the
//! chassis by `Omega dt` (turning on the spot at 1/240 s: -3.6e-3 and -4.0e-3 against
//! `Omega dt` = 4.1e-3, in the creep run and its Coulomb twin alike; on the arc -1.1e-3 in the
//! twin against 1.0e-3; the wheels' positions along the axle stay constant to 1e-6 m). Times
//! the spin's lateral force it reads -4.7e-4 W per wheel turning on the spot;
//! `ContactMean::law_creepage` gives the law's own creepages. The power is taken at the
//! contact's point (a wheel's patch, a ball's lowest point), where Rapier applied the impulse. A
//! wheel's
//! angular velocity is taken as its joint holds it (the chassis' plus its own about the axle):
//! the plugin applies the twisting moment to the wheel alone after the step and the joint shares
//! it with the chassis in the next solve. The Coulomb twin's wheels touch at one patch point
//! each (creep-rapier's wheel module), with no twisting friction: they dissipate only where
//! Rapier's rows slip.
//!
//! # The wheels' lateral forces
//!
//! Turning on the spot each wheel presses on the floor sideways with 1.14 N (0.27 `mu P`), in
//! opposite directions (the axle is squeezed): the **lateral force of spin** (Kalker's `C23`
//! term; the wheels spin at `phi_n = phi G c^3/(mu P) = 0.33`), less what a lateral creepage
//! against the spin takes (`eta_n = -0.013`), which the creep law gives at the wheels'
//! creepages within 1 % (creep-scenes' `tests/robot.rs`; Kalker's exact theory for pure spin,
//! the boundary elements, 1.23 N). That lateral creepage is set in the first steps from rest:
//! with the law's slopes at zero creepage a few per cent different the run settles at `eta_n =
//! +0.0016` and 1.29 N, so the force of a spot turn is known to about 12 %. On an arc the spin's lateral forces (+0.37 N
//! inner, +0.25 N outer at 0.1 and 0.15 m/s) are balanced by lateral creep, the two wheels
//! slipping sideways at one speed (one rigid axle), and what is left is the centripetal force.
//!
//! Each wheel's creepages, forces and moments per step, or a whole run with its means:
//!
//! ```
//! use creep_scenes::robot::{self, Fidelity, Robot, RobotParams, WheelSpeeds};
//! let mut r = Robot::new(&RobotParams::default(), Fidelity::Creep).unwrap();
//! r.set_speeds(WheelSpeeds::spot(0.1)).unwrap(); // rim speeds -0.1, +0.1 m/s
//! let s = r.step().unwrap();                     // wheels' creepages, forces, moments, power
//! // or the whole run with its means over the second half:
//! let run = robot::run(&RobotParams::default(), WheelSpeeds::arc(0.1, 0.15), Fidelity::Creep).unwrap();
//! ```

use std::f64::consts::FRAC_PI_2;

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::{Material, Surface, Vec3};
/// The fidelity a robot's contacts run at (re-exported for the robot's users).
pub use creep_rapier::Fidelity;
use creep_rapier::diagnostics::{ContactKey, ContactRecord, solver_tangents};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld};
use rapier3d::prelude::*;

use crate::measure::{SceneError, positive};
use crate::wheels::{crown_for_ratio, wheel_rubber};

/// Parameters of the robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotParams {
    /// Wheel radius `R` \[m\].
    pub wheel_radius: f64,
    /// Wheel width (cylinder length) \[m\].
    pub wheel_width: f64,
    /// Axis ratio `a/b` of the crowned wheels' elliptic contact (`a` along the rolling
    /// direction), in (0.05, 1): sets the crown radius (`wheels::crown_for_ratio`).
    pub contact_ratio: f64,
    /// Track `b`: distance between the wheels' mid-planes \[m\].
    pub track: f64,
    /// Distance from the axle line back to the caster ball's centre \[m\].
    pub wheelbase: f64,
    /// Chassis mass \[kg\] (a box `1.4 wheelbase` long, `0.8 track` wide, `0.8 R` high,
    /// centred `0.4 wheelbase` behind the axle, so the caster carries part of its weight).
    pub chassis_mass: f64,
    /// Caster ball radius \[m\].
    pub caster_radius: f64,
    /// Material of the wheels, the caster ball and the floor.
    pub material: Material,
    /// Motor strength: the velocity motor's damping factor (Rapier's `motor_velocity`
    /// factor, acceleration-based) [1/s].
    pub motor_factor: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; summaries average over the second half.
    pub duration: f64,
}

impl Default for RobotParams {
    fn default() -> Self {
        Self {
            wheel_radius: 0.05,
            wheel_width: 0.02,
            contact_ratio: 0.5,
            track: 0.2,
            wheelbase: 0.15,
            chassis_mass: 1.0,
            caster_radius: 0.02,
            material: wheel_rubber(),
            motor_factor: 1.0e3,
            dt: 1.0 / 240.0,
            duration: 4.0,
        }
    }
}

impl RobotParams {
    /// Checks the parameters.
    pub fn validate(&self) -> Result<(), SceneError> {
        positive("wheel_radius", self.wheel_radius)?;
        positive("wheel_width", self.wheel_width)?;
        positive("track", self.track)?;
        positive("wheelbase", self.wheelbase)?;
        positive("chassis_mass", self.chassis_mass)?;
        positive("caster_radius", self.caster_radius)?;
        positive("motor_factor", self.motor_factor)?;
        positive("dt", self.dt)?;
        positive("duration", self.duration)?;
        if !(self.contact_ratio > 0.05 && self.contact_ratio < 1.0) {
            return Err(SceneError::Parameter(format!(
                "contact_ratio must be in (0.05, 1), got {}",
                self.contact_ratio
            )));
        }
        if !(self.caster_radius < self.wheel_radius) {
            return Err(SceneError::Parameter(format!(
                "caster_radius {} must be below wheel_radius {}",
                self.caster_radius, self.wheel_radius
            )));
        }
        if !(self.wheel_width < self.track) {
            return Err(SceneError::Parameter(format!(
                "wheel_width {} must be below the track {}",
                self.wheel_width, self.track
            )));
        }
        Ok(())
    }

    /// The crown radius of the wheels \[m\] (`wheels::crown_for_ratio`).
    pub fn crown(&self) -> Result<f64, SceneError> {
        crown_for_ratio(self.wheel_radius, self.contact_ratio)
    }
}

/// The two wheels' rim speeds \[m/s\] (positive forward).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelSpeeds {
    /// Left wheel.
    pub left: f64,
    /// Right wheel.
    pub right: f64,
}

impl WheelSpeeds {
    /// Turning on the spot to the left at rim speed `v` (`left = -v`, `right = v`).
    pub fn spot(v: f64) -> Self {
        Self { left: -v, right: v }
    }
    /// An arc: the two rim speeds.
    pub fn arc(left: f64, right: f64) -> Self {
        Self { left, right }
    }
    /// The closed forms of the module docs for a track `track`: `(V, Omega, R)`, the axle
    /// midpoint's speed \[m/s\], the yaw rate [rad/s] and the arc radius \[m\] (infinite for a
    /// straight run, 0 on the spot).
    pub fn kinematics(&self, track: f64) -> (f64, f64, f64) {
        let v = 0.5 * (self.right + self.left);
        let omega = (self.right - self.left) / track;
        let r = if omega != 0.0 {
            v / omega
        } else {
            f64::INFINITY
        };
        (v, omega, r)
    }
}

/// One contact of the robot with the floor in one step (module docs: frame and signs).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactSample {
    /// Normal force \[N\].
    pub p: f64,
    /// The floor's force on the body, world frame \[N\].
    pub force: Vec3,
    /// Force along the creep frame's `x` and `y` \[N\].
    pub fx: f64,
    /// See `fx`.
    pub fy: f64,
    /// Twisting moment of the creep law on the body about `n` [N m] (0 without creep).
    pub mz: f64,
    /// Rolling speed `V` [m/s].
    pub speed: f64,
    /// Longitudinal creepage `xi` [-].
    pub xi: f64,
    /// Lateral creepage `eta` [-].
    pub eta: f64,
    /// Spin creepage `phi` \[1/m\].
    pub phi: f64,
    /// Slip velocities along `x` and `y`, `v_disp . x`, `v_disp . y` [m/s].
    pub slip: [f64; 2],
    /// Relative spin `w_twist = (w_q - w_p) . n` [rad/s].
    pub twist: f64,
    /// The slip the creep law prescribed for the step (the hook's target, along `x` and `y`)
    /// [m/s]; 0 without creep. Over `speed` it is the law's creepage, free of the engine's own
    /// slip (contact bounces, joint compliance), which the measured creepages include.
    pub target: [f64; 2],
    /// Measured dissipation `Q . v_disp + M_z w_twist` \[W\].
    pub power: f64,
    /// The hook's booked creep power for this contact, `q_used . target + M_z w_twist` \[W\].
    pub hook_power: f64,
}

/// The robot in one step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RobotSample {
    /// Time \[s\].
    pub t: f64,
    /// The axle midpoint \[m\].
    pub position: Vec3,
    /// Heading angle about `y` \[rad\] (0: forward along world `x`).
    pub yaw: f64,
    /// Speed of the axle midpoint along the heading [m/s].
    pub speed: f64,
    /// Yaw rate `Omega` [rad/s].
    pub yaw_rate: f64,
    /// Rim speeds (left, right) [m/s].
    pub rim_speeds: [f64; 2],
    /// The wheels' contacts (left, right).
    pub wheels: [ContactSample; 2],
    /// The caster ball's contact.
    pub caster: ContactSample,
    /// The hook's creep power of the step, all contacts (`StepCounts::creep_power`) \[W\].
    pub hook_creep_power: f64,
    /// Kinetic energy of the chassis, wheels and caster \[J\].
    pub kinetic_energy: f64,
}

impl RobotSample {
    /// Measured dissipation of the three contacts \[W\].
    pub fn power(&self) -> f64 {
        self.wheels[0].power + self.wheels[1].power + self.caster.power
    }
}

/// A robot world: the Rapier world with the plugin and the handles of its parts.
pub struct Robot {
    /// The world.
    pub world: CreepWorld,
    /// The chassis.
    pub chassis: RigidBodyHandle,
    /// The wheels (left, right).
    pub wheels: [RigidBodyHandle; 2],
    /// The wheels' colliders (left, right).
    pub wheel_colliders: [ColliderHandle; 2],
    /// The wheels' revolute joints with their motors (left, right).
    pub motors: [ImpulseJointHandle; 2],
    /// The caster ball.
    pub caster: RigidBodyHandle,
    /// The caster ball's collider.
    pub caster_collider: ColliderHandle,
    /// The floor (fixed).
    pub floor: RigidBodyHandle,
    /// The floor's collider.
    pub floor_collider: ColliderHandle,
    params: RobotParams,
    speeds: WheelSpeeds,
    t: f64,
}

/// Gauss-Seidel iterations per substep (the joints and three contacts are coupled).
pub const PGS_ITERATIONS: usize = 16;

impl Robot {
    /// Builds the robot at rest on the floor, heading along world `x`, its motors at zero
    /// speed; `fidelity` for the wheels, the caster and the floor.
    pub fn new(params: &RobotParams, fidelity: Fidelity) -> Result<Self, SceneError> {
        params.validate()?;
        let crown = params.crown()?;
        let mut w = CreepWorld::new(
            params.dt as f32,
            CreepSettings::default().with_rapier_solver(),
        )?;
        // One substep (the rotation-gap correction is exact there), Gauss-Seidel iterations
        // for the coupled joints and contacts, the wheel's radius as the length unit (Rapier's
        // allowed overlap is 1e-3 units: a rolling-radius error below the creepages).
        let ip = &mut w.physics.integration_parameters;
        ip.num_solver_iterations = 1;
        ip.num_internal_pgs_iterations = PGS_ITERATIONS;
        ip.length_unit = params.wheel_radius as f32;
        let mu = params.material.friction() as f32;
        let mat = CreepMaterial::new(params.material).with_fidelity(fidelity);
        let (floor, floor_collider) = w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
            ColliderBuilder::cuboid(1.0e3, 0.5, 1.0e3).friction(mu),
            Some(mat),
        );
        let r = params.wheel_radius as f32;
        let half_track = 0.5 * params.track as f32;
        // The chassis body's origin is the axle midpoint (at the wheels' centre height); its
        // box is centred 0.4 wheelbase behind it.
        let lb = params.wheelbase as f32;
        let (hx, hy, hz) = (0.7 * lb, 0.4 * r, 0.4 * params.track as f32);
        let volume = 8.0 * f64::from(hx * hy * hz);
        let (chassis, _) = w.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, r, 0.0))
                .can_sleep(false),
            ColliderBuilder::cuboid(hx, hy, hz)
                .translation(Vector::new(-0.4 * lb, 0.0, 0.0))
                .density((params.chassis_mass / volume) as f32),
            None,
        );
        let mut wheels = [chassis; 2];
        let mut wheel_colliders = [floor_collider; 2];
        let mut motors = [ImpulseJointHandle::invalid(); 2];
        for (i, side) in [-1.0f32, 1.0].into_iter().enumerate() {
            let anchor = Vector::new(0.0, 0.0, side * half_track);
            let (wb, wc) = w.insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(0.0, r, side * half_track))
                    .can_sleep(false),
                // Rapier's cylinder has its axis along local y: turned onto the body's z.
                ColliderBuilder::cylinder(0.5 * params.wheel_width as f32, r)
                    .rotation(Vector::new(FRAC_PI_2 as f32, 0.0, 0.0))
                    .friction(mu),
                Some(mat),
            );
            w.hooks_mut().set_wheel_crown(wc, Some(crown))?;
            let joint = RevoluteJointBuilder::new(Vector::Z)
                .local_anchor1(anchor)
                .local_anchor2(Vector::ZERO)
                .contacts_enabled(false)
                .motor_velocity(0.0, params.motor_factor as f32);
            motors[i] = w.physics.impulse_joints.insert(chassis, wb, joint, true);
            wheels[i] = wb;
            wheel_colliders[i] = wc;
        }
        let rc = params.caster_radius as f32;
        let (caster, caster_collider) = w.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(-lb, rc, 0.0))
                .can_sleep(false),
            ColliderBuilder::ball(rc).friction(mu),
            Some(mat),
        );
        let joint = SphericalJointBuilder::new()
            .local_anchor1(Vector::new(-lb, rc - r, 0.0))
            .local_anchor2(Vector::ZERO)
            .contacts_enabled(false);
        w.physics
            .impulse_joints
            .insert(chassis, caster, joint, true);
        Ok(Self {
            world: w,
            chassis,
            wheels,
            wheel_colliders,
            motors,
            caster,
            caster_collider,
            floor,
            floor_collider,
            params: *params,
            speeds: WheelSpeeds::arc(0.0, 0.0),
            t: 0.0,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &RobotParams {
        &self.params
    }

    /// The motors' current target rim speeds.
    pub fn speeds(&self) -> WheelSpeeds {
        self.speeds
    }

    /// Sets the motors' target rim speeds \[m/s\] (finite).
    pub fn set_speeds(&mut self, speeds: WheelSpeeds) -> Result<(), SceneError> {
        if !(speeds.left.is_finite() && speeds.right.is_finite()) {
            return Err(SceneError::Parameter(format!(
                "wheel speeds must be finite, got {speeds:?}"
            )));
        }
        let r = self.params.wheel_radius;
        let factor = self.params.motor_factor as f32;
        for (handle, v) in self.motors.iter().zip([speeds.left, speeds.right]) {
            if let Some(j) = self.world.physics.impulse_joints.get_mut(*handle, true) {
                // Forward rolling turns the wheel about -z relative to the chassis.
                j.data
                    .set_motor_velocity(JointAxis::AngX, (-v / r) as f32, factor);
            }
        }
        self.speeds = speeds;
        Ok(())
    }

    /// One step; returns the robot's state and contacts after it.
    pub fn step(&mut self) -> Result<RobotSample, SceneError> {
        let counts = self.world.step()?;
        self.t += self.params.dt;
        let mut s = self.sample();
        s.hook_creep_power = counts.creep_power;
        Ok(s)
    }

    /// The robot's state and contacts now (the contacts of the last step; `hook_creep_power`
    /// is left at 0: [`Robot::step`] fills it), measured by [`RobotProbe::sample`].
    pub fn sample(&self) -> RobotSample {
        let records = self.world.hooks().records();
        RobotProbe {
            bodies: &self.world.physics.bodies,
            narrow_phase: &self.world.physics.narrow_phase,
            records: &records,
            handles: self.handles(),
            params: &self.params,
        }
        .sample(self.t, self.params.dt, 0.0)
        .expect("a robot's handles name bodies of its own world")
    }

    /// The Rapier handles of the robot's parts.
    pub fn handles(&self) -> RobotHandles {
        RobotHandles {
            chassis: self.chassis,
            wheels: self.wheels,
            wheel_colliders: self.wheel_colliders,
            caster: self.caster,
            caster_collider: self.caster_collider,
            floor: self.floor,
            floor_collider: self.floor_collider,
        }
    }
}

/// The Rapier handles of a robot's parts, in whichever Rapier world holds them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotHandles {
    /// The chassis (its origin: the axle midpoint).
    pub chassis: RigidBodyHandle,
    /// The wheels (left, right).
    pub wheels: [RigidBodyHandle; 2],
    /// The wheels' colliders (left, right).
    pub wheel_colliders: [ColliderHandle; 2],
    /// The caster ball.
    pub caster: RigidBodyHandle,
    /// The caster ball's collider.
    pub caster_collider: ColliderHandle,
    /// The floor.
    pub floor: RigidBodyHandle,
    /// The floor's collider.
    pub floor_collider: ColliderHandle,
}

/// The robot's measurement over what any host of its Rapier world has: the bodies, the narrow
/// phase, the creep hooks' contact records, the parameters and the parts' handles. [`Robot`]
/// and an ECS host (creep-bevy's robot) both measure through it (frames, signs and formulas
/// in the module docs).
#[derive(Clone, Copy)]
pub struct RobotProbe<'a> {
    /// The rigid bodies.
    pub bodies: &'a RigidBodySet,
    /// The narrow phase of the last step (its contact impulses and overlaps).
    pub narrow_phase: &'a NarrowPhase,
    /// The creep hooks' records of the last step (`CreepHooks::records`).
    pub records: &'a [(ContactKey, ContactRecord)],
    /// The robot's parts.
    pub handles: RobotHandles,
    /// The robot's parameters (its wheel and caster radii).
    pub params: &'a RobotParams,
}

impl RobotProbe<'_> {
    /// The robot's state and contacts after the last step at time `t` \[s\], its time step `dt`
    /// \[s\] (impulses over `dt` are forces), with `hook_creep_power` \[W\] the hook's creep power
    /// of the step (`StepCounts::creep_power`); `None` if a handle names no body.
    pub fn sample(&self, t: f64, dt: f64, hook_creep_power: f64) -> Option<RobotSample> {
        let h = &self.handles;
        let bodies = self.bodies;
        let ch = bodies.get(h.chassis)?;
        let rot = *ch.rotation();
        let heading = v3(rot * Vector::X);
        let axle = v3(rot * Vector::Z);
        let w_ch = v3(ch.angvel());
        let r = self.params.wheel_radius;
        let mut rim = [0.0; 2];
        let mut wheels = [ContactSample::default(); 2];
        for i in 0..2 {
            let wb = bodies.get(h.wheels[i])?;
            rim[i] = -r * (v3(wb.angvel()) - w_ch).dot(axle);
            // The wheel's angular velocity as its joint holds it: the chassis' plus the
            // wheel's own turn about the axle. The plugin applies the wheel's spin-creep moment
            // after the step to the wheel alone (creep-rapier's rolling module), which the
            // joint shares out with the chassis only in the next solve; the wheel's own
            // angular velocity in between is not the motion the step made.
            let w_joint = w_ch + axle * (v3(wb.angvel()) - w_ch).dot(axle);
            wheels[i] = self.contact(
                h.wheels[i],
                h.wheel_colliders[i],
                r,
                Some((heading, w_joint)),
                dt,
            )?;
        }
        let caster = self.contact(
            h.caster,
            h.caster_collider,
            self.params.caster_radius,
            None,
            dt,
        )?;
        let mut kinetic_energy = 0.0;
        for b in [h.chassis, h.wheels[0], h.wheels[1], h.caster] {
            kinetic_energy += f64::from(bodies.get(b)?.kinetic_energy());
        }
        let hx = rot * Vector::X;
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
            hook_creep_power,
            kinetic_energy,
        })
    }

    /// One body's contact with the floor (module docs): for a wheel, its heading (its `x` is
    /// along it) and its angular velocity as its joint holds it; `None` for the ball
    /// (`x = -v_roll/|v_roll|`, its own angular velocity).
    fn contact(
        &self,
        body: RigidBodyHandle,
        collider: ColliderHandle,
        radius: f64,
        wheel: Option<(Vec3, Vec3)>,
        dt: f64,
    ) -> Option<ContactSample> {
        let heading = wheel.map(|(h, _)| h);
        let rb = self.bodies.get(body)?;
        let fl = self.bodies.get(self.handles.floor)?;
        let centre = v3(rb.translation());
        let n = Vec3::new(0.0, -1.0, 0.0);
        // Rapier rolls a body about the point midway between the surfaces (docs/ARCHITECTURE.md
        // §6): `R - delta/2` below the centre, `delta` the overlap of the last step.
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
                .map_or(Vec3::new(-1.0, 0.0, 0.0), |v| -v),
        };
        let y = n.cross(x);
        let speed = rates.v_roll.dot(x).abs();
        let (p, force) = self.impulses(collider, dt);
        // The contact's power at the point Rapier applied its impulses: a wheel's one patch
        // contact (creep-rapier's wheel module) and a ball's contact both act at `point`. The
        // manifold point a wheel's patch contact names (for its impulses) lies elsewhere on the
        // cylinder; evaluated there, the slip turning on the spot read -2.6e-3 W against
        // -4.7e-4 W at the patch.
        let v_disp = (q_motion.velocity_at(point) - p_motion.velocity_at(point)).reject(n);
        let power = force.dot(v_disp);
        // The creep law's twisting moment on the body (the plugin applies it after the step)
        // and the hook's booked power, from the pair's records.
        let (mut mz, mut hook_power, mut target) = (0.0, 0.0, Vec3::ZERO);
        for rec in self.pair_records(collider) {
            let (on_body, sign) = if rec.bodies.0 == Some(body) {
                (-rec.spin_torque, 1.0)
            } else {
                (rec.spin_torque, -1.0)
            };
            mz += on_body.dot(n);
            hook_power += rec.q_used.dot(rec.target).max(0.0);
            // The target is the slip of body 2 relative to body 1: as `v_disp` when the body
            // is body 1.
            target += rec.target * sign;
        }
        // The moment on the body dissipates `mz (w_q - w_p) . n` (it opposes the relative spin).
        let spin_power = mz * (q_motion.angular_velocity - p_motion.angular_velocity).dot(n);
        hook_power += spin_power.max(0.0);
        let inv_v = if speed > 0.0 { 1.0 / speed } else { 0.0 };
        Some(ContactSample {
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
        })
    }

    /// The mean overlap \[m\] (>= 0) of a collider's solver contacts with the floor, read from
    /// the solver contacts' own distances: a wheel's patch contact (creep-rapier's wheel
    /// module) carries the patch's, while the manifold point it names lies elsewhere on the
    /// cylinder, whose distance the narrow phase may leave stale (turning on the spot it once
    /// read 0.46 m).
    fn overlap(&self, collider: ColliderHandle) -> f64 {
        let Some(pair) = self
            .narrow_phase
            .contact_pair(collider, self.handles.floor_collider)
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

    /// Normal force and the floor's tangential force on the body \[N\] over the solver
    /// contacts of the last step (Rapier's impulses over `dt`).
    fn impulses(&self, collider: ColliderHandle, dt: f64) -> (f64, Vec3) {
        let Some(pair) = self
            .narrow_phase
            .contact_pair(collider, self.handles.floor_collider)
        else {
            return (0.0, Vec3::ZERO);
        };
        let sign = if pair.collider1 == collider {
            1.0
        } else {
            -1.0
        };
        let (mut p, mut q) = (0.0, Vec3::ZERO);
        for m in pair.manifolds() {
            let (t1, t2) = solver_tangents(v3(m.data.normal));
            for sc in &m.data.solver_contacts {
                let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
                let Some(pt) = m.points.get(cid) else {
                    continue;
                };
                p += f64::from(pt.data.impulse) / dt;
                let ti = pt.data.tangent_impulse;
                q += (t1 * f64::from(ti.x) + t2 * f64::from(ti.y)) * (sign / dt);
            }
        }
        (p, q)
    }

    /// The contact records of a collider's pair with the floor (either order).
    fn pair_records(&self, a: ColliderHandle) -> impl Iterator<Item = &ContactRecord> {
        let b = self.handles.floor_collider;
        self.records
            .iter()
            .filter(move |(k, _)| {
                (k.collider1 == a && k.collider2 == b) || (k.collider1 == b && k.collider2 == a)
            })
            .map(|(_, r)| r)
    }
}

fn v3(v: Vector) -> Vec3 {
    Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// Means of one contact over the measured half of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactMean {
    /// Normal force \[N\].
    pub p: f64,
    /// Force along the creep frame's `x` \[N\].
    pub fx: f64,
    /// Force along `y` \[N\].
    pub fy: f64,
    /// Twisting moment on the body [N m].
    pub mz: f64,
    /// Rolling speed [m/s].
    pub speed: f64,
    /// Longitudinal creepage, the mean slip over the mean speed (robust to a step in which
    /// a bouncing wheel hardly rolls) [-].
    pub xi: f64,
    /// Lateral creepage, likewise [-].
    pub eta: f64,
    /// Spin creepage, the mean relative spin over the mean speed \[1/m\].
    pub phi: f64,
    /// Mean slip velocities along `x`, `y` [m/s].
    pub slip: [f64; 2],
    /// Mean relative spin [rad/s].
    pub twist: f64,
    /// The creep law's creepages (`ContactSample::target` over the mean speed) along `x`
    /// and `y` [-].
    pub law_creepage: [f64; 2],
    /// Measured dissipation \[W\].
    pub power: f64,
    /// The hook's booked creep power \[W\].
    pub hook_power: f64,
}

impl ContactMean {
    fn add(&mut self, s: &ContactSample, k: f64) {
        self.p += k * s.p;
        self.fx += k * s.fx;
        self.fy += k * s.fy;
        self.mz += k * s.mz;
        self.speed += k * s.speed;
        self.slip[0] += k * s.slip[0];
        self.slip[1] += k * s.slip[1];
        self.twist += k * s.twist;
        self.law_creepage[0] += k * s.target[0];
        self.law_creepage[1] += k * s.target[1];
        self.power += k * s.power;
        self.hook_power += k * s.hook_power;
    }

    fn finish(&mut self) {
        let inv_v = if self.speed > 0.0 {
            1.0 / self.speed
        } else {
            0.0
        };
        self.xi = self.slip[0] * inv_v;
        self.eta = self.slip[1] * inv_v;
        self.phi = self.twist * inv_v;
        self.law_creepage = [self.law_creepage[0] * inv_v, self.law_creepage[1] * inv_v];
    }
}

/// A run's means over its second half, next to the closed forms of the module docs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RobotSummary {
    /// Mean rim speeds (left, right) [m/s].
    pub rim_speeds: [f64; 2],
    /// Mean speed of the axle midpoint along the heading [m/s].
    pub speed: f64,
    /// Mean yaw rate [rad/s].
    pub yaw_rate: f64,
    /// Closed-form yaw rate from the mean rim speeds, `(v_r - v_l)/b` [rad/s].
    pub yaw_rate_closed_form: f64,
    /// Measured arc radius `speed / yaw_rate` \[m\].
    pub radius: f64,
    /// Closed-form radius from the mean rim speeds, `(b/2)(v_r + v_l)/(v_r - v_l)` \[m\].
    pub radius_closed_form: f64,
    /// The wheels' contacts (left, right).
    pub wheels: [ContactMean; 2],
    /// The caster's contact.
    pub caster: ContactMean,
    /// Energy the contacts dissipated over the measured half (measured) \[J\].
    pub dissipated: f64,
    /// The hook's creep power integrated over the measured half \[J\].
    pub hook_energy: f64,
    /// Length of the measured half \[s\].
    pub window: f64,
}

/// A run of the robot: every step's sample and the summary.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotRun {
    /// The fidelity of the wheels', caster's and floor's materials.
    pub fidelity: Fidelity,
    /// The motors' targets.
    pub speeds: WheelSpeeds,
    /// One sample per step.
    pub samples: Vec<RobotSample>,
    /// Means over the second half.
    pub summary: RobotSummary,
}

/// Drives the robot from rest at the motor targets `speeds` for `params.duration` and averages
/// the second half.
pub fn run(
    params: &RobotParams,
    speeds: WheelSpeeds,
    fidelity: Fidelity,
) -> Result<RobotRun, SceneError> {
    let mut robot = Robot::new(params, fidelity)?;
    robot.set_speeds(speeds)?;
    let steps = (params.duration / params.dt).round() as usize;
    let mut samples = Vec::with_capacity(steps);
    for _ in 0..steps {
        samples.push(robot.step()?);
    }
    Ok(RobotRun {
        fidelity,
        speeds,
        summary: summarize(&samples, params),
        samples,
    })
}

/// A run's means over the second half of `samples` (one per step of `params.dt`), next to the
/// closed forms of the module docs: what [`run`] reports.
pub fn summarize(samples: &[RobotSample], params: &RobotParams) -> RobotSummary {
    let half = &samples[samples.len() / 2..];
    let k = 1.0 / half.len().max(1) as f64;
    let mut s = RobotSummary::default();
    for x in half {
        s.rim_speeds[0] += k * x.rim_speeds[0];
        s.rim_speeds[1] += k * x.rim_speeds[1];
        s.speed += k * x.speed;
        s.yaw_rate += k * x.yaw_rate;
        s.wheels[0].add(&x.wheels[0], k);
        s.wheels[1].add(&x.wheels[1], k);
        s.caster.add(&x.caster, k);
        s.dissipated += x.power() * params.dt;
        s.hook_energy += x.hook_creep_power * params.dt;
    }
    s.window = half.len() as f64 * params.dt;
    s.wheels[0].finish();
    s.wheels[1].finish();
    s.caster.finish();
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
