//! # creep-rapier
//!
//! Creep-friction for the Rapier physics engine (rapier3d 0.36): a `PhysicsHooks` plugin that
//! replaces Coulomb's tangential response of the pairs that opt in by creep-friction (Kuhn 2011),
//! in the *rigid* regime (Rapier keeps its non-penetration and friction constraints; the plugin
//! prescribes the creep slip velocity). See [`hooks`] for the physics, the stability argument
//! and the settings the plugin requires.
//!
//! Three lines with the stepping helper:
//! ```
//! use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld};
//! use rapier3d::prelude::*;
//! let mut world = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
//! let steel = CreepMaterial::new(creep_law::Material::steel());
//! world.insert(RigidBodyBuilder::fixed(), ColliderBuilder::cuboid(10.0, 0.1, 10.0), Some(steel));
//! world.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.2, 0.0)), ColliderBuilder::ball(0.1), Some(steel));
//! for _ in 0..10 { world.step().unwrap(); }
//! ```
#![forbid(unsafe_code)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod compliant;
pub mod error;
pub mod hooks;
pub mod registry;
pub mod world;

pub use compliant::{
    CompliantCounts, CompliantEnergy, CompliantRegime, CompliantSettings, RayleighCheck,
};
pub use error::PluginError;
pub use hooks::{
    ContactKey, ContactStore, CreepHooks, CreepSettings, StepCounts, check_parameters,
    configure_parameters,
};
pub use registry::{CreepMaterial, Fidelity, MaterialRegistry, RollingResistance};
pub use world::{CreepWorld, clone_physics};
