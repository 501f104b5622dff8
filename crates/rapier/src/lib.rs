//! # creep-rapier
//!
//! Creep-friction for the Rapier physics engine (rapier3d 0.36): a `PhysicsHooks` plugin that
//! replaces Coulomb's tangential response of the pairs that opt in by creep-friction (Kuhn 2011),
//! in the *rigid* regime (Rapier keeps its non-penetration and friction constraints; the plugin
//! prescribes the creep slip velocity), and soft-sphere DEM in the *compliant* regime. See
//! [`CreepHooks`] for the physics of the rigid regime, the stability argument and the settings
//! it requires, and [`CreepPipeline`] for the step (one call does both regimes in order).
//!
//! Three lines with [`CreepWorld`], the world that steps itself:
//! ```
//! use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld};
//! use rapier3d::prelude::*;
//! let mut world = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
//! let steel = CreepMaterial::new(creep_law::Material::steel());
//! world.insert(RigidBodyBuilder::fixed(), ColliderBuilder::cuboid(10.0, 0.1, 10.0), Some(steel));
//! world.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.2, 0.0)), ColliderBuilder::ball(0.1), Some(steel));
//! for _ in 0..10 { world.step().unwrap(); }
//! ```
//!
//! # Defaults, and the opt-out
//! [`CreepWorld::new`] and [`configure_parameters`] (for a world of your own) set what the plugin
//! requires (`FrictionModel::Coulomb`, `contact_clustering = false`) and what rolling balls and
//! wheels need at game steps ([`SolverPreset::Rolling`]): one solver substep
//! (`num_solver_iterations = 1`, where the plugin's correction of Rapier's rotation gap is exact
//! and Rapier's spin cap is lifted on registered balls) with [`ROLLING_PGS_ITERATIONS`]
//! Gauss-Seidel iterations. A scene that needs Rapier's substeps more than rolling accuracy
//! (tall stacks, long joint chains) keeps them with [`SolverPreset::Rapier`]
//! (`CreepSettings::default().with_rapier_solver()`, or
//! `configure_parameters_for(&mut params, SolverPreset::Rapier)`); a registered ball or wheel
//! that then rolls fast gets a [`CreepWarning::RotationGap`]. Set a collider's friction from its
//! material (`.friction(material.friction() as f32)`): the plugin uses the collider's.
//!
//! # Your own loop
//! Register each collider with its material (unregistered colliders stay plain Coulomb, with a
//! [`CreepWarning`] when they touch registered ones) and give it the material's density, then
//! step through the pipeline:
//! ```
//! use creep_rapier::prelude::*;
//! use rapier3d::prelude::*;
//! let mut physics = PhysicsWorld::default();
//! configure_parameters(&mut physics.integration_parameters);
//! let mut creep = CreepPipeline::new(CreepSettings::default()).unwrap();
//! let steel = Material::steel();
//! let mu = steel.friction() as f32;
//! let floor = physics.insert(
//!     RigidBodyBuilder::fixed(),
//!     ColliderBuilder::cuboid(10.0, 0.1, 10.0).friction(mu).build(),
//! );
//! let ball = physics.insert(
//!     RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.2, 0.0)),
//!     ColliderBuilder::ball(0.1).density(steel.density() as f32).friction(mu).build(),
//! );
//! for (_, collider) in [floor, ball] {
//!     creep.registry_mut().insert(collider, CreepMaterial::new(steel));
//! }
//! for _ in 0..10 {
//!     let counts = creep.step_world(&mut physics, &()).unwrap();
//!     for warning in &counts.warnings {
//!         eprintln!("creep-friction: {warning}");
//!     }
//! }
//! ```
//!
//! # Wheels
//! A cylinder collider rolling on its round face on a flat collider is a wheel
//! ([`supported_shape`]): Carter's line contact, or Hertz's ellipse with a crown radius
//! ([`CreepMaterial::with_crown`]). Put it on its own dynamic body with the cylinder turned so
//! that its axis (Rapier's local `y`) is the axle, and hold the axle with a revolute joint to
//! the chassis (contacts between the two off); a joint motor or a torque drives it. With the
//! defaults nothing else is needed: a driven rubber wheel built this way follows Carter's law
//! within 2 % of `mu P` from 0.2 to 0.9 `mu P` at 1/60 and 1/240 s (creep-scenes'
//! `wheel_from_the_recipe_follows_carter`).
//! ```
//! use creep_rapier::prelude::*;
//! use rapier3d::prelude::*;
//! let mut world = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
//! let rubber = Material::rubber();
//! let mu = rubber.friction() as f32;
//! let tyre = CreepMaterial::new(rubber).with_crown(0.2);
//! world.insert(RigidBodyBuilder::fixed(), ColliderBuilder::cuboid(50.0, 0.1, 50.0).friction(mu), Some(CreepMaterial::new(rubber)));
//! let (chassis, _) = world.insert(
//!     RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.4, 0.0)),
//!     ColliderBuilder::cuboid(0.5, 0.1, 0.3).density(200.0),
//!     None, // the chassis touches nothing: no material needed (its other wheels hold it level)
//! );
//! let (wheel, _) = world.insert(
//!     RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.4, 0.35)),
//!     ColliderBuilder::cylinder(0.04, 0.3)
//!         .rotation(Vector::new(std::f32::consts::FRAC_PI_2, 0.0, 0.0)) // axle along z
//!         .friction(mu),
//!     Some(tyre),
//! );
//! let axle = RevoluteJointBuilder::new(Vector::Z)
//!     .local_anchor1(Vector::new(0.0, 0.0, 0.35))
//!     .contacts_enabled(false)
//!     .motor_velocity(-5.0, 10.0);
//! world.physics.impulse_joints.insert(chassis, wheel, axle, true);
//! for _ in 0..10 { world.step().unwrap(); }
//! ```
//!
//! # What the plugin reports
//! Each step returns [`StepCounts`]: what each contact took (creep, Coulomb and why), the
//! [`CreepWarning`]s first seen in that step (each once: a fast ball or wheel with substeps
//! kept, an unregistered collider touching a registered one, no registered collider at all, a
//! body Rapier quarantined), and the bodies and colliders Rapier quarantined. Bad input is a
//! [`PluginError`] (a NaN or negative friction on any collider of a pair the plugin sees, an
//! invalid crown radius, integration parameters the plugin cannot run with).
#![forbid(unsafe_code)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod compliant;
mod convert;
mod error;
mod gap;
mod hooks;
mod pipeline;
mod registry;
mod rigid;
mod rolling;
mod shape;
mod store;
mod warning;
mod world;

pub use compliant::{
    CompliantCounts, CompliantEnergy, CompliantRegime, CompliantSettings, RayleighCheck,
};
pub use error::PluginError;
pub use pipeline::{CreepPipeline, RapierStep};
pub use registry::{CreepMaterial, Fidelity, MaterialRegistry, Regime, RollingResistance};
pub use rigid::{
    CreepHooks, CreepSettings, ROLLING_PGS_ITERATIONS, SolverPreset, StepCounts, check_parameters,
    configure_parameters, configure_parameters_for,
};
pub use shape::{FlatShape, SUPPORTED_SHAPES, SupportedShape, supported_shape};
pub use warning::{CreepWarning, ROTATION_GAP_TURN};
pub use world::{CreepWorld, clone_physics};

/// What the plugin keeps per contact and the basis Rapier's friction impulses are in: for
/// scenes, tests and tools that read the rigid regime's state
/// ([`CreepHooks::records`], [`CreepHooks::record`]) or Rapier's impulses directly.
pub mod diagnostics {
    pub use crate::convert::solver_tangents;
    pub use crate::store::{ContactKey, ContactRecord};
}

/// What a user of the plugin needs, in one `use creep_rapier::prelude::*;` (with
/// `rapier3d::prelude::*` for Rapier's own types).
pub mod prelude {
    pub use crate::{
        CreepMaterial, CreepPipeline, CreepSettings, CreepWarning, CreepWorld, Fidelity,
        PluginError, RapierStep, Regime, RollingResistance, SolverPreset, StepCounts,
        SupportedShape, configure_parameters, configure_parameters_for, supported_shape,
    };
    pub use creep_law::Material;
}

/// The README's Rust snippets, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;
