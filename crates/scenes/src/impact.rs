//! A normal impact in the compliant (soft-sphere DEM) regime, after Chung & Ooi (2011, "Benchmark
//! tests for verifying discrete element modelling codes at particle impact level", Granular
//! Matter 13, 643-656, test 2): a sphere meets a fixed wall of the same material head-on at
//! speed `v`, gravity off, at a time step given as a fraction of the Rayleigh time step. Against
//! Hertz's impact (`creep_reference::hertz::HertzImpact`; Johnson 1985, *Contact Mechanics*,
//! §11.4): contact duration and peak force (elastic, `e = 1`), and the rebound speed over the
//! approach speed against the restitution the colliders ask for (the regime's damping is chosen
//! to give it exactly in the continuous limit).
//!
//! The contact duration is timed from the sphere's gap to the wall, `y - top - R`, interpolated
//! linearly to its zero crossings between steps (the approach is at constant speed, so the
//! entry time is exact; the exit interpolation errs by O(dt^2)), so that it measures the
//! integration and not the step's quantisation. The peak force is the largest the regime
//! applied in a step. The wall's face is at `y = -R`, so the sphere's centre meets it near the
//! origin, where f32 positions are finest.

use creep_law::{Material, PairMaterial, Surface, hertz};
use creep_rapier::{CompliantSettings, CreepMaterial, CreepSettings, CreepWorld};
use creep_reference::hertz::HertzImpact;
use rapier3d::prelude::*;

use crate::measure::{SceneError, positive};

/// Parameters of the impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactParams {
    /// Material of the sphere and the wall.
    pub material: Material,
    /// Sphere radius R \[m\].
    pub radius: f64,
    /// Approach speed v [m/s].
    pub speed: f64,
    /// Coefficient of restitution of the colliders, in (0, 1].
    pub restitution: f64,
    /// Time step as a fraction of the sphere's Rayleigh time step `T_R`
    /// (`creep_law::hertz::rayleigh_time_step`), in (0, 1].
    pub dt_over_rayleigh: f64,
}

impl Default for ImpactParams {
    /// A glass sphere of 10 mm at 1 m/s (`t_c` = 6.9 `T_R`), elastic, at 0.1 `T_R`.
    fn default() -> Self {
        Self {
            material: Material::glass(),
            radius: 0.01,
            speed: 1.0,
            restitution: 1.0,
            dt_over_rayleigh: 0.1,
        }
    }
}

/// What the impact measured, next to Hertz's closed form.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactResult {
    /// The time step \[s\].
    pub dt: f64,
    /// The Rayleigh time step `T_R` \[s\].
    pub rayleigh_time: f64,
    /// Contact duration, interpolated to the gap's zero crossings \[s\].
    pub duration: f64,
    /// Largest normal force the regime applied \[N\].
    pub peak_force: f64,
    /// Rebound speed over approach speed [-].
    pub rebound: f64,
    /// Hertz's impact (Johnson 1985, §11.4) for this sphere, wall and speed.
    pub hertz: HertzImpact,
    /// Steps with the contact open (overlap at the step's start).
    pub contact_steps: usize,
}

impl ImpactResult {
    /// `duration / t_c - 1` [-].
    pub fn duration_error(&self) -> f64 {
        self.duration / self.hertz.duration - 1.0
    }

    /// `peak_force / P_max - 1` [-].
    pub fn peak_force_error(&self) -> f64 {
        self.peak_force / self.hertz.peak_force - 1.0
    }
}

/// Runs the impact; the restitution error is `rebound / restitution - 1`.
pub fn run(p: &ImpactParams) -> Result<ImpactResult, SceneError> {
    positive("radius", p.radius)?;
    positive("speed", p.speed)?;
    positive("restitution", p.restitution)?;
    positive("dt_over_rayleigh", p.dt_over_rayleigh)?;
    if p.restitution > 1.0 || p.dt_over_rayleigh > 1.0 {
        return Err(SceneError::Parameter(format!(
            "restitution ({}) and dt_over_rayleigh ({}) must be in (0, 1]",
            p.restitution, p.dt_over_rayleigh
        )));
    }
    let r = p.radius;
    let mass = crate::measure::sphere_mass(p.material.density(), r);
    let pair = PairMaterial::new(&p.material, &p.material, Surface::Plane, Surface::Sphere(r))?;
    let hertz_impact = HertzImpact::new(mass, r, pair.e_star, p.speed)
        .map_err(|e| SceneError::Parameter(e.to_string()))?;
    let t_r = hertz::rayleigh_time_step(&p.material, r);
    let dt = p.dt_over_rayleigh * t_r;
    let mut w = CreepWorld::new(dt as f32, CreepSettings::default().with_rapier_solver())?;
    w.physics.gravity = Vector::ZERO;
    // One solver iteration: symplectic Euler for the contact forces (the regime's requirement).
    w.physics.integration_parameters.num_solver_iterations = 1;
    w.compliant_mut().set_settings(CompliantSettings {
        rayleigh_fraction: p
            .dt_over_rayleigh
            .max(CompliantSettings::default().rayleigh_fraction),
        ..CompliantSettings::default()
    })?;
    let mat = Some(CreepMaterial::compliant(p.material));
    let (e, mu) = (p.restitution as f32, p.material.friction() as f32);
    // A fixed wall whose top face is the plane y = -R.
    let top = -r;
    let (wall, _) = w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, (top - 0.05) as f32, 0.0)),
        ColliderBuilder::cuboid(1.0, 0.05, 1.0)
            .restitution(e)
            .friction(mu),
        mat,
    );
    // Three steps of approach before the contact.
    let gap0 = 3.0 * p.speed * dt;
    let (h, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, (top + r + gap0) as f32, 0.0))
            .linvel(Vector::new(0.0, -p.speed as f32, 0.0)),
        ColliderBuilder::ball(r as f32)
            .density(p.material.density() as f32)
            .restitution(e)
            .friction(mu),
        mat,
    );
    // The wall's face and the sphere's radius as the engine holds them (f32): the face's
    // rounding, a few nm, is 6e-5 of the contact's duration.
    let face = f64::from(w.physics.bodies[wall].translation().y) + f64::from(0.05f32);
    let radius = f64::from(r as f32);
    let gap = |w: &CreepWorld| f64::from(w.physics.bodies[h].translation().y) - face - radius;
    let max_steps = (20.0 * hertz_impact.duration / dt) as usize + 100;
    let (mut t_in, mut t_out) = (None, None);
    let (mut peak, mut contact_steps) = (0.0f64, 0usize);
    let mut g_prev = gap(&w);
    for step in 0..max_steps {
        w.step()?;
        let g = gap(&w);
        if !g.is_finite() {
            return Err(SceneError::Parameter(format!(
                "the impact became non-finite at step {step}"
            )));
        }
        let t = (step + 1) as f64 * dt;
        // Linear interpolation of the gap's zero crossing within the step.
        let crossing = t - dt * g / (g - g_prev);
        if t_in.is_none() && g <= 0.0 {
            t_in = Some(crossing);
        } else if t_in.is_some() && g > 0.0 && g_prev <= 0.0 {
            t_out = Some(crossing);
        }
        if w.compliant().counts().contacts > 0 {
            contact_steps += 1;
            for (_, c) in w.compliant().contacts() {
                peak = peak.max(c.normal_force);
            }
        }
        g_prev = g;
        if t_out.is_some() && w.compliant().counts().contacts == 0 {
            break;
        }
    }
    let (Some(t_in), Some(t_out)) = (t_in, t_out) else {
        return Err(SceneError::Parameter(format!(
            "the impact did not end within {max_steps} steps"
        )));
    };
    let rebound = f64::from(w.physics.bodies[h].linvel().y) / p.speed;
    Ok(ImpactResult {
        dt,
        rayleigh_time: t_r,
        duration: t_out - t_in,
        peak_force: peak,
        rebound,
        hertz: hertz_impact,
        contact_steps,
    })
}
