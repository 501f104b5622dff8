//! The specimen: the packing's generation in its box of six walls, stepping, copies.

use creep_rapier::{
    CompliantRegime, CompliantSettings, CreepHooks, CreepMaterial, CreepSettings, CreepWorld,
    RayleighCheck, clone_physics,
};
use rand_xoshiro::SplitMix64;
use rand_xoshiro::rand_core::{Rng, SeedableRng};
use rapier3d::prelude::*;

use super::TriaxialParams;
use crate::SceneError;

/// One wall: a kinematic cuboid whose inner face is normal to `axis`, on side `side` (+1: the
/// face looks towards -axis).
#[derive(Debug, Clone, Copy)]
pub(super) struct Wall {
    pub(super) body: RigidBodyHandle,
    pub(super) collider: ColliderHandle,
    pub(super) axis: usize,
    pub(super) side: f64,
}

/// Half-thickness of the walls, in mean radii.
const WALL_THICKNESS: f64 = 5.0;

/// A packing in its box: the world and what the test needs to find in it.
pub struct Specimen {
    pub(super) world: CreepWorld,
    pub(super) params: TriaxialParams,
    pub(super) balls: Vec<(RigidBodyHandle, ColliderHandle)>,
    pub(super) walls: [Wall; 6],
    pub(super) steps: usize,
}

impl Specimen {
    /// Generates the loose packing in its box (step 1 of the module docs).
    pub fn generate(params: TriaxialParams) -> Result<Self, SceneError> {
        params.validate()?;
        let dt = params.time_step();
        let mut world = CreepWorld::new(dt as f32, CreepSettings::default().with_rapier_solver())?;
        world.physics.gravity = Vector::ZERO;
        world.physics.integration_parameters.num_solver_iterations = 1;
        // Rapier's prediction distance is 2e-3 length units: with the default unit (1 m) every
        // millimetre ball would be paired with dozens of neighbours. One mean diameter as the
        // unit keeps it at 4e-6 m here, still far above a step's relative motion (checked each
        // step, see `Specimen::step`).
        world.physics.integration_parameters.length_unit = params.mean_diameter() as f32;
        world.compliant_mut().set_settings(CompliantSettings {
            rayleigh_fraction: params.rayleigh_fraction,
            rayleigh_check: RayleighCheck::Error,
            creep: false,
            ..CompliantSettings::default()
        })?;
        let mat = CreepMaterial::compliant(params.material);
        let n = params.n_per_side;
        let r = params.radius;
        let r_max = r * (1.0 + params.radius_spread);
        let spacing = 2.0 * r_max * 1.05;
        let side = n as f64 * spacing;
        let mut rng = SplitMix64::seed_from_u64(params.seed);
        let mut balls = Vec::with_capacity(n * n * n);
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let ri = r * (1.0 + params.radius_spread * (2.0 * unit(&mut rng) - 1.0));
                    let slack = (spacing / 2.0 - ri).max(0.0);
                    let mut x = [0.0; 3];
                    for (d, idx) in x.iter_mut().zip([i, j, k]) {
                        *d = (idx as f64 + 0.5) * spacing - side / 2.0
                            + slack * (2.0 * unit(&mut rng) - 1.0) * 0.9;
                    }
                    let body = RigidBodyBuilder::dynamic()
                        .translation(Vector::new(x[0] as f32, x[1] as f32, x[2] as f32))
                        .can_sleep(false);
                    let collider = ColliderBuilder::ball(ri as f32)
                        .density(params.material.density() as f32)
                        .friction(0.0)
                        .restitution(params.restitution as f32);
                    balls.push(world.insert(body, collider, Some(mat)));
                }
            }
        }
        let t = WALL_THICKNESS * r;
        let half = side / 2.0;
        let span = (half + 2.0 * t) as f32;
        let mut walls = Vec::with_capacity(6);
        for axis in 0..3 {
            for s in [-1.0f64, 1.0] {
                let mut c = [0.0f32; 3];
                c[axis] = (s * (half + t)) as f32;
                let mut h = [span; 3];
                h[axis] = t as f32;
                // Never asleep: a slow wall (below Rapier's sleep threshold) would stop.
                let body = RigidBodyBuilder::kinematic_velocity_based()
                    .translation(Vector::new(c[0], c[1], c[2]))
                    .can_sleep(false);
                let collider = ColliderBuilder::cuboid(h[0], h[1], h[2])
                    .friction(0.0)
                    .friction_combine_rule(CoefficientCombineRule::Min)
                    .restitution(params.restitution as f32);
                let (b, co) = world.insert(body, collider, Some(mat));
                walls.push(Wall {
                    body: b,
                    collider: co,
                    axis,
                    side: s,
                });
            }
        }
        Ok(Self {
            world,
            params,
            balls,
            walls: walls.try_into().expect("six walls"),
            steps: 0,
        })
    }

    /// The parameters.
    pub fn params(&self) -> &TriaxialParams {
        &self.params
    }

    /// The world (Rapier and the plugin), e.g. to draw it.
    pub fn world(&self) -> &CreepWorld {
        &self.world
    }

    /// Steps taken since generation.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Number of balls.
    pub fn len(&self) -> usize {
        self.balls.len()
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.balls.is_empty()
    }

    /// Position of a wall's inner face along its axis \[m\].
    pub(super) fn face(&self, w: &Wall) -> f64 {
        let x = self.world.physics.bodies[w.body].translation()[w.axis];
        f64::from(x) - w.side * WALL_THICKNESS * self.params.radius
    }

    /// Box dimensions between the inner faces \[m\].
    pub(super) fn dims(&self) -> [f64; 3] {
        std::array::from_fn(|axis| {
            self.face(&self.walls[2 * axis + 1]) - self.face(&self.walls[2 * axis])
        })
    }

    /// Sets the wall velocities: each wall's outward speed [m/s] (negative: inwards).
    pub(super) fn set_wall_speeds(&mut self, outward: [f64; 6]) {
        for (w, v) in self.walls.iter().zip(outward) {
            let mut vel = [0.0f32; 3];
            vel[w.axis] = (w.side * v) as f32;
            self.world.physics.bodies[w.body].set_linvel(Vector::new(vel[0], vel[1], vel[2]), true);
        }
    }

    pub(super) fn step(&mut self) -> Result<(), SceneError> {
        self.world.step()?;
        self.steps += 1;
        // A contact cannot start unseen while two bodies close in by less than the prediction
        // distance in a step (compliant regime docs).
        let moved = self.world.compliant().counts().max_step_displacement;
        let prediction = f64::from(
            self.world
                .physics
                .integration_parameters
                .prediction_distance(),
        );
        if 2.0 * moved > prediction {
            return Err(SceneError::Parameter(format!(
                "triaxial: a ball moved {moved:.3e} m in one step, more than half the prediction distance {prediction:.3e} m: lower the inertial number or the time step"
            )));
        }
        Ok(())
    }
}

/// The packing's generator, named in a run's outputs: SplitMix64 (Steele, Lea & Flood 2014),
/// `rand_xoshiro::SplitMix64` seeded with [`TriaxialParams::seed`] by `seed_from_u64` (the
/// seed is the initial state), so a seed gives the same packing on every machine.
pub const GENERATOR: &str = "SplitMix64 (Steele, Lea & Flood 2014; rand_xoshiro 0.8)";

/// A uniform draw in `[0, 1)`: the top 53 bits of the next 64-bit output over `2^53`.
fn unit(rng: &mut SplitMix64) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

impl Specimen {
    /// A copy with fresh plugin state (same registry and settings but `creep`), so that two
    /// shears start from the same packing.
    pub(super) fn clone_fresh(&self, creep: bool) -> Result<Self, SceneError> {
        let hooks = CreepHooks::new(
            self.world.hooks().registry().clone(),
            *self.world.hooks().settings(),
        )?;
        let mut world = CreepWorld::from_parts(clone_physics(&self.world.physics), hooks)?;
        *world.compliant_mut() = CompliantRegime::new(CompliantSettings {
            creep,
            ..*self.world.compliant().settings()
        })?;
        Ok(Self {
            world,
            params: self.params,
            balls: self.balls.clone(),
            walls: self.walls,
            steps: self.steps,
        })
    }
}

impl Specimen {
    /// A copy of this (compacted) specimen at rest for timing: fresh plugin state with creep on
    /// or off, the balls with the shear's friction, walls fixed, one step taken (Rapier rebuilds
    /// its workspace after a copy). Step it with [`Specimen::step_at_rest`].
    pub fn at_rest(&self, creep: bool) -> Result<Self, SceneError> {
        let mut s = self.clone_fresh(creep)?;
        for &(_, c) in &s.balls {
            if let Some(co) = s.world.physics.colliders.get_mut(c) {
                co.set_friction(s.params.mu as f32);
            }
        }
        s.set_wall_speeds([0.0; 6]);
        s.step()?;
        Ok(s)
    }

    /// One step with the walls as they are.
    pub fn step_at_rest(&mut self) -> Result<(), SceneError> {
        self.step()
    }

    /// The same packing in plain Rapier (its own rigid contacts with Coulomb friction, no
    /// hooks; same dt and length unit, Rapier's default solver iterations), for scale.
    pub fn plain_rapier(&self) -> PhysicsWorld {
        let mut p = clone_physics(&self.world.physics);
        let dt = p.integration_parameters.dt;
        let unit = p.integration_parameters.length_unit;
        p.integration_parameters = IntegrationParameters {
            dt,
            length_unit: unit,
            ..IntegrationParameters::default()
        };
        let handles: Vec<ColliderHandle> = p.colliders.iter().map(|(h, _)| h).collect();
        for h in handles {
            let co = &mut p.colliders[h];
            co.set_active_hooks(ActiveHooks::empty());
            co.set_solver_groups(InteractionGroups::all());
            if co.shape().as_ball().is_some() {
                co.set_friction(self.params.mu as f32);
            }
        }
        p.step();
        p
    }
}

/// The specimen's packing in the creep-dem engine ([`creep_dem::Dem`]): the same balls (radius,
/// position, velocities), the six walls as planes at their inner faces (normals into the box,
/// frictionless: the walls' friction 0 under Rapier's `Min` rule), the balls' friction
/// [`TriaxialParams::mu`] and restitution, the same time step, creep on or off (Kuhn's model),
/// neighbour skin 2 % of the mean diameter (the peers' skin in `bench/peers`). `parallel` runs
/// the force loop on rayon's threads.
pub fn dem_engine<T: creep_dem::TangentialLaw>(
    specimen: &Specimen,
    creep: bool,
    parallel: bool,
) -> Result<creep_dem::Dem<T>, SceneError> {
    dem_engine_tiled(specimen, creep, parallel, 1)
}

/// [`dem_engine`] with the packing repeated `tiles` times along each axis (`tiles^3` copies
/// side by side, box dimensions apart, inside walls around the whole): a larger dense packing
/// for the engine's scale table (`creep bench dem --scale`). The copies' seams are as dense as
/// the packing at its walls.
pub fn dem_engine_tiled<T: creep_dem::TangentialLaw>(
    specimen: &Specimen,
    creep: bool,
    parallel: bool,
    tiles: usize,
) -> Result<creep_dem::Dem<T>, SceneError> {
    if !(1..=16).contains(&tiles) {
        return Err(SceneError::Parameter(format!(
            "tiles must be in [1, 16], got {tiles}"
        )));
    }
    use creep_dem::{Dem, DemConfig, MaterialTable, Particle};
    use creep_law::pair::PairConstants;
    use creep_law::{CreepModel, Vec3};
    let err = |e: creep_dem::DemError| SceneError::Parameter(format!("DEM engine: {e}"));
    let p = &specimen.params;
    let physics = &specimen.world.physics;
    let v3 = |v: Vector| Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z));
    let dims = specimen.dims();
    let lo: [f64; 3] = std::array::from_fn(|a| specimen.face(&specimen.walls[2 * a]));
    let mut particles = Vec::with_capacity(specimen.balls.len() * tiles.pow(3));
    for &(b, c) in &specimen.balls {
        let body = &physics.bodies[b];
        let radius = physics.colliders[c]
            .shape()
            .as_ball()
            .map(|ball| f64::from(ball.radius))
            .ok_or_else(|| SceneError::Parameter("a ball collider is not a ball".into()))?;
        particles.push(Particle {
            position: v3(body.translation()),
            velocity: v3(body.linvel()),
            angular_velocity: v3(body.angvel()),
            radius,
            material: 0,
        });
    }
    let one = particles.len();
    for t in 1..tiles.pow(3) {
        let (i, j, k) = (t % tiles, (t / tiles) % tiles, t / (tiles * tiles));
        let shift = Vec3::new(i as f64 * dims[0], j as f64 * dims[1], k as f64 * dims[2]);
        for q in 0..one {
            let mut copy = particles[q];
            copy.position += shift;
            particles.push(copy);
        }
    }
    let walls: Vec<creep_dem::Wall> = specimen
        .walls
        .iter()
        .map(|w| {
            let mut point = [0.0; 3];
            point[w.axis] = if w.side > 0.0 {
                lo[w.axis] + tiles as f64 * dims[w.axis]
            } else {
                specimen.face(w)
            };
            let mut normal = [0.0; 3];
            normal[w.axis] = -w.side;
            let mut vel = [0.0; 3];
            vel[w.axis] = f64::from(physics.bodies[w.body].linvel()[w.axis]);
            creep_dem::Wall {
                point: Vec3::new(point[0], point[1], point[2]),
                normal: Vec3::new(normal[0], normal[1], normal[2]),
                velocity: Vec3::new(vel[0], vel[1], vel[2]),
                material: 1,
            }
        })
        .collect();
    let ball = p.material.with_friction(p.mu)?;
    let wall = p.material.with_friction(0.0)?;
    let model = creep.then_some(CreepModel::Kuhn);
    let mut table = MaterialTable::new(&[ball, wall], p.restitution, model, None).map_err(err)?;
    // Ball-wall pairs frictionless (Rapier's `Min` rule with the walls' 0).
    table
        .set_pair(
            0,
            1,
            PairConstants::new(&ball, &wall, 0.0, p.restitution, model, None)?,
        )
        .map_err(err)?;
    let cfg = DemConfig {
        dt: f64::from(physics.integration_parameters.dt),
        skin: 0.02 * p.mean_diameter(),
        parallel,
        ..DemConfig::default()
    };
    Dem::new(cfg, table, &particles, &walls).map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The packing of `TriaxialParams::quick()` (seed 2011) is the one the hand-written
    /// SplitMix64 this generator replaced gave: positions and radii recorded from that code
    /// before the change (bit for bit, f32 as Rapier holds them).
    #[test]
    fn the_packing_is_the_former_generators() {
        let s = Specimen::generate(TriaxialParams::quick()).unwrap();
        let expected: [(usize, [f32; 3], f32); 4] = [
            (
                0,
                [-0.007_363_186_7, -0.007_548_337, -0.007_561_216_6],
                0.000_808_586_37,
            ),
            (
                1,
                [-0.007_749_378_7, -0.007_823_195, -0.004_988_527],
                0.000_825_407_57,
            ),
            (
                2,
                [-0.007_439_138, -0.007_723_349, -0.002_719_267_3],
                0.001_036_759_3,
            ),
            (
                342,
                [0.007_778_702, 0.007_553_211_4, 0.007_780_981_7],
                0.000_977_356,
            ),
        ];
        for (i, x, r) in expected {
            let (b, c) = s.balls[i];
            let t = s.world.physics.bodies[b].translation();
            assert_eq!([t.x, t.y, t.z], x, "ball {i}");
            let radius = s.world.physics.colliders[c]
                .shape()
                .as_ball()
                .unwrap()
                .radius;
            assert_eq!(radius, r, "ball {i}");
        }
        // The generator's own first outputs for that seed (SplitMix64's reference algorithm).
        let mut g = SplitMix64::seed_from_u64(2011);
        assert_eq!(
            [g.next_u64(), g.next_u64(), g.next_u64()],
            [
                0x057e_cade_6a7c_2132,
                0xbe02_0c31_9a78_d0d8,
                0x83ac_adce_c37d_6309
            ]
        );
    }

    #[test]
    fn another_seed_gives_another_packing() {
        let a = Specimen::generate(TriaxialParams::quick()).unwrap();
        let b = Specimen::generate(TriaxialParams {
            seed: 2012,
            ..TriaxialParams::quick()
        })
        .unwrap();
        let x = |s: &Specimen| s.world.physics.bodies[s.balls[0].0].translation();
        assert_ne!(x(&a), x(&b));
    }
}
