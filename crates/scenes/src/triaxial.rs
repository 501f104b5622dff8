//! The talk's drained triaxial compression of a dense packing of spheres, in the compliant
//! (soft-sphere DEM) regime of creep-rapier, once with Coulomb-Mindlin contacts and once with
//! Kuhn's creep-friction, from the same packing.
//!
//! # The test
//! 1. **Generation**: `n^3` spheres (4,096 by default) on a cubic lattice with a small random
//!    jitter, radii uniform in `[r (1 - s), r (1 + s)]` (default `s = 0.2`: a 1.5:1 size ratio,
//!    enough to prevent crystallisation), no initial overlap, zero gravity, inside six
//!    frictionless walls (kinematic cuboids; friction 0 with Rapier's `Min` combine rule, so the
//!    ball-wall pairs are frictionless whatever the balls' friction).
//! 2. **Isotropic compaction**: frictionless balls (`mu = 0`, which gives the densest random
//!    packing the walls can make), all six walls servo-controlled to the confining pressure
//!    `p0`, until every wall stress is within 1 % of `p0` and the packing's kinetic energy has
//!    decayed (see [`compact`]).
//! 3. **Shear** (drained, constant lateral stress): the balls get their friction `mu`; the top
//!    and bottom walls approach at a constant axial strain rate, the four lateral walls keep
//!    `p0` by servo control, to 20 % axial strain; run twice from the same packing, with
//!    `CompliantSettings::creep` off (Coulomb-Mindlin) and on (Kuhn 2011's creep-friction).
//!
//! # Quasi-static
//! The strain rate comes from the inertial number `I = eps_dot d sqrt(rho / p0)` (GDR MiDi 2004,
//! eq. 3; `d` the mean diameter): default `I = 8e-4`; below ~1e-3 the response is rate
//! independent (GDR MiDi 2004; da Cruz et al. 2005). The time step is a fraction of the Rayleigh time of the smallest ball (the
//! compliant regime's check, creep-law `hertz::rayleigh_time_step`), so the number of steps of
//! a shear is `0.2 / (eps_dot dt)`, which grows as `sqrt(G / p0)`: the default material is a
//! softened glass (G = 29 MPa, `G / p0 = 290`), with overlaps of ~2 % of the diameter. DEM
//! practice softens the particles (e.g. Thornton 2000 used a reduced modulus) because the
//! quasi-static response depends on stiffness only through the overlap.
//!
//! # Stress
//! * Walls: `sigma_i = (F_i+ + F_i-) / (2 A_i)` with `F` the normal forces on the two walls of
//!   axis `i` and `A_i` the current face area.
//! * Contacts (Love 1927, Weber 1966; Christoffersen, Mehrabadi & Nemat-Nasser 1981):
//!   `sigma = -(1/V) sum_particles sum_contacts (x_c - x_p) (x) f_c`, `V` the box volume,
//!   compression positive. In static equilibrium the two agree exactly (up to the contact
//!   points lying half an overlap inside the walls); their difference measures the packing's
//!   inertia.
//!
//! Axial strain `eps_a = (H0 - H) / H0`, volumetric strain `eps_v = (V0 - V) / V0` (compression
//! positive: dilation makes it fall), `p = (sigma_1 + 2 sigma_3) / 3`, `q = sigma_1 - sigma_3`
//! with `sigma_3` the mean lateral stress. Peak friction angle `sin phi = (sigma_1 - sigma_3) /
//! (sigma_1 + sigma_3)`; dilatancy rate `D = -d eps_v / d eps_a` and angle
//! `sin psi = D / (2 + D)` (triaxial compression, e.g. Bolton 1986).

use creep_law::Material;
use creep_rapier::{
    CompliantRegime, CompliantSettings, CreepHooks, CreepMaterial, CreepSettings, CreepWorld,
    Fidelity, RayleighCheck, clone_physics,
};
use rapier3d::prelude::*;

use crate::SceneError;

/// Parameters of the triaxial test (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriaxialParams {
    /// Spheres per lattice side (`n^3` spheres), in `[2, 40]`.
    pub n_per_side: usize,
    /// Mean radius \[m\], > 0.
    pub radius: f64,
    /// Half-width of the uniform radius distribution relative to the mean, in `[0, 0.5]`.
    pub radius_spread: f64,
    /// Ball (and wall) material: shear modulus, Poisson's ratio, density.
    pub material: Material,
    /// Ball-ball friction coefficient of the shear, in `[0, 10]`.
    pub mu: f64,
    /// Restitution coefficient of every contact (sets the normal damping), in `[0.05, 1]`.
    pub restitution: f64,
    /// Confining pressure `p0` \[Pa\], > 0.
    pub confining_pressure: f64,
    /// Inertial number of the shear (sets the axial strain rate), in `(0, 0.1]`.
    pub inertial_number: f64,
    /// Final axial strain [-], in `(0, 0.5]`.
    pub axial_strain: f64,
    /// Time step as a fraction of the smallest Rayleigh time, in `(0, 0.3]`.
    pub rayleigh_fraction: f64,
    /// Seed of the packing's generator.
    pub seed: u64,
    /// Rows recorded per 1 % of axial strain (>= 1).
    pub rows_per_percent: usize,
}

impl Default for TriaxialParams {
    /// The default test: 4,096 softened-glass spheres of mean radius 1 mm (radii +-20 %),
    /// G = 29 MPa, nu = 0.2, rho = 2,500 kg/m^3, mu = 0.5, e = 0.5, p0 = 100 kPa, I = 8e-4,
    /// 20 % axial strain, dt = 0.2 T_R (the repository's `assets/triaxial.conf`).
    fn default() -> Self {
        Self {
            n_per_side: 16,
            radius: 1e-3,
            radius_spread: 0.2,
            material: Material::new(29e6, 0.2, 0.5, 2500.0).expect("valid constants"),
            mu: 0.5,
            restitution: 0.5,
            confining_pressure: 100e3,
            inertial_number: 8e-4,
            axial_strain: 0.2,
            rayleigh_fraction: 0.2,
            seed: 2011,
            rows_per_percent: 4,
        }
    }
}

impl TriaxialParams {
    /// The `--quick` size for smoke tests: 7^3 = 343 spheres, the shear to 10 % at I = 5e-3
    /// (outside the quasi-static range: a smoke test, not a result).
    pub fn quick() -> Self {
        Self {
            n_per_side: 7,
            inertial_number: 5e-3,
            axial_strain: 0.1,
            rows_per_percent: 2,
            ..Self::default()
        }
    }

    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<(), SceneError> {
        let check = |name: &str, v: f64, lo: f64, hi: f64, open_lo: bool| {
            let ok = v.is_finite() && v <= hi && if open_lo { v > lo } else { v >= lo };
            if ok {
                Ok(())
            } else {
                let bracket = if open_lo { "(" } else { "[" };
                Err(SceneError::Parameter(format!(
                    "triaxial: {name} = {v} must be in {bracket}{lo}, {hi}]"
                )))
            }
        };
        check("n_per_side", self.n_per_side as f64, 2.0, 40.0, false)?;
        check("radius [m]", self.radius, 0.0, 10.0, true)?;
        check("radius_spread", self.radius_spread, 0.0, 0.5, false)?;
        check("mu", self.mu, 0.0, 10.0, false)?;
        check("restitution", self.restitution, 0.05, 1.0, false)?;
        check(
            "confining_pressure [Pa]",
            self.confining_pressure,
            0.0,
            1e9,
            true,
        )?;
        check("inertial_number", self.inertial_number, 0.0, 0.1, true)?;
        check("axial_strain", self.axial_strain, 0.0, 0.5, true)?;
        check("rayleigh_fraction", self.rayleigh_fraction, 0.0, 0.3, true)?;
        check(
            "rows_per_percent",
            self.rows_per_percent as f64,
            1.0,
            1e3,
            false,
        )?;
        Ok(())
    }

    /// Parameters from a `key = value` text (the form of the repository's
    /// `assets/triaxial.conf`; `#` starts a comment); keys not given keep their defaults.
    pub fn from_conf(text: &str) -> Result<Self, SceneError> {
        let mut p = Self::default();
        let (mut g, mut nu, mut rho) = (
            p.material.shear_modulus(),
            p.material.poisson_ratio(),
            p.material.density(),
        );
        for (i, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let bad = |why: &str| {
                SceneError::Parameter(format!("triaxial config line {}: {why}: `{line}`", i + 1))
            };
            let (key, value) = line
                .split_once('=')
                .ok_or_else(|| bad("expected key = value"))?;
            let (key, value) = (key.trim(), value.trim());
            let num = || value.parse::<f64>().map_err(|_| bad("not a number"));
            let int = || value.parse::<u64>().map_err(|_| bad("not a whole number"));
            match key {
                "n_per_side" => p.n_per_side = int()? as usize,
                "radius" => p.radius = num()?,
                "radius_spread" => p.radius_spread = num()?,
                "shear_modulus" => g = num()?,
                "poisson_ratio" => nu = num()?,
                "density" => rho = num()?,
                "mu" => p.mu = num()?,
                "restitution" => p.restitution = num()?,
                "confining_pressure" => p.confining_pressure = num()?,
                "inertial_number" => p.inertial_number = num()?,
                "axial_strain" => p.axial_strain = num()?,
                "rayleigh_fraction" => p.rayleigh_fraction = num()?,
                "seed" => p.seed = int()?,
                "rows_per_percent" => p.rows_per_percent = int()? as usize,
                _ => return Err(bad("unknown key")),
            }
        }
        p.material = Material::new(g, nu, p.mu, rho)?;
        p.validate()?;
        Ok(p)
    }

    /// Mean diameter \[m\].
    pub fn mean_diameter(&self) -> f64 {
        2.0 * self.radius
    }

    /// Axial strain rate of the shear [1/s]: `I / (d sqrt(rho / p0))`.
    pub fn strain_rate(&self) -> f64 {
        self.inertial_number
            / (self.mean_diameter() * (self.material.density() / self.confining_pressure).sqrt())
    }

    /// Time step \[s\]: `rayleigh_fraction` of the smallest ball's Rayleigh time.
    pub fn time_step(&self) -> f64 {
        let r_min = self.radius * (1.0 - self.radius_spread);
        self.rayleigh_fraction * creep_law::hertz::rayleigh_time_step(&self.material, r_min)
    }
}

/// One wall: a kinematic cuboid whose inner face is normal to `axis`, on side `side` (+1: the
/// face looks towards -axis).
#[derive(Debug, Clone, Copy)]
struct Wall {
    body: RigidBodyHandle,
    collider: ColliderHandle,
    axis: usize,
    side: f64,
}

/// A contact counts as creeping when its creep displacement in a step is at least this share
/// of its sliding displacement (Kuhn's rule: the creep term then changes the tangential
/// increment by 10 % or more).
pub const CREEPING: f64 = 0.1;

/// Half-thickness of the walls, in mean radii.
const WALL_THICKNESS: f64 = 5.0;

/// A packing in its box: the world and what the test needs to find in it.
pub struct Specimen {
    world: CreepWorld,
    params: TriaxialParams,
    balls: Vec<(RigidBodyHandle, ColliderHandle)>,
    walls: [Wall; 6],
    steps: usize,
}

/// One row of the record (SI units; stresses compression positive).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TriaxialRow {
    /// Axial strain `(H0 - H) / H0` [-].
    pub axial_strain: f64,
    /// Volumetric strain `(V0 - V) / V0` [-] (compression positive).
    pub volumetric_strain: f64,
    /// Stress ratio `q / p` from the walls [-].
    pub q_over_p: f64,
    /// Mean stress from the walls \[Pa\].
    pub p: f64,
    /// Deviatoric stress from the walls \[Pa\].
    pub q: f64,
    /// Axial wall stress `sigma_1` \[Pa\].
    pub sigma_axial: f64,
    /// Mean lateral wall stress `sigma_3` \[Pa\].
    pub sigma_lateral: f64,
    /// Mean stress from the contacts (Love-Weber) \[Pa\].
    pub p_contacts: f64,
    /// Deviatoric stress from the contacts \[Pa\].
    pub q_contacts: f64,
    /// Touching ball-ball contacts.
    pub contacts: usize,
    /// Mean coordination number (ball-ball contacts per ball, times 2) [-].
    pub coordination: f64,
    /// Share of the ball-ball contacts at the Coulomb limit [-].
    pub share_sliding: f64,
    /// Share of the ball-ball contacts rolling more than sliding (`|v_roll| > |v_disp|`) [-].
    pub share_rolling: f64,
    /// Share of the ball-ball contacts whose creep displacement in the step is at least
    /// [`CREEPING`] of their sliding displacement [-].
    pub share_creeping: f64,
    /// Solid fraction [-].
    pub solid_fraction: f64,
    /// Kinetic energy of the balls \[J\].
    pub kinetic_energy: f64,
}

/// A stress measurement.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Stress {
    /// Box dimensions between the walls' inner faces \[m\].
    dims: [f64; 3],
    /// Wall stresses per axis \[Pa\].
    walls: [f64; 3],
    /// Per-wall stress \[Pa\], index `2 axis + (side > 0)`.
    each: [f64; 6],
    /// Love-Weber stress \[Pa\].
    love: [[f64; 3]; 3],
    /// Normal contact stiffness summed over each wall's contacts [N/m] (Hertz:
    /// `dP/d delta = 1.5 P / delta`).
    stiffness: [f64; 6],
}

impl Specimen {
    /// Generates the loose packing in its box (step 1 of the module docs).
    pub fn generate(params: TriaxialParams) -> Result<Self, SceneError> {
        params.validate()?;
        let dt = params.time_step();
        let mut world = CreepWorld::new(dt as f32, CreepSettings::default())?;
        world.physics.gravity = Vector::ZERO;
        world.physics.integration_parameters.num_solver_iterations = 1;
        // Rapier's prediction distance is 2e-3 length units: with the default unit (1 m) every
        // millimetre ball would be paired with dozens of neighbours. One mean diameter as the
        // unit keeps it at 4e-6 m here, still far above a step's relative motion (checked each
        // step, see `Specimen::step`).
        world.physics.integration_parameters.length_unit = params.mean_diameter() as f32;
        world.compliant.set_settings(CompliantSettings {
            rayleigh_fraction: params.rayleigh_fraction,
            rayleigh_check: RayleighCheck::Error,
            creep: false,
            ..CompliantSettings::default()
        })?;
        let mat = CreepMaterial::new(params.material).with_fidelity(Fidelity::Compliant);
        let n = params.n_per_side;
        let r = params.radius;
        let r_max = r * (1.0 + params.radius_spread);
        let spacing = 2.0 * r_max * 1.05;
        let side = n as f64 * spacing;
        let mut rng = SplitMix64(params.seed);
        let mut balls = Vec::with_capacity(n * n * n);
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let ri = r * (1.0 + params.radius_spread * (2.0 * rng.unit() - 1.0));
                    let slack = (spacing / 2.0 - ri).max(0.0);
                    let mut x = [0.0; 3];
                    for (d, idx) in x.iter_mut().zip([i, j, k]) {
                        *d = (idx as f64 + 0.5) * spacing - side / 2.0
                            + slack * (2.0 * rng.unit() - 1.0) * 0.9;
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
    fn face(&self, w: &Wall) -> f64 {
        let x = self.world.physics.bodies[w.body].translation()[w.axis];
        f64::from(x) - w.side * WALL_THICKNESS * self.params.radius
    }

    /// Box dimensions between the inner faces \[m\].
    fn dims(&self) -> [f64; 3] {
        std::array::from_fn(|axis| {
            self.face(&self.walls[2 * axis + 1]) - self.face(&self.walls[2 * axis])
        })
    }

    /// Sets the wall velocities: each wall's outward speed [m/s] (negative: inwards).
    fn set_wall_speeds(&mut self, outward: [f64; 6]) {
        for (w, v) in self.walls.iter().zip(outward) {
            let mut vel = [0.0f32; 3];
            vel[w.axis] = (w.side * v) as f32;
            self.world.physics.bodies[w.body].set_linvel(Vector::new(vel[0], vel[1], vel[2]), true);
        }
    }

    fn step(&mut self) -> Result<(), SceneError> {
        self.world.step()?;
        self.steps += 1;
        // A contact cannot start unseen while two bodies close in by less than the prediction
        // distance in a step (compliant regime docs).
        let moved = self.world.compliant.counts().max_step_displacement;
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

    /// The stresses from the walls and from the contacts of the last step.
    fn stress(&self) -> Stress {
        let dims = self.dims();
        let volume = dims[0] * dims[1] * dims[2];
        let mut each = [0.0; 6];
        let mut stiffness = [0.0; 6];
        let mut love = [[0.0; 3]; 3];
        let wall_of = |c: ColliderHandle| self.walls.iter().position(|w| w.collider == c);
        let bodies = &self.world.physics.bodies;
        let colliders = &self.world.physics.colliders;
        let centre = |c: ColliderHandle| {
            colliders
                .get(c)
                .and_then(|co| co.parent())
                .map(|b| bodies[b].translation())
                .map(|x| [f64::from(x.x), f64::from(x.y), f64::from(x.z)])
                .unwrap_or_default()
        };
        for (&(c1, c2), rec) in self.world.compliant.contacts() {
            // Force on p (collider1) from q.
            let f = rec.tangential_force - rec.normal * rec.normal_force;
            let f = [f.x, f.y, f.z];
            let point = [rec.point.x, rec.point.y, rec.point.z];
            let mut add = |arm: [f64; 3], force: [f64; 3]| {
                for i in 0..3 {
                    for j in 0..3 {
                        love[i][j] -= arm[i] * force[j] / volume;
                    }
                }
            };
            match (wall_of(c1), wall_of(c2)) {
                (None, None) => {
                    let (xp, xq) = (centre(c1), centre(c2));
                    add([xq[0] - xp[0], xq[1] - xp[1], xq[2] - xp[2]], f);
                }
                (Some(w), None) => {
                    // The ball is q and gets -f; the wall gets f.
                    let x = centre(c2);
                    add(
                        [point[0] - x[0], point[1] - x[1], point[2] - x[2]],
                        [-f[0], -f[1], -f[2]],
                    );
                    each[w] += self.walls[w].side * f[self.walls[w].axis];
                    stiffness[w] += 1.5 * rec.normal_force / rec.overlap;
                }
                (None, Some(w)) => {
                    let x = centre(c1);
                    add([point[0] - x[0], point[1] - x[1], point[2] - x[2]], f);
                    each[w] -= self.walls[w].side * f[self.walls[w].axis];
                    stiffness[w] += 1.5 * rec.normal_force / rec.overlap;
                }
                (Some(_), Some(_)) => {}
            }
        }
        let mut walls = [0.0; 3];
        for axis in 0..3 {
            let area = dims[(axis + 1) % 3] * dims[(axis + 2) % 3];
            each[2 * axis] /= area;
            each[2 * axis + 1] /= area;
            walls[axis] = 0.5 * (each[2 * axis] + each[2 * axis + 1]);
        }
        Stress {
            dims,
            walls,
            each,
            love,
            stiffness,
        }
    }

    /// Kinetic energy of the balls \[J\].
    fn kinetic_energy(&self) -> f64 {
        self.balls
            .iter()
            .map(|&(b, _)| {
                let rb = &self.world.physics.bodies[b];
                let w = rb.angvel();
                let iw = rb.mass_properties().effective_angular_inertia() * w;
                0.5 * f64::from(rb.mass()) * f64::from(rb.linvel().length_squared())
                    + 0.5 * f64::from(w.dot(iw))
            })
            .sum()
    }

    /// Volume of the balls [m^3].
    fn solids(&self) -> f64 {
        self.balls
            .iter()
            .map(|&(_, c)| {
                let r = f64::from(
                    self.world.physics.colliders[c]
                        .shape()
                        .as_ball()
                        .map_or(0.0, |b| b.radius),
                );
                4.0 / 3.0 * std::f64::consts::PI * r * r * r
            })
            .sum()
    }

    /// Contact statistics of the ball-ball contacts: (contacts, sliding, rolling, creeping).
    fn contact_shares(&self) -> (usize, usize, usize, usize) {
        let is_wall = |c: ColliderHandle| self.walls.iter().any(|w| w.collider == c);
        let (mut n, mut sliding, mut rolling, mut creeping) = (0, 0, 0, 0);
        for (&(c1, c2), rec) in self.world.compliant.contacts() {
            if is_wall(c1) || is_wall(c2) {
                continue;
            }
            n += 1;
            sliding += usize::from(rec.sliding);
            creeping += usize::from(rec.creep_ratio >= CREEPING);
            rolling += usize::from(rec.v_roll.length() > rec.v_disp.length());
        }
        (n, sliding, rolling, creeping)
    }
}

/// A deterministic generator (SplitMix64, Steele, Lea & Flood 2014), so a seed gives the same
/// packing on every machine.
#[derive(Debug, Clone, Copy)]
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Share of a wall's stress error the servo corrects per step (the servo of Itasca's PFC,
/// e.g. Cundall & Strack's walls: the wall speed `alpha (sigma - p0) A / (K dt)` with `K` the
/// summed normal stiffness of its contacts would remove the error `alpha` per step if the
/// packing were a spring). With the stiffness of a Hertz packing, the stress lag of a wall
/// moving at `v` is `~ 1.5 v dt / (alpha delta)` of p0 (0.1 % at the default test's lateral
/// speeds).
const SERVO_ALPHA: f64 = 0.3;

impl Stress {
    /// The servo speed of wall `k` (outwards, m/s) towards `p0`, capped at `cap` [m/s].
    fn servo(&self, k: usize, p0: f64, dt: f64, cap: f64) -> f64 {
        let axis = k / 2;
        let area = self.dims[(axis + 1) % 3] * self.dims[(axis + 2) % 3];
        let v = if self.stiffness[k] > 0.0 {
            SERVO_ALPHA * (self.each[k] - p0) * area / (self.stiffness[k] * dt)
        } else {
            -cap // nothing touches: close in
        };
        v.clamp(-cap, cap)
    }
}

/// Summary of the isotropic compaction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactionSummary {
    /// Steps taken.
    pub steps: usize,
    /// Solid fraction reached [-].
    pub solid_fraction: f64,
    /// Mean wall stress \[Pa\].
    pub p_walls: f64,
    /// Mean stress from the contacts \[Pa\].
    pub p_contacts: f64,
    /// Largest deviation of a wall's stress from `p0`, relative [-].
    pub max_wall_error: f64,
    /// Mean coordination number [-].
    pub coordination: f64,
}

/// Compacts the specimen isotropically to `p0` (frictionless balls, all walls servo-controlled),
/// until every wall is within 1 % of `p0` and the contact stress agrees with the walls' within
/// 1 % for 200 consecutive steps; `progress(fraction)` is called as it goes (the fraction is an
/// estimate: the steps are not known in advance). Errors if it has not settled after
/// `max_steps`.
pub fn compact(
    specimen: &mut Specimen,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
) -> Result<CompactionSummary, SceneError> {
    compact_observed(specimen, max_steps, progress, &mut |_| {})
}

/// [`compact`], calling `observe` with the specimen after every step (e.g. to draw it: the
/// desktop demo `triaxial_view`).
pub fn compact_observed(
    specimen: &mut Specimen,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&Specimen),
) -> Result<CompactionSummary, SceneError> {
    let p0 = specimen.params.confining_pressure;
    let rate = specimen.params.strain_rate();
    let dt = specimen.params.time_step();
    let mut settled_for = 0;
    let mut last = Stress::default();
    for i in 0..max_steps {
        let s = specimen.stress();
        let mut v = [0.0; 6];
        // Fast while nothing touches (a gas: up to 20 eps_dot), then at most 5 eps_dot.
        let cap = if s.walls.iter().all(|&w| w < 0.05 * p0) {
            20.0
        } else {
            5.0
        };
        for (k, w) in specimen.walls.iter().enumerate() {
            v[k] = s.servo(k, p0, dt, cap * rate * s.dims[w.axis] / 2.0);
        }
        specimen.set_wall_speeds(v);
        specimen.step()?;
        observe(specimen);
        last = specimen.stress();
        let wall_err = last
            .each
            .iter()
            .map(|&w| (w / p0 - 1.0).abs())
            .fold(0.0, f64::max);
        let p_love = (last.love[0][0] + last.love[1][1] + last.love[2][2]) / 3.0;
        let p_walls = last.walls.iter().sum::<f64>() / 3.0;
        let agree = (p_love / p_walls - 1.0).abs();
        if wall_err < 0.01 && agree < 0.01 {
            settled_for += 1;
        } else {
            settled_for = 0;
        }
        if i % 200 == 0 {
            let est = (p_walls / p0).clamp(0.0, 1.0) * 0.9 + 0.1 * settled_for as f64 / 200.0;
            progress(est);
        }
        if settled_for >= 200 {
            specimen.set_wall_speeds([0.0; 6]);
            progress(1.0);
            let (n, ..) = specimen.contact_shares();
            let dims = last.dims;
            return Ok(CompactionSummary {
                steps: i + 1,
                solid_fraction: specimen.solids() / (dims[0] * dims[1] * dims[2]),
                p_walls,
                p_contacts: p_love,
                max_wall_error: wall_err,
                coordination: 2.0 * n as f64 / specimen.len() as f64,
            });
        }
    }
    let p_walls = last.walls.iter().sum::<f64>() / 3.0;
    Err(SceneError::Parameter(format!(
        "triaxial: the isotropic compaction did not settle in {max_steps} steps (mean wall stress {p_walls:.4e} Pa against p0 = {p0:.4e} Pa)"
    )))
}

/// The record of one shear.
#[derive(Debug, Clone, PartialEq)]
pub struct ShearRun {
    /// Whether Kuhn's creep term was on.
    pub creep: bool,
    /// The rows, from the start of the shear.
    pub rows: Vec<TriaxialRow>,
    /// Steps taken.
    pub steps: usize,
    /// Largest relative difference of the contact stress (p and q) from the walls' over the
    /// rows after 1 % axial strain (quasi-static check) [-].
    pub max_stress_mismatch: f64,
    /// Energy dissipated by creep over the shear \[J\].
    pub creep_dissipation: f64,
    /// Energy dissipated by slip over the shear \[J\].
    pub slip_dissipation: f64,
}

/// Shears a copy of the compacted `specimen` (drained, constant lateral stress, module docs)
/// to the final axial strain, with creep-friction on or off; `progress(fraction)` is called
/// as it goes.
pub fn shear(
    specimen: &Specimen,
    creep: bool,
    progress: &mut dyn FnMut(f64),
) -> Result<ShearRun, SceneError> {
    shear_observed(specimen, creep, progress, &mut |_, _| {})
}

/// [`shear`], calling `observe` with the sheared copy before every step and at the end, with
/// the row when one was recorded there (e.g. to draw it: the desktop demo `triaxial_view`).
pub fn shear_observed(
    specimen: &Specimen,
    creep: bool,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&Specimen, Option<&TriaxialRow>),
) -> Result<ShearRun, SceneError> {
    let mut s = specimen.clone_fresh(creep)?;
    let params = s.params;
    let p0 = params.confining_pressure;
    let rate = params.strain_rate();
    let dt = params.time_step();
    // Friction on the balls (the walls stay frictionless by their Min combine rule).
    for &(_, c) in &s.balls {
        if let Some(co) = s.world.physics.colliders.get_mut(c) {
            co.set_friction(params.mu as f32);
        }
    }
    // One step at rest, so that the fresh regime has found its contacts.
    s.set_wall_speeds([0.0; 6]);
    s.step()?;
    let s0 = s.stress();
    let h0 = s0.dims[1];
    let v0 = s0.dims[0] * s0.dims[1] * s0.dims[2];
    let solids = s.solids();
    let total_steps = (params.axial_strain / (rate * dt)).ceil() as usize;
    let record_every = (total_steps as f64
        / (params.axial_strain * 100.0 * params.rows_per_percent as f64))
        .max(1.0) as usize;
    let mut rows = Vec::new();
    let mut mismatch = 0f64;
    s.world.compliant.reset_energy();
    for i in 0..=total_steps {
        let st = s.stress();
        let eps_a = (h0 - st.dims[1]) / h0;
        let last = i == total_steps || eps_a >= params.axial_strain;
        if i % record_every == 0 || last {
            let row = row(&s, &st, eps_a, v0, solids);
            if eps_a > 0.01 {
                let dp = (row.p_contacts / row.p - 1.0).abs();
                let dq = ((row.q_contacts - row.q) / row.p).abs();
                mismatch = mismatch.max(dp).max(dq);
            }
            rows.push(row);
            progress(i as f64 / total_steps as f64);
            observe(&s, rows.last());
        } else {
            observe(&s, None);
        }
        if last {
            break;
        }
        let mut v = [0.0; 6];
        for (k, w) in s.walls.iter().enumerate() {
            v[k] = if w.axis == 1 {
                -0.5 * rate * h0
            } else {
                st.servo(k, p0, dt, 5.0 * rate * st.dims[w.axis] / 2.0)
            };
        }
        s.set_wall_speeds(v);
        s.step()?;
    }
    let e = s.world.compliant.energy();
    Ok(ShearRun {
        creep,
        steps: s.steps - specimen.steps,
        rows,
        max_stress_mismatch: mismatch,
        creep_dissipation: e.creep,
        slip_dissipation: e.slip,
    })
}

fn row(s: &Specimen, st: &Stress, eps_a: f64, v0: f64, solids: f64) -> TriaxialRow {
    let v = st.dims[0] * st.dims[1] * st.dims[2];
    let sigma_1 = st.walls[1];
    let sigma_3 = 0.5 * (st.walls[0] + st.walls[2]);
    let p = (sigma_1 + 2.0 * sigma_3) / 3.0;
    let q = sigma_1 - sigma_3;
    let l = st.love;
    let p_c = (l[0][0] + l[1][1] + l[2][2]) / 3.0;
    let q_c = l[1][1] - 0.5 * (l[0][0] + l[2][2]);
    let (n, sliding, rolling, creeping) = s.contact_shares();
    let share = |k: usize| if n > 0 { k as f64 / n as f64 } else { 0.0 };
    TriaxialRow {
        axial_strain: eps_a,
        volumetric_strain: (v0 - v) / v0,
        q_over_p: q / p,
        p,
        q,
        sigma_axial: sigma_1,
        sigma_lateral: sigma_3,
        p_contacts: p_c,
        q_contacts: q_c,
        contacts: n,
        coordination: 2.0 * n as f64 / s.len() as f64,
        share_sliding: share(sliding),
        share_rolling: share(rolling),
        share_creeping: share(creeping),
        solid_fraction: solids / v,
        kinetic_energy: s.kinetic_energy(),
    }
}

impl Specimen {
    /// A copy with fresh plugin state (same registry and settings but `creep`), so that two
    /// shears start from the same packing.
    fn clone_fresh(&self, creep: bool) -> Result<Self, SceneError> {
        let hooks = CreepHooks::new(
            self.world.hooks.registry().clone(),
            *self.world.hooks.settings(),
        )?;
        let mut world = CreepWorld::from_parts(clone_physics(&self.world.physics), hooks)?;
        world.compliant = CompliantRegime::new(CompliantSettings {
            creep,
            ..*self.world.compliant.settings()
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

/// What a shear shows, in the numbers the talk's conclusion is about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShearSummary {
    /// Peak stress ratio `q / p` [-].
    pub peak_q_over_p: f64,
    /// Axial strain at the peak [-].
    pub peak_axial_strain: f64,
    /// Peak friction angle `asin((s1 - s3)/(s1 + s3))` \[deg\].
    pub peak_friction_angle_deg: f64,
    /// Largest dilatancy rate `-d eps_v / d eps_a` (over 1 % strain windows) [-].
    pub max_dilatancy_rate: f64,
    /// Dilatancy angle at that rate, `asin(D / (2 + D))` \[deg\].
    pub dilatancy_angle_deg: f64,
    /// Volumetric strain at the end [-].
    pub final_volumetric_strain: f64,
    /// Stress ratio at the end [-].
    pub final_q_over_p: f64,
    /// Mean shares of sliding, rolling and creeping contacts after 1 % strain [-].
    pub mean_shares: [f64; 3],
}

impl ShearRun {
    /// The peak friction angle, the dilatancy and the contact shares (module docs).
    pub fn summary(&self) -> ShearSummary {
        let peak = self
            .rows
            .iter()
            .copied()
            .max_by(|a, b| a.q_over_p.total_cmp(&b.q_over_p))
            .unwrap_or_default();
        let phi = ((peak.sigma_axial - peak.sigma_lateral)
            / (peak.sigma_axial + peak.sigma_lateral))
            .asin()
            .to_degrees();
        let mut d_max = f64::NEG_INFINITY;
        for (i, a) in self.rows.iter().enumerate() {
            if let Some(b) = self.rows[i..]
                .iter()
                .find(|b| b.axial_strain >= a.axial_strain + 0.01)
            {
                let d = -(b.volumetric_strain - a.volumetric_strain)
                    / (b.axial_strain - a.axial_strain);
                d_max = d_max.max(d);
            }
        }
        let late: Vec<&TriaxialRow> = self.rows.iter().filter(|r| r.axial_strain > 0.01).collect();
        let mean = |f: &dyn Fn(&TriaxialRow) -> f64| {
            if late.is_empty() {
                0.0
            } else {
                late.iter().map(|r| f(r)).sum::<f64>() / late.len() as f64
            }
        };
        let last = self.rows.last().copied().unwrap_or_default();
        ShearSummary {
            peak_q_over_p: peak.q_over_p,
            peak_axial_strain: peak.axial_strain,
            peak_friction_angle_deg: phi,
            max_dilatancy_rate: d_max,
            dilatancy_angle_deg: (d_max / (2.0 + d_max)).asin().to_degrees(),
            final_volumetric_strain: last.volumetric_strain,
            final_q_over_p: last.q_over_p,
            mean_shares: [
                mean(&|r| r.share_sliding),
                mean(&|r| r.share_rolling),
                mean(&|r| r.share_creeping),
            ],
        }
    }
}

/// The CSV header of [`TriaxialRow::csv`].
pub const CSV_HEADER: &str = "axial_strain,volumetric_strain,q_over_p,p,q,sigma_axial,sigma_lateral,p_contacts,q_contacts,contacts,coordination,share_sliding,share_rolling,share_creeping,solid_fraction,kinetic_energy";

impl TriaxialRow {
    /// The row as CSV (see [`CSV_HEADER`]).
    pub fn csv(&self) -> String {
        format!(
            "{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.4},{:.5},{:.5},{:.5},{:.6},{:.4e}",
            self.axial_strain,
            self.volumetric_strain,
            self.q_over_p,
            self.p,
            self.q,
            self.sigma_axial,
            self.sigma_lateral,
            self.p_contacts,
            self.q_contacts,
            self.contacts,
            self.coordination,
            self.share_sliding,
            self.share_rolling,
            self.share_creeping,
            self.solid_fraction,
            self.kinetic_energy
        )
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

/// Wall-clock seconds of each of `steps` steps of [`Specimen::at_rest`] (the speed measure of
/// `creep bench dem`).
pub fn time_compliant_steps(
    specimen: &Specimen,
    creep: bool,
    steps: usize,
) -> Result<Vec<f64>, SceneError> {
    let mut s = specimen.at_rest(creep)?;
    let mut times = Vec::with_capacity(steps);
    for _ in 0..steps {
        let t = std::time::Instant::now();
        s.step_at_rest()?;
        times.push(t.elapsed().as_secs_f64());
    }
    Ok(times)
}

/// Wall-clock seconds of each of `steps` steps of [`Specimen::plain_rapier`].
pub fn time_plain_rapier_steps(specimen: &Specimen, steps: usize) -> Vec<f64> {
    let mut p = specimen.plain_rapier();
    (0..steps)
        .map(|_| {
            let t = std::time::Instant::now();
            p.step();
            t.elapsed().as_secs_f64()
        })
        .collect()
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

/// Wall-clock seconds of each of `steps` steps of the packing at rest in the creep-dem engine
/// ([`dem_engine`], the balls' friction on), on `threads` threads (1: the serial force loop;
/// more: rayon's, which needs creep-dem's `parallel` feature).
pub fn time_dem_steps<T: creep_dem::TangentialLaw>(
    specimen: &Specimen,
    creep: bool,
    threads: usize,
    steps: usize,
) -> Result<Vec<f64>, SceneError> {
    let run = || -> Result<Vec<f64>, SceneError> {
        let mut d = dem_engine::<T>(specimen, creep, threads > 1)?;
        let mut times = Vec::with_capacity(steps);
        for _ in 0..steps {
            let t = std::time::Instant::now();
            d.step()
                .map_err(|e| SceneError::Parameter(format!("DEM engine: {e}")))?;
            times.push(t.elapsed().as_secs_f64());
        }
        Ok(times)
    };
    if threads <= 1 {
        return run();
    }
    creep_dem::with_threads(threads, run)
        .map_err(|e| SceneError::Parameter(format!("DEM engine: {e}")))?
}
