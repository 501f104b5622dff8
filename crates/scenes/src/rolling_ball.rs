//! A 0.1 m ball rolling freely on a level ground (half-space, flat triangle mesh or flat
//! heightfield): no tangential load, so neither creep nor any physical loss. Whatever energy the
//! ball gains or loses, and however far its centre leaves its resting height, is the engine's
//! (or the plugin's) own error. Used by `creep run rolling-ball` and the fast-rolling matrix
//! ([`crate::hard_cases::fast_rolling`]).

use creep_law::Material;
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::measure::{SceneError, positive};

/// Ball radius \[m\].
pub const RADIUS: f64 = 0.1;
/// Gravity [m/s^2] (along -y).
pub const GRAVITY: f64 = 9.81;
/// Steps of the rest run that finds the resting height.
const REST_STEPS: usize = 120;

/// The ground the ball rolls on; its top face is the plane `y = 0`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ground {
    /// A half-space (Rapier's `HalfSpace`).
    Plane,
    /// A flat triangle mesh of 1 m x 1 m cells (two triangles each), internal edges fixed.
    Trimesh,
    /// A flat heightfield of 1 m cells. Built without `HeightFieldFlags::FIX_INTERNAL_EDGES`:
    /// with that flag Rapier 0.36 gives this flat heightfield no contact with the ball at all
    /// (measured: the ball falls 490 m in 10 s, in plain Rapier alike).
    Heightfield,
}

impl Ground {
    /// All grounds.
    pub const ALL: [Ground; 3] = [Ground::Plane, Ground::Trimesh, Ground::Heightfield];
    /// Name as the CLI spells it.
    pub fn label(self) -> &'static str {
        match self {
            Ground::Plane => "plane",
            Ground::Trimesh => "trimesh",
            Ground::Heightfield => "heightfield",
        }
    }
    /// Parses a CLI name.
    pub fn parse(s: &str) -> Result<Self, SceneError> {
        Ground::ALL
            .into_iter()
            .find(|g| g.label() == s)
            .ok_or_else(|| SceneError::Parameter(format!("unknown ground {s:?}")))
    }
}

/// Who steps the world.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stepper {
    /// Plain Rapier: no plugin at all, the plugin's integration parameters.
    Plain,
    /// The plugin with this fidelity on both colliders.
    Plugin(FidelityChoice),
}

/// The fidelities of the rigid regime a scene can ask for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FidelityChoice {
    /// `Fidelity::Coulomb`.
    Coulomb,
    /// `Fidelity::Auto`.
    Auto,
    /// `Fidelity::Creep`.
    Creep,
}

impl Stepper {
    /// Parses `plain|coulomb|auto|creep`.
    pub fn parse(s: &str) -> Result<Self, SceneError> {
        Ok(match s {
            "plain" => Stepper::Plain,
            "coulomb" => Stepper::Plugin(FidelityChoice::Coulomb),
            "auto" => Stepper::Plugin(FidelityChoice::Auto),
            "creep" => Stepper::Plugin(FidelityChoice::Creep),
            _ => return Err(SceneError::Parameter(format!("unknown fidelity {s:?}"))),
        })
    }
    /// Name as the CLI spells it.
    pub fn label(self) -> &'static str {
        match self {
            Stepper::Plain => "plain",
            Stepper::Plugin(FidelityChoice::Coulomb) => "coulomb",
            Stepper::Plugin(FidelityChoice::Auto) => "auto",
            Stepper::Plugin(FidelityChoice::Creep) => "creep",
        }
    }
}

/// One rolling-ball run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingBall {
    /// Ball and ground material.
    pub material: Material,
    /// Launch speed [m/s], rolling without slip along +x (0: at rest).
    pub speed: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Ground shape.
    pub ground: Ground,
    /// Who steps it.
    pub stepper: Stepper,
    /// Number of steps.
    pub steps: usize,
    /// Rapier's solver substeps (`num_solver_iterations`; Rapier's default is 4, the
    /// rotation-gap correction is exact with 1).
    pub substeps: usize,
}

/// The state of the ball after a step (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time \[s\].
    pub t: f64,
    /// Centre position along the rolling direction \[m\].
    pub x: f64,
    /// Height of the centre above the ground's top face \[m\].
    pub height: f64,
    /// Speed of the centre [m/s].
    pub speed: f64,
    /// Angular speed times radius [m/s] (rolling without slip it is `speed R / (R - delta/2)`,
    /// `delta` the overlap at rest, 3.5e-4 above `speed` for steel: the solver rolls the ball about
    /// its contact point midway between the surfaces).
    pub omega_r: f64,
    /// Kinetic energy, translation and rotation \[J\].
    pub kinetic_energy: f64,
    /// Potential energy relative to the start, `m g (y - y0)` \[J\].
    pub potential_energy: f64,
}

/// What a run measured against its bounds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Initial mechanical energy \[J\].
    pub e0: f64,
    /// Largest `(E - E0) / E0` over the run (energy gained) [-].
    pub max_gain: f64,
    /// `(E0 - E_end) / E0` (energy lost over the run) [-].
    pub loss: f64,
    /// Largest rise of the centre above its resting height \[m\].
    pub max_rise: f64,
    /// Largest sinking of the centre below its resting height \[m\].
    pub max_sink: f64,
    /// Resting height of the centre \[m\] (from a run of the ball at rest).
    pub rest_height: f64,
}

enum World {
    Plain(Box<PhysicsWorld>),
    Plugin(Box<CreepWorld>),
}

impl World {
    fn physics(&self) -> &PhysicsWorld {
        match self {
            World::Plain(p) => p,
            World::Plugin(w) => &w.physics,
        }
    }
    fn step(&mut self) -> Result<(), SceneError> {
        match self {
            World::Plain(p) => p.step(),
            World::Plugin(w) => {
                w.step()?;
            }
        }
        Ok(())
    }
}

fn ground_collider(ground: Ground, length: f32) -> Result<ColliderBuilder, SceneError> {
    Ok(match ground {
        Ground::Plane => ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y)),
        Ground::Trimesh => {
            // Cells of 1 m along x from -2 m to `length`, across z from -2 m to 2 m.
            let nx = (length + 2.0).ceil() as u32 + 1;
            let nz = 4u32;
            let mut vertices = Vec::new();
            for i in 0..=nx {
                for k in 0..=nz {
                    vertices.push(Vector::new(-2.0 + i as f32, 0.0, -2.0 + k as f32));
                }
            }
            let id = |i: u32, k: u32| i * (nz + 1) + k;
            let mut indices = Vec::new();
            for i in 0..nx {
                for k in 0..nz {
                    indices.push([id(i, k), id(i, k + 1), id(i + 1, k + 1)]);
                    indices.push([id(i, k), id(i + 1, k + 1), id(i + 1, k)]);
                }
            }
            ColliderBuilder::trimesh_with_flags(vertices, indices, TriMeshFlags::FIX_INTERNAL_EDGES)
                .map_err(|e| SceneError::Parameter(format!("trimesh: {e:?}")))?
        }
        Ground::Heightfield => {
            let ncols = (length + 4.0).ceil() as usize + 1; // along x, 1 m cells
            let nrows = 5; // along z
            let heights = Array2::repeat(nrows, ncols, 0.0);
            let scale = Vector::new((ncols - 1) as f32, 1.0, (nrows - 1) as f32);
            // Centred at the origin: shift so that it spans x in [-2, length + 2].
            ColliderBuilder::heightfield(heights, scale).translation(Vector::new(
                0.5 * (ncols - 1) as f32 - 2.0,
                0.0,
                0.0,
            ))
        }
    })
}

/// The lever arm \[m\] about which Rapier's friction solve rolls a ball whose centre rests at
/// `y0` above the ground's face: its contact point lies midway between the two surfaces, so the
/// arm is `R - delta/2` with the overlap `delta = R - y0` (measured: a ball launched at `v = w R`
/// settles at `v - w R = -w delta / 2` within the first step, through a real tangential impulse).
/// Launching at `w = v / arm` rolls without slip at that point from the first step, so that no
/// tangential load acts at all.
fn rolling_arm(y0: f64) -> f64 {
    RADIUS - 0.5 * (RADIUS - y0.min(RADIUS))
}

/// A world with the ground and the ball (not yet moving), and the ball's handle.
#[allow(clippy::too_many_arguments)]
fn build(
    material: Material,
    dt: f64,
    ground: Ground,
    stepper: Stepper,
    length: f64,
    y0: f64,
    speed: f64,
    substeps: usize,
) -> Result<(World, RigidBodyHandle), SceneError> {
    let mut w = CreepWorld::new(dt as f32, CreepSettings::default().with_rapier_solver())?;
    w.physics.integration_parameters.num_solver_iterations = substeps;
    let body = RigidBodyBuilder::dynamic()
        .translation(Vector::new(0.0, y0 as f32, 0.0))
        .linvel(Vector::new(speed as f32, 0.0, 0.0))
        .angvel(Vector::new(0.0, 0.0, (-speed / rolling_arm(y0)) as f32))
        .can_sleep(false);
    let ball = ColliderBuilder::ball(RADIUS as f32)
        .density(material.density() as f32)
        .friction(material.friction() as f32);
    let floor = ground_collider(ground, length as f32)?.friction(material.friction() as f32);
    let handle = match stepper {
        Stepper::Plain => {
            let p = &mut w.physics;
            p.insert(RigidBodyBuilder::fixed(), floor);
            p.insert(body, ball).0
        }
        Stepper::Plugin(f) => {
            let fidelity = match f {
                FidelityChoice::Coulomb => Fidelity::Coulomb,
                FidelityChoice::Auto => Fidelity::Auto,
                FidelityChoice::Creep => Fidelity::Creep,
            };
            let mat = CreepMaterial::new(material).with_fidelity(fidelity);
            w.insert(RigidBodyBuilder::fixed(), floor, Some(mat));
            w.insert(body, ball, Some(mat)).0
        }
    };
    let world = match stepper {
        Stepper::Plain => World::Plain(Box::new(creep_rapier::clone_physics(&w.physics))),
        Stepper::Plugin(_) => World::Plugin(Box::new(w)),
    };
    Ok((world, handle))
}

fn sample(p: &PhysicsWorld, ball: RigidBodyHandle, t: f64, y0: f64) -> Sample {
    let rb = &p.bodies[ball];
    let m = f64::from(rb.mass());
    let v = rb.linvel();
    let w = rb.angvel();
    let inertia = rb.mass_properties().local_mprops.principal_inertia();
    let ke = 0.5 * m * f64::from(v.length_squared())
        + 0.5
            * (f64::from(inertia.x) * f64::from(w.x).powi(2)
                + f64::from(inertia.y) * f64::from(w.y).powi(2)
                + f64::from(inertia.z) * f64::from(w.z).powi(2));
    let y = f64::from(rb.translation().y);
    Sample {
        t,
        x: f64::from(rb.translation().x),
        height: y,
        speed: f64::from(v.length()),
        omega_r: f64::from(w.length()) * RADIUS,
        kinetic_energy: ke,
        potential_energy: m * GRAVITY * (y - y0),
    }
}

/// The resting height of the ball's centre on this ground at this step: a ball set at rest on
/// the ground, after `REST_STEPS` steps \[m\].
pub fn rest_height(
    material: Material,
    dt: f64,
    ground: Ground,
    stepper: Stepper,
    substeps: usize,
) -> Result<f64, SceneError> {
    let (mut w, ball) = build(material, dt, ground, stepper, 1.0, RADIUS, 0.0, substeps)?;
    for _ in 0..REST_STEPS {
        w.step()?;
    }
    Ok(f64::from(w.physics().bodies[ball].translation().y))
}

impl RollingBall {
    /// Runs the ball, calling `each` with the start and every step's sample; returns the
    /// run's summary. Energies are Rapier's (no leap-frog correction: the ball's vertical
    /// velocity is zero when it rolls right, and a hop is what the bound is about).
    pub fn run(&self, mut each: impl FnMut(&Sample)) -> Result<Summary, SceneError> {
        positive("dt", self.dt)?;
        if !(self.speed >= 0.0 && self.speed.is_finite()) {
            return Err(SceneError::Parameter(format!(
                "speed must be finite and >= 0, got {}",
                self.speed
            )));
        }
        if self.substeps == 0 {
            return Err(SceneError::Parameter("substeps must be >= 1".into()));
        }
        let rest = rest_height(
            self.material,
            self.dt,
            self.ground,
            self.stepper,
            self.substeps,
        )?;
        let length = self.speed * self.dt * self.steps as f64 + 2.0;
        let (mut w, ball) = build(
            self.material,
            self.dt,
            self.ground,
            self.stepper,
            length,
            rest,
            self.speed,
            self.substeps,
        )?;
        let s0 = sample(w.physics(), ball, 0.0, rest);
        each(&s0);
        let e0 = s0.kinetic_energy;
        let (mut max_gain, mut max_rise, mut max_sink) = (0f64, 0f64, 0f64);
        let mut last = s0;
        for k in 1..=self.steps {
            w.step()?;
            let s = sample(w.physics(), ball, k as f64 * self.dt, rest);
            let e = s.kinetic_energy + s.potential_energy;
            if !(e.is_finite() && s.height.is_finite()) {
                return Err(SceneError::Parameter(format!(
                    "the run produced a non-finite state at step {k}"
                )));
            }
            if e0 > 0.0 {
                max_gain = max_gain.max((e - e0) / e0);
            }
            max_rise = max_rise.max(s.height - rest);
            max_sink = max_sink.max(rest - s.height);
            each(&s);
            last = s;
        }
        let loss = if e0 > 0.0 {
            (e0 - last.kinetic_energy - last.potential_energy) / e0
        } else {
            0.0
        };
        Ok(Summary {
            e0,
            max_gain,
            loss,
            max_rise,
            max_sink,
            rest_height: rest,
        })
    }
}
