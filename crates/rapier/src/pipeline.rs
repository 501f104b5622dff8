//! The step owner: [`CreepPipeline`] runs one Rapier step with creep-friction, doing in the
//! right order what the two regimes need around Rapier's own `PhysicsPipeline::step`:
//!
//! 1. choose the registered colliders to visit (those of awake bodies; all of them on the
//!    first step, after a registry change, when colliders were added or removed, and every
//!    few hundred steps, forgetting the materials of colliders Rapier no longer has), refuse
//!    their NaN or negative friction and invalid materials, check the integration parameters,
//!    prepare the rigid hooks (time step, substeps, counts, contact generation), lift Rapier's
//!    angular speed cap on registered balls (one substep);
//! 2. switch each visited collider's hook on or off ([`crate::CreepSettings::activation_speed`]),
//!    and note what deserves a [`crate::CreepWarning`] (a fast ball or wheel with substeps, no
//!    registered collider, an unregistered collider touching a registered one);
//! 3. the compliant regime's forces (pairs with a [`crate::Regime::Compliant`] collider);
//! 4. Rapier's step, with the rigid hooks (which also refuse a NaN or negative friction on a
//!    registered collider's unregistered partner);
//! 5. what Rapier quarantined; the compliant regime restores the user forces; the rigid hooks
//!    apply the contact-torque rolling impulses (without waking a body) and sweep the records
//!    of contacts that ended.
//!
//! A user's own loop calls [`CreepPipeline::step`] (the arguments of `PhysicsPipeline::step`,
//! in a [`RapierStep`]) or [`CreepPipeline::step_world`]. A host that runs Rapier's step itself
//! (bevy_rapier3d) calls [`CreepPipeline::prepare_host_step_with_islands`] (or
//! [`CreepPipeline::prepare_host_step`]) before, [`CreepPipeline::report_quarantine`] and
//! [`CreepPipeline::finish_host_step`] after it; misuse is a typed error: finishing an
//! unprepared step ([`PluginError::StepNotPrepared`]), preparing twice
//! ([`PluginError::StepAlreadyPrepared`]), or a Rapier step that used the hooks without the
//! pipeline ([`PluginError::HookOutsideStep`], reported by the next step; those contacts were
//! left to Coulomb).
//!
//! Each collider's [`crate::Regime`] says which regime solves its pairs: rigid at a
//! [`crate::Fidelity`] (Coulomb < Auto < Creep; a pair uses the lower), or compliant, which a
//! pair is as soon as one of its colliders is ([`crate::Regime::pair`]).

use rapier3d::prelude::*;

use crate::compliant::{CompliantRegime, CompliantSettings};
use crate::error::PluginError;
use crate::registry::MaterialRegistry;
use crate::rigid::{CreepHooks, CreepSettings, StepCounts};

/// What `PhysicsPipeline::step` takes (but the hooks, which the pipeline supplies).
pub struct RapierStep<'a> {
    /// Rapier's pipeline.
    pub pipeline: &'a mut PhysicsPipeline,
    /// Gravity [m/s^2].
    pub gravity: Vector,
    /// Integration parameters (checked by the step).
    pub params: &'a IntegrationParameters,
    /// Island manager.
    pub islands: &'a mut IslandManager,
    /// Broad phase.
    pub broad_phase: &'a mut BroadPhaseBvh,
    /// Narrow phase.
    pub narrow_phase: &'a mut NarrowPhase,
    /// Rigid bodies.
    pub bodies: &'a mut RigidBodySet,
    /// Colliders.
    pub colliders: &'a mut ColliderSet,
    /// Impulse joints.
    pub impulse_joints: &'a mut ImpulseJointSet,
    /// Multibody joints.
    pub multibody_joints: &'a mut MultibodyJointSet,
    /// Soft bodies.
    pub soft_bodies: &'a mut SoftBodySet,
    /// CCD solver.
    pub ccd_solver: &'a mut CCDSolver,
    /// Event handler (`&()` for none).
    pub events: &'a dyn EventHandler,
}

/// The creep-friction step owner: the rigid regime's hooks and the compliant regime, stepped
/// together in the right order (module docs).
pub struct CreepPipeline {
    /// The rigid regime's hooks (materials, settings, contact records, counts). Read-only use
    /// is free; give them to Rapier only through [`CreepPipeline::step`] (or the host pair).
    pub hooks: CreepHooks,
    /// The compliant (DEM) regime: forces of the pairs with a [`crate::Regime::Compliant`]
    /// collider (inactive without such colliders).
    pub compliant: CompliantRegime,
}

impl CreepPipeline {
    /// A pipeline with no materials, the given rigid settings and default compliant settings.
    pub fn new(settings: CreepSettings) -> Result<Self, PluginError> {
        Self::from_parts(
            CreepHooks::new(MaterialRegistry::new(), settings)?,
            CompliantSettings::default(),
        )
    }

    /// A pipeline from hooks and compliant settings.
    pub fn from_parts(
        hooks: CreepHooks,
        compliant: CompliantSettings,
    ) -> Result<Self, PluginError> {
        Ok(Self {
            hooks,
            compliant: CompliantRegime::new(compliant)?,
        })
    }

    /// The material registry.
    pub fn registry(&self) -> &MaterialRegistry {
        self.hooks.registry()
    }

    /// The material registry, to add or remove colliders.
    pub fn registry_mut(&mut self) -> &mut MaterialRegistry {
        self.hooks.registry_mut()
    }

    /// One step of a [`PhysicsWorld`], with creep-friction; returns what the rigid hooks did.
    pub fn step_world(
        &mut self,
        world: &mut PhysicsWorld,
        events: &dyn EventHandler,
    ) -> Result<StepCounts, PluginError> {
        self.step(RapierStep {
            pipeline: &mut world.physics_pipeline,
            gravity: world.gravity,
            params: &world.integration_parameters,
            islands: &mut world.islands,
            broad_phase: &mut world.broad_phase,
            narrow_phase: &mut world.narrow_phase,
            bodies: &mut world.bodies,
            colliders: &mut world.colliders,
            impulse_joints: &mut world.impulse_joints,
            multibody_joints: &mut world.multibody_joints,
            soft_bodies: &mut world.soft_bodies,
            ccd_solver: &mut world.ccd_solver,
            events,
        })
    }

    /// One step, with creep-friction: prepares both regimes, runs `PhysicsPipeline::step`
    /// with the rigid hooks, finishes both regimes. Returns what the rigid hooks did.
    pub fn step(&mut self, s: RapierStep<'_>) -> Result<StepCounts, PluginError> {
        self.prepare(
            s.params,
            Some(&*s.islands),
            s.bodies,
            s.colliders,
            s.narrow_phase,
        )?;
        s.pipeline.step(
            s.gravity,
            s.params,
            s.islands,
            s.broad_phase,
            s.narrow_phase,
            s.bodies,
            s.colliders,
            s.impulse_joints,
            s.multibody_joints,
            s.soft_bodies,
            s.ccd_solver,
            &self.hooks,
            s.events,
        );
        self.report_quarantine(s.pipeline.quarantine());
        self.finish_host_step(s.bodies)
    }

    /// For a host that runs Rapier's step itself: passes what Rapier quarantined in the step
    /// (`PhysicsPipeline::quarantine`) to the step's [`StepCounts`] (call between the host's
    /// step and [`CreepPipeline::finish_host_step`]; [`CreepPipeline::step`] does it).
    pub fn report_quarantine(&mut self, quarantine: &rapier3d::pipeline::Quarantine) {
        if self.hooks.is_step_prepared() {
            self.hooks.report_quarantine(quarantine);
        }
    }

    /// For a host that runs Rapier's step itself (bevy_rapier3d): everything the pipeline does
    /// before the step (module docs, 1-3), with the step's parameters (`params.dt` the step's
    /// time step). On error nothing is prepared and the host's step leaves every contact to
    /// Rapier (the error says why); call [`CreepPipeline::finish_host_step`] after the host's
    /// step only if this returned `Ok`. Visits every registered collider every step; a host
    /// with Rapier's island manager at hand uses
    /// [`CreepPipeline::prepare_host_step_with_islands`] instead.
    pub fn prepare_host_step(
        &mut self,
        params: &IntegrationParameters,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        narrow_phase: &NarrowPhase,
    ) -> Result<(), PluginError> {
        self.prepare(params, None, bodies, colliders, narrow_phase)
    }

    /// [`CreepPipeline::prepare_host_step`] with the host's island manager (bevy_rapier3d's
    /// `RapierContextSimulation::islands`): on most steps the preparation then visits only the
    /// colliders of awake bodies, as [`CreepPipeline::step`] does, so that a settled world
    /// whose bodies sleep costs about what it costs plain Rapier.
    pub fn prepare_host_step_with_islands(
        &mut self,
        params: &IntegrationParameters,
        islands: &IslandManager,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        narrow_phase: &NarrowPhase,
    ) -> Result<(), PluginError> {
        self.prepare(params, Some(islands), bodies, colliders, narrow_phase)
    }

    fn prepare(
        &mut self,
        params: &IntegrationParameters,
        islands: Option<&IslandManager>,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        narrow_phase: &NarrowPhase,
    ) -> Result<(), PluginError> {
        self.hooks.select_colliders(islands, bodies, colliders);
        self.check_friction(colliders)?;
        self.hooks.gather_coincident(narrow_phase);
        self.hooks.begin_step(params)?;
        self.hooks.lift_rotation_cap(bodies, colliders);
        self.hooks.update_activation(bodies, colliders);
        self.hooks.scan_unregistered(narrow_phase, colliders.len());
        if let Err(e) = self.compliant.begin_step(
            self.hooks.registry(),
            params,
            bodies,
            colliders,
            narrow_phase,
        ) {
            self.compliant.end_step(bodies);
            self.hooks.abandon_step();
            return Err(e);
        }
        Ok(())
    }

    /// For a host that runs Rapier's step itself: everything the pipeline does after the step
    /// (module docs, 5). [`PluginError::StepNotPrepared`] without a prepared step.
    pub fn finish_host_step(
        &mut self,
        bodies: &mut RigidBodySet,
    ) -> Result<StepCounts, PluginError> {
        if !self.hooks.is_step_prepared() {
            return Err(PluginError::StepNotPrepared);
        }
        self.compliant.end_step(bodies);
        self.hooks.end_step(bodies)?;
        Ok(self.hooks.counts())
    }

    /// For a host whose prepared step did not run (e.g. bevy_rapier3d took no step this
    /// frame): undoes the preparation (the compliant forces are removed, no rolling torque is
    /// applied), so that the next step can be prepared.
    pub fn cancel_host_step(&mut self, bodies: &mut RigidBodySet) {
        self.compliant.end_step(bodies);
        self.hooks.abandon_step();
    }

    /// Refuses a registered collider whose friction coefficient is NaN, infinite or negative,
    /// or whose material is invalid (a wheel's crown radius).
    fn check_friction(&self, colliders: &ColliderSet) -> Result<(), PluginError> {
        for &handle in self.hooks.selected() {
            let Some(mat) = self.hooks.registry().get(handle) else {
                continue;
            };
            mat.validate()?;
            if mat.is_compliant() {
                continue;
            }
            if let Some(co) = colliders.get(handle) {
                crate::registry::check_friction(handle, co.friction())?;
            }
        }
        Ok(())
    }
}
