//! The talk's figure "Effect of rolling upon tangential force" (Kuhn 2011, EMI talk "Rolling and
//! friction in discrete element simulations"): one Hertz contact of two equal spheres at constant
//! normal force `P`, loaded from zero tangential force by a monotonic sliding displacement
//! `delta` while it rolls `du_roll = r |du_disp|`, for several ratios `r` of rolling to sliding.
//!
//! Two models drive the same paths:
//!
//! * **Kuhn's rule** ([`creep_law::CreepState`], the talk's eq. 1): the Cattaneo-Mindlin algorithm
//!   fed `du_disp - F_ss(|Q|/(mu P)) Q/|Q| |du_roll|`;
//! * **the exact theory** ([`creep_reference::bem::TransientSolver`]): Kalker's transient rolling
//!   and shift of the elastic half-spaces by boundary elements (Kalker 1990, ch. 5), each step
//!   rolling `dq = r d` and shifting the bodies rigidly by `dW_x = d`.
//!
//! Kuhn's rule is also run through the Rapier compliant regime ([`RollingEffect::compliant_path`]:
//! two dynamic balls in a `creep_rapier::CreepWorld`, their motion imposed every step), which
//! measures the engine's coupling to the law (kinematics, f32 poses, the step), not the law.
//!
//! `r = 0` is Cattaneo-Mindlin loading (Mindlin 1949): `delta = 3 mu P/(16 G* a) [1 - (1 -
//! Q/(mu P))^(2/3)]` (docs/ARCHITECTURE.md §4). For large `r` the contact rolls many contact radii before `Q`
//! saturates and tends to steady rolling at creepage `delta / (r delta) = 1/r` (Kalker 2000;
//! exact: [`creep_reference::bem::SteadySolver`]).
//!
//! # Conventions
//!
//! docs/ARCHITECTURE.md §4 and `creep_reference::bem`: `du_disp = du_q - du_p` is the rigid shift of body q
//! relative to body p (the boundary elements' `dW`), `Q` is the force on p from q, and `Q`
//! follows `du_disp` (`Q . du_disp >= 0`). Sliding and rolling are both along `+x` (the
//! contact moves in `+x` over both surfaces). Reversing the rolling direction gives the same
//! `|Q|` (mirror symmetry of the circular contact with the oddness of the Coulomb problem), and
//! Kuhn's rule uses only `|du_roll|`; rolling *across* the sliding direction would bring Kalker's
//! `C22` into the exact theory and is not part of this figure.
//!
//! Both spheres are of one material, so Kalker's combined constants are the material's (`G`,
//! `nu`) and Mindlin's modulus is `G* = G / (2 (2 - nu))`: the law and the boundary elements
//! solve the same contact. Displacements are normalised by `mu P / (G a)` and forces by `mu P`.
//! The figure depends on the load and the material only through `nu` and the ratio
//! `epsilon = mu P / (G a^2)` ([`RollingEffect::epsilon`]): the rolling distance of a path, in
//! contact radii, is `r epsilon delta G a/(mu P)`, so the ratio `r` at which creep matters scales
//! as `1/epsilon`.

use creep_law::{
    CreepInput, CreepLaw, CreepModel, CreepState, LawError, Material, PairMaterial, SteadyLaw,
    Surface, Vec2, hertz,
};
use creep_rapier::{CompliantSettings, CreepMaterial, CreepSettings, CreepWorld, PluginError};
use creep_reference::RefError;
use creep_reference::bem::{Creepage, SolverOptions, SteadySolver, TransientSolver};
use creep_reference::contact::CircularContact;
use creep_reference::mindlin::Mindlin;
use rapier3d::math::Rotation;
use rapier3d::prelude::{ColliderBuilder, RigidBodyBuilder, Vector};

/// The ratios `r = |du_roll| / |du_disp|` of the talk's figure.
pub const RATIOS: [f64; 7] = [0.0, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0];

/// Why the figure could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RollingEffectError {
    /// A material parameter was refused.
    #[error(transparent)]
    Law(#[from] LawError),
    /// The boundary-element reference refused an input or did not converge.
    #[error(transparent)]
    Reference(#[from] RefError),
    /// The Rapier plugin refused the compliant scene (e.g. its time step).
    #[error(transparent)]
    Plugin(#[from] PluginError),
    /// The compliant regime did not report exactly one contact between the two balls.
    #[error("engine step {step}: {contacts} compliant contacts, expected exactly one")]
    EngineContact {
        /// Engine step (0: the first warm-up step).
        step: usize,
        /// Contacts reported by `CompliantRegime::contacts()`.
        contacts: usize,
    },
    /// A parameter of the figure outside its range.
    #[error("{name} = {value} is outside its valid range: {expected}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// The valid range, in words.
        expected: &'static str,
    },
}

fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<f64, RollingEffectError> {
    if ok && value.is_finite() {
        Ok(value)
    } else {
        Err(RollingEffectError::Parameter {
            name,
            value,
            expected,
        })
    }
}

/// Parameters of the figure. [`RollingEffectConfig::default`] is the project's choice (the talk
/// states no values): two soda-lime glass spheres ([`Material::glass`]: `G = 29 GPa`,
/// `nu = 0.23`, `mu = 0.5`) of radius 1 mm pressed by `P = 1 N` (Hertz: `a = 21.5 um`,
/// `p0 = 1.03 GPa`, `epsilon = mu P/(G a^2) = 0.037`), paths to `delta G a/(mu P) = 2` in 200
/// steps, boundary elements on N = 32.
#[derive(Debug, Clone, PartialEq)]
pub struct RollingEffectConfig {
    /// Material of both spheres.
    pub material: Material,
    /// Radius of each sphere \[m\], finite and > 0.
    pub radius: f64,
    /// Constant normal force `P` \[N\], finite and > 0.
    pub normal_force: f64,
    /// Ratios `r = |du_roll| / |du_disp|` \[dimensionless\], each finite and >= 0.
    pub ratios: Vec<f64>,
    /// End of every path, in normalised sliding displacement `delta G a / (mu P)`
    /// \[dimensionless\], finite and > 0 (Cattaneo-Mindlin saturates at `3 (2 - nu)/8`, 0.66 for
    /// glass).
    pub end: f64,
    /// Recorded steps along each path (the boundary elements take one solve per step), in
    /// `[1, 100 000]`.
    pub steps: usize,
    /// Sub-steps of Kuhn's rule per recorded step (its creep term is explicit), in
    /// `[1, 10 000]`.
    pub kuhn_substeps: usize,
    /// Boundary-element grid `N` (elements across the contact diameter), in `[4, 256]`.
    pub grid: usize,
}

impl Default for RollingEffectConfig {
    fn default() -> Self {
        RollingEffectConfig {
            material: Material::glass(),
            radius: 1e-3,
            normal_force: 1.0,
            ratios: RATIOS.to_vec(),
            end: 2.0,
            steps: 200,
            kuhn_substeps: 20,
            grid: 32,
        }
    }
}

/// One path of the figure: `Q/(mu P)` against `delta G a/(mu P)` by both models.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Ratio `r = |du_roll| / |du_disp|`.
    pub r: f64,
    /// Normalised sliding displacement `delta G a / (mu P)` at each record, from 0.
    pub delta: Vec<f64>,
    /// `Q/(mu P)` by the exact theory (boundary elements) at each record.
    pub exact: Vec<f64>,
    /// `Q/(mu P)` by Kuhn's rule at each record.
    pub kuhn: Vec<f64>,
}

/// Error of Kuhn's rule against the exact theory along one path, in units of `mu P`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathError {
    /// Ratio `r`.
    pub r: f64,
    /// Largest `|Q_kuhn - Q_exact| / (mu P)` over the path's records.
    pub max: f64,
    /// Root mean square of `(Q_kuhn - Q_exact) / (mu P)` over the path's records (the first,
    /// `Q = 0`, excluded).
    pub rms: f64,
    /// `(Q_kuhn - Q_exact) / (mu P)` at the path's end.
    pub end: f64,
}

impl PathError {
    /// Error of `model` against `reference` on the same records (in units of `mu P`): the
    /// largest and RMS `model - reference` over the records after the first (where both start
    /// from zero by construction), and its value at the last record.
    fn between(r: f64, model: &[f64], reference: &[f64]) -> Self {
        let d: Vec<f64> = model
            .iter()
            .zip(reference)
            .skip(1)
            .map(|(m, e)| m - e)
            .collect();
        let max = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let rms = if d.is_empty() {
            0.0
        } else {
            (d.iter().map(|v| v * v).sum::<f64>() / d.len() as f64).sqrt()
        };
        Self {
            r,
            max,
            rms,
            end: d.last().copied().unwrap_or(0.0),
        }
    }
}

impl Curve {
    /// Error of Kuhn's rule against the exact curve.
    pub fn error(&self) -> PathError {
        PathError::between(self.r, &self.kuhn, &self.exact)
    }
}

/// One path of the figure run through the Rapier compliant regime
/// ([`RollingEffect::compliant_path`]).
#[derive(Debug, Clone, PartialEq)]
pub struct CompliantPath {
    /// Ratio `r`.
    pub r: f64,
    /// `Q/(mu P)` at each record: the regime's tangential force on the lower ball along `+x`
    /// over the configured `mu P` (the first record: the contact closed, no tangential motion).
    pub q: Vec<f64>,
    /// Sliding displacement at each record, `delta G a/(mu P)`, integrated from the regime's
    /// own `v_disp dt` (upper ball relative to the lower one, along `+x`).
    pub delta: Vec<f64>,
    /// Rolling displacement at the path's end, `|du_roll| G a/(mu P)` summed from the regime's
    /// `|v_roll| dt` (the path asks for `r` times the end of `delta`).
    pub rolled: f64,
    /// Normal force the regime computed at the imposed overlap \[N\] (Hertz plus Tsuji damping,
    /// whose rate of approach is zero here).
    pub normal_force: f64,
    /// Overlap of the two balls as the regime sees it (f32 centres and radius, in f64) \[m\].
    pub overlap: f64,
    /// Engine time step \[s\] (one tenth of the balls' Rayleigh time step).
    pub dt: f64,
}

impl CompliantPath {
    /// Error of the engine's curve against `reference` (e.g. [`RollingEffect::kuhn_path`] on the
    /// same records), in units of `mu P`, as for [`Curve::error`]: `max`, `rms` (first record
    /// excluded) and `end` of `Q_engine - Q_reference`.
    pub fn error_against(&self, reference: &[f64]) -> PathError {
        PathError::between(self.r, &self.q, reference)
    }
}

/// Linear interpolation of the samples `(xs, ys)` (`xs` increasing) at `x`; `None` outside.
pub fn interpolate(xs: &[f64], ys: &[f64], x: f64) -> Option<f64> {
    let k = xs.windows(2).position(|w| w[0] <= x && x <= w[1])?;
    let (x0, x1, y0, y1) = (xs[k], xs[k + 1], ys[k], ys[k + 1]);
    Some(if x1 > x0 {
        y0 + (y1 - y0) * (x - x0) / (x1 - x0)
    } else {
        y0
    })
}

/// The first `x` at which the samples `(xs, ys)` reach `level` (linear interpolation), `None` if
/// they never do.
pub fn first_crossing(xs: &[f64], ys: &[f64], level: f64) -> Option<f64> {
    let k = ys.windows(2).position(|w| w[0] < level && w[1] >= level)?;
    let (x0, x1, y0, y1) = (xs[k], xs[k + 1], ys[k], ys[k + 1]);
    Some(x0 + (x1 - x0) * (level - y0) / (y1 - y0))
}

/// The figure's contact and its two models.
#[derive(Debug, Clone)]
pub struct RollingEffect {
    config: RollingEffectConfig,
    pair: PairMaterial,
    contact: CircularContact,
    mindlin: Mindlin,
}

impl RollingEffect {
    /// Validates the configuration and builds the contact (Hertz: `a = (3 P R*/(4 E*))^(1/3)`,
    /// Johnson 1985 §4.2, with `R* = R/2` for two equal spheres).
    pub fn new(config: RollingEffectConfig) -> Result<Self, RollingEffectError> {
        let m = config.material;
        if !(m.friction() > 0.0 && m.friction().is_finite()) {
            return Err(RollingEffectError::Parameter {
                name: "friction coefficient mu",
                value: m.friction(),
                expected: "finite and > 0",
            });
        }
        if m.poisson_ratio() < 0.0 {
            return Err(RollingEffectError::Parameter {
                name: "Poisson ratio nu",
                value: m.poisson_ratio(),
                expected: "in [0, 0.5] (the boundary elements' range)",
            });
        }
        check(
            "normal force P [N]",
            config.normal_force,
            config.normal_force > 0.0,
            "finite and > 0",
        )?;
        check(
            "end of the path (delta G a/(mu P))",
            config.end,
            config.end > 0.0,
            "finite and > 0",
        )?;
        for &r in &config.ratios {
            check("ratio r", r, r >= 0.0, "finite and >= 0")?;
        }
        let count = |name, n: usize, hi: usize, expected| {
            check(name, n as f64, (1..=hi).contains(&n), expected)
        };
        count("steps", config.steps, 100_000, "in [1, 100000]")?;
        count(
            "Kuhn sub-steps",
            config.kuhn_substeps,
            10_000,
            "in [1, 10000]",
        )?;
        check(
            "grid N",
            config.grid as f64,
            (4..=256).contains(&config.grid),
            "in [4, 256]",
        )?;
        let pair = PairMaterial::new(
            &m,
            &m,
            Surface::Sphere(config.radius),
            Surface::Sphere(config.radius),
        )?;
        let p = config.normal_force;
        let a = hertz::contact_radius(&pair, p);
        let contact = CircularContact::new(a, p, pair.g, pair.nu, pair.mu)?;
        let mindlin = Mindlin::new(contact.mu_p(), pair.g_star, a)?;
        Ok(RollingEffect {
            config,
            pair,
            contact,
            mindlin,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &RollingEffectConfig {
        &self.config
    }

    /// The pair's combined properties (creep-law).
    pub fn pair(&self) -> &PairMaterial {
        &self.pair
    }

    /// The contact solved by the boundary elements.
    pub fn contact(&self) -> &CircularContact {
        &self.contact
    }

    /// Contact radius `a` \[m\].
    pub fn a(&self) -> f64 {
        self.contact.a()
    }

    /// Coulomb limit `mu P` \[N\].
    pub fn mu_p(&self) -> f64 {
        self.contact.mu_p()
    }

    /// Displacement scale `mu P / (G a)` \[m\] (`G`: Kalker's combined modulus, here the
    /// material's).
    pub fn displacement_scale(&self) -> f64 {
        self.mu_p() / (self.contact.g() * self.a())
    }

    /// `epsilon = mu P / (G a^2)` \[dimensionless\]: the creepage scale of the contact; a path
    /// rolls `r epsilon delta_n` contact radii.
    pub fn epsilon(&self) -> f64 {
        self.contact.creepage_scale()
    }

    /// Normalised sliding displacement at which Cattaneo-Mindlin loading saturates,
    /// `K = 3 mu P/(16 G* a)` over `mu P/(G a)` \[dimensionless\] (Mindlin 1949;
    /// creep-reference's [`Mindlin::sliding_shift`]).
    pub fn mindlin_saturation(&self) -> f64 {
        self.mindlin.sliding_shift() / self.displacement_scale()
    }

    /// `Q/(mu P)` of Cattaneo-Mindlin loading at normalised displacement `delta_n`:
    /// `1 - (1 - delta/K)^(3/2)`, 1 beyond `K` (Mindlin 1949; creep-reference's
    /// [`Mindlin::loading_force`]). Negative or non-finite `delta_n` gives 0.
    pub fn mindlin_force(&self, delta_n: f64) -> f64 {
        let delta = delta_n.max(0.0) * self.displacement_scale();
        self.mindlin
            .loading_force(delta)
            .map_or(0.0, |q| q / self.mindlin.mu_p())
    }

    /// Normalised sliding displacement of each record, `k end / steps`, `k = 0..=steps`.
    pub fn deltas(&self) -> Vec<f64> {
        let n = self.config.steps;
        (0..=n)
            .map(|k| self.config.end * k as f64 / n as f64)
            .collect()
    }

    /// `Q/(mu P)` along the path of ratio `r` by Kuhn's rule ([`CreepState::update`]), one value
    /// per record (the first is 0).
    pub fn kuhn_path(&self, r: f64) -> Result<Vec<f64>, RollingEffectError> {
        self.kuhn_path_at(r, self.config.normal_force)
    }

    /// [`RollingEffect::kuhn_path`] with the normal force `p` \[N\] (finite, > 0) in place of the
    /// configured `P`, on the same increments and still normalised by the configured `mu P`
    /// (e.g. at the normal force [`CompliantPath::normal_force`] of the engine's f32 overlap, to
    /// separate that from the rest of the coupling).
    pub fn kuhn_path_at(&self, r: f64, p: f64) -> Result<Vec<f64>, RollingEffectError> {
        check("ratio r", r, r >= 0.0, "finite and >= 0")?;
        check("normal force P [N]", p, p > 0.0, "finite and > 0")?;
        let c = &self.config;
        let d = c.end * self.displacement_scale() / (c.steps * c.kuhn_substeps) as f64;
        let mut st = CreepState::new();
        // Close the contact at P before any tangential motion.
        st.update(
            &CreepLaw::kuhn(self.pair),
            CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
        );
        let mut out = Vec::with_capacity(c.steps + 1);
        out.push(st.force().x / self.mu_p());
        for _ in 0..c.steps {
            for _ in 0..c.kuhn_substeps {
                st.update(
                    &CreepLaw::kuhn(self.pair),
                    CreepInput::new(p, Vec2::new(d, 0.0), Vec2::new(r * d, 0.0)),
                );
            }
            out.push(st.force().x / self.mu_p());
        }
        Ok(out)
    }

    /// `Q/(mu P)` along the path of ratio `r` by the Rapier compliant regime
    /// (`creep_rapier::compliant`), which runs Kuhn's rule ([`CreepState`], [`CreepModel::Kuhn`])
    /// from Rapier's poses and velocities: the figure's contact as two dynamic balls of the
    /// configured material and radius in a [`CreepWorld`], both `Regime::Compliant`, gravity
    /// off, one solver iteration, `dt` one tenth of the Rayleigh time step (creep-law
    /// `hertz::rayleigh_time_step`, Li, Xu & Thornton 2005).
    ///
    /// The motion is imposed: before every engine step both centres are put back on the `y`
    /// axis at a distance `2R - delta_P` (Hertz overlap for the configured `P`, `delta = a^2/R*`,
    /// Johnson 1985 §4.2; rounded to the f32 grid, see [`CompliantPath::overlap`]), their
    /// orientations to the identity and their linear velocities to zero, and their angular
    /// velocities (about `z`) set so that the surface velocities at the contact point `c` are
    /// `u'_q = v_roll + v_disp/2` (upper ball) and `u'_p = v_roll - v_disp/2` (lower ball)
    /// along `+x`: Kuhn & Bagi (2004) rates (docs/ARCHITECTURE.md §4) with fixed centres (`c' = 0`) give
    /// exactly `v_disp = u'_q - u'_p` and `v_roll = (u'_q + u'_p)/2`, and a pure spin leaves the
    /// overlap, hence `P` and `a`, unchanged. Each engine step moves `v_disp dt` = the increment
    /// of one sub-step of [`RollingEffect::kuhn_path`] (`kuhn_substeps` engine steps per
    /// record), so the law sees the same increments as the Kuhn path and the difference
    /// measures only the coupling (kinematics, f32 poses and velocities, the step).
    ///
    /// Two warm-up steps at rest close the contact (the narrow phase pairs the balls in the
    /// first, the regime computes the pair from the second on). `Q` is read from
    /// `CompliantRegime::contacts()` after each step (the force of that step's increment).
    pub fn compliant_path(&self, r: f64) -> Result<CompliantPath, RollingEffectError> {
        check("ratio r", r, r >= 0.0, "finite and >= 0")?;
        let c = &self.config;
        let m = c.material;
        // Radius and centres are f32 in Rapier: the overlap the regime sees is `2 R - y_a - y_b`
        // of the rounded values. The upper centre is rounded after the lower one, so the
        // overlap is within half an f32 spacing at `R` (about 6e-8 R) of Hertz's.
        let radius = c.radius as f32;
        let r64 = f64::from(radius);
        let engine_pair = PairMaterial::new(&m, &m, Surface::Sphere(r64), Surface::Sphere(r64))?;
        let target = hertz::overlap(&engine_pair, c.normal_force);
        let y_a = (r64 - 0.5 * target) as f32;
        let y_b = (2.0 * r64 - target - f64::from(y_a)) as f32;
        let (ya, yb) = (f64::from(y_a), f64::from(y_b));
        let overlap = 2.0 * r64 - ya - yb;
        check(
            "overlap of the compliant balls [m]",
            overlap,
            overlap > 0.0 && overlap < r64,
            "> 0 and < R after f32 rounding",
        )?;
        // Contact point: the middle of the overlap on the y axis; lever arms to the centres.
        let c_y = 0.5 * (yb - ya);
        let (rho_a, rho_b) = (c_y + ya, yb - c_y);

        let t_r = hertz::rayleigh_time_step(&m, r64);
        let dt32 = (0.1 * t_r) as f32;
        check(
            "engine time step [s]",
            f64::from(dt32),
            dt32 > 0.0,
            "> 0 (a material with density and stiffness)",
        )?;
        let dt = f64::from(dt32);
        let mut world = CreepWorld::new(dt32, CreepSettings::default().with_rapier_solver())?;
        world.physics.gravity = Vector::ZERO;
        world.physics.integration_parameters.num_solver_iterations = 1;
        world.compliant_mut().set_settings(CompliantSettings {
            creep: true,
            creep_model: CreepModel::Kuhn,
            ..CompliantSettings::default()
        })?;
        let mat = CreepMaterial::compliant(m);
        let mut insert = |y: f32| {
            let body = RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, y, 0.0))
                .can_sleep(false);
            let collider = ColliderBuilder::ball(radius)
                .density(m.density() as f32)
                .friction(m.friction() as f32)
                .restitution(0.5);
            world.insert(body, collider, Some(mat))
        };
        let (body_a, coll_a) = insert(-y_a);
        let (body_b, _) = insert(y_b);

        // Per engine step: the sub-step increment of the Kuhn path.
        let d = c.end * self.displacement_scale() / (c.steps * c.kuhn_substeps) as f64;
        let (v_disp, v_roll) = (d / dt, r * d / dt);
        // Surface velocity along x of a spin w_z at the contact: -w rho (lower), +w rho (upper).
        let w_a = (-(v_roll - 0.5 * v_disp) / rho_a) as f32;
        let w_b = ((v_roll + 0.5 * v_disp) / rho_b) as f32;
        let impose = |world: &mut CreepWorld, spin: bool| {
            let bodies = &mut world.physics.bodies;
            for (h, y, w) in [(body_a, -y_a, w_a), (body_b, y_b, w_b)] {
                if let Some(rb) = bodies.get_mut(h) {
                    rb.set_translation(Vector::new(0.0, y, 0.0), false);
                    rb.set_rotation(Rotation::IDENTITY, false);
                    rb.set_linvel(Vector::ZERO, false);
                    rb.set_angvel(Vector::new(0.0, 0.0, if spin { w } else { 0.0 }), false);
                }
            }
            bodies.propagate_modified_body_positions_to_colliders(&mut world.physics.colliders);
        };
        // The one contact: (force on the lower ball along x, v_disp of the upper ball relative
        // to the lower along x, |v_roll|, P). The regime's p is the narrow phase's collider1,
        // either ball: its tangential force (on p) and v_disp (q relative to p) flip with it.
        let read = |world: &CreepWorld, step: usize| {
            let mut it = world.compliant().contacts();
            match (it.next(), it.next()) {
                (Some((key, rec)), None) => {
                    let s = if key.0 == coll_a { 1.0 } else { -1.0 };
                    Ok((
                        s * rec.tangential_force.x,
                        s * rec.v_disp.x,
                        rec.v_roll.length(),
                        rec.normal_force,
                    ))
                }
                _ => Err(RollingEffectError::EngineContact {
                    step,
                    contacts: world.compliant().contacts().count(),
                }),
            }
        };

        let mu_p = self.mu_p();
        let scale = self.displacement_scale();
        for _ in 0..2 {
            impose(&mut world, false);
            world.step()?;
        }
        let (q0, _, _, normal_force) = read(&world, 1)?;
        let mut q = Vec::with_capacity(c.steps + 1);
        let mut delta = Vec::with_capacity(c.steps + 1);
        q.push(q0 / mu_p);
        delta.push(0.0);
        let (mut slid, mut rolled) = (0.0, 0.0);
        let mut step = 2;
        for _ in 0..c.steps {
            let mut qx = 0.0;
            for _ in 0..c.kuhn_substeps {
                impose(&mut world, true);
                world.step()?;
                let (f, vd, vr, _) = read(&world, step)?;
                qx = f;
                slid += vd * dt;
                rolled += vr * dt;
                step += 1;
            }
            q.push(qx / mu_p);
            delta.push(slid / scale);
        }
        Ok(CompliantPath {
            r,
            q,
            delta,
            rolled: rolled / scale,
            normal_force,
            overlap,
            dt,
        })
    }

    /// `Q/(mu P)` along the path of ratio `r` by the exact theory on a grid of `grid` elements
    /// across the diameter, one value per record (the first is 0). Each record step of sliding
    /// `d` is split into the fewest boundary-element steps ([`TransientSolver::advance`], each
    /// rolling `dq = r d / k` and shifting `dW_x = d / k`) that roll at most one element side
    /// `h = 2a/N` (the transient discretisation tends to the steady one of
    /// [`SteadySolver`] when `dq <= h`). `progress` is called after each record.
    pub fn exact_path(
        &self,
        r: f64,
        grid: usize,
        progress: &mut dyn FnMut(),
    ) -> Result<Vec<f64>, RollingEffectError> {
        check("ratio r", r, r >= 0.0, "finite and >= 0")?;
        let c = &self.config;
        let d = c.end * self.displacement_scale() / c.steps as f64;
        let k = self.exact_substeps(r, grid);
        let dd = d / k as f64;
        let mut solver =
            TransientSolver::new(self.contact, SolverOptions::with_grid(grid), r * dd)?;
        let mut out = Vec::with_capacity(c.steps + 1);
        out.push(0.0);
        for _ in 0..c.steps {
            let mut q = 0.0;
            for _ in 0..k {
                q = solver.advance(dd, 0.0, 0.0)?.fx_over_mu_p;
            }
            out.push(q);
            progress();
        }
        Ok(out)
    }

    /// Boundary-element steps per record on the path of ratio `r` with grid `grid`: the fewest
    /// that roll at most one element side each (1 for `r = 0`).
    pub fn exact_substeps(&self, r: f64, grid: usize) -> usize {
        let d = self.config.end * self.displacement_scale() / self.config.steps as f64;
        let h = 2.0 * self.a() / grid.max(1) as f64;
        let k = (r * d / h).ceil();
        if k.is_finite() && k >= 1.0 {
            k as usize
        } else {
            1
        }
    }

    /// Both models along the path of ratio `r` (the exact one on the configured grid).
    pub fn curve(&self, r: f64, progress: &mut dyn FnMut()) -> Result<Curve, RollingEffectError> {
        Ok(Curve {
            r,
            delta: self.deltas(),
            exact: self.exact_path(r, self.config.grid, progress)?,
            kuhn: self.kuhn_path(r)?,
        })
    }

    /// Every path of the configuration, in the order of `ratios`. `progress` is called after
    /// each boundary-element step (`ratios.len() * steps` calls).
    pub fn curves(&self, progress: &mut dyn FnMut()) -> Result<Vec<Curve>, RollingEffectError> {
        self.config
            .ratios
            .iter()
            .map(|&r| self.curve(r, progress))
            .collect()
    }

    /// Steady rolling at creepage `1/r` (`r > 0`): `Q/(mu P)` by the exact theory (steady
    /// boundary elements on `grid`) and by Kalker's closed form `F_ss` inverted (Kalker 2000,
    /// the law Kuhn's rule tends to), as `(exact, kuhn)`.
    pub fn steady(&self, r: f64, grid: usize) -> Result<(f64, f64), RollingEffectError> {
        check("ratio r", r, r > 0.0, "finite and > 0")?;
        let xi = 1.0 / r;
        let mut s = SteadySolver::new(self.contact, SolverOptions::with_grid(grid))?;
        let exact = s.solve(Creepage::longitudinal(xi))?.fx / self.mu_p();
        let kuhn = SteadyLaw::Kuhn { c11: self.pair.c11 }.force_ratio(xi / self.epsilon());
        Ok((exact, kuhn))
    }
}

/// How much rolling changes `Q` at a fixed sliding displacement: the displacement `delta_ref`
/// where the `r = 0` curve of one model reaches `level * mu P`, and the relative reduction
/// `1 - Q_r(delta_ref) / Q_0(delta_ref)` of every curve of the same model there.
#[derive(Debug, Clone, PartialEq)]
pub struct CreepEffect {
    /// The force level of the `r = 0` curve that fixes the displacement, `Q/(mu P)`.
    pub level: f64,
    /// Normalised sliding displacement where the `r = 0` curve reaches `level`.
    pub delta: f64,
    /// `(r, 1 - Q_r/Q_0)` per curve, in increasing `r` \[dimensionless\].
    pub change: Vec<(f64, f64)>,
}

impl CreepEffect {
    /// The effect for the model picked by `values` (e.g. `|c| &c.exact`) at `level`; `None` if
    /// there is no `r = 0` curve or it never reaches `level`.
    pub fn measure(
        curves: &[Curve],
        values: impl Fn(&Curve) -> &[f64],
        level: f64,
    ) -> Option<CreepEffect> {
        let base = curves.iter().find(|c| c.r == 0.0)?;
        let delta = first_crossing(&base.delta, values(base), level)?;
        let q0 = interpolate(&base.delta, values(base), delta)?;
        let change = curves
            .iter()
            .filter_map(|c| {
                let q = interpolate(&c.delta, values(c), delta)?;
                Some((c.r, 1.0 - q / q0))
            })
            .collect::<Vec<_>>();
        let mut change = change;
        change.sort_by(|a, b| a.0.total_cmp(&b.0));
        Some(CreepEffect {
            level,
            delta,
            change,
        })
    }

    /// The smallest ratio `r` at which the change reaches `threshold` (linear interpolation
    /// between the sampled ratios); `None` if no sampled ratio reaches it.
    pub fn threshold_ratio(&self, threshold: f64) -> Option<f64> {
        if let Some(&(r, c)) = self.change.first()
            && c >= threshold
        {
            return Some(r);
        }
        self.change.windows(2).find_map(|w| {
            let ((r0, c0), (r1, c1)) = (w[0], w[1]);
            (c0 < threshold && c1 >= threshold)
                .then(|| r0 + (r1 - r0) * (threshold - c0) / (c1 - c0))
        })
    }
}
