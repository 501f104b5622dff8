//! A ball launched sliding without spin on a level floor (a cue ball): kinetic friction `mu m g`
//! decelerates it and spins it up until it rolls, after `t_s = 2 v0 / (7 mu g)`, at
//! `v = (5/7) v0` (a uniform solid sphere). Creep-friction must leave this as Coulomb does:
//! in gross slip the friction is at its limit either way.

use creep_law::Material;
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::incline::G;
use crate::measure::{SceneError, positive};

/// Result of the cue-ball scene for one fidelity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CueBallRun {
    /// Speed once rolling [m/s].
    pub final_speed: f64,
    /// Time at which slip fell below 1 % of the speed \[s\].
    pub slip_time: f64,
}

/// Result with the closed forms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CueBallResult {
    /// Coulomb run.
    pub coulomb: CueBallRun,
    /// Creep-friction run.
    pub creep: CueBallRun,
    /// `(5/7) v0` [m/s].
    pub final_speed_expected: f64,
    /// `2 v0 / (7 mu g)` \[s\].
    pub slip_time_expected: f64,
}

fn run_one(
    material: Material,
    v0: f64,
    dt: f64,
    fidelity: Fidelity,
) -> Result<CueBallRun, SceneError> {
    let mut w = CreepWorld::new(dt as f32, CreepSettings::default().with_rapier_solver())?;
    let mat = CreepMaterial::new(material).with_fidelity(fidelity);
    let mu = material.friction() as f32;
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 10.0).friction(mu),
        Some(mat),
    );
    let r = 0.03f32;
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r, 0.0))
            .linvel(Vector::new(v0 as f32, 0.0, 0.0))
            .can_sleep(false),
        ColliderBuilder::ball(r)
            .density(material.density() as f32)
            .friction(mu),
        Some(mat),
    );
    let t_end = 3.0 * 2.0 * v0 / (7.0 * material.friction() * G);
    let steps = (t_end / dt).ceil() as usize;
    let mut slip_time = f64::NAN;
    for i in 0..steps {
        w.step()?;
        let b = &w.physics.bodies[ball];
        let v = f64::from(b.linvel().x);
        let slip = v + f64::from(b.angvel().z) * f64::from(r);
        if slip_time.is_nan() && slip.abs() < 0.01 * v {
            slip_time = (i + 1) as f64 * dt;
        }
    }
    Ok(CueBallRun {
        final_speed: f64::from(w.physics.bodies[ball].linvel().x),
        slip_time,
    })
}

/// Runs the cue ball (launch speed `v0` [m/s], step `dt` \[s\]) with Coulomb and with creep.
pub fn run(material: Material, v0: f64, dt: f64) -> Result<CueBallResult, SceneError> {
    positive("v0", v0)?;
    positive("dt", dt)?;
    positive("mu", material.friction())?;
    Ok(CueBallResult {
        coulomb: run_one(material, v0, dt, Fidelity::Coulomb)?,
        creep: run_one(material, v0, dt, Fidelity::Creep)?,
        final_speed_expected: 5.0 / 7.0 * v0,
        slip_time_expected: 2.0 * v0 / (7.0 * material.friction() * G),
    })
}
