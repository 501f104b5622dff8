//! A sphere rolling down an incline. Without creep (Coulomb, rolling without slip) its
//! acceleration is `(5/7) g sin(theta)` (a uniform solid sphere: `I = (2/5) m R^2`); the friction
//! force is `Q = (2/7) m g sin(theta)` at `P = m g cos(theta)`. With creep-friction the contact
//! also slips forward by Kalker's steady creepage `F_ss(Q/(mu P))` per unit rolled distance.
//! The incline is a fixed flat cuboid with the gravity tilted by `theta`.

use creep_law::steady_law::SteadyLaw;
use creep_law::{CreepModel, Material, PairMaterial, Surface};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity, StepCounts};
use rapier3d::prelude::*;

use crate::measure::{RollingMeter, SceneError, positive};

/// Standard gravity [m/s^2].
pub const G: f64 = 9.81;

/// Parameters of the incline scene.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InclineParams {
    /// Incline angle theta \[rad\], in (0, atan(7 mu / 2)) for rolling.
    pub theta: f64,
    /// Sphere radius R \[m\].
    pub radius: f64,
    /// Material of ball and incline (G, nu, rho; friction mu).
    pub material: Material,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; slip is measured over the second half.
    pub duration: f64,
    /// The plugin's steady creep law (and the one the expectation uses).
    pub creep_model: CreepModel,
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
            creep_model: CreepModel::Kuhn,
        }
    }
}

impl InclineParams {
    /// The closed-form loads of rolling without slip, `(P, Q)` = `(m g cos(theta), (2/7) m g
    /// sin(theta))` \[N\] (a uniform solid sphere, `I = (2/5) m R^2`).
    pub fn rolling_loads(&self) -> (f64, f64) {
        let m = crate::measure::sphere_mass(self.material.density(), self.radius);
        (
            m * G * self.theta.cos(),
            2.0 / 7.0 * m * G * self.theta.sin(),
        )
    }

    /// The steady creepage [-] of the ball on the plane at normal force `pn` and friction force
    /// `q` \[N\]: the plugin's steady law (`creep_model`; Kalker's `F_ss(Q/(mu P))` for `Kuhn`,
    /// Kalker 2000, Kuhn 2011) with Hertz's contact radius at `pn`.
    pub fn expected_creepage(&self, pn: f64, q: f64) -> Result<f64, SceneError> {
        let pair = PairMaterial::new(
            &self.material,
            &self.material,
            Surface::Plane,
            Surface::Sphere(self.radius),
        )?;
        Ok(
            SteadyLaw::with_c11(self.creep_model, pair.nu, pair.c11).contact_creepage(
                &pair,
                self.material.friction(),
                pn,
                q,
            ),
        )
    }
}

/// What the incline measured, for one fidelity.
#[derive(Debug, Clone, PartialEq)]
pub struct InclineRun {
    /// Mean acceleration along the incline [m/s^2].
    pub acceleration: f64,
    /// Slip over the second half, `(dx - R dtheta) / dx` from positions [-].
    pub slip: f64,
    /// Mean friction force the contact transmitted over the second half (the plugin's record;
    /// 0 when the plugin kept no record) \[N\].
    pub q: f64,
    /// Mean normal force over the second half (idem) \[N\].
    pub p: f64,
    /// What the plugin did in the last step.
    pub counts: StepCounts,
}

/// The incline measured with Coulomb and with creep-friction, and the closed forms.
#[derive(Debug, Clone, PartialEq)]
pub struct InclineResult {
    /// Coulomb run (Rapier's own rolling, including its spurious slip).
    pub coulomb: InclineRun,
    /// Creep-friction run.
    pub creep: InclineRun,
    /// `(5/7) g sin(theta)` [m/s^2].
    pub acceleration_expected: f64,
    /// Creep slip measured: creep run minus Coulomb run [-].
    pub creepage_measured: f64,
    /// The steady creep law's creepage (`params.creep_model`; Kalker's `F_ss` for `Kuhn`) at
    /// the measured `Q` and `P` [-].
    pub creepage_expected: f64,
    /// `Q / (mu P)` the contact transmitted (measured) [-].
    pub q_over_mu_p: f64,
}

/// The scene's world: a fixed flat cuboid (top face at `y = 0`) and the ball resting on it at
/// the origin, gravity tilted by `theta`, both colliders registered with `material` (`None`:
/// unregistered, plain Rapier), the plugin's steady law `p.creep_model`. Returns the world and
/// the ball. Shared by this scene, the hard cases' sphere at rest and creep-bevy's tests.
pub fn world(
    p: &InclineParams,
    material: Option<CreepMaterial>,
) -> Result<(CreepWorld, RigidBodyHandle), SceneError> {
    let settings = CreepSettings {
        creep_model: p.creep_model,
        ..Default::default()
    }
    .with_rapier_solver();
    let mut w = CreepWorld::new(p.dt as f32, settings)?;
    w.physics.gravity = Vector::new((G * p.theta.sin()) as f32, (-G * p.theta.cos()) as f32, 0.0);
    let mu = p.material.friction() as f32;
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e4, 0.5, 10.0).friction(mu),
        material,
    );
    let r = p.radius as f32;
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r, 0.0))
            .can_sleep(false),
        ColliderBuilder::ball(r)
            .density(p.material.density() as f32)
            .friction(mu),
        material,
    );
    Ok((w, ball))
}

fn run_one(p: &InclineParams, fidelity: Fidelity) -> Result<InclineRun, SceneError> {
    let mat = CreepMaterial::new(p.material).with_fidelity(fidelity);
    let (mut w, ball) = world(p, Some(mat))?;
    let steps = (p.duration / p.dt).round() as usize;
    let mut meter = RollingMeter::default();
    let mut x0 = 0.0;
    let (mut q_sum, mut p_sum, mut n) = (0.0, 0.0, 0usize);
    let mut counts = StepCounts::default();
    for i in 0..steps {
        counts = w.step()?;
        let b = &w.physics.bodies[ball];
        if i == steps / 2 {
            x0 = f64::from(b.translation().x);
            meter = RollingMeter::default();
        }
        meter.update(*b.rotation(), Vector::Z);
        if i > steps / 2 {
            for (_, rec) in w.hooks().records() {
                q_sum += rec.q_used.length();
                p_sum += rec.p;
                n += 1;
            }
        }
    }
    let b = &w.physics.bodies[ball];
    let dx = f64::from(b.translation().x) - x0;
    let t = steps as f64 * p.dt;
    let n = n.max(1) as f64;
    Ok(InclineRun {
        acceleration: f64::from(b.linvel().x) / t,
        slip: (dx + meter.angle * p.radius) / dx,
        q: q_sum / n,
        p: p_sum / n,
        counts,
    })
}

/// Runs the incline with Coulomb and with creep-friction (same scene, same step).
pub fn run(p: &InclineParams) -> Result<InclineResult, SceneError> {
    positive("radius", p.radius)?;
    positive("dt", p.dt)?;
    positive("duration", p.duration)?;
    let mu = p.material.friction();
    if !(p.theta > 0.0 && p.theta.tan() < 3.5 * mu) {
        return Err(SceneError::Parameter(format!(
            "theta = {} rad: the ball rolls only for 0 < tan(theta) < 7 mu / 2 = {}",
            p.theta,
            3.5 * mu
        )));
    }
    let coulomb = run_one(p, Fidelity::Coulomb)?;
    let creep = run_one(p, Fidelity::Creep)?;
    // The force the contact transmits: (2/7) m g sin(theta) when rolling without slip; with
    // creep the rotation lags and it is smaller (by about the creepage), so the measured force
    // is used where the plugin recorded one.
    let (pn, q) = if creep.q > 0.0 && creep.p > 0.0 {
        (creep.p, creep.q)
    } else {
        p.rolling_loads()
    };
    let creepage_measured = creep.slip - coulomb.slip;
    Ok(InclineResult {
        coulomb,
        creep,
        acceleration_expected: 5.0 / 7.0 * G * p.theta.sin(),
        creepage_measured,
        creepage_expected: p.expected_creepage(pn, q)?,
        q_over_mu_p: q / (mu * pn),
    })
}
