//! The angle of repose of a pile of monodisperse spheres against rolling resistance, on the
//! creep-dem engine (cheap tangential tier, f64): Coulomb-Mindlin only, Kuhn's creep-friction
//! (rolling resistance by dissipation, no contact moment), and creep plus a contact-torque
//! rolling resistance (Ai et al. 2011 type C, EPSD).
//!
//! # Protocol (a quasi-2-D column collapse onto a rough base)
//!
//! The grains form a slab periodic in `z` ([`ReposeParams::thickness`] diameters thick, so no
//! side walls touch the pile), with gravity along `-y`:
//!
//! 1. *Base*: a layer of fixed grains of the same size and material, on a square lattice of
//!    touching spheres (spacing `d = 2R`) along `x` and `z`, each lowered by a random
//!    `U(0, R/2)`: a rough, bumpy base as in Zhou et al. (2001, 2002), whose grains are fixed
//!    (see [`FixedGrains`]). Without it, monodisperse spheres without rolling resistance roll
//!    away on a flat plate and no pile forms at all.
//! 2. *Fill*: a column of `columns x layers x thickness` grains on a lattice of spacing
//!    `1.1 d` (jittered by `+-0.05 d` in `x` and `y`) falls onto the base between a back wall at
//!    `x = 0` and a gate ([`gate_x`]); it settles for [`ReposeParams::fill_time`].
//! 3. *Release*: the gate is moved away (in 20 steps, beyond the end wall); the column collapses and
//!    spreads along `+x` over the base (the granular column collapse of Lajeunesse, Mangeney-
//!    Castelnau & Vilotte 2004, Phys. Fluids 16, 2371, and Lube et al. 2005, J. Fluid Mech. 508,
//!    175; at the aspect ratios used here, height/width about 1, their deposits end in a slope
//!    at the angle of repose). An end wall catches grains that run out of the base.
//! 4. *Settle*: until the fastest mobile grain moves slower than
//!    [`ReposeParams::settle_speed`] `sqrt(g d)` at [`ReposeParams::settled_checks`] checks in
//!    a row, 200 steps apart, or until [`ReposeParams::max_time`] (then
//!    [`ReposeRun::settled`] is false).
//!
//! # The angle (the method)
//!
//! The free surface is the height of the highest mobile grain's top (`y + R`) in bins of width
//! `d` along `x` (over the whole slab thickness), above the base's nominal top `y = R`. With
//! `H` the highest bin, the slope is the contiguous run of bins from the crest (the last bin
//! at `>= 0.8 H` counted from the back wall) to the toe (the first bin after it below
//! `0.2 H`), and the angle is `atan(-b)` of the least-squares line `h = a + b x` through the bins
//! of that run with heights in `[0.2 H, 0.8 H]` (the fit of the free surface's straight part,
//! as Zhou et al. 2002 measure their piles). At least three bins are needed.
//!
//! # The reference: Zhou, Xu, Yu & Zulli (2002)
//!
//! [`zhou_correlation_deg`]: the empirical equation of Zhou, Xu, Yu & Zulli (2002, "An
//! experimental and numerical study of the angle of repose of coarse spheres", Powder Technol.
//! 125, 45-54), fitted to their DEM sandpiles of monosized spheres between two parallel walls,
//!
//! `theta = 68.61 mu_s,pw^0.27 mu_s,pp^0.22 mu_r,pw^0.06 mu_r,pp^0.12 d^-0.2` \[degrees\],
//!
//! with `mu_s` the sliding and `mu_r` the rolling friction coefficients between particles (pp)
//! and between particle and wall (pw), `mu_r` a length in mm (their rolling torque is
//! `M = mu_r P`, Zhou et al. 1999, Physica A 269, 536), `d` the diameter in mm. Caveats: (a)
//! the equation is quoted from the paper's abstract as the project knows it; the paper's text
//! was not checked, so its constants, units and range of validity
//! (the sliding and rolling coefficients, sizes and container thickness of their runs, coarse
//! spheres of millimetres) must be checked against the paper before a number here is
//! published; (b) their piles stand between two walls 4-ish diameters apart, which raise the
//! angle (the `pw` terms), while this slab is periodic: the scene takes the walls' coefficients
//! equal to the particles' (the base, which the grains touch, is made of them); (c) it is a
//! power law in `mu_r`: it gives 0 at `mu_r = 0` and has no value for Coulomb-only or
//! creep-only piles (their `correlation_deg` is `None`). The rolling coefficient of this scene
//! is the EPSD model's dimensionless `mu_r` (torque cap `mu_r R* P`), so Zhou's length is
//! `mu_r R*` with `R* = R/2` for equal spheres.
//!
//! # Results
//!
//! `creep run repose --mu M --rolling 0.1,0.3 --grains 576 --out DIR` (release build; a
//! 12 x 12 x 4 column of 576 grains on a 46 x 4 base of 184 fixed grains, every case settled;
//! 16-18 s of CPU per four cases). Angles in degrees; `mu = 0.5` with seeds 1, 2, 3 (median, range), the other
//! `mu` seed 1 only. Rolling: the EPSD `mu_r`; the correlation at `mu_r R* = 0.05` and
//! `0.15 mm`, `d = 2 mm`.
//!
//! | mu | Coulomb only | creep only | creep + mu_r = 0.1 | (Zhou) | creep + mu_r = 0.3 | (Zhou) |
//! |---|---|---|---|---|---|---|
//! | 0.3 | 24.6 | 26.1 | 22.5 | 19.3 | 30.7 | 23.5 |
//! | 0.5 | 22.0 (21.7-24.1) | 22.1 (20.8-24.6) | 28.8 (23.1-30.3) | 24.8 | 27.3 (26.6-27.4) | 30.2 |
//! | 0.7 | 21.0 | 20.4 | 25.0 | 29.2 | 28.6 | 35.6 |
//!
//! What the piles show: (1) monodisperse spheres without rolling resistance still pile on the
//! rough base, at 21-25 degrees, nearly independent of `mu` (0.3 to 0.7): the pile is limited
//! by rolling, not sliding (Zhou et al. 2001 find sliding and rolling friction together make a
//! sandpile; here the rough base lets a shallow one stand without rolling resistance). (2) Kuhn's creep-friction leaves the angle where Coulomb-Mindlin puts it
//! (22.1 against 22.0 at `mu = 0.5`, within the 3-degree scatter between seeds): it dissipates
//! while grains roll under load but exerts no moment on a grain at rest, so it cannot hold a
//! static slope steeper than the sliding-only one. (3) The contact torque steepens the pile by
//! 3-9 degrees (at `mu = 0.5`, medians: +6.8 and +5.2 degrees for `mu_r` 0.1 and 0.3), but the
//! seed scatter (up to 7 degrees at `mu_r = 0.1`) is as large as the difference between 0.1
//! and 0.3, and the angle does not grow with `mu` as the correlation's `mu^0.49` does. Against
//! Zhou et al.'s correlation the six creep + torque piles lie between -20 % and +30 %
//! (medians at `mu = 0.5`: +16 % and -10 %); the piles are 10 grains high and their slopes 10-12
//! bins long, so a single pile's angle carries a few degrees of noise, and the geometry differs
//! from Zhou's (periodic slab, not a box between two walls; a collapsed column, not a poured
//! heap). Piles of a few thousand grains and several seeds per case would be needed to test
//! the correlation's exponents.
//!
//! # Material
//!
//! Grains of radius 1 mm and density 2,500 kg/m^3 with a shear modulus of 1 MPa (`nu = 0.3`),
//! softened as DEM practice does so that the time step is affordable: the largest overlap at
//! the foot of a 3 cm pile is then `~(rho g H / E)^(2/3)`, about 0.4 % of `d`. Softening
//! matters for creep: Kuhn's creep displacement per rolling distance scales with `a/R`, i.e.
//! `(delta/R)^(1/2)`, so softer grains creep more (at 1 MPa about 6 times glass's).

use creep_dem::{
    Cheap, Dem, DemConfig, DemError, ExternalForces, ExternalView, MaterialTable, Particle, Wall,
};
use creep_law::rolling_torque::RollingModel;
use creep_law::{CreepModel, Material, Vec3};
use rand_xoshiro::SplitMix64;
use rand_xoshiro::rand_core::{Rng, SeedableRng};

use crate::SceneError;

/// Gravity [m/s^2] (along `-y`).
pub const GRAVITY: f64 = 9.81;

/// Damping ratio of the EPSD rolling dashpot [-] (Ai et al. 2011 use 0.3).
pub const EPSD_ETA: f64 = 0.3;

/// Parameters of one pile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReposeParams {
    /// Grain radius \[m\].
    pub radius: f64,
    /// Grain density [kg/m^3].
    pub density: f64,
    /// Shear modulus G \[Pa\].
    pub shear_modulus: f64,
    /// Poisson's ratio [-].
    pub poisson_ratio: f64,
    /// Sliding friction mu (grain-grain, grain-base and grain-wall) [-].
    pub mu: f64,
    /// Restitution coefficient [-] (Tsuji damping solved for it).
    pub restitution: f64,
    /// Kuhn's creep-friction at the contacts (`false`: plain Coulomb-Mindlin).
    pub creep: bool,
    /// Contact-torque rolling resistance: the EPSD model's `mu_r` [-] (torque cap `mu_r R* P`),
    /// `None` for none.
    pub rolling: Option<f64>,
    /// Grains across the column (`x`).
    pub columns: usize,
    /// Grain layers of the column (`y`).
    pub layers: usize,
    /// Slab thickness in diameters (`z`, periodic), >= 4 (creep-dem's periodic box spans at
    /// least three cells of `2 R + skin`, the skin being `0.2 d`).
    pub thickness: usize,
    /// Base length in diameters (`x`); 0: `3.5 columns + 4`.
    pub base_length: usize,
    /// Time step as a fraction of the Rayleigh time step [-].
    pub dt_fraction: f64,
    /// Time the column settles behind the gate \[s\].
    pub fill_time: f64,
    /// Settled when the fastest mobile grain is slower than this times `sqrt(g d)` [-].
    pub settle_speed: f64,
    /// Consecutive settled checks (200 steps apart) that end the run.
    pub settled_checks: usize,
    /// Longest time after the release \[s\].
    pub max_time: f64,
    /// Seed of the base's roughness and the column's jitter.
    pub seed: u64,
}

impl Default for ReposeParams {
    fn default() -> Self {
        Self {
            radius: 1e-3,
            density: 2500.0,
            shear_modulus: 1e6,
            poisson_ratio: 0.3,
            mu: 0.5,
            restitution: 0.5,
            creep: true,
            rolling: None,
            columns: 14,
            layers: 14,
            thickness: 4,
            base_length: 0,
            dt_fraction: 0.2,
            fill_time: 0.15,
            settle_speed: 0.01,
            settled_checks: 5,
            max_time: 2.0,
            seed: 1,
        }
    }
}

impl ReposeParams {
    /// A square column of about `grains` grains (`thickness` 4): `columns = layers =
    /// round(sqrt(grains / 4))`, at least 3.
    pub fn with_grains(grains: usize) -> Self {
        let n = ((grains as f64 / 4.0).sqrt().round() as usize).max(3);
        Self {
            columns: n,
            layers: n,
            ..Self::default()
        }
    }

    /// Grains in the column.
    pub fn grains(&self) -> usize {
        self.columns * self.layers * self.thickness
    }

    /// Base length in diameters.
    pub fn base_cells(&self) -> usize {
        if self.base_length == 0 {
            (3.5 * self.columns as f64).ceil() as usize + 4
        } else {
            self.base_length
        }
    }

    /// The grains' material.
    pub fn material(&self) -> Result<Material, SceneError> {
        Ok(Material::new(
            self.shear_modulus,
            self.poisson_ratio,
            self.mu,
            self.density,
        )?)
    }

    /// The time step \[s\]: [`ReposeParams::dt_fraction`] of the Rayleigh time step
    /// (creep-law's `hertz::rayleigh_time_step`, Li, Xu & Thornton 2005).
    pub fn time_step(&self) -> Result<f64, SceneError> {
        Ok(self.dt_fraction * creep_law::hertz::rayleigh_time_step(&self.material()?, self.radius))
    }

    /// Checks every field.
    pub fn validate(&self) -> Result<(), SceneError> {
        let pos = |name: &str, v: f64| crate::measure::positive(name, v).map(|_| ());
        pos("radius", self.radius)?;
        pos("density", self.density)?;
        pos("dt_fraction", self.dt_fraction)?;
        pos("fill_time", self.fill_time)?;
        pos("settle_speed", self.settle_speed)?;
        pos("max_time", self.max_time)?;
        if !(self.mu.is_finite() && self.mu >= 0.0) {
            return Err(SceneError::Parameter(format!(
                "mu must be finite and >= 0, got {}",
                self.mu
            )));
        }
        if !(self.restitution > 0.0 && self.restitution <= 1.0) {
            return Err(SceneError::Parameter(format!(
                "restitution must be in (0, 1], got {}",
                self.restitution
            )));
        }
        if let Some(r) = self.rolling {
            RollingModel::epsd(r, EPSD_ETA)?;
        }
        if self.dt_fraction > 0.5 {
            return Err(SceneError::Parameter(format!(
                "dt_fraction must be <= 0.5 of the Rayleigh time step, got {}",
                self.dt_fraction
            )));
        }
        if self.columns < 3 || self.layers < 3 || self.thickness < 4 {
            return Err(SceneError::Parameter(format!(
                "the column needs >= 3 columns, >= 3 layers and a thickness >= 4, got {} x {} x {}",
                self.columns, self.layers, self.thickness
            )));
        }
        if self.grains() > 200_000 {
            return Err(SceneError::Parameter(format!(
                "{} grains is more than this scene is meant for (200,000)",
                self.grains()
            )));
        }
        if self.base_cells() < 2 * self.columns {
            return Err(SceneError::Parameter(format!(
                "the base ({} diameters) must be at least twice the column ({} grains across)",
                self.base_cells(),
                self.columns
            )));
        }
        if self.settled_checks == 0 {
            return Err(SceneError::Parameter("settled_checks must be >= 1".into()));
        }
        self.material()?;
        Ok(())
    }
}

/// Keeps some grains fixed: an [`ExternalForces`] that replaces the force and torque on each
/// fixed grain by `-m v / dt` and `-I w / dt` (`I = (2/5) m R^2`) at the half-step velocities.
/// With velocity Verlet's two half-kicks by the same force this makes the next half-step
/// velocity exactly zero, so a fixed grain moves only once, in the first step, by the initial
/// force's `F dt^2/(2m)` (3 nm under gravity at this scene's step), and never after. Contacts
/// with fixed grains use their finite mass for the damping's effective mass.
#[derive(Debug, Clone)]
pub struct FixedGrains {
    /// Whether each particle id is fixed.
    pub fixed: Vec<bool>,
}

impl ExternalForces for FixedGrains {
    fn add_forces(&mut self, view: ExternalView<'_>) -> Result<(), DemError> {
        let inv_dt = 1.0 / view.dt;
        for k in 0..view.ids.len() {
            if self.fixed[view.ids[k] as usize] {
                let m = view.masses[k];
                let r = view.radii[k];
                view.forces[k] = view.velocities[k] * (-m * inv_dt);
                view.torques[k] = view.angular_velocities[k] * (-0.4 * m * r * r * inv_dt);
            }
        }
        Ok(())
    }
}

/// The settled free surface and the angle fitted to it.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile {
    /// Bin centres along `x` \[m\].
    pub x: Vec<f64>,
    /// Surface height of each bin above the base's top \[m\] (0 for an empty bin).
    pub height: Vec<f64>,
    /// First and one-past-last bin of the fitted run.
    pub fitted: (usize, usize),
    /// Fitted slope `dh/dx` [-].
    pub slope: f64,
    /// Angle of repose `atan(-slope)` \[degrees\].
    pub angle_deg: f64,
}

/// One pile's outcome.
#[derive(Debug, Clone, PartialEq)]
pub struct ReposeRun {
    /// The parameters it ran with.
    pub params: ReposeParams,
    /// Measured angle of repose \[degrees\].
    pub angle_deg: f64,
    /// Zhou et al.'s (2002) correlation for these coefficients \[degrees\] (`None` without a
    /// rolling torque: the power law has no value at `mu_r = 0`).
    pub correlation_deg: Option<f64>,
    /// The surface profile and fit.
    pub profile: Profile,
    /// Whether the pile met the settling criterion before `max_time`.
    pub settled: bool,
    /// Simulated time after the release \[s\].
    pub time: f64,
    /// Steps in all (fill and collapse).
    pub steps: u64,
    /// Mobile grains.
    pub grains: usize,
    /// Fixed base grains.
    pub base_grains: usize,
    /// Fastest mobile grain at the end [m/s].
    pub max_speed: f64,
}

/// Zhou, Xu, Yu & Zulli's (2002) correlation (see the module docs and its caveats):
/// `theta = 68.61 mu_s,pw^0.27 mu_s,pp^0.22 mu_r,pw^0.06 mu_r,pp^0.12 d^-0.2` \[degrees\], rolling
/// coefficients `mu_r` (lengths) and the diameter `d` in mm. Errors on a non-positive or
/// non-finite argument (the power law is 0 or undefined there).
pub fn zhou_correlation_deg(
    mu_s_pw: f64,
    mu_s_pp: f64,
    mu_r_pw_mm: f64,
    mu_r_pp_mm: f64,
    d_mm: f64,
) -> Result<f64, SceneError> {
    for (name, v) in [
        ("mu_s,pw", mu_s_pw),
        ("mu_s,pp", mu_s_pp),
        ("mu_r,pw [mm]", mu_r_pw_mm),
        ("mu_r,pp [mm]", mu_r_pp_mm),
        ("d [mm]", d_mm),
    ] {
        crate::measure::positive(name, v)?;
    }
    Ok(68.61
        * mu_s_pw.powf(0.27)
        * mu_s_pp.powf(0.22)
        * mu_r_pw_mm.powf(0.06)
        * mu_r_pp_mm.powf(0.12)
        * d_mm.powf(-0.2))
}

/// The correlation for a scene's coefficients: walls' coefficients equal to the particles',
/// Zhou's rolling length `mu_r R*` with `R* = R/2`; `None` without rolling torque or at
/// `mu = 0`.
pub fn correlation_for(p: &ReposeParams) -> Option<f64> {
    let mu_r = p.rolling?;
    let len_mm = mu_r * 0.5 * p.radius * 1e3;
    zhou_correlation_deg(p.mu, p.mu, len_mm, len_mm, 2.0 * p.radius * 1e3).ok()
}

/// The rolling coefficient (EPSD `mu_r` [-], this scene's convention) for which Zhou et al.'s
/// correlation gives `angle_deg` at sliding friction `mu` and radius `radius` \[m\]: the
/// correlation inverted, `mu_r R* = (theta / (68.61 mu^0.49 d^-0.2))^(1/0.18)` mm. A way to
/// state what rolling resistance a Coulomb-only or creep-only pile behaves like.
pub fn equivalent_rolling(angle_deg: f64, mu: f64, radius: f64) -> Result<f64, SceneError> {
    crate::measure::positive("angle", angle_deg)?;
    crate::measure::positive("mu", mu)?;
    crate::measure::positive("radius", radius)?;
    let d_mm = 2.0 * radius * 1e3;
    let len_mm = (angle_deg / (68.61 * mu.powf(0.49) * d_mm.powf(-0.2))).powf(1.0 / 0.18);
    Ok(len_mm / (0.5 * radius * 1e3))
}

fn dem_err(e: DemError) -> SceneError {
    SceneError::Parameter(format!("DEM engine: {e}"))
}

/// A uniform draw in `[0, 1)` (top 53 bits of SplitMix64, as the triaxial specimen's).
fn unit(rng: &mut SplitMix64) -> f64 {
    (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64
}

/// Index of the gate among the walls.
const GATE: usize = 1;

/// The engine with the base, the column and the walls (back wall, gate, end wall), and the
/// fixed-grain mask.
pub fn build(p: &ReposeParams) -> Result<(Dem<Cheap>, FixedGrains), SceneError> {
    p.validate()?;
    let r = p.radius;
    let d = 2.0 * r;
    let mat = p.material()?;
    let creep = p.creep.then_some(CreepModel::Kuhn);
    let rolling = match p.rolling {
        Some(mu_r) => Some(RollingModel::epsd(mu_r, EPSD_ETA)?),
        None => None,
    };
    let table = MaterialTable::new(&[mat], p.restitution, creep, rolling).map_err(dem_err)?;
    let mut rng = SplitMix64::seed_from_u64(p.seed);
    let nz = p.thickness;
    let width = nz as f64 * d;
    let nb = p.base_cells();
    let mut particles = Vec::with_capacity(nb * nz + p.grains());
    let mut fixed = Vec::with_capacity(nb * nz + p.grains());
    for i in 0..nb {
        for k in 0..nz {
            particles.push(Particle {
                position: Vec3::new(
                    (i as f64 + 0.5) * d,
                    -0.5 * r * unit(&mut rng),
                    (k as f64 + 0.5) * d,
                ),
                velocity: Vec3::ZERO,
                angular_velocity: Vec3::ZERO,
                radius: r,
                material: 0,
            });
            fixed.push(true);
        }
    }
    let s = 1.1 * d;
    for j in 0..p.layers {
        for i in 0..p.columns {
            for k in 0..nz {
                let jx = (unit(&mut rng) - 0.5) * 0.1 * d;
                let jy = (unit(&mut rng) - 0.5) * 0.1 * d;
                particles.push(Particle {
                    position: Vec3::new(
                        0.6 * d + i as f64 * s + jx,
                        1.2 * d + j as f64 * s + jy,
                        (k as f64 + 0.5) * d,
                    ),
                    velocity: Vec3::ZERO,
                    angular_velocity: Vec3::ZERO,
                    radius: r,
                    material: 0,
                });
                fixed.push(false);
            }
        }
    }
    let end_x = nb as f64 * d;
    let walls = [
        Wall {
            point: Vec3::ZERO,
            normal: Vec3::new(1.0, 0.0, 0.0),
            velocity: Vec3::ZERO,
            material: 0,
        },
        // The gate starts beyond the end wall (a half-space gate at its place would hold the
        // base grains past it inside it and kick them at the engine's first force
        // evaluation, before `FixedGrains` acts); [`run`] closes it.
        Wall {
            point: Vec3::new(end_x + d, 0.0, 0.0),
            normal: Vec3::new(-1.0, 0.0, 0.0),
            velocity: Vec3::ZERO,
            material: 0,
        },
        Wall {
            point: Vec3::new(end_x, 0.0, 0.0),
            normal: Vec3::new(-1.0, 0.0, 0.0),
            velocity: Vec3::ZERO,
            material: 0,
        },
    ];
    let cfg = DemConfig {
        dt: p.time_step()?,
        skin: 0.2 * d,
        periodic: [None, None, Some((0.0, width))],
        gravity: Vec3::new(0.0, -GRAVITY, 0.0),
        parallel: false,
    };
    let dem = Dem::<Cheap>::new(cfg, table, &particles, &walls).map_err(dem_err)?;
    Ok((dem, FixedGrains { fixed }))
}

/// Where the gate stands during the fill \[m\]: 0.6 d beyond the column's last lattice
/// centre.
pub fn gate_x(p: &ReposeParams) -> f64 {
    let d = 2.0 * p.radius;
    0.6 * d + (p.columns as f64 - 1.0) * 1.1 * d + 0.6 * d
}

/// Moves the gate to `x` in [`GATE_STEPS`] steps, then stops it.
fn move_gate(dem: &mut Dem<Cheap>, fixed: &mut FixedGrains, x: f64) -> Result<(), SceneError> {
    let dt = dem.config().dt;
    let v = (x - dem.walls()[GATE].point.x) / (GATE_STEPS as f64 * dt);
    dem.set_wall_velocity(GATE, Vec3::new(v, 0.0, 0.0))
        .map_err(dem_err)?;
    for _ in 0..GATE_STEPS {
        dem.step_with(fixed).map_err(dem_err)?;
    }
    dem.set_wall_velocity(GATE, Vec3::ZERO).map_err(dem_err)
}

/// Steps the gate takes to close or open.
pub const GATE_STEPS: usize = 20;

/// Fastest mobile grain [m/s].
fn max_speed(dem: &Dem<Cheap>, fixed: &FixedGrains) -> f64 {
    dem.velocities()
        .iter()
        .zip(dem.ids())
        .filter(|(_, id)| !fixed.fixed[**id as usize])
        .map(|(v, _)| v.length())
        .fold(0.0, f64::max)
}

/// Steps between settling checks.
const CHECK_EVERY: usize = 200;

/// Runs one pile: fill, release, settle, measure (module docs). `progress` gets the fraction
/// of `max_time` done after each check.
pub fn run(p: &ReposeParams, progress: &mut dyn FnMut(f64)) -> Result<ReposeRun, SceneError> {
    run_observed(p, progress, &mut |_, _| Ok(()))
}

/// What [`run_observed`] calls with the engine (and whether the pile has settled).
pub type ReposeObserver<'a> = dyn FnMut(&Dem<Cheap>, bool) -> Result<(), SceneError> + 'a;

/// [`run`], calling `observe(engine, false)` before the first step and after every step, and
/// `observe(engine, true)` once more with the settled pile (e.g. to write snapshots).
pub fn run_observed(
    p: &ReposeParams,
    progress: &mut dyn FnMut(f64),
    observe: &mut ReposeObserver<'_>,
) -> Result<ReposeRun, SceneError> {
    let (mut dem, mut fixed) = build(p)?;
    observe(&dem, false)?;
    let dt = dem.config().dt;
    // Close the gate (the column's grains fall 2 um meanwhile), fill, release: the gate
    // leaves past the end wall.
    let open = dem.walls()[GATE].point.x;
    move_gate(&mut dem, &mut fixed, gate_x(p))?;
    let fill_steps = (p.fill_time / dt).ceil() as usize;
    for _ in 0..fill_steps {
        dem.step_with(&mut fixed).map_err(dem_err)?;
        observe(&dem, false)?;
    }
    move_gate(&mut dem, &mut fixed, open)?;
    let t0 = dem.time();
    let tol = p.settle_speed * (GRAVITY * 2.0 * p.radius).sqrt();
    let mut calm = 0;
    let mut settled = false;
    let mut vmax = f64::INFINITY;
    while dem.time() - t0 < p.max_time {
        for _ in 0..CHECK_EVERY {
            dem.step_with(&mut fixed).map_err(dem_err)?;
            observe(&dem, false)?;
        }
        vmax = max_speed(&dem, &fixed);
        progress(((dem.time() - t0) / p.max_time).min(1.0));
        if vmax < tol {
            calm += 1;
            if calm >= p.settled_checks {
                settled = true;
                break;
            }
        } else {
            calm = 0;
        }
    }
    observe(&dem, true)?;
    let profile = surface_profile(&dem, &fixed, p)?;
    let grains = fixed.fixed.iter().filter(|f| !**f).count();
    Ok(ReposeRun {
        params: *p,
        angle_deg: profile.angle_deg,
        correlation_deg: correlation_for(p),
        profile,
        settled,
        time: dem.time() - t0,
        steps: dem.steps(),
        grains,
        base_grains: fixed.fixed.len() - grains,
        max_speed: vmax,
    })
}

/// The free surface of the pile and the fitted angle (module docs, "The angle").
pub fn surface_profile(
    dem: &Dem<Cheap>,
    fixed: &FixedGrains,
    p: &ReposeParams,
) -> Result<Profile, SceneError> {
    let d = 2.0 * p.radius;
    let nb = p.base_cells();
    let mut height = vec![0.0f64; nb];
    for ((x, r), id) in dem.positions().iter().zip(dem.radii()).zip(dem.ids()) {
        if fixed.fixed[*id as usize] {
            continue;
        }
        let b = (x.x / d).floor();
        if !(b >= 0.0 && (b as usize) < nb) {
            continue;
        }
        let top = x.y + r - p.radius;
        let h = &mut height[b as usize];
        *h = h.max(top);
    }
    let x: Vec<f64> = (0..nb).map(|i| (i as f64 + 0.5) * d).collect();
    let top = height.iter().copied().fold(0.0, f64::max);
    let (hi, lo) = (0.8 * top, 0.2 * top);
    // Crest: the last bin >= 0.8 H before the first bin below 0.2 H (after the highest bin).
    let peak = height.iter().position(|&h| h == top).unwrap_or(0);
    let toe = (peak..nb).find(|&i| height[i] < lo).unwrap_or(nb);
    let crest = (peak..toe).rev().find(|&i| height[i] >= hi).unwrap_or(peak);
    let run: Vec<usize> = (crest..toe)
        .filter(|&i| height[i] >= lo && height[i] <= hi)
        .collect();
    if run.len() < 3 || !(top > 0.0) {
        return Err(SceneError::Parameter(format!(
            "repose: the pile's slope spans {} bins (at least 3 needed; pile height {top:.3e} m)",
            run.len()
        )));
    }
    let n = run.len() as f64;
    let mx = run.iter().map(|&i| x[i]).sum::<f64>() / n;
    let my = run.iter().map(|&i| height[i]).sum::<f64>() / n;
    let sxy: f64 = run.iter().map(|&i| (x[i] - mx) * (height[i] - my)).sum();
    let sxx: f64 = run.iter().map(|&i| (x[i] - mx).powi(2)).sum();
    let slope = sxy / sxx;
    Ok(Profile {
        x,
        height,
        fitted: (run[0], run[run.len() - 1] + 1),
        slope,
        angle_deg: (-slope).atan().to_degrees(),
    })
}

/// The cases of the study at sliding friction `mu`: Coulomb only, creep only, and creep plus
/// EPSD rolling resistance at each of `rolling` ([`ReposeParams::rolling`]).
pub fn cases(base: &ReposeParams, mu: f64, rolling: &[f64]) -> Vec<ReposeParams> {
    let mut v = vec![
        ReposeParams {
            mu,
            creep: false,
            rolling: None,
            ..*base
        },
        ReposeParams {
            mu,
            creep: true,
            rolling: None,
            ..*base
        },
    ];
    for &r in rolling {
        v.push(ReposeParams {
            mu,
            creep: true,
            rolling: Some(r),
            ..*base
        });
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn correlation_matches_hand_value_and_refuses_zero() {
        // 68.61 * 0.5^0.49 * 0.05^0.18 * 2^-0.2, by hand: 24.81 degrees.
        let t = zhou_correlation_deg(0.5, 0.5, 0.05, 0.05, 2.0).unwrap();
        let by_hand = 68.61 * 0.5f64.powf(0.49) * 0.05f64.powf(0.18) * 2f64.powf(-0.2);
        assert!((t - by_hand).abs() < 1e-12);
        assert!((t - 24.81).abs() < 0.01, "{t}");
        assert!(zhou_correlation_deg(0.5, 0.5, 0.0, 0.05, 2.0).is_err());
        assert!(zhou_correlation_deg(0.5, f64::NAN, 0.05, 0.05, 2.0).is_err());
        // The inversion gives back the rolling coefficient.
        let p = ReposeParams {
            rolling: Some(0.1),
            ..Default::default()
        };
        let c = correlation_for(&p).unwrap();
        let back = equivalent_rolling(c, p.mu, p.radius).unwrap();
        assert!((back - 0.1).abs() < 1e-9, "{back}");
    }

    #[test]
    fn invalid_parameters_are_typed_errors() {
        for p in [
            ReposeParams {
                mu: -0.1,
                ..Default::default()
            },
            ReposeParams {
                rolling: Some(-1.0),
                ..Default::default()
            },
            ReposeParams {
                columns: 2,
                ..Default::default()
            },
            ReposeParams {
                thickness: 3,
                ..Default::default()
            },
            ReposeParams {
                radius: f64::NAN,
                ..Default::default()
            },
            ReposeParams {
                base_length: 5,
                ..Default::default()
            },
        ] {
            assert!(matches!(
                p.validate(),
                Err(SceneError::Parameter(_) | SceneError::Law(_))
            ));
        }
    }

    #[test]
    fn fixed_grains_stay_put() {
        let p = ReposeParams {
            columns: 3,
            layers: 3,
            thickness: 4,
            base_length: 8,
            ..Default::default()
        };
        let (mut dem, mut fixed) = build(&p).unwrap();
        let before: Vec<Vec3> = (0..fixed.fixed.len())
            .map(|id| dem.particle(id).position)
            .collect();
        for _ in 0..2000 {
            dem.step_with(&mut fixed).unwrap();
        }
        let dt = dem.config().dt;
        for (id, x0) in before.iter().enumerate() {
            let moved = (dem.particle(id).position - *x0).length();
            if fixed.fixed[id] {
                // Only the first step's g dt^2/2 (plus contact forces of the first step: none).
                assert!(moved <= 0.51 * GRAVITY * dt * dt, "{id}: {moved}");
            } else {
                assert!(moved > 1e-4, "mobile grain {id} did not fall: {moved}");
            }
        }
    }
}
