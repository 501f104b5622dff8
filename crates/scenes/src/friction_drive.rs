//! Friction drive: a sphere driven at a fixed angular speed turns a second sphere, pressed onto
//! it, against a brake torque. Both centres are fixed (the output sphere may only move along the
//! line of centres and turn about the drive axis). In steady state the friction force balances
//! the brake, `Q = T / R_out` (the engine transmits it through a lever arm shortened by its
//! contact penetration, so the measured `Q` is used), at `P = m_out g + F_press`, and the output turns slower than the
//! input by the creepage `xi = v_slip / v_roll = F_ss(Q / (mu P))` (Kalker 2000; Kuhn 2011):
//! torque preserved, speed lost — the talk's "torque-preserving" rolling resistance.

use creep_law::{Material, PairMaterial, Surface, hertz, kalker};
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::incline::G;
use crate::measure::{RollingMeter, SceneError, positive};

/// Parameters of the friction drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveParams {
    /// Radius of both spheres \[m\].
    pub radius: f64,
    /// Material of both spheres.
    pub material: Material,
    /// Angular speed of the driving sphere [rad/s].
    pub omega: f64,
    /// Extra force pressing the output sphere onto the driver \[N\] (>= 0).
    pub press: f64,
    /// Time step \[s\].
    pub dt: f64,
    /// Duration \[s\]; the creepage is measured over the last half.
    pub duration: f64,
}

impl Default for DriveParams {
    fn default() -> Self {
        Self {
            radius: 0.05,
            material: Material::steel(),
            omega: 10.0,
            press: 0.0,
            dt: 1.0 / 240.0,
            duration: 2.0,
        }
    }
}

impl DriveParams {
    /// Mass of each sphere \[kg\] (uniform solid sphere).
    pub fn mass(&self) -> f64 {
        crate::measure::sphere_mass(self.material.density(), self.radius)
    }
    /// Normal force of the contact: the output sphere's weight plus `press` \[N\].
    pub fn normal_force(&self) -> f64 {
        self.mass() * G + self.press
    }

    /// Kalker's steady creepage `F_ss(Q/(mu P))` [-] (Kalker 2000; Kuhn 2011) of the two
    /// spheres' contact at normal force `pn` and tangential force `q` \[N\], with Hertz's contact
    /// radius at `pn`.
    pub fn expected_creepage(&self, pn: f64, q: f64) -> Result<f64, SceneError> {
        let pair = PairMaterial::new(
            &self.material,
            &self.material,
            Surface::Sphere(self.radius),
            Surface::Sphere(self.radius),
        )?;
        let mu_p = self.material.friction() * pn;
        let a = hertz::contact_radius(&pair, pn);
        Ok(kalker::steady_creepage(q / mu_p, mu_p, pair.g, a, pair.c11))
    }
}

/// One brake torque of the drive.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriveRow {
    /// Brake torque on the output sphere [N m].
    pub brake_torque: f64,
    /// Normal force P \[N\].
    pub p: f64,
    /// Friction force the contact transmitted, measured \[N\] (`T / R` up to the engine's
    /// contact-penetration lever arm, a fraction of a percent).
    pub q: f64,
    /// Q / (mu P) [-].
    pub q_over_mu_p: f64,
    /// Hertz contact radius \[m\].
    pub contact_radius: f64,
    /// Combined shear modulus (Kalker) \[Pa\].
    pub g: f64,
    /// Combined Poisson ratio (Kalker) [-].
    pub nu: f64,
    /// Friction coefficient [-].
    pub mu: f64,
    /// Creepage measured: creep run minus Coulomb run of the same drive [-].
    pub creepage_measured: f64,
    /// Kalker's F_ss(Q/(mu P)) at the measured Q and P [-].
    pub creepage_expected: f64,
    /// Creepage of the Coulomb run alone (the engine's own slip) [-].
    pub creepage_engine: f64,
}

/// What one run measured over its second half.
struct Measured {
    /// Creepage `(R w_in - R w_out) / (R (w_in + w_out) / 2)` from the accumulated angles.
    creepage: f64,
    /// Mean friction force the contact transmitted (the plugin's record) \[N\].
    q: f64,
    /// Mean normal force \[N\].
    p: f64,
}

fn run_one(p: &DriveParams, torque: f64, fidelity: Fidelity) -> Result<Measured, SceneError> {
    let mut w = CreepWorld::new(p.dt as f32, CreepSettings::default().with_rapier_solver())?;
    let mat = CreepMaterial::new(p.material).with_fidelity(fidelity);
    let r = p.radius as f32;
    let mu = p.material.friction() as f32;
    let (driver, _) = w.insert(
        RigidBodyBuilder::kinematic_velocity_based().angvel(Vector::new(0.0, 0.0, p.omega as f32)),
        ColliderBuilder::ball(r).friction(mu),
        Some(mat),
    );
    let (out, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 2.0 * r, 0.0))
            .enabled_translations(false, true, false)
            .can_sleep(false),
        ColliderBuilder::ball(r)
            .density(p.material.density() as f32)
            .friction(mu),
        Some(mat),
    );
    {
        let b = &mut w.physics.bodies[out];
        // The output counter-rotates (w_out = -w_in); the brake opposes it.
        b.add_torque(Vector::new(0.0, 0.0, torque as f32), true);
        b.add_force(Vector::new(0.0, -p.press as f32, 0.0), true);
        b.set_angvel(Vector::new(0.0, 0.0, -p.omega as f32), true);
    }
    let steps = (p.duration / p.dt).round() as usize;
    let (mut m_in, mut m_out) = (RollingMeter::default(), RollingMeter::default());
    let (mut q_sum, mut p_sum, mut n) = (0.0, 0.0, 0usize);
    for i in 0..steps {
        w.step()?;
        if i == steps / 2 {
            m_in = RollingMeter::default();
            m_out = RollingMeter::default();
        }
        if i > steps / 2 {
            for (_, rec) in w.hooks().records() {
                q_sum += rec.q_used.length();
                p_sum += rec.p;
                n += 1;
            }
        }
        m_in.update(*w.physics.bodies[driver].rotation(), Vector::Z);
        m_out.update(*w.physics.bodies[out].rotation(), Vector::Z);
    }
    let (a_in, a_out) = (m_in.angle, -m_out.angle);
    let n = n.max(1) as f64;
    Ok(Measured {
        creepage: (a_in - a_out) / (0.5 * (a_in + a_out)),
        q: q_sum / n,
        p: p_sum / n,
    })
}

/// Runs the drive at each brake torque [N m] (creep and Coulomb runs of the same scene).
pub fn run(p: &DriveParams, torques: &[f64]) -> Result<Vec<DriveRow>, SceneError> {
    positive("radius", p.radius)?;
    positive("omega", p.omega)?;
    positive("dt", p.dt)?;
    positive("duration", p.duration)?;
    if !(p.press >= 0.0 && p.press.is_finite()) {
        return Err(SceneError::Parameter(format!(
            "press must be finite and >= 0, got {}",
            p.press
        )));
    }
    let mu = p.material.friction();
    let pn = p.normal_force();
    let pair = PairMaterial::new(
        &p.material,
        &p.material,
        Surface::Sphere(p.radius),
        Surface::Sphere(p.radius),
    )?;
    let mut rows = Vec::with_capacity(torques.len());
    for &t in torques {
        let q = t / p.radius;
        if !(t >= 0.0 && q < mu * pn) {
            return Err(SceneError::Parameter(format!(
                "brake torque {t} N m must be in [0, mu P R) = [0, {})",
                mu * pn * p.radius
            )));
        }
        let engine = run_one(p, t, Fidelity::Coulomb)?;
        let creep = run_one(p, t, Fidelity::Creep)?;
        let (q, pm) = if creep.q > 0.0 && creep.p > 0.0 {
            (creep.q, creep.p)
        } else {
            (q, pn)
        };
        let a = hertz::contact_radius(&pair, pm);
        rows.push(DriveRow {
            brake_torque: t,
            p: pm,
            q,
            q_over_mu_p: q / (mu * pm),
            contact_radius: a,
            g: pair.g,
            nu: pair.nu,
            mu,
            creepage_measured: creep.creepage - engine.creepage,
            creepage_expected: p.expected_creepage(pm, q)?,
            creepage_engine: engine.creepage,
        });
    }
    Ok(rows)
}
