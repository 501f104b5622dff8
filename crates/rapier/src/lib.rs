//! # creep-rapier
//!
//! Creep-friction for the Rapier physics engine (rapier3d 0.36): a `PhysicsHooks` plugin that
//! replaces Coulomb's tangential response of the pairs that opt in by creep-friction (Kuhn 2011),
//! in the *rigid* regime (Rapier keeps its non-penetration and friction constraints; the plugin
//! prescribes the creep slip velocity), and soft-sphere DEM in the *compliant* regime. See
//! [`CreepHooks`] for the physics of the rigid regime, the stability argument and the settings
//! it requires, and [`CreepPipeline`] for the step (one call does both regimes in order).
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

mod ball_hook;
pub mod compliant;
mod convert;
mod creep3d;
mod error;
mod gap;
mod hooks;
mod pair_cache;
mod pipeline;
mod registry;
mod rigid;
mod rolling;
mod shape;
mod store;
mod warning;
mod wheel;
mod wheel_hook;
mod world;

pub use compliant::{
    CompliantCounts, CompliantEnergy, CompliantRegime, CompliantSettings, RayleighCheck,
};
pub use error::PluginError;
pub use pipeline::{CreepPipeline, RapierStep};
pub use registry::{
    CreepMaterial, Fidelity, MaterialRegistry, RollingResistance, rigid_surface_of, surface_of,
};
pub use rigid::{
    CreepHooks, CreepSettings, ROLLING_PGS_ITERATIONS, SolverPreset, StepCounts, check_parameters,
    configure_parameters, configure_parameters_for, solver_tangents,
};
pub use shape::{FlatShape, SUPPORTED_SHAPES, SupportedShape, supported_shape};
pub use store::{ContactKey, ContactRecord, ContactStore, KeyHasher};
pub use warning::{CreepWarning, ROTATION_GAP_TURN};
pub use world::{CreepWorld, clone_physics};

/// What a user of the plugin needs, in one `use creep_rapier::prelude::*;` (with
/// `rapier3d::prelude::*` for Rapier's own types).
pub mod prelude {
    pub use crate::{
        CreepMaterial, CreepPipeline, CreepSettings, CreepWarning, CreepWorld, Fidelity,
        PluginError, RapierStep, RollingResistance, SolverPreset, StepCounts, SupportedShape,
        configure_parameters, configure_parameters_for, supported_shape,
    };
    pub use creep_law::Material;
}

/// The README's Rust snippets, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
