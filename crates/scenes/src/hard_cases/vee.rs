//! The V-incline (module docs of [`super`]): its force field and the scene builder [`Vee`].

use creep_law::{Material, PairMaterial, Surface, hertz, kalker};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use super::*;
use crate::measure::SceneError;

/// Applies the V-incline force field for the coming step; returns the force along x.
pub(super) fn apply_vee(s: &mut Scene) -> f64 {
    let Some((b, mag)) = s.vee else {
        return 0.0;
    };
    let rb = &mut s.w.physics.bodies[b];
    let dt = f(s.w.physics.integration_parameters.dt);
    let n = s.w.physics.integration_parameters.num_solver_iterations;
    let m_eff = 1.4 * f(rb.mass());
    let fx = vee_force(f(rb.translation().x), f(rb.linvel().x), dt, mag, m_eff, n);
    rb.reset_forces(false);
    rb.add_force(Vector::new(fx as f32, 0.0, 0.0), false);
    fx
}

/// The V-incline force for a step from `x` at velocity `v`: the discrete gradient
/// `-(U(x1) - U(x)) / (x1 - x)` of `U = mag |x|` over the step's move `x1 - x`, predicted as
/// Rapier integrates a constant force over `n` substeps, `x1 = x + v dt + F/m_eff dt^2 (1 +
/// 1/n)/2` (`m_eff = 7/5 m` for a rolling ball), solved for `F` by fixed point. It is `-mag
/// sign(x)` except in the step that crosses `x = 0`, where the work done equals the potential
/// drop (a force taken from the step's start alone pushes the ball on past the bottom and feeds
/// it energy at every crossing; a linear core is worse: Rapier holds a user force constant over
/// the step's substeps, which is unstable for a position-dependent force, the energy growing by
/// `(1 - 5/8) (w dt)^2` per step with 4 substeps).
pub(super) fn vee_force(x: f64, v: f64, dt: f64, mag: f64, m_eff: f64, substeps: usize) -> f64 {
    let k = dt * dt * (1.0 + 1.0 / substeps as f64) / 2.0 / m_eff;
    let mut force = -mag * x.signum();
    for _ in 0..50 {
        let x1 = x + v * dt + force * k;
        if x * x1 > 0.0 || (x1 - x).abs() < 1e-12 {
            break;
        }
        force = -mag * (x1.abs() - x.abs()) / (x1 - x);
    }
    force
}

/// A V-incline scene (module docs).
#[derive(Debug, Clone, Copy)]
pub(super) struct Vee {
    pub(super) dt: f32,
    /// Ball (and floor) material; the ball's density is the material's.
    pub(super) mat: Material,
    /// Ball radius \[m\].
    pub(super) r: f32,
    /// Collider friction (all colliders).
    pub(super) mu: f32,
    /// Incline angle \[rad\].
    pub(super) theta: f64,
    /// Start position of the ball along x \[m\] (at rest unless `w0`).
    pub(super) x_start: f32,
    /// Initial angular velocity [rad/s].
    pub(super) w0: Vector,
    /// A free thin slab of this mass \[kg\] between the ball and the floor.
    pub(super) slab: Option<f32>,
    /// Rapier's solver substeps (`num_solver_iterations`), if not the default.
    pub(super) substeps: Option<usize>,
    /// See [`Scene::min_amplitude`] \[m\].
    pub(super) min_amplitude: f64,
    /// The ball's density [kg/m^3], if not its material's.
    pub(super) ball_density: Option<f32>,
    /// Whether the slab's energy is counted (a slab far heavier than the ball is the ground:
    /// its f32 state's energy rounding would swamp the ball's).
    pub(super) count_slab: bool,
    /// How the creep and the energy are judged.
    pub(super) check: Check,
}

impl Vee {
    pub(super) fn build(&self, fidelity: Fidelity) -> Result<Scene, SceneError> {
        let Vee {
            dt,
            mat: ball_mat,
            r,
            mu,
            theta,
            x_start,
            w0,
            slab,
            substeps,
            min_amplitude,
            ball_density,
            count_slab,
            check: _,
        } = *self;
        let mut w = CreepWorld::new(dt, CreepSettings::default().with_rapier_solver())?;
        if let Some(n) = substeps {
            w.physics.integration_parameters.num_solver_iterations = n;
        }
        w.physics.gravity = Vector::new(0.0, (-G * theta.cos()) as f32, 0.0);
        let mat = CreepMaterial::new(ball_mat).with_fidelity(fidelity);
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
            ColliderBuilder::cuboid(1000.0, 0.5, 1000.0).friction(mu),
            Some(mat),
        );
        let mut dynamic = vec![];
        let mut support = None;
        let mut y = r;
        if let Some(m_slab) = slab {
            // A thin light slab, 4 m x 2 cm x 4 m, resting on the floor.
            let (s, _) = w.insert(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(0.0, 0.01, 0.0))
                    .can_sleep(false),
                ColliderBuilder::cuboid(2.0, 0.01, 2.0)
                    .mass(m_slab)
                    .friction(mu),
                Some(mat),
            );
            if count_slab {
                dynamic.push(s);
            }
            support = Some(s);
            y += 0.02;
        }
        let (ball, _) = w.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(x_start, y, 0.0))
                .angvel(w0)
                .can_sleep(false),
            ColliderBuilder::ball(r)
                .density(ball_density.unwrap_or(ball_mat.density() as f32))
                .friction(mu),
            Some(mat),
        );
        dynamic.push(ball);
        let m = f(w.physics.bodies[ball].mass());
        // Kalker's steady creepage of the ball on the plane: P = m g cos(theta).
        let pair = PairMaterial::new(
            &ball_mat,
            &ball_mat,
            Surface::Plane,
            Surface::Sphere(f64::from(r)),
        )?
        .with_friction(f64::from(mu))?;
        let p = m * G * theta.cos();
        let a = hertz::contact_radius(&pair, p);
        let mu_p = f64::from(mu) * p;
        let f_ss = move |q: f64| kalker::steady_creepage(q / mu_p, mu_p, pair.g, a, pair.c11);
        Ok(Scene {
            w,
            dynamic,
            vee: Some((ball, m * G * theta.sin())),
            f_ss: Some(Box::new(f_ss)),
            support,
            radius: f64::from(r),
            min_amplitude,
        })
    }

    /// Runs the case both ways: the creep increment over Kalker's prediction, the traces, the
    /// verdicts and the lines describing it.
    pub(super) fn case(
        &self,
        label: &str,
        steps: usize,
        measure_from: usize,
    ) -> Result<Outcome, SceneError> {
        let (tc, _) = run(self.build(Fidelity::Coulomb)?, steps, measure_from)?;
        let (tk, _) = run(self.build(Fidelity::Creep)?, steps, measure_from)?;
        let s_max = 2.0 / 7.0 * self.theta.tan() / f64::from(self.mu);
        let engine = tc.slip / tc.path;
        let creep = tk.slip / tk.path;
        let expect = tk.predicted / tk.path;
        let paired = tk.paired_slip / tk.path;
        let ratio = match self.check {
            Check::Paired => paired,
            Check::RunDifference => creep - engine,
        } / expect;
        let mut lines = vec![format!(
            "{label}: Q/(mu P) <= {s_max:.3}; slip per rolled distance: coulomb run {engine:+.4e}, creep run {creep:+.4e} (run difference {:+.4e}); creep added per step against the twin {paired:.4e} vs Kalker {expect:.4e} (judged by {:?}: ratio {ratio:.4}); rolled {:.1} m",
            creep - engine,
            self.check,
            tk.path
        )];
        let mut verdicts = common_verdicts(label, &tk, &tc, self.check, &mut lines);
        verdicts.push(creep_converges(ratio));
        Ok(Outcome {
            creep_ratio: Some(ratio),
            creep: tk,
            coulomb: tc,
            verdicts,
            lines,
        })
    }
}

pub(super) fn steel_vee() -> Vee {
    Vee {
        dt: 1.0 / 60.0,
        mat: Material::steel(),
        r: 0.1,
        mu: 0.5,
        theta: 0.3490658503988659, // 20 degrees
        x_start: 1.0,
        w0: Vector::ZERO,
        slab: None,
        substeps: None,
        min_amplitude: 0.0,
        ball_density: None,
        count_slab: true,
        check: Check::Paired,
    }
}

/// Rubber (G = 1 MPa, nu = 0.49) on rubber, mu = 0.9, the V steep enough that the incline
/// demands Q/(mu P) = 0.8 (theta = 68.4 deg): Kalker's creepage ~0.05, the contact radius
/// ~9 mm, from rest 0.5 m up; creep measured while the ball's amplitude is at least 0.1 m (as
/// in the spin case: below it the force reverses every few steps).
pub(super) fn rubber_vee(dt: f32) -> Vee {
    let mu = 0.9;
    Vee {
        dt,
        mat: Material::rubber(),
        mu: mu as f32,
        theta: (0.8 * 3.5 * mu).atan(),
        x_start: 0.5,
        min_amplitude: 0.1,
        check: Check::RunDifference,
        ..steel_vee()
    }
}

/// The ball mass of the steel V \[kg\].
pub(super) fn steel_ball_mass() -> f32 {
    crate::measure::sphere_mass(7850.0, 0.1) as f32
}
