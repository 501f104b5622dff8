//! The compliant (soft-sphere DEM) regime: per pair, the plugin takes the contact out of
//! Rapier's contact solve (the hook clears its solver contacts) and applies, each step, the
//! contact forces and torques itself. Rapier keeps broad phase, narrow phase and integration.
//!
//! Its pairs are those with a collider registered as [`Regime::Compliant`](crate::Regime):
//! a pair is compliant as soon as one of its colliders is ([`crate::Regime::pair`]), so a
//! compliant ball meets a wall (or ball) registered in the rigid regime through these forces,
//! with both colliders' materials. The time-step check below takes the Rayleigh time of the
//! compliant balls only.
//!
//! # The contact law (all in f64)
//! Bodies p (the narrow phase's collider1) and q, unit normal `n` from p to q, overlap `delta`,
//! contact point `c` in the middle of the overlap (conventions: docs/ARCHITECTURE.md §4).
//! * Normal: Hertz `P_e = (4/3) E* sqrt(R*) delta^(3/2)` (Johnson 1985, §4.2) plus the damping
//!   of Tsuji et al. (1992), `alpha sqrt(m* k_H) delta^(1/4) delta_dot`, with `alpha` chosen so
//!   that the impact rebounds with the pair's restitution `e` exactly (see [`damping`]); the
//!   total is never attractive (`P >= 0`).
//! * Tangential: Cattaneo-Mindlin with Kuhn's creep term, creep-law's [`CreepState`](creep_law::CreepState), fed
//!   `du_disp = v_disp dt` and `du_roll = v_roll dt` (Kuhn & Bagi 2004 rates, creep-law
//!   [`contact_rates`](creep_law::kinematics::contact_rates)) at the contact radius `a = sqrt(R* delta)`; its Coulomb limit is
//!   `mu P_e` (creep-law's spring row carries `mu` times the Hertz pressure).
//!   [`CompliantSettings::creep`] = false feeds no rolling displacement: plain Coulomb-Mindlin.
//! * The tangential history lives in a tangent basis `(t1, t2)` carried by the contact: each
//!   step the basis turns with the normal (the smallest rotation taking the last normal to the
//!   new one) and about the normal with the pair's mean spin `(w_p + w_q) . n / 2`, then is
//!   re-orthonormalised. The stored 2-D force therefore follows the contact as a rigid body and
//!   needs no re-projection.
//! * Optional contact-torque rolling resistance (creep-law `rolling_torque`), from the
//!   colliders' [`RollingResistance`](crate::RollingResistance).
//! * Walls (cuboid faces, half-spaces) are the same law with an infinite radius on the wall side
//!   (`Surface::Plane`); a sphere over a cuboid's edge or corner meets it along the line to the
//!   closest point.
//!
//! Friction and restitution of a pair are the colliders' own (`Collider::friction`,
//! `Collider::restitution`) combined by Rapier's combine rules, so Rapier's defaults apply: the
//! default restitution 0 is refused (`MIN_RESTITUTION <= e <= 1`, [`PluginError::Restitution`]):
//! set it on the colliders.
//!
//! # Stepping
//! The step owner ([`crate::CreepPipeline`]) runs the regime's `begin_step` (before `PhysicsPipeline::step`), which computes the geometry of
//! every candidate pair from the *current* poses, the forces with the current velocities, and
//! adds them to the bodies' user forces, saving these first; its `end_step`
//! (after the step) restores the saved user forces exactly. Settled bodies sleep as in plain
//! Rapier: the forces are added without waking a body, except a sleeping one that a moving
//! body touches. Forces at `x_n` with Rapier's
//! velocity-then-position update are symplectic Euler when
//! `IntegrationParameters::num_solver_iterations == 1`; with `k` substeps Rapier applies the
//! frozen force in each substep (still first order, not symplectic): use 1 for DEM scenes.
//! Measured on the elastic sphere-wall impact at 300 steps per contact: energy error 2.6e-5
//! and rebound 1.0000 with 1 substep, 9.3e-3 and 1.0047 with 2, 1.4e-2 and 1.0070 with 4
//! (Rapier's default).
//!
//! Candidate pairs are the narrow phase's contact pairs (broad-phase AABB overlaps with the
//! prediction margin) of the last step. A contact cannot start unseen as long as the pair's
//! relative displacement in one step stays below the prediction distance (default 2 mm per
//! length unit): with DEM steps (a fraction of the Rayleigh time, micro-seconds for mm
//! particles) that is a relative speed of hundreds of m/s.
//!
//! # Time step
//! Explicit: `dt` must be a fraction of the smallest Rayleigh time step `T_R` of the compliant
//! balls (creep-law `hertz::rayleigh_time_step`, Li, Xu & Thornton 2005).
//! [`CompliantSettings::rayleigh_fraction`] (default 0.2) sets the fraction; above it
//! `begin_step` returns [`PluginError::RayleighTimeStep`], or with
//! [`RayleighCheck::Warn`] sets [`CompliantCounts::rayleigh_exceeded`] instead.
//!
//! # f32
//! rapier3d is f32: poses and velocities are rounded to 24 bits; the contact law runs in f64
//! from the f32 poses. Measured (`cargo test -p creep-rapier --test compliant -- --nocapture`,
//! test `f32_resolution_against_step_size`; an aluminium sphere of radius 0.1 m hitting a wall
//! at 0.2 m/s, overlap 49 um): with the centre meeting the wall at y = 0.1 m (f32 spacing, ulp,
//! 7.5e-9 m) the energy error of the impact is 3.8e-4, 1.3e-3, 6.7e-4 and 4.8e-3 at 100, 300,
//! 1000 and 4000 steps per contact (per-step displacement `v dt` = 257, 86, 26 and 6 ulp) and
//! the contact duration is off by +1.3 % at 4000 steps; with the centre meeting the wall at
//! y = 0 the same impact conserves energy to 2.6e-5 and 2.9e-6 at 300 and 4000 steps. The error
//! is the rounding of `x + v dt` to the ulp of `x`: it grows as the step shrinks, and with the
//! distance from the origin (ulp ~ 6e-8 |x|). Rule of thumb: f32 is adequate while the
//! per-step displacement is >= ~100 ulp and the overlap >= ~1e3 ulp of the coordinates. That
//! holds for impacts (these tests), not for quasi-static granular tests: a 5 cm triaxial box
//! (ulp 3.7e-9 m) of 3 mm glass spheres at 100 kPa has overlaps of ~0.75 um (200 ulp: about
//! 1 % noise on the contact forces) and interior particles that move far less than one ulp
//! per step at inertial numbers below 1e-3, so their motion is lost to rounding. Such scenes
//! need rapier3d-f64: rapier publishes it as a separate crate with the same API (`Real = f64`);
//! the plugin would need a cargo feature choosing `rapier3d` or `rapier3d-f64` (renamed to one
//! dependency name), its `f32` casts at the engine boundary (`v3`, `vf`, `f64::from(..)` of
//! `Real` values, `as f32`) made generic over `Real`, and the f32-only tests adjusted; the
//! contact laws (creep-law) are already f64.

mod colliders;
pub mod damping;
mod geometry;
mod pairs;
mod records;
mod settings;

use creep_law::{Vec3, hertz};
use rapier3d::prelude::*;

pub use damping::{
    MIN_RESTITUTION, alpha_without_cutoff, damping_coefficient, restitution_for_damping,
};

use crate::error::PluginError;
use crate::hooks::{FastMap, vf};
use crate::registry::MaterialRegistry;
pub use records::*;
pub use settings::*;

/// The compliant regime: per-contact state, the forces it added, its energy totals.
#[derive(Debug, Clone)]
pub struct CompliantRegime {
    settings: CompliantSettings,
    contacts: FastMap<PairKey, CompliantContact>,
    /// Force and torque per body of the step (reused to avoid allocating every step).
    accum: FastMap<RigidBodyHandle, (Vec3, Vec3, bool)>,
    generation: u64,
    saved: Vec<(RigidBodyHandle, Vector, Vector)>,
    energy: CompliantEnergy,
    counts: CompliantCounts,
    alpha_cache: Vec<(f64, f64)>,
}

impl CompliantRegime {
    /// A regime with the given settings.
    pub fn new(settings: CompliantSettings) -> Result<Self, PluginError> {
        settings.validate()?;
        Ok(Self {
            settings,
            contacts: FastMap::default(),
            accum: FastMap::default(),
            generation: 0,
            saved: Vec::new(),
            energy: CompliantEnergy::default(),
            counts: CompliantCounts::default(),
            alpha_cache: Vec::new(),
        })
    }

    /// The settings.
    pub fn settings(&self) -> &CompliantSettings {
        &self.settings
    }
    /// Replaces the settings (validated).
    pub fn set_settings(&mut self, settings: CompliantSettings) -> Result<(), PluginError> {
        settings.validate()?;
        self.settings = settings;
        Ok(())
    }
    /// Energy totals (elastic terms as of the last step).
    pub fn energy(&self) -> CompliantEnergy {
        self.energy
    }
    /// Zeroes the accumulated dissipation.
    pub fn reset_energy(&mut self) {
        let e = self.energy;
        self.energy = CompliantEnergy {
            normal_elastic: e.normal_elastic,
            tangential_elastic: e.tangential_elastic,
            ..CompliantEnergy::default()
        };
    }
    /// What the last step did.
    pub fn counts(&self) -> CompliantCounts {
        self.counts
    }
    /// The live contacts.
    pub fn contacts(&self) -> impl Iterator<Item = (&PairKey, &CompliantContact)> {
        self.contacts.iter()
    }

    /// The smallest Rayleigh time step \[s\] over the registered `Compliant` balls
    /// (`f64::INFINITY` if there are none).
    pub fn rayleigh_time_step(registry: &MaterialRegistry, colliders: &ColliderSet) -> f64 {
        let mut t_min = f64::INFINITY;
        for (&h, m) in registry.iter() {
            if !m.is_compliant() {
                continue;
            }
            if let Some(ball) = colliders.get(h).and_then(|c| c.shape().as_ball()) {
                let t = hertz::rayleigh_time_step(&m.material, f64::from(ball.radius));
                if t > 0.0 {
                    t_min = t_min.min(t);
                }
            }
        }
        t_min
    }

    fn alpha(&mut self, e: f64) -> Result<f64, PluginError> {
        if let Some(&(_, a)) = self.alpha_cache.iter().find(|(ee, _)| *ee == e) {
            return Ok(a);
        }
        let a = damping_coefficient(e)?;
        if self.alpha_cache.len() > 64 {
            self.alpha_cache.clear();
        }
        self.alpha_cache.push((e, a));
        Ok(a)
    }

    /// Called by the step owner ([`crate::CreepPipeline`]) before `PhysicsPipeline::step`:
    /// checks the time step against the Rayleigh time, computes every compliant contact's force
    /// from the current poses and velocities and adds it to the bodies' user forces and torques
    /// (saving them for `end_step`). Without `Compliant` colliders in the registry it does
    /// nothing.
    pub(crate) fn begin_step(
        &mut self,
        registry: &MaterialRegistry,
        params: &IntegrationParameters,
        bodies: &mut RigidBodySet,
        colliders: &ColliderSet,
        narrow_phase: &NarrowPhase,
    ) -> Result<CompliantCounts, PluginError> {
        self.end_step(bodies); // a missed end_step must not leave forces behind
        self.generation += 1;
        self.counts = CompliantCounts {
            rayleigh_time_step: f64::INFINITY,
            ..CompliantCounts::default()
        };
        if registry.compliant_len() == 0 {
            self.contacts.clear();
            self.energy.normal_elastic = 0.0;
            self.energy.tangential_elastic = 0.0;
            return Ok(self.counts);
        }
        let dt = f64::from(params.dt);
        if !(dt.is_finite() && dt > 0.0) {
            return Err(PluginError::TimeStep(params.dt));
        }
        // The forces are frozen over the step: only one substep makes it symplectic Euler
        // (module docs: energy error 2.6e-5 with 1 substep, 1.4e-2 with Rapier's default 4).
        if params.num_solver_iterations != 1 {
            return Err(PluginError::CompliantSubsteps(params.num_solver_iterations));
        }
        let t_r = Self::rayleigh_time_step(registry, colliders);
        self.counts.rayleigh_time_step = t_r;
        for (&h, m) in registry.iter() {
            if !m.is_compliant() {
                continue;
            }
            let Some(co) = colliders.get(h) else {
                continue;
            };
            // A restitution the damping cannot reproduce is an error before any contact state
            // moves (the pair loop below only meets it again for a product of two valid
            // coefficients under `CoefficientCombineRule::Multiply`).
            let e = f64::from(co.restitution());
            if !(MIN_RESTITUTION..=1.0).contains(&e) {
                return Err(PluginError::Restitution(e));
            }
            if let Some(rb) = co.parent().and_then(|b| bodies.get(b)) {
                let d = f64::from(rb.linvel().length()) * dt;
                self.counts.max_step_displacement = self.counts.max_step_displacement.max(d);
            }
        }
        // Rapier's `dt` and the ball radii are f32: a step set to exactly the fraction (in f64)
        // arrives rounded, up to a few f32 ulps above it; that is not a violation.
        if dt > self.settings.rayleigh_fraction * t_r * (1.0 + RAYLEIGH_ROUNDING) {
            match self.settings.rayleigh_check {
                RayleighCheck::Error => {
                    return Err(PluginError::RayleighTimeStep {
                        dt,
                        rayleigh: t_r,
                        fraction: self.settings.rayleigh_fraction,
                    });
                }
                RayleighCheck::Warn => self.counts.rayleigh_exceeded = true,
                RayleighCheck::Off => {}
            }
        }

        let mut accum = std::mem::take(&mut self.accum);
        accum.clear();
        let mut elastic = (0.0, 0.0);
        for pair in narrow_phase.contact_pairs() {
            self.pair_contact(
                pair,
                registry,
                bodies,
                colliders,
                dt,
                &mut accum,
                &mut elastic,
            )?;
        }
        let g = self.generation;
        self.contacts.retain(|_, r| r.generation == g);
        self.energy.normal_elastic = elastic.0;
        self.energy.tangential_elastic = elastic.1;

        for (&h, &(f, m, touched_by_awake)) in &accum {
            if let Some(rb) = bodies.get_mut(h) {
                self.saved.push((h, rb.user_force(), rb.user_torque()));
                // Wake a sleeping body only when a moving body touches it: waking every body
                // every step (its timer restarted) kept a settled compliant pile awake for
                // ever, and two sleeping bodies' steady contact force needs no wake-up.
                let wake = rb.is_sleeping() && touched_by_awake;
                rb.add_force(vf(f), wake);
                rb.add_torque(vf(m), wake);
            }
        }
        self.accum = accum;
        Ok(self.counts)
    }

    /// Called by the step owner after `PhysicsPipeline::step`: puts back the user forces and
    /// torques the bodies had before `begin_step` (exactly: reset, then the saved values).
    pub(crate) fn end_step(&mut self, bodies: &mut RigidBodySet) {
        for (h, f, m) in self.saved.drain(..) {
            if let Some(rb) = bodies.get_mut(h) {
                rb.reset_forces(false);
                rb.reset_torques(false);
                rb.add_force(f, false);
                rb.add_torque(m, false);
            }
        }
    }
}
