//! Headless stepping in one value: a Rapier `PhysicsWorld` and its [`CreepPipeline`], stepped
//! together. Rapier stays fully visible (`world.physics` is the plain `PhysicsWorld`); a user
//! with their own loop uses a [`CreepPipeline`] directly. The rigid hooks, the registry and the
//! compliant regime read through [`CreepWorld::hooks`], [`CreepWorld::registry`] and
//! [`CreepWorld::compliant`] (`world.hooks().counts()`).

use rapier3d::prelude::*;

use crate::compliant::{CompliantRegime, CompliantSettings};
use crate::error::PluginError;
use crate::pipeline::CreepPipeline;
use crate::registry::{CreepMaterial, MaterialRegistry};
use crate::rigid::{CreepHooks, CreepSettings, StepCounts, configure_parameters_for};

/// A Rapier world stepped with creep-friction.
pub struct CreepWorld {
    /// The Rapier world (bodies, colliders, parameters, pipeline).
    pub physics: PhysicsWorld,
    /// The step owner (rigid hooks and compliant regime).
    pub pipeline: CreepPipeline,
}

impl CreepWorld {
    /// The rigid regime's hooks (records, counts, settings, wheel crowns).
    pub fn hooks(&self) -> &CreepHooks {
        &self.pipeline.hooks
    }
    /// The rigid regime's hooks, mutably.
    pub fn hooks_mut(&mut self) -> &mut CreepHooks {
        &mut self.pipeline.hooks
    }
    /// The material registry.
    pub fn registry(&self) -> &MaterialRegistry {
        self.pipeline.registry()
    }
    /// The material registry, to add or remove colliders.
    pub fn registry_mut(&mut self) -> &mut MaterialRegistry {
        self.pipeline.registry_mut()
    }
    /// The compliant regime (its settings, counts and energy).
    pub fn compliant(&self) -> &CompliantRegime {
        &self.pipeline.compliant
    }
    /// The compliant regime, mutably.
    pub fn compliant_mut(&mut self) -> &mut CompliantRegime {
        &mut self.pipeline.compliant
    }
    /// An empty world with gravity `(0, -9.81, 0)` m/s^2, time step `dt` \[s\], and the
    /// integration parameters the plugin needs with those of `settings.solver`
    /// ([`crate::configure_parameters_for`]: by default one solver substep, what rolling balls
    /// and wheels need; [`crate::SolverPreset::Rapier`] keeps Rapier's four).
    pub fn new(dt: f32, settings: CreepSettings) -> Result<Self, PluginError> {
        let mut physics = PhysicsWorld::default();
        physics.integration_parameters.dt = dt;
        configure_parameters_for(&mut physics.integration_parameters, settings.solver);
        crate::rigid::check_parameters(&physics.integration_parameters)?;
        Ok(Self {
            physics,
            pipeline: CreepPipeline::new(settings)?,
        })
    }

    /// A world from a Rapier world and hooks (e.g. a [`clone_physics`] copy stepped with other
    /// hooks), with a fresh compliant regime (default settings, no contact history).
    pub fn from_parts(physics: PhysicsWorld, hooks: CreepHooks) -> Result<Self, PluginError> {
        crate::rigid::check_parameters(&physics.integration_parameters)?;
        Ok(Self {
            physics,
            pipeline: CreepPipeline::from_parts(hooks, CompliantSettings::default())?,
        })
    }

    /// Inserts a body with one collider; with `material`, the collider is registered (each step's
    /// activation then turns its `ActiveHooks::MODIFY_SOLVER_CONTACTS` on while it moves, as the
    /// Bevy plugin's registration does), and a collider left at Rapier's default density
    /// (1 kg/m^3) takes the material's density (its mass follows).
    pub fn insert(
        &mut self,
        body: impl Into<RigidBody>,
        collider: impl Into<Collider>,
        material: Option<CreepMaterial>,
    ) -> (RigidBodyHandle, ColliderHandle) {
        let mut collider: Collider = collider.into();
        if let Some(m) = &material
            && collider.density() == DEFAULT_DENSITY
        {
            collider.set_density(m.material.density() as f32);
        }
        let (b, c) = self.physics.insert(body, collider);
        if let Some(m) = material {
            self.pipeline.hooks.registry_mut().insert(c, m);
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
            self.pipeline.hooks.registry_mut().remove(c);
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

    /// One step of `integration_parameters.dt` ([`CreepPipeline::step_world`]).
    pub fn step(&mut self) -> Result<StepCounts, PluginError> {
        self.pipeline.step_world(&mut self.physics, &())
    }
}

/// Rapier's default collider density [kg/m^3] (`ColliderBuilder::default_density`).
const DEFAULT_DENSITY: f32 = 1.0;

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
