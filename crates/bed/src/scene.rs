//! Scenes of a bed and a Rapier world: a settled bed in a box, a rigid sphere resting on it
//! (the bed carries its weight), a driven wheel on it. One code for tests, the CLI and
//! benches.

use creep_dem::{Dem, DemConfig, MaterialTable, Particle, TangentialLaw, Wall};
use creep_law::{CreepModel, Material, Vec3};
use rapier3d::glamx::Vec3 as FVec3;
use rapier3d::prelude::*;

use crate::{Bed, BedConfig, BedError};

/// A bed of grains poured into a box of plane walls and settled under gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BedSpec {
    /// Grains along x, y (layers before settling) and z.
    pub counts: [usize; 3],
    /// Largest grain radius \[m\]; radii uniform in `[0.8, 1] r`.
    pub radius: f64,
    /// Grain shear modulus \[Pa\] (soft, so the DEM step is long).
    pub shear_modulus: f64,
    /// Grain Poisson ratio [-].
    pub poisson_ratio: f64,
    /// Grain friction coefficient [-].
    pub friction: f64,
    /// Grain density \[kg/m^3\].
    pub density: f64,
    /// Restitution of every contact [-].
    pub restitution: f64,
    /// Creep model at grain contacts (`None`: Coulomb-Mindlin only).
    pub creep: Option<CreepModel>,
    /// Gravity along -y \[m/s^2\].
    pub gravity: f64,
    /// DEM step as a fraction of the Rayleigh time step of the smallest grain [-].
    pub dt_fraction: f64,
    /// Seed of the lattice jitter, initial velocities and radii.
    pub seed: u64,
    /// Periodic along z (no side walls at `z = 0` and `z = lz`): a slice of an infinitely wide
    /// bed, e.g. under a wheel spanning the slice (plane strain).
    pub periodic_z: bool,
}

impl Default for BedSpec {
    fn default() -> Self {
        Self {
            counts: [8, 4, 8],
            radius: 2e-3,
            shear_modulus: 29e6,
            poisson_ratio: 0.23,
            friction: 0.5,
            density: 2500.0,
            restitution: 0.5,
            creep: Some(CreepModel::Kuhn),
            gravity: 9.81,
            dt_fraction: 0.2,
            seed: 12345,
            periodic_z: false,
        }
    }
}

/// Grain spacing of the initial lattice, in radii.
const SPACING: f64 = 2.2;

impl BedSpec {
    /// A Rapier world for this bed (its gravity along -y, the game step `dt_rigid` \[s\]) with
    /// one dynamic body at `position` \[m\] carrying `collider`, and the bed built from `dem`
    /// with that collider as its boundary (material id 1): the set-up every coupled scene shares.
    pub fn coupled_world<T: TangentialLaw>(
        &self,
        dem: Dem<T>,
        dt_rigid: f64,
        position: FVec3,
        collider: Collider,
    ) -> Result<(PhysicsWorld, RigidBodyHandle, Bed<T>), BedError> {
        let mut world = PhysicsWorld {
            gravity: FVec3::new(0.0, -self.gravity as f32, 0.0),
            ..Default::default()
        };
        world.integration_parameters.dt = dt_rigid as f32;
        let body = world.bodies.insert(
            RigidBodyBuilder::dynamic()
                .translation(position)
                .can_sleep(false)
                .build(),
        );
        let ch = world
            .colliders
            .insert_with_parent(collider, body, &mut world.bodies);
        let mut bed = Bed::new(
            dem,
            BedConfig {
                skin: 0.2 * self.radius,
            },
        )?;
        bed.add_boundary(ch, 1, &world.bodies, &world.colliders)?;
        Ok((world, body, bed))
    }
    /// The grain material.
    pub fn material(&self) -> Result<Material, BedError> {
        Ok(Material::new(
            self.shear_modulus,
            self.poisson_ratio,
            self.friction,
            self.density,
        )
        .map_err(creep_dem::DemError::from)?)
    }

    /// Box size along x and z \[m\].
    pub fn footprint(&self) -> (f64, f64) {
        (
            self.counts[0] as f64 * SPACING * self.radius,
            self.counts[2] as f64 * SPACING * self.radius,
        )
    }

    /// The DEM step \[s\].
    pub fn dt(&self) -> Result<f64, BedError> {
        let t_r = creep_law::hertz::rayleigh_time_step(&self.material()?, 0.8 * self.radius);
        let dt = self.dt_fraction * t_r;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(BedError::Parameter {
                name: "dt_fraction",
                value: self.dt_fraction,
                why: "must give a finite, positive DEM step",
            });
        }
        Ok(dt)
    }

    /// The engine with the grains on a lattice (random jitter, velocities and radii from the
    /// seed), walls at `y = 0` and the four sides (two with [`BedSpec::periodic_z`]); material 0 the grains, material 1
    /// `boundary` (the rigid bodies' material).
    pub fn engine<T: TangentialLaw>(&self, boundary: Material) -> Result<Dem<T>, BedError> {
        let r = self.radius;
        if !(r.is_finite() && r > 0.0) || self.counts.contains(&0) {
            return Err(BedError::Parameter {
                name: "grain radius or counts",
                value: r,
                why: "radius finite > 0 and counts >= 1",
            });
        }
        let g = self.material()?;
        let table = MaterialTable::new(&[g, boundary], self.restitution, self.creep, None)?;
        let mut s = self.seed;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut ps = Vec::with_capacity(self.counts.iter().product());
        let [nx, ny, nz] = self.counts;
        for j in 0..ny {
            for k in 0..nz {
                for i in 0..nx {
                    ps.push(Particle {
                        position: Vec3::new(
                            (i as f64 + 0.5) * SPACING * r + 0.1 * r * (rnd() - 0.5),
                            (j as f64 + 0.5) * SPACING * r + 0.1 * r * rnd(),
                            (k as f64 + 0.5) * SPACING * r + 0.1 * r * (rnd() - 0.5),
                        ),
                        velocity: Vec3::new(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5) * 0.02,
                        angular_velocity: Vec3::ZERO,
                        radius: r * (0.8 + 0.2 * rnd()),
                        material: 0,
                    });
                }
            }
        }
        let (lx, lz) = self.footprint();
        let wall = |point: Vec3, normal: Vec3| Wall {
            point,
            normal,
            velocity: Vec3::ZERO,
            material: 0,
        };
        let mut walls = vec![
            wall(Vec3::ZERO, Vec3::Y),
            wall(Vec3::ZERO, Vec3::X),
            wall(Vec3::new(lx, 0.0, 0.0), -Vec3::X),
        ];
        let mut periodic = [None; 3];
        if self.periodic_z {
            periodic[2] = Some((0.0, lz));
        } else {
            walls.push(wall(Vec3::ZERO, Vec3::Z));
            walls.push(wall(Vec3::new(0.0, 0.0, lz), -Vec3::Z));
        }
        let cfg = DemConfig {
            dt: self.dt()?,
            skin: 0.2 * r,
            gravity: Vec3::new(0.0, -self.gravity, 0.0),
            periodic,
            ..Default::default()
        };
        Ok(Dem::new(cfg, table, &ps, &walls)?)
    }

    /// Settles the engine: steps until the kinetic energy per grain is below
    /// `1e-4 m g r` of the mean grain (at most `max_steps` steps). Returns the steps taken.
    pub fn settle<T: TangentialLaw>(
        &self,
        dem: &mut Dem<T>,
        max_steps: usize,
    ) -> Result<usize, BedError> {
        let m = self.density * 4.0 / 3.0 * std::f64::consts::PI * (0.9 * self.radius).powi(3);
        let limit = 1e-4 * m * self.gravity * self.radius * dem.len() as f64;
        let mut steps = 0;
        while steps < max_steps {
            for _ in 0..100 {
                dem.step()?;
            }
            steps += 100;
            if steps > 1000 && dem.kinetic_energy() < limit {
                break;
            }
        }
        Ok(steps)
    }
}

/// Height of the bed's surface: the mean top of the highest grains over the middle of the box
/// \[m\].
pub fn surface_height<T: TangentialLaw>(dem: &Dem<T>) -> f64 {
    let tops: Vec<f64> = dem
        .positions()
        .iter()
        .zip(dem.radii())
        .map(|(x, r)| x.y + r)
        .collect();
    let max = tops.iter().copied().fold(f64::MIN, f64::max);
    // The top layer: grains within one diameter of the highest.
    let d = 2.0 * dem.radii().iter().copied().fold(0.0, f64::max);
    let top: Vec<f64> = tops.into_iter().filter(|&t| t > max - d).collect();
    top.iter().sum::<f64>() / top.len().max(1) as f64
}

/// The highest grain top \[m\] among the grains whose centres are within `half.x` along x and
/// `half.z` along z of `centre` (a body's footprint), or [`surface_height`] if none is.
pub fn highest_under<T: TangentialLaw>(dem: &Dem<T>, centre: Vec3, half: Vec3) -> f64 {
    dem.positions()
        .iter()
        .zip(dem.radii())
        .filter(|(x, _)| (x.x - centre.x).abs() < half.x && (x.z - centre.z).abs() < half.z)
        .map(|(x, r)| x.y + r)
        .fold(None, |m: Option<f64>, t| Some(m.map_or(t, |m| m.max(t))))
        .unwrap_or_else(|| surface_height(dem))
}

/// The resting-sphere scene's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestingSphere {
    /// The bed.
    pub bed: BedSpec,
    /// Sphere radius in grain radii [-].
    pub radius_factor: f64,
    /// Sphere density \[kg/m^3\].
    pub density: f64,
    /// DEM steps per game step [-].
    pub substeps: usize,
    /// Steps to settle the bed alone (at most).
    pub settle_steps: usize,
    /// Game steps with the sphere before measuring.
    pub rest_steps: usize,
    /// Game steps averaged.
    pub window: usize,
}

/// What the resting-sphere scene measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestingReport {
    /// Grains.
    pub grains: usize,
    /// Sphere weight `m g` \[N\] (Rapier's f32 mass).
    pub weight: f64,
    /// Mean vertical force of the grains on the sphere over the window \[N\].
    pub mean_force: f64,
    /// `mean_force / weight` [-].
    pub ratio: f64,
    /// Sphere's vertical speed at the end \[m/s\].
    pub speed: f64,
    /// Sinkage: bed surface minus the sphere's lowest point \[m\].
    pub sinkage: f64,
    /// Grain-sphere contacts at the end.
    pub contacts: usize,
}

/// Settles a bed, drops a rigid sphere on it from rest just above the surface, waits, then
/// averages the grains' force on it over a window of game steps.
pub fn resting_sphere<T: TangentialLaw>(s: &RestingSphere) -> Result<RestingReport, BedError> {
    let b = s.bed;
    let ball_mat =
        Material::new(79.3e6, 0.29, 0.3, s.density).map_err(creep_dem::DemError::from)?;
    let mut dem = b.engine::<T>(ball_mat)?;
    b.settle(&mut dem, s.settle_steps)?;
    let top = surface_height(&dem);
    let grains = dem.len();
    let dt = dem.config().dt;
    let dt_rigid = dt * s.substeps as f64;
    let (lx, lz) = b.footprint();
    let rb = s.radius_factor * b.radius;

    // Just above the highest grain under the sphere (the mean surface is lower: a sphere placed
    // on it would start overlapping the highest grains and be kicked off).
    let reach = rb + b.radius;
    let start = highest_under(
        &dem,
        Vec3::new(0.5 * lx, 0.0, 0.5 * lz),
        Vec3::new(reach, 0.0, reach),
    );
    let (mut world, ball, mut bed) = b.coupled_world(
        dem,
        dt_rigid,
        FVec3::new(
            (0.5 * lx) as f32,
            (start + rb + 0.05 * b.radius) as f32,
            (0.5 * lz) as f32,
        ),
        ColliderBuilder::ball(rb as f32)
            .density(s.density as f32)
            .build(),
    )?;
    for _ in 0..s.rest_steps {
        bed.step(dt_rigid, &mut world.bodies)?;
        world.step();
    }
    let mut sum = 0.0;
    for _ in 0..s.window {
        bed.step(dt_rigid, &mut world.bodies)?;
        world.step();
        sum += bed.boundaries().exchange(0).map_or(0.0, |e| e.mean_force.y);
    }
    let body = &world.bodies[ball];
    let weight = f64::from(body.mass()) * b.gravity;
    let mean_force = sum / s.window.max(1) as f64;
    Ok(RestingReport {
        grains,
        weight,
        mean_force,
        ratio: mean_force / weight,
        speed: f64::from(body.linvel().y),
        sinkage: top - (f64::from(body.translation().y) - rb),
        contacts: bed.boundaries().exchange(0).map_or(0, |e| e.contacts),
    })
}
