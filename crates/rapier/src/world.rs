//! A headless stepping helper: a Rapier `PhysicsWorld` with the creep hooks, stepped together.
//! Rapier stays fully visible (`world.physics` is the plain `PhysicsWorld`), so a user can also
//! bring their own loop and call [`CreepHooks::begin_step`] / [`CreepHooks::end_step`] around
//! `PhysicsPipeline::step`.

use rapier3d::prelude::*;

use crate::compliant::{CompliantRegime, CompliantSettings};
use crate::error::PluginError;
use crate::hooks::{CreepHooks, CreepSettings, StepCounts, configure_parameters};
use crate::registry::{CreepMaterial, MaterialRegistry};

/// A Rapier world stepped with creep-friction.
pub struct CreepWorld {
    /// The Rapier world (bodies, colliders, parameters, pipeline).
    pub physics: PhysicsWorld,
    /// The creep hooks (materials, settings, per-contact state, counts).
    pub hooks: CreepHooks,
    /// The compliant (DEM) regime: forces of the pairs whose colliders are both
    /// `Fidelity::Compliant` (inactive without such colliders).
    pub compliant: CompliantRegime,
}

impl CreepWorld {
    /// An empty world with gravity `(0, -9.81, 0)` m/s^2, time step `dt` [s], and the
    /// integration parameters the plugin needs.
    pub fn new(dt: f32, settings: CreepSettings) -> Result<Self, PluginError> {
        let mut physics = PhysicsWorld::default();
        physics.integration_parameters.dt = dt;
        configure_parameters(&mut physics.integration_parameters);
        crate::hooks::check_parameters(&physics.integration_parameters)?;
        Ok(Self {
            physics,
            hooks: CreepHooks::new(MaterialRegistry::new(), settings)?,
            compliant: CompliantRegime::new(CompliantSettings::default())?,
        })
    }

    /// A world from a Rapier world and hooks (e.g. a [`clone_physics`] copy stepped with other
    /// hooks), with a fresh compliant regime (default settings, no contact history).
    pub fn from_parts(physics: PhysicsWorld, hooks: CreepHooks) -> Result<Self, PluginError> {
        crate::hooks::check_parameters(&physics.integration_parameters)?;
        Ok(Self {
            physics,
            hooks,
            compliant: CompliantRegime::new(CompliantSettings::default())?,
        })
    }

    /// Inserts a body with one collider; with `material`, the collider opts in to creep-friction
    /// (`ActiveHooks::MODIFY_SOLVER_CONTACTS`) and is registered.
    pub fn insert(
        &mut self,
        body: impl Into<RigidBody>,
        collider: impl Into<Collider>,
        material: Option<CreepMaterial>,
    ) -> (RigidBodyHandle, ColliderHandle) {
        let mut collider: Collider = collider.into();
        if material.is_some() {
            collider
                .set_active_hooks(collider.active_hooks() | ActiveHooks::MODIFY_SOLVER_CONTACTS);
        }
        let (b, c) = self.physics.insert(body, collider);
        if let Some(m) = material {
            self.hooks.registry_mut().insert(c, m);
        }
        (b, c)
    }

    /// Removes a body with its colliders and forgets their materials.
    pub fn remove_body(&mut self, body: RigidBodyHandle) {
        let colliders: Vec<ColliderHandle> = self
            .physics
            .bodies
            .get(body)
            .map(|rb| rb.colliders().to_vec())
            .unwrap_or_default();
        for c in colliders {
            self.hooks.registry_mut().remove(c);
        }
        let w = &mut self.physics;
        w.bodies.remove(
            body,
            &mut w.islands,
            &mut w.colliders,
            &mut w.impulse_joints,
            &mut w.multibody_joints,
            &mut w.soft_bodies,
            true,
        );
    }

    /// One step of `integration_parameters.dt`.
    pub fn step(&mut self) -> Result<StepCounts, PluginError> {
        self.hooks
            .begin_step(&self.physics.integration_parameters)?;
        self.hooks
            .update_activation(&self.physics.bodies, &mut self.physics.colliders);
        let w = &mut self.physics;
        self.compliant.begin_step(
            self.hooks.registry(),
            &w.integration_parameters,
            &mut w.bodies,
            &w.colliders,
            &w.narrow_phase,
        )?;
        self.physics.step_with_events(&self.hooks, &());
        self.compliant.end_step(&mut self.physics.bodies);
        self.hooks.end_step(&mut self.physics.bodies);
        Ok(self.hooks.counts())
    }
}

/// A copy of a Rapier world: the same bodies, colliders, joints, contacts and parameters, with
/// fresh pipelines (they hold only workspace), so that two copies step identically. Used to run
/// a scene twice from one state (e.g. with and without creep) and by the benchmarks.
pub fn clone_physics(p: &PhysicsWorld) -> PhysicsWorld {
    PhysicsWorld {
        gravity: p.gravity,
        integration_parameters: p.integration_parameters,
        physics_pipeline: PhysicsPipeline::new(),
        collision_pipeline: CollisionPipeline::new(),
        islands: p.islands.clone(),
        broad_phase: p.broad_phase.clone(),
        narrow_phase: p.narrow_phase.clone(),
        bodies: p.bodies.clone(),
        colliders: p.colliders.clone(),
        impulse_joints: p.impulse_joints.clone(),
        multibody_joints: p.multibody_joints.clone(),
        soft_bodies: p.soft_bodies.clone(),
        ccd_solver: p.ccd_solver.clone(),
    }
}
