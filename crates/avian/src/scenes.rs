//! Headless scenes in Avian, each run with the plugin and as its Coulomb twin (or plain Avian),
//! measured against a closed form: the incline, the friction drive, free rolling, the
//! fast-rolling matrix and the poured pile. The tests, examples and benches use them; they need
//! no renderer.
//!
//! Every scene is a Bevy `App` with `MinimalPlugins`, `TransformPlugin` and Avian's
//! `PhysicsPlugins` in `PostUpdate`, stepped one physics step per `App::update` at a fixed
//! `dt` (`TimeUpdateStrategy::ManualDuration`).

use core::time::Duration;

use avian3d::prelude::*;
use bevy::math::{DQuat, DVec3};
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use creep_law::{CreepModel, Material, PairMaterial, SteadyLaw, Surface};

use crate::{CreepAvianPlugin, CreepHooks, CreepMaterial, CreepState, Fidelity, StepCounts};

/// Standard gravity \[m/s^2\].
pub const G: f64 = 9.81;

/// Avian's default solver substeps.
pub const DEFAULT_SUBSTEPS: u32 = 6;

/// How a scene's contacts are solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Run {
    /// Plain Avian: no hooks, no plugin.
    Plain,
    /// The plugin installed, every collider at this fidelity.
    Plugin(Fidelity),
    /// The plugin with its per-substep rotation-gap removal on
    /// ([`crate::CreepSettings::rotation_gap_removal`]), every collider at this fidelity.
    GapRemoved(Fidelity),
}

/// A headless app stepping physics once per update at `dt` with `substeps` substeps.
pub fn headless_app(dt: f64, substeps: u32, gravity: Vec3, run: Run) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin));
    match run {
        Run::Plain => {
            app.add_plugins(PhysicsPlugins::new(PostUpdate));
        }
        Run::Plugin(_) | Run::GapRemoved(_) => {
            app.add_plugins((
                PhysicsPlugins::new(PostUpdate).with_collision_hooks::<CreepHooks>(),
                CreepAvianPlugin::default()
                    .with_rotation_gap_removal(matches!(run, Run::GapRemoved(_))),
            ));
        }
    }
    app.insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f64(
        dt,
    )))
    .insert_resource(SubstepCount(substeps))
    .insert_resource(Gravity(gravity));
    app.finish();
    app.cleanup();
    // The first update has no elapsed time (no physics step): take it now.
    app.update();
    app
}

/// Runs one physics step (one update; a second one if the first advanced no physics time).
pub fn step(app: &mut App) {
    let before = app.world().resource::<Time<Physics>>().elapsed();
    for _ in 0..3 {
        app.update();
        if app.world().resource::<Time<Physics>>().elapsed() != before {
            return;
        }
    }
}

/// The creep material of a run (`None` for plain Avian).
fn creep_material(material: Material, run: Run) -> Option<CreepMaterial> {
    match run {
        Run::Plain => None,
        Run::Plugin(f) | Run::GapRemoved(f) => Some(CreepMaterial::new(material).with_fidelity(f)),
    }
}

/// Spawns `bundle` with the run's creep material.
/// (In one spawn: Avian reads a collider's `ActiveCollisionHooks` when the collider is added.)
fn spawn_with(app: &mut App, bundle: impl Bundle, material: Option<CreepMaterial>) -> Entity {
    match material {
        Some(m) => app.world_mut().spawn((bundle, m)).id(),
        None => app.world_mut().spawn(bundle).id(),
    }
}

/// The rotation of a body about an axis, accumulated step by step in f64 from its
/// quaternions \[rad\].
#[derive(Debug, Clone, Copy, Default)]
pub struct RollingMeter {
    last: Option<DQuat>,
    /// Accumulated angle about the axis \[rad\].
    pub angle: f64,
}

impl RollingMeter {
    /// Adds the rotation from the last quaternion to `q` about unit `axis`.
    pub fn update(&mut self, q: Quat, axis: DVec3) {
        let q = q.as_dquat();
        if let Some(last) = self.last {
            let mut d = q * last.inverse();
            if d.w < 0.0 {
                d = -d;
            }
            let v = DVec3::new(d.x, d.y, d.z);
            let s = v.length();
            if s > 0.0 {
                let angle = 2.0 * s.atan2(d.w);
                self.angle += angle * v.dot(axis) / s;
            }
        }
        self.last = Some(q);
    }
}

/// The first creep contact's normal force \[N\] and measured tangential force \[N\] after a
/// step (`None` without a record).
fn contact_loads(app: &App) -> Option<(f64, creep_law::Vec3)> {
    let state = app.world().get_resource::<CreepState>()?;
    let c = state.contacts();
    c.first().map(|c| (c.p, c.q_meas))
}

/// Kalker's steady creepage `F_ss(Q/(mu P))` \[-\] (Kalker 2000; Kuhn 2011, eq. 1) of a
/// contact of `material` on itself between surfaces `s1`, `s2` at normal force `pn` and
/// tangential force `q` \[N\], with Hertz's contact radius at `pn` (Johnson 1985, §4.2).
pub fn kalker_creepage(
    material: &Material,
    s1: Surface,
    s2: Surface,
    pn: f64,
    q: f64,
) -> Result<f64, creep_law::LawError> {
    let pair = PairMaterial::new(material, material, s1, s2)?;
    Ok(
        SteadyLaw::with_c11(CreepModel::Kuhn, pair.nu, pair.c11).contact_creepage(
            &pair,
            material.friction(),
            pn,
            q,
        ),
    )
}

/// Mass of a uniform solid sphere \[kg\].
pub fn sphere_mass(density: f64, radius: f64) -> f64 {
    density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3)
}

// ----------------------------------------------------------------------------------------
// The incline.

/// A ball rolling down an incline (gravity tilted by `theta`, a flat static cuboid).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineParams {
    /// Incline angle \[rad\], in `(0, atan(7 mu / 2))` for rolling.
    pub theta: f64,
    /// Ball radius \[m\].
    pub radius: f64,
    /// Material of ball and incline (friction: its `mu`).
    pub material: Material,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; the slip is measured over the second half.
    pub duration: f64,
    /// Solver substeps.
    pub substeps: u32,
}

impl Default for InclineParams {
    fn default() -> Self {
        Self {
            theta: 20f64.to_radians(),
            radius: 0.1,
            material: Material::steel()
                .with_friction(0.5)
                .unwrap_or_else(|_| Material::steel()),
            dt: 1.0 / 240.0,
            duration: 1.0,
            substeps: DEFAULT_SUBSTEPS,
        }
    }
}

impl InclineParams {
    /// Rolling without slip: `(P, Q) = (m g cos(theta), (2/7) m g sin(theta))` \[N\] (uniform
    /// solid sphere, `I = (2/5) m R^2`).
    pub fn rolling_loads(&self) -> (f64, f64) {
        let m = sphere_mass(self.material.density(), self.radius);
        (
            m * G * self.theta.cos(),
            2.0 / 7.0 * m * G * self.theta.sin(),
        )
    }
}

/// What one incline run measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineRun {
    /// Mean acceleration along the incline \[m/s^2\].
    pub acceleration: f64,
    /// Slip over the second half, `(dx - R dtheta) / dx` from positions and rotations \[-\].
    pub slip: f64,
    /// Mean normal force of the creep contact over the second half (0 without records) \[N\].
    pub p: f64,
    /// Magnitude of the mean tangential force it transmitted (idem) \[N\].
    pub q: f64,
    /// The plugin's counts of the last step.
    pub counts: StepCounts,
}

/// The incline with the plugin and its Coulomb twin, and Kalker's figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineResult {
    /// Coulomb twin (Avian's own rolling, with its own slip).
    pub coulomb: InclineRun,
    /// Creep run.
    pub creep: InclineRun,
    /// Creep slip measured: creep run's slip less the twin's \[-\].
    pub creepage_measured: f64,
    /// Kalker's `F_ss` at the transmitted `Q`, `P` \[-\].
    pub creepage_expected: f64,
    /// `Q / (mu P)` transmitted \[-\].
    pub q_over_mu_p: f64,
}

/// One incline run.
pub fn incline_run(p: &InclineParams, run: Run) -> InclineRun {
    let gravity = Vec3::new((G * p.theta.sin()) as f32, (-G * p.theta.cos()) as f32, 0.0);
    let mut app = headless_app(p.dt, p.substeps, gravity, run);
    let mat = creep_material(p.material, run);
    let mu = p.material.friction() as f32;
    spawn_with(
        &mut app,
        (
            RigidBody::Static,
            Collider::cuboid(2.0e3, 1.0, 20.0),
            Position(Vec3::new(0.0, -0.5, 0.0)),
            Friction::new(mu),
        ),
        mat,
    );
    let r = p.radius as f32;
    let ball = spawn_with(
        &mut app,
        (
            RigidBody::Dynamic,
            Collider::sphere(r),
            ColliderDensity(p.material.density() as f32),
            Friction::new(mu),
            Position(Vec3::new(0.0, r, 0.0)),
            SleepingDisabled,
        ),
        mat,
    );
    let steps = (p.duration / p.dt).round() as usize;
    let mut meter = RollingMeter::default();
    let mut x0 = 0.0;
    let (mut q_sum, mut p_sum, mut n) = (creep_law::Vec3::ZERO, 0.0, 0usize);
    for i in 0..steps {
        step(&mut app);
        let rot = app
            .world()
            .get::<Rotation>(ball)
            .map_or(Quat::IDENTITY, |r| r.0);
        let x = app.world().get::<Position>(ball).map_or(0.0, |p| p.0.x);
        if i == steps / 2 {
            x0 = f64::from(x);
            meter = RollingMeter::default();
        }
        meter.update(rot, DVec3::Z);
        if i > steps / 2
            && let Some((pn, q)) = contact_loads(&app)
        {
            p_sum += pn;
            q_sum += q;
            n += 1;
        }
    }
    let x = f64::from(app.world().get::<Position>(ball).map_or(0.0, |p| p.0.x));
    let v = f64::from(
        app.world()
            .get::<LinearVelocity>(ball)
            .map_or(0.0, |v| v.0.x),
    );
    let dx = x - x0;
    let counts = app
        .world()
        .get_resource::<CreepState>()
        .map(|s| s.counts())
        .unwrap_or_default();
    let n = n.max(1) as f64;
    InclineRun {
        acceleration: v / (steps as f64 * p.dt),
        slip: (dx + meter.angle * p.radius) / dx,
        p: p_sum / n,
        q: q_sum.length() / n,
        counts,
    }
}

/// The incline with creep and with Coulomb (same scene, the plugin installed in both, with its
/// rotation-gap removal: without it the contact goes slack in the last substeps of each step,
/// and Avian's own slip, about twice Kalker's creepage, varies from run to run with the
/// substeps it hits).
pub fn incline(p: &InclineParams) -> Result<InclineResult, creep_law::LawError> {
    let coulomb = incline_run(p, Run::GapRemoved(Fidelity::Coulomb));
    let creep = incline_run(p, Run::GapRemoved(Fidelity::Creep));
    let (pn, q) = if creep.p > 0.0 {
        (creep.p, creep.q)
    } else {
        p.rolling_loads()
    };
    Ok(InclineResult {
        coulomb,
        creep,
        creepage_measured: creep.slip - coulomb.slip,
        creepage_expected: kalker_creepage(
            &p.material,
            Surface::Plane,
            Surface::Sphere(p.radius),
            pn,
            q,
        )?,
        q_over_mu_p: q / (p.material.friction() * pn),
    })
}

// ----------------------------------------------------------------------------------------
// The friction drive.

/// A ball driven at a fixed angular speed turns a second ball resting on it against a brake
/// torque; the output's centre may only move vertically and it turns about the drive axis
/// only. In steady state `Q = T / R` at `P = m g`, and the output turns slower than the input
/// by Kalker's creepage `F_ss(Q/(mu P))` (Kalker 2000; Kuhn 2011).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveParams {
    /// Radius of both balls \[m\].
    pub radius: f64,
    /// Material of both (friction: its `mu`).
    pub material: Material,
    /// Angular speed of the driver \[rad/s\].
    pub omega: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; the creepage is measured over the second half.
    pub duration: f64,
    /// Solver substeps.
    pub substeps: u32,
}

impl Default for DriveParams {
    fn default() -> Self {
        Self {
            radius: 0.05,
            material: Material::steel(),
            omega: 10.0,
            dt: 1.0 / 240.0,
            duration: 2.0,
            substeps: DEFAULT_SUBSTEPS,
        }
    }
}

impl DriveParams {
    /// The output ball's weight, the contact's normal force \[N\].
    pub fn normal_force(&self) -> f64 {
        sphere_mass(self.material.density(), self.radius) * G
    }
}

/// One drive run's figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveRun {
    /// Speed loss `(w_in - w_out) / mean` over the second half \[-\].
    pub creepage: f64,
    /// Mean normal force of the creep contact (0 without records) \[N\].
    pub p: f64,
    /// Magnitude of the mean tangential force transmitted (idem) \[N\].
    pub q: f64,
}

/// One drive run at brake torque `torque` \[N m\].
pub fn drive_run(p: &DriveParams, torque: f64, run: Run) -> DriveRun {
    let mut app = headless_app(p.dt, p.substeps, Vec3::new(0.0, -G as f32, 0.0), run);
    let mat = creep_material(p.material, run);
    let mu = p.material.friction() as f32;
    let r = p.radius as f32;
    let driver = spawn_with(
        &mut app,
        (
            RigidBody::Kinematic,
            Collider::sphere(r),
            Friction::new(mu),
            AngularVelocity(Vec3::new(0.0, 0.0, p.omega as f32)),
        ),
        mat,
    );
    let out = spawn_with(
        &mut app,
        (
            RigidBody::Dynamic,
            Collider::sphere(r),
            ColliderDensity(p.material.density() as f32),
            Friction::new(mu),
            Position(Vec3::new(0.0, 2.0 * r, 0.0)),
            LockedAxes::new().lock_translation_x().lock_translation_z(),
            // The output counter-rotates; the brake opposes it.
            AngularVelocity(Vec3::new(0.0, 0.0, -p.omega as f32)),
            ConstantTorque(Vec3::new(0.0, 0.0, torque as f32)),
            SleepingDisabled,
        ),
        mat,
    );
    let steps = (p.duration / p.dt).round() as usize;
    let (mut m_in, mut m_out) = (RollingMeter::default(), RollingMeter::default());
    let (mut q_sum, mut p_sum, mut n) = (creep_law::Vec3::ZERO, 0.0, 0usize);
    for i in 0..steps {
        step(&mut app);
        if i == steps / 2 {
            m_in = RollingMeter::default();
            m_out = RollingMeter::default();
        }
        let rot = |e: Entity| {
            app.world()
                .get::<Rotation>(e)
                .map_or(Quat::IDENTITY, |r| r.0)
        };
        m_in.update(rot(driver), DVec3::Z);
        m_out.update(rot(out), DVec3::Z);
        if i > steps / 2
            && let Some((pn, q)) = contact_loads(&app)
        {
            p_sum += pn;
            q_sum += q;
            n += 1;
        }
    }
    let (a_in, a_out) = (m_in.angle, -m_out.angle);
    let n = n.max(1) as f64;
    DriveRun {
        creepage: (a_in - a_out) / (0.5 * (a_in + a_out)),
        p: p_sum / n,
        q: q_sum.length() / n,
    }
}

/// One row of the drive: creep and Coulomb at one brake torque, Kalker's figure.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveRow {
    /// Brake torque \[N m\].
    pub torque: f64,
    /// Creep run.
    pub creep: DriveRun,
    /// Coulomb twin.
    pub coulomb: DriveRun,
    /// Creepage measured: creep less the twin \[-\].
    pub creepage_measured: f64,
    /// Kalker's `F_ss` at the creep run's `Q`, `P` \[-\].
    pub creepage_expected: f64,
    /// `Q / (mu P)` \[-\].
    pub q_over_mu_p: f64,
}

/// The drive at brake torque `s mu P R` for each `s`, creep run and Coulomb twin both with the
/// plugin's rotation-gap removal ([`Run::GapRemoved`]): two balls spinning in place open
/// Avian's rotation gap on both sides, and without its removal the contact goes slack in the
/// last substeps of each step while the brake keeps acting.
pub fn drive(p: &DriveParams, ratios: &[f64]) -> Result<Vec<DriveRow>, creep_law::LawError> {
    let pn = p.normal_force();
    let mu = p.material.friction();
    ratios
        .iter()
        .map(|&s| {
            let torque = s * mu * pn * p.radius;
            let creep = drive_run(p, torque, Run::GapRemoved(Fidelity::Creep));
            let coulomb = drive_run(p, torque, Run::GapRemoved(Fidelity::Coulomb));
            let (pm, q) = if creep.p > 0.0 {
                (creep.p, creep.q)
            } else {
                (pn, s * mu * pn)
            };
            Ok(DriveRow {
                torque,
                creep,
                coulomb,
                creepage_measured: creep.creepage - coulomb.creepage,
                creepage_expected: kalker_creepage(
                    &p.material,
                    Surface::Sphere(p.radius),
                    Surface::Sphere(p.radius),
                    pm,
                    q,
                )?,
                q_over_mu_p: q / (mu * pm),
            })
        })
        .collect()
}

// ----------------------------------------------------------------------------------------
// Free rolling and the fast-rolling matrix.

/// Radius of the fast-rolling ball \[m\].
pub const ROLL_RADIUS: f64 = 0.1;
/// Largest energy gain over a fast-rolling run, relative to the start.
pub const MAX_GAIN: f64 = 1e-6;
/// Largest energy loss over a fast-rolling run, relative to the start.
pub const MAX_LOSS: f64 = 1e-3;
/// Largest rise or sinking of the centre from its resting height \[m\].
pub const MAX_HEIGHT_ERROR: f64 = 1e-4;

/// The ground a ball rolls on; its top face is the plane `y = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ground {
    /// A half-space.
    Plane,
    /// A flat triangle mesh of 1 m x 1 m cells (two triangles each).
    Trimesh,
}

impl Ground {
    /// Both grounds.
    pub const ALL: [Ground; 2] = [Ground::Plane, Ground::Trimesh];
    /// Name.
    pub fn label(self) -> &'static str {
        match self {
            Ground::Plane => "plane",
            Ground::Trimesh => "mesh",
        }
    }
    /// The ground's collider (static, top at `y = 0`), long enough for `length` \[m\] along +x.
    fn collider(self, length: f64) -> Collider {
        match self {
            Ground::Plane => Collider::half_space(Vec3::Y),
            Ground::Trimesh => {
                let cells = length.ceil().max(1.0) as u32 + 4;
                let mut vertices = Vec::new();
                let mut indices = Vec::new();
                for i in 0..=cells {
                    let x = i as f32 - 2.0;
                    vertices.push(Vec3::new(x, 0.0, -1.0));
                    vertices.push(Vec3::new(x, 0.0, 1.0));
                }
                for i in 0..cells {
                    let (a, b, c, d) = (2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3);
                    indices.push([a, b, c]);
                    indices.push([c, b, d]);
                }
                Collider::trimesh(vertices, indices)
            }
        }
    }
}

/// A ball rolling freely on a ground.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingBall {
    /// Material (friction: its `mu`).
    pub material: Material,
    /// Launch speed \[m/s\].
    pub speed: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\].
    pub duration: f64,
    /// Ground.
    pub ground: Ground,
    /// Solver substeps.
    pub substeps: u32,
}

/// A free-rolling run's figures.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Summary {
    /// Initial mechanical energy \[J\].
    pub e0: f64,
    /// Largest `(E - E0) / E0` over the run \[-\].
    pub max_gain: f64,
    /// `(E0 - E_end) / E0` \[-\].
    pub loss: f64,
    /// Largest rise of the centre above its resting height \[m\].
    pub max_rise: f64,
    /// Largest sinking of the centre below its resting height \[m\].
    pub max_sink: f64,
    /// Resting height of the centre \[m\] (from a run of the ball at rest).
    pub rest_height: f64,
    /// Mechanical energy at the end \[J\].
    pub e_end: f64,
}

impl Summary {
    /// Whether the run meets the fast-rolling bounds ([`MAX_GAIN`], [`MAX_LOSS`],
    /// [`MAX_HEIGHT_ERROR`]).
    pub fn within_bounds(&self) -> bool {
        self.max_gain <= MAX_GAIN
            && self.loss <= MAX_LOSS
            && self.max_rise <= MAX_HEIGHT_ERROR
            && self.max_sink <= MAX_HEIGHT_ERROR
    }
}

impl RollingBall {
    fn build(&self, run: Run, speed: f64, y: f64) -> (App, Entity) {
        let mut app = headless_app(self.dt, self.substeps, Vec3::new(0.0, -G as f32, 0.0), run);
        let mat = creep_material(self.material, run);
        let mu = self.material.friction() as f32;
        spawn_with(
            &mut app,
            (
                RigidBody::Static,
                self.ground.collider(speed * self.duration + 2.0),
                Friction::new(mu),
            ),
            mat,
        );
        let r = ROLL_RADIUS as f32;
        // Rolling without slip about the contact point, `y` below the centre.
        let ball = spawn_with(
            &mut app,
            (
                RigidBody::Dynamic,
                Collider::sphere(r),
                ColliderDensity(self.material.density() as f32),
                Friction::new(mu),
                Position(Vec3::new(0.0, y as f32, 0.0)),
                LinearVelocity(Vec3::new(speed as f32, 0.0, 0.0)),
                AngularVelocity(Vec3::new(0.0, 0.0, (-speed / y) as f32)),
                SleepingDisabled,
            ),
            mat,
        );
        (app, ball)
    }

    /// The centre's height after 0.5 s at rest \[m\].
    pub fn rest_height(&self, run: Run) -> f64 {
        let (mut app, ball) = self.build(run, 0.0, ROLL_RADIUS);
        for _ in 0..(0.5 / self.dt).ceil() as usize {
            step(&mut app);
        }
        f64::from(app.world().get::<Position>(ball).map_or(0.0, |p| p.0.y))
    }

    /// Runs the ball; `each` gets every step's energy \[J\] and height \[m\].
    pub fn run(&self, run: Run, mut each: impl FnMut(f64, f64)) -> Summary {
        let rest = self.rest_height(run);
        let (mut app, ball) = self.build(run, self.speed, rest);
        let energy = |app: &App| {
            let w = app.world();
            let (Some(m), Some(i), Some(v), Some(om), Some(p)) = (
                w.get::<ComputedMass>(ball),
                w.get::<ComputedAngularInertia>(ball),
                w.get::<LinearVelocity>(ball),
                w.get::<AngularVelocity>(ball),
                w.get::<Position>(ball),
            ) else {
                return (0.0, 0.0);
            };
            let m = f64::from(m.value());
            let iw = (i.value() * om.0).as_dvec3();
            let e = 0.5 * m * v.0.as_dvec3().length_squared()
                + 0.5 * iw.dot(om.0.as_dvec3())
                + m * G * f64::from(p.0.y);
            (e, f64::from(p.0.y))
        };
        // Reference the potential energy to the resting height.
        let m_g_rest = {
            let m = app
                .world()
                .get::<ComputedMass>(ball)
                .map_or(0.0, |m| f64::from(m.value()));
            m * G * rest
        };
        let (e0, _) = energy(&app);
        let e0 = e0 - m_g_rest;
        let mut s = Summary {
            e0,
            rest_height: rest,
            ..Default::default()
        };
        let steps = (self.duration / self.dt).round() as usize;
        let mut e = e0;
        for _ in 0..steps {
            step(&mut app);
            let (e1, y) = energy(&app);
            e = e1 - m_g_rest;
            each(e, y);
            s.max_gain = s.max_gain.max((e - e0) / e0);
            s.max_rise = s.max_rise.max(y - rest);
            s.max_sink = s.max_sink.max(rest - y);
        }
        s.loss = (e0 - e) / e0;
        s.e_end = e;
        s
    }
}

/// One case of the fast-rolling matrix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastCase {
    /// Material name (`steel`, `glass`, `rubber`).
    pub material: &'static str,
    /// Launch speed \[m/s\].
    pub speed: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Ground.
    pub ground: Ground,
}

/// The matrix's materials by name (`None` for another name).
pub fn fast_material(name: &str) -> Option<Material> {
    match name {
        "steel" => Some(Material::steel()),
        "glass" => Some(Material::glass()),
        "rubber" => Some(Material::rubber()),
        _ => None,
    }
}

/// The matrix: 3 materials x 4 speeds (2, 5, 10, 20 m/s) x 3 steps (1/30, 1/60, 1/120 s) x
/// 2 grounds.
pub fn fast_matrix() -> Vec<FastCase> {
    let mut v = Vec::new();
    for ground in Ground::ALL {
        for material in ["steel", "glass", "rubber"] {
            for speed in [2.0, 5.0, 10.0, 20.0] {
                for dt in [1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0] {
                    v.push(FastCase {
                        material,
                        speed,
                        dt,
                        ground,
                    });
                }
            }
        }
    }
    v
}

/// One case run with the plugin (`Fidelity::Creep`), with the plugin and its rotation-gap
/// removal, and with plain Avian.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FastOutcome {
    /// The case.
    pub case: FastCase,
    /// The plugin.
    pub plugin: Summary,
    /// The plugin with its rotation-gap removal
    /// ([`crate::CreepSettings::rotation_gap_removal`]).
    pub removed: Summary,
    /// Plain Avian.
    pub plain: Summary,
}

/// Runs one case for `duration` \[s\] at `substeps` (`None` for an unknown material).
pub fn fast_case(case: FastCase, duration: f64, substeps: u32) -> Option<FastOutcome> {
    let ball = RollingBall {
        material: fast_material(case.material)?,
        speed: case.speed,
        dt: case.dt,
        duration,
        ground: case.ground,
        substeps,
    };
    Some(FastOutcome {
        case,
        plugin: ball.run(Run::Plugin(Fidelity::Creep), |_, _| {}),
        removed: ball.run(Run::GapRemoved(Fidelity::Creep), |_, _| {}),
        plain: ball.run(Run::Plain, |_, _| {}),
    })
}

// ----------------------------------------------------------------------------------------
// The poured pile.

/// Radius of the pile's spheres \[m\].
pub const PILE_RADIUS: f32 = 0.05;
/// Time step of the pile \[s\].
pub const PILE_DT: f64 = 1.0 / 60.0;
/// Half thickness of the pile box's walls \[m\].
const WALL: f32 = 0.1;

/// `n^3` glass spheres of 5 cm (density 2,500 kg/m^3) in a lattice 10 % apart with a small
/// deterministic jitter, above a box of static cuboids (floor top at `y = 0`, inner faces at
/// `|x|, |z| = 0.9` m, walls 4 m high); sleeping off, `dt` = 1/60 s, Avian's default substeps.
/// Every collider has the run's fidelity (none for plain Avian).
pub fn pile_app(n: usize, run: Run) -> App {
    let mut app = headless_app(
        PILE_DT,
        DEFAULT_SUBSTEPS,
        Vec3::new(0.0, -G as f32, 0.0),
        run,
    );
    let mat = creep_material(Material::glass(), run);
    let (hx, hz, height) = (0.9f32, 0.9f32, 4.0f32);
    spawn_with(
        &mut app,
        (
            RigidBody::Static,
            Collider::cuboid(2.0 * (hx + 2.0 * WALL), 2.0 * WALL, 2.0 * (hz + 2.0 * WALL)),
            Position(Vec3::new(0.0, -WALL, 0.0)),
        ),
        mat,
    );
    let h = 0.5 * height;
    for (x, z, wx, wz) in [
        (hx + WALL, 0.0, WALL, hz),
        (-hx - WALL, 0.0, WALL, hz),
        (0.0, hz + WALL, hx, WALL),
        (0.0, -hz - WALL, hx, WALL),
    ] {
        spawn_with(
            &mut app,
            (
                RigidBody::Static,
                Collider::cuboid(2.0 * wx, 2.0 * h, 2.0 * wz),
                Position(Vec3::new(x, h, z)),
            ),
            mat,
        );
    }
    let spacing = 2.0 * PILE_RADIUS * 1.1;
    let offset = -(n as f32 - 1.0) * spacing / 2.0;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let jit = ((i * 7 + j * 13 + k * 29) % 11) as f32 * 1e-3;
                let p = Vec3::new(
                    offset + i as f32 * spacing + jit,
                    PILE_RADIUS + 0.01 + j as f32 * spacing,
                    offset + k as f32 * spacing - jit,
                );
                spawn_with(
                    &mut app,
                    (
                        RigidBody::Dynamic,
                        Collider::sphere(PILE_RADIUS),
                        ColliderDensity(2500.0),
                        Position(p),
                        SleepingDisabled,
                    ),
                    mat,
                );
            }
        }
    }
    app
}
