//! Free rolling on a level floor: no tangential force is needed to keep a ball rolling, so
//! creep-friction (which needs a force to creep) adds no resistance — the talk's distinction
//! from contact-torque rolling resistance. The speed with creep must equal Coulomb's.

use creep_law::Material;
use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity};
use rapier3d::prelude::*;

use crate::measure::{SceneError, positive};

/// Speeds after `duration` with Coulomb and with creep-friction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeRollingResult {
    /// Speed of the Coulomb run [m/s].
    pub coulomb_speed: f64,
    /// Speed of the creep run [m/s].
    pub creep_speed: f64,
    /// Launch speed [m/s].
    pub v0: f64,
}

fn run_one(
    material: Material,
    v0: f64,
    dt: f64,
    duration: f64,
    fidelity: Fidelity,
) -> Result<f64, SceneError> {
    let mut w = CreepWorld::new(dt as f32, CreepSettings::default().with_rapier_solver())?;
    let mat = CreepMaterial::new(material).with_fidelity(fidelity);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1.0e3, 0.5, 10.0),
        Some(mat),
    );
    let r = 0.1;
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, r as f32, 0.0))
            .linvel(Vector::new(v0 as f32, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, (-v0 / r) as f32))
            .can_sleep(false),
        ColliderBuilder::ball(r as f32).density(material.density() as f32),
        Some(mat),
    );
    for _ in 0..(duration / dt).round() as usize {
        w.step()?;
    }
    Ok(f64::from(w.physics.bodies[ball].linvel().x))
}

/// A 0.1 m ball launched rolling at `v0` [m/s] for `duration` \[s\] at step `dt` \[s\].
pub fn run(
    material: Material,
    v0: f64,
    dt: f64,
    duration: f64,
) -> Result<FreeRollingResult, SceneError> {
    positive("v0", v0)?;
    positive("dt", dt)?;
    positive("duration", duration)?;
    Ok(FreeRollingResult {
        coulomb_speed: run_one(material, v0, dt, duration, Fidelity::Coulomb)?,
        creep_speed: run_one(material, v0, dt, duration, Fidelity::Creep)?,
        v0,
    })
}
