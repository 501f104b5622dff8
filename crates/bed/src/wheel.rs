//! A driven rigid wheel (a Rapier cylinder) on a granular bed: sinkage, drawbar pull and
//! driving torque against the slip ratio, in steady state, with and without creep-friction at
//! the grain contacts.
//!
//! **The test.** The wheel's spin `w` and forward speed `v = w R (1 - s)` are prescribed each
//! game step (`s = 1 - v/(w R)` the slip ratio of a driven wheel, Wong 2008, *Theory of Ground
//! Vehicles*, 4th ed., ch. 2), its vertical motion is free (its weight against
//! the bed): the slip-controlled single-wheel test of the terramechanics laboratories (Wong &
//! Reece 1967, *J. Terramech.* 4(1) 81-98; 4(2) 7-25), so the sinkage is the scene's answer.
//! Drawbar pull: the grains' force on the wheel along the travel (+x) \[N\]; driving torque: the
//! torque the motor must apply to keep the spin, i.e. the grains' torque about the axle along
//! +z (the wheel spins about -z to roll towards +x; resisting grains give a torque along +z, so
//! a positive value is a motor doing work) \[N m\]. Sinkage: the undisturbed surface
//! ([`surface_level`] of the settled bed) minus the wheel's lowest point \[m\].
//!
//! **The bed.** A slice periodic along z (the wheel's axis), walls at `y = 0` and at both ends
//! of the track; the wheel spans the slice (its cylinder is 4 grain radii longer than the
//! period, so no grain sees an end cap): a wheel infinitely wide against a grain-scale bed,
//! plane strain, no side walls. Gravity is raised to `100 m/s^2` ("centrifuge" scaling, which
//! keeps the grains rigid, `rho g d / G ~ 2e-4` with the default 5 MPa grains, and lets the bed settle and the wheel run
//! fast at a small Froude number `Fr = w^2 R / g`); forces are reported in newtons and as the
//! dimensionless coefficients `DP/W` and `T/(W R)` the literature plots.
//!
//! **Reuse.** [`settle`] settles the bed once; [`SettledBed::land`] sets the wheel on it and lets
//! it sink at rest, once per contact model (the settled state cloned, the grains' material
//! table switched by [`creep_dem::Dem::set_table`]); [`Landed::drive`] drives a clone of the
//! landed state at one slip. Every slip and both contact models start from the same grains.
//!
//! **Steady state.** The drive is split in quarters; the steady values are the means over the
//! last half, and [`WheelSteady`] carries how steady they are: the change from the third to the
//! fourth quarter of each quantity and the sinkage rate (least squares over the last half).

use creep_dem::{Dem, MaterialTable, TangentialLaw};
use creep_law::{CreepModel, Material, Vec3};
use rapier3d::glamx::{Quat, Vec3 as FVec3};
use rapier3d::prelude::*;

use crate::scene::{BedSpec, highest_under};
use crate::{Bed, BedConfig, BedError};

/// The wheel scene's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelOnSand {
    /// The bed (`counts[0]` along the travel, `counts[2]` across: the period along z).
    pub bed: BedSpec,
    /// Wheel radius in grain radii [-].
    pub radius_factor: f64,
    /// Wheel density \[kg/m^3\] (its mass is `density pi R^2` times its length).
    pub density: f64,
    /// Spin \[rad/s\].
    pub spin: f64,
    /// DEM steps per game step.
    pub substeps: usize,
    /// Steps to settle the bed (at most).
    pub settle_steps: usize,
    /// Game steps the wheel sinks in at rest before driving.
    pub sink_steps: usize,
    /// Game steps driven.
    pub drive_steps: usize,
}

/// Grains per lattice column of [`WheelOnSand::with_grains`] (10 layers, 8 across).
const COLUMN: usize = 80;

impl WheelOnSand {
    /// A bed of about `grains` grains (10 layers before settling, 8 across the periodic slice,
    /// the rest along the travel), radius 2 mm (uniform in `[1.6, 2]` mm), shear modulus 5 MPa
    /// (soft, for a long DEM step, `dt = 2.46e-5 s`; Hertz's overlap for 0.5 N on a grain
    /// under the wheel is ~4 % of its radius), a wheel of 10 grain radii (20 mm), density 1000 kg/m^3, spin 5 rad/s
    /// (`Fr = 0.005`), 20 DEM steps per game step, 200 game steps sinking in, 1000 driven
    /// (0.49 s). At least 8 columns: `grains` below 640 give 640.
    pub fn with_grains(grains: usize) -> Result<Self, BedError> {
        if grains == 0 {
            return Err(BedError::Parameter {
                name: "grains",
                value: 0.0,
                why: "at least one grain",
            });
        }
        let nx = (grains / COLUMN).max(8);
        Ok(Self {
            bed: BedSpec {
                counts: [nx, 10, 8],
                shear_modulus: 5e6,
                gravity: 100.0,
                periodic_z: true,
                ..BedSpec::default()
            },
            radius_factor: 10.0,
            density: 1000.0,
            spin: 5.0,
            substeps: 20,
            settle_steps: 60_000,
            sink_steps: 200,
            drive_steps: 1000,
        })
    }

    /// Wheel radius \[m\].
    pub fn wheel_radius(&self) -> f64 {
        self.radius_factor * self.bed.radius
    }

    /// Game step \[s\].
    pub fn dt_rigid(&self) -> Result<f64, BedError> {
        Ok(self.bed.dt()? * self.substeps as f64)
    }

    /// Where the wheel's axle starts along x \[m\]: 1.5 wheel radii from the end wall.
    pub fn start_x(&self) -> f64 {
        1.5 * self.wheel_radius()
    }

    /// Distance the axle travels in the drive at slip 0 \[m\].
    pub fn longest_travel(&self) -> Result<f64, BedError> {
        Ok(self.spin * self.wheel_radius() * self.drive_steps as f64 * self.dt_rigid()?)
    }

    fn check(&self) -> Result<(), BedError> {
        let bad = |name, value, why| Err(BedError::Parameter { name, value, why });
        if !(self.radius_factor.is_finite() && self.radius_factor > 2.0) {
            return bad(
                "radius_factor",
                self.radius_factor,
                "must be finite and > 2",
            );
        }
        if !(self.density.is_finite() && self.density > 0.0) {
            return bad("density", self.density, "must be finite and > 0 [kg/m^3]");
        }
        if !(self.spin.is_finite() && self.spin > 0.0) {
            return bad("spin", self.spin, "must be finite and > 0 [rad/s]");
        }
        if self.substeps == 0 {
            return bad("substeps", 0.0, "at least one DEM step per game step");
        }
        if self.drive_steps < 4 {
            return bad(
                "drive_steps",
                self.drive_steps as f64,
                "at least 4 (the steady state is judged on quarters)",
            );
        }
        if !self.bed.periodic_z {
            return bad(
                "bed.periodic_z",
                0.0,
                "the wheel spans a periodic slice: periodic_z must be true",
            );
        }
        let (lx, _) = self.bed.footprint();
        let end = self.start_x() + self.longest_travel()? + 1.5 * self.wheel_radius();
        if end > lx {
            return bad(
                "drive_steps",
                self.drive_steps as f64,
                "the wheel would reach the far wall at slip 0: more grains (a longer bed) or fewer steps",
            );
        }
        Ok(())
    }

    /// The wheel's (boundary's) material: steel-like moduli, friction 0.5, the wheel's density.
    fn wheel_material(&self) -> Result<Material, BedError> {
        Ok(Material::new(79.3e6, 0.29, 0.5, self.density).map_err(creep_dem::DemError::from)?)
    }

    /// The engine's material table with `creep` at every contact.
    fn table(&self, creep: Option<CreepModel>) -> Result<MaterialTable, BedError> {
        Ok(MaterialTable::new(
            &[self.bed.material()?, self.wheel_material()?],
            self.bed.restitution,
            creep,
            None,
        )?)
    }

    /// A Rapier world with the wheel (a cylinder about z spanning the slice) at `pose`.
    fn world(&self, pose: Pose, linvel: FVec3, angvel: FVec3) -> Result<Wheel, BedError> {
        let mut world = PhysicsWorld {
            gravity: FVec3::new(0.0, -self.bed.gravity as f32, 0.0),
            ..Default::default()
        };
        world.integration_parameters.dt = self.dt_rigid()? as f32;
        let body = world
            .bodies
            .insert(RigidBodyBuilder::dynamic().can_sleep(false).build());
        let rb = &mut world.bodies[body];
        rb.set_position(pose, true);
        rb.set_linvel(linvel, true);
        rb.set_angvel(angvel, true);
        let (_, lz) = self.bed.footprint();
        let half = 0.5 * lz + 2.0 * self.bed.radius;
        // Rapier's cylinder is about y: turn it about x so that its axis is z.
        let collider = world.colliders.insert_with_parent(
            ColliderBuilder::cylinder(half as f32, self.wheel_radius() as f32)
                .rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2).to_scaled_axis())
                .density(self.density as f32)
                .build(),
            body,
            &mut world.bodies,
        );
        Ok(Wheel {
            world,
            body,
            collider,
        })
    }
}

struct Wheel {
    world: PhysicsWorld,
    body: RigidBodyHandle,
    collider: ColliderHandle,
}

impl Wheel {
    /// Prescribes the forward speed `v` \[m/s\] and the spin `w` \[rad/s\] (about -z); the
    /// vertical speed is left to the bed and gravity. Called before the bed's step (the grains
    /// see the prescribed motion) and after it (Rapier integrates the prescribed motion, the
    /// bed's impulse moving the wheel only vertically).
    fn drive(&mut self, v: f64, w: f64) {
        let rb = &mut self.world.bodies[self.body];
        let vy = rb.linvel().y;
        rb.set_linvel(FVec3::new(v as f32, vy, 0.0), true);
        rb.set_angvel(FVec3::new(0.0, 0.0, -w as f32), true);
    }
    fn height(&self) -> f64 {
        f64::from(self.world.bodies[self.body].translation().y)
    }
}

/// The level of a bed's free surface \[m\]: the grains binned in columns of one grain diameter
/// (2 `r_max`) in x and z, the mean over the columns of the highest grain top in each; the
/// columns within `margin` \[m\] of the end walls (x) are left out.
pub fn surface_level<T: TangentialLaw>(dem: &Dem<T>, lx: f64, margin: f64) -> f64 {
    let d = 2.0 * dem.radii().iter().copied().fold(0.0, f64::max);
    if !(d > 0.0) {
        return 0.0;
    }
    let zmin = dem.positions().iter().map(|x| x.z).fold(f64::MAX, f64::min);
    let zmax = dem.positions().iter().map(|x| x.z).fold(f64::MIN, f64::max);
    let nx = ((lx / d).ceil() as usize).max(1);
    let nz = (((zmax - zmin) / d).ceil() as usize).max(1);
    let mut top = vec![f64::NEG_INFINITY; nx * nz];
    for (x, r) in dem.positions().iter().zip(dem.radii()) {
        if x.x < margin || x.x > lx - margin {
            continue;
        }
        let i = ((x.x / d) as usize).min(nx - 1);
        let k = (((x.z - zmin) / d) as usize).min(nz - 1);
        let t = &mut top[i * nz + k];
        *t = t.max(x.y + r);
    }
    let (sum, n) = top
        .iter()
        .filter(|t| t.is_finite())
        .fold((0.0, 0usize), |(s, n), t| (s + t, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// A settled bed, reused for every slip and contact model.
#[derive(Debug, Clone)]
pub struct SettledBed<T: TangentialLaw> {
    spec: WheelOnSand,
    dem: Dem<T>,
    /// The undisturbed surface level ([`surface_level`]) \[m\].
    pub surface: f64,
    /// DEM steps the settling took.
    pub settle_steps: usize,
}

/// Builds the bed of `s` (with Kuhn's creep at the grain contacts while settling) and settles
/// it.
pub fn settle<T: TangentialLaw>(s: &WheelOnSand) -> Result<SettledBed<T>, BedError> {
    s.check()?;
    let mut bed = s.bed;
    bed.creep = Some(CreepModel::Kuhn);
    let mut dem = bed.engine::<T>(s.wheel_material()?)?;
    let settle_steps = bed.settle(&mut dem, s.settle_steps)?;
    let (lx, _) = bed.footprint();
    let surface = surface_level(&dem, lx, 2.0 * bed.radius);
    Ok(SettledBed {
        spec: *s,
        dem,
        surface,
        settle_steps,
    })
}

impl<T: TangentialLaw> SettledBed<T> {
    /// Grains in the bed.
    pub fn grains(&self) -> usize {
        self.dem.len()
    }
    /// The settings.
    pub fn spec(&self) -> &WheelOnSand {
        &self.spec
    }

    /// Sets the wheel just above the highest grain under it and lets it sink at rest for
    /// `sink_steps` game steps, with `creep` at every contact (`None`: Coulomb-Mindlin only).
    pub fn land(&self, creep: Option<CreepModel>) -> Result<Landed<T>, BedError> {
        let s = &self.spec;
        let mut dem = self.dem.clone();
        dem.set_table(s.table(creep)?)?;
        let rw = s.wheel_radius();
        let r = s.bed.radius;
        let (_, lz) = s.bed.footprint();
        let x0 = s.start_x();
        let start = highest_under(
            &dem,
            Vec3::new(x0, 0.0, 0.5 * lz),
            Vec3::new(rw + r, 0.0, lz),
        );
        let pose = Pose::from_translation(FVec3::new(
            x0 as f32,
            (start + rw + 0.02 * r) as f32,
            (0.5 * lz) as f32,
        ));
        let mut wheel = s.world(pose, FVec3::ZERO, FVec3::ZERO)?;
        let mut bed = Bed::new(dem, BedConfig { skin: 0.2 * r })?;
        bed.add_boundary(
            wheel.collider,
            1,
            &wheel.world.bodies,
            &wheel.world.colliders,
        )?;
        let dt_rigid = s.dt_rigid()?;
        for _ in 0..s.sink_steps {
            wheel.drive(0.0, 0.0);
            bed.step(dt_rigid, &mut wheel.world.bodies)?;
            // The carriage and the motor hold the prescribed motion against the bed's impulse.
            wheel.drive(0.0, 0.0);
            wheel.world.step();
        }
        let rb = &wheel.world.bodies[wheel.body];
        Ok(Landed {
            spec: *s,
            creep,
            surface: self.surface,
            bed,
            pose: *rb.position(),
            linvel: rb.linvel(),
            angvel: rb.angvel(),
            weight: f64::from(rb.mass()) * s.bed.gravity,
        })
    }
}

/// The wheel landed on the bed with one contact model, reused for every slip.
#[derive(Debug, Clone)]
pub struct Landed<T: TangentialLaw> {
    spec: WheelOnSand,
    creep: Option<CreepModel>,
    surface: f64,
    bed: Bed<T>,
    pose: Pose,
    linvel: FVec3,
    angvel: FVec3,
    /// The wheel's weight `m g` \[N\] (Rapier's f32 mass).
    pub weight: f64,
}

/// One row of the wheel's time series.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelRow {
    /// Time since the drive started \[s\].
    pub t: f64,
    /// Slip ratio [-].
    pub slip: f64,
    /// Sinkage: the undisturbed surface minus the wheel's lowest point \[m\].
    pub sinkage: f64,
    /// Drawbar pull: the grains' force on the wheel along +x, mean over the game step \[N\].
    pub drawbar_pull: f64,
    /// Driving torque (the grains' torque on the wheel about its axle along +z), mean over the
    /// game step \[N m\].
    pub torque: f64,
}

/// The steady state of one drive (module docs: how steady is judged).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelSteady {
    /// Slip ratio [-].
    pub slip: f64,
    /// Whether creep-friction acted at the grain contacts.
    pub creep: bool,
    /// Mean sinkage over the last half of the drive \[m\].
    pub sinkage: f64,
    /// Mean drawbar pull over the last half \[N\].
    pub drawbar_pull: f64,
    /// Mean driving torque over the last half \[N m\].
    pub torque: f64,
    /// The wheel's weight \[N\].
    pub weight: f64,
    /// Wheel radius \[m\].
    pub radius: f64,
    /// Sinkage rate over the last half (least squares) \[m/s\].
    pub sinkage_rate: f64,
    /// Mean of the fourth quarter minus the third's: sinkage \[m\], pull \[N\], torque \[N m\].
    pub drift: [f64; 3],
    /// Distance the axle travelled during the drive \[m\].
    pub travel: f64,
    /// Duration of the drive \[s\].
    pub duration: f64,
    /// Wall-clock seconds the drive took.
    pub seconds: f64,
    /// Prescribed spin \[rad/s\].
    pub spin: f64,
    /// Prescribed forward speed `w R (1 - s)` \[m/s\].
    pub speed: f64,
}

impl WheelSteady {
    /// Drawbar pull coefficient `DP / W` [-].
    pub fn pull_coefficient(&self) -> f64 {
        self.drawbar_pull / self.weight
    }
    /// Torque coefficient `T / (W R)` [-].
    pub fn torque_coefficient(&self) -> f64 {
        self.torque / (self.weight * self.radius)
    }
    /// Mean power the wheel puts into the bed \[W\]: the motor's `T w`, the carriage's
    /// `-DP v` (it holds the speed against the pull `DP`) and gravity's `W dz/dt` (the wheel
    /// sinking at the sinkage rate). In a steady state the bed dissipates it: it must be
    /// `>= 0`. A negative torque (the bed turning the wheel forward) is allowed when the
    /// carriage pushes the wheel (`DP < 0`): the towed-wheel part of the power.
    pub fn power(&self) -> f64 {
        self.torque * self.spin - self.drawbar_pull * self.speed + self.weight * self.sinkage_rate
    }
}

/// The steady values of `rows` (module docs).
pub fn steady(rows: &[WheelRow]) -> Option<([f64; 3], [f64; 3], f64)> {
    let n = rows.len();
    if n < 4 {
        return None;
    }
    let mean = |a: usize, b: usize| {
        let k = (b - a) as f64;
        let s = rows[a..b].iter().fold([0.0; 3], |s, r| {
            [s[0] + r.sinkage, s[1] + r.drawbar_pull, s[2] + r.torque]
        });
        [s[0] / k, s[1] / k, s[2] / k]
    };
    let (h, q3) = (n / 2, 3 * n / 4);
    let m = mean(h, n);
    let (a, b) = (mean(h, q3), mean(q3, n));
    // Least-squares slope of the sinkage against time over the last half.
    let w = &rows[h..];
    let k = w.len() as f64;
    let tm = w.iter().map(|r| r.t).sum::<f64>() / k;
    let zm = w.iter().map(|r| r.sinkage).sum::<f64>() / k;
    let (num, den) = w.iter().fold((0.0, 0.0), |(p, q), r| {
        (p + (r.t - tm) * (r.sinkage - zm), q + (r.t - tm).powi(2))
    });
    let rate = if den > 0.0 { num / den } else { 0.0 };
    Some((m, [b[0] - a[0], b[1] - a[1], b[2] - a[2]], rate))
}

impl<T: TangentialLaw> Landed<T> {
    /// Whether creep acts at the grain contacts.
    pub fn creep(&self) -> Option<CreepModel> {
        self.creep
    }

    /// Drives a clone of the landed state at slip `slip` in `[0, 1)` for `drive_steps` game
    /// steps; `row` is called after every game step. Returns the steady state.
    pub fn drive(&self, slip: f64, mut row: impl FnMut(WheelRow)) -> Result<WheelSteady, BedError> {
        let mut d = self.start(slip)?;
        for _ in 0..self.spec.drive_steps {
            row(d.step()?);
        }
        d.finish()
    }

    /// Starts a drive at slip `slip` in `[0, 1)` from a clone of the landed state, to be
    /// advanced one game step at a time ([`Driving::step`]; what [`Landed::drive`] does
    /// `drive_steps` times), e.g. by a viewer that draws the grains between steps.
    pub fn start(&self, slip: f64) -> Result<Driving<T>, BedError> {
        if !(slip.is_finite() && (0.0..1.0).contains(&slip)) {
            return Err(BedError::Parameter {
                name: "slip",
                value: slip,
                why: "must be in [0, 1)",
            });
        }
        let s = &self.spec;
        let bed = self.bed.clone();
        let wheel = s.world(self.pose, self.linvel, self.angvel)?;
        if bed.boundaries().collider(0) != Some(wheel.collider) {
            return Err(BedError::MissingCollider(wheel.collider));
        }
        let x0 = f64::from(wheel.world.bodies[wheel.body].translation().x);
        Ok(Driving {
            spec: *s,
            creep: self.creep,
            surface: self.surface,
            weight: self.weight,
            slip,
            speed: s.spin * s.wheel_radius() * (1.0 - slip),
            dt_rigid: s.dt_rigid()?,
            clock: std::time::Instant::now(),
            bed,
            wheel,
            x0,
            rows: Vec::with_capacity(s.drive_steps),
        })
    }
}

/// A drive in progress ([`Landed::start`]): the bed and the wheel's Rapier world, advanced one
/// game step at a time.
pub struct Driving<T: TangentialLaw> {
    spec: WheelOnSand,
    creep: Option<CreepModel>,
    surface: f64,
    weight: f64,
    slip: f64,
    speed: f64,
    dt_rigid: f64,
    clock: std::time::Instant,
    bed: Bed<T>,
    wheel: Wheel,
    x0: f64,
    rows: Vec<WheelRow>,
}

impl<T: TangentialLaw> std::fmt::Debug for Driving<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Driving")
            .field("slip", &self.slip)
            .field("creep", &self.creep)
            .field("steps", &self.rows.len())
            .finish_non_exhaustive()
    }
}

impl<T: TangentialLaw> Driving<T> {
    /// The settings.
    pub fn spec(&self) -> &WheelOnSand {
        &self.spec
    }

    /// The slip ratio of this drive [-].
    pub fn slip(&self) -> f64 {
        self.slip
    }

    /// The prescribed forward speed `w R (1 - s)` \[m/s\].
    pub fn speed(&self) -> f64 {
        self.speed
    }

    /// Whether creep acts at the grain contacts.
    pub fn creep(&self) -> Option<CreepModel> {
        self.creep
    }

    /// One game step: the bed's DEM sub-steps with the wheel at its prescribed speed and spin,
    /// then Rapier's step. Returns the step's row.
    pub fn step(&mut self) -> Result<WheelRow, BedError> {
        let (v, w) = (self.speed, self.spec.spin);
        self.wheel.drive(v, w);
        self.bed.step(self.dt_rigid, &mut self.wheel.world.bodies)?;
        // The carriage and the motor hold the prescribed speed and spin: the bed's impulse
        // along x and its torque impulse are theirs to absorb (the pull and the torque the
        // scene reports); only the vertical part moves the wheel. Without this Rapier
        // would integrate `v + J/m`, and the wheel would travel slower than prescribed
        // (at slip 0 and a pull of -0.36 W, 16 % slower: an actual slip of 0.16).
        self.wheel.drive(v, w);
        let e = self.bed.boundaries().exchange(0).unwrap_or_default();
        self.wheel.world.step();
        let r = WheelRow {
            t: (self.rows.len() + 1) as f64 * self.dt_rigid,
            slip: self.slip,
            sinkage: self.surface - (self.wheel.height() - self.spec.wheel_radius()),
            drawbar_pull: e.mean_force.x,
            torque: e.mean_torque.z,
        };
        self.rows.push(r);
        Ok(r)
    }

    /// The bed (read-only: its grains, `Bed::dem`, and the wheel's contacts,
    /// `Bed::boundaries`).
    pub fn bed(&self) -> &Bed<T> {
        &self.bed
    }

    /// The wheel's pose (Rapier's, f32): its centre and its rotation (the cylinder's axis is
    /// the body's z).
    pub fn wheel_pose(&self) -> Pose {
        *self.wheel.world.bodies[self.wheel.body].position()
    }

    /// The game steps taken so far.
    pub fn steps(&self) -> usize {
        self.rows.len()
    }

    /// The undisturbed surface level of the settled bed \[m\].
    pub fn surface(&self) -> f64 {
        self.surface
    }

    /// The wheel's weight `m g` \[N\].
    pub fn weight(&self) -> f64 {
        self.weight
    }

    /// Whether the wheel would reach the far end wall's margin (1.5 wheel radii) in the next
    /// game step: a viewer stops there.
    pub fn at_track_end(&self) -> bool {
        let (lx, _) = self.spec.bed.footprint();
        let x = f64::from(self.wheel_pose().translation.x);
        x + self.speed * self.dt_rigid > lx - 1.5 * self.spec.wheel_radius()
    }

    /// The steady state of the rows so far (module docs); an error before 4 game steps.
    pub fn finish(self) -> Result<WheelSteady, BedError> {
        let s = &self.spec;
        let x1 = f64::from(self.wheel.world.bodies[self.wheel.body].translation().x);
        let (m, drift, rate) = steady(&self.rows).ok_or(BedError::Parameter {
            name: "drive_steps",
            value: self.rows.len() as f64,
            why: "at least 4",
        })?;
        Ok(WheelSteady {
            slip: self.slip,
            creep: self.creep.is_some(),
            sinkage: m[0],
            drawbar_pull: m[1],
            torque: m[2],
            weight: self.weight,
            radius: s.wheel_radius(),
            sinkage_rate: rate,
            drift,
            travel: x1 - self.x0,
            duration: self.rows.len() as f64 * self.dt_rigid,
            seconds: self.clock.elapsed().as_secs_f64(),
            spin: s.spin,
            speed: self.speed,
        })
    }
}

/// One drive of a [`sweep`]: its steady state and its time series.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// The steady state.
    pub steady: WheelSteady,
    /// Every game step of the drive.
    pub rows: Vec<WheelRow>,
}

/// What [`sweep`] reports as it goes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Progress<'a> {
    /// The bed settled: grains, DEM steps, surface level \[m\].
    Settled(usize, usize, f64),
    /// The wheel landed with each model: its weight \[N\].
    Landed(f64),
    /// One drive finished.
    Drove(&'a WheelSteady),
}

/// The wheel scene's sweep: the bed settled once, the wheel landed once per contact model in
/// `models` (`None`: Coulomb-Mindlin only), then one drive per (model, slip), on up to `jobs`
/// threads (each drive on its own clone, so the results do not depend on `jobs`). Results in
/// the order models x slips.
pub fn sweep<T: TangentialLaw + Send + Sync>(
    s: &WheelOnSand,
    slips: &[f64],
    models: &[Option<CreepModel>],
    jobs: usize,
    progress: impl Fn(Progress<'_>) + Sync,
) -> Result<Vec<Drive>, BedError> {
    if jobs == 0 {
        return Err(BedError::Parameter {
            name: "jobs",
            value: 0.0,
            why: "at least one thread",
        });
    }
    if slips.is_empty() || models.is_empty() {
        return Err(BedError::Parameter {
            name: "slips and models",
            value: 0.0,
            why: "at least one slip ratio and one contact model",
        });
    }
    for &x in slips {
        if !(x.is_finite() && (0.0..1.0).contains(&x)) {
            return Err(BedError::Parameter {
                name: "slip",
                value: x,
                why: "must be in [0, 1)",
            });
        }
    }
    let settled = settle::<T>(s)?;
    progress(Progress::Settled(
        settled.grains(),
        settled.settle_steps,
        settled.surface,
    ));
    let landed = parallel(jobs, models.len(), |k| settled.land(models[k]))?;
    progress(Progress::Landed(landed[0].weight));
    let tasks: Vec<(usize, f64)> = (0..landed.len())
        .flat_map(|m| slips.iter().map(move |&x| (m, x)))
        .collect();
    parallel(jobs, tasks.len(), |k| {
        let (m, slip) = tasks[k];
        let mut rows = Vec::with_capacity(s.drive_steps);
        let steady = landed[m].drive(slip, |r| rows.push(r))?;
        progress(Progress::Drove(&steady));
        Ok(Drive { steady, rows })
    })
}

/// Runs `f(0..n)` on up to `jobs` scoped threads; results in index order, the first error (in
/// index order) returned.
fn parallel<R: Send>(
    jobs: usize,
    n: usize,
    f: impl Fn(usize) -> Result<R, BedError> + Sync,
) -> Result<Vec<R>, BedError> {
    use std::sync::Mutex;
    use std::sync::atomic::{AtomicUsize, Ordering};
    let next = AtomicUsize::new(0);
    let results: Mutex<Vec<Option<Result<R, BedError>>>> =
        Mutex::new((0..n).map(|_| None).collect());
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(n).max(1) {
            scope.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    if k >= n {
                        break;
                    }
                    let r = f(k);
                    if let Ok(mut g) = results.lock() {
                        g[k] = Some(r);
                    }
                }
            });
        }
    });
    let results = results.into_inner().unwrap_or_default();
    let mut out = Vec::with_capacity(n);
    for r in results {
        match r {
            Some(r) => out.push(r?),
            None => {
                return Err(BedError::Parameter {
                    name: "jobs",
                    value: jobs as f64,
                    why: "a worker thread stopped without a result",
                });
            }
        }
    }
    Ok(out)
}
