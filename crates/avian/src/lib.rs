//! Creep-friction for Avian (avian3d): rolling contacts that creep as Kalker's theory says.
//!
//! A loaded ball rolling on a plane or on another ball does not roll without slip: its
//! surface creeps forward by Kalker's steady creepage `F_ss(Q/(mu P))` per unit distance
//! rolled (Kalker 2000; Kuhn 2011). Avian's Coulomb friction rolls such a contact with no slip
//! at all. This crate's [`CreepHooks`] (Avian's contact modification hook) gives each loaded
//! rolling contact of colliders with a [`CreepMaterial`] the creep slip as the manifold's
//! `tangent_velocity`, which Avian's solver enforces within its Coulomb limit.
//!
//! - [`CreepAvianPlugin`]: the plugin (builder options, the hook flags, the bookkeeping);
//! - [`CreepHooks`]: the hook, a `SystemParam`;
//! - [`CreepMaterial`], [`Fidelity`]: a collider's elastic material and how its contacts are
//!   solved;
//! - [`CreepState`]: settings, per-contact records, per-step [`StepCounts`], warnings.
//!
//! Supported: balls on balls and on flat colliders (cuboids, half-spaces, meshes, height
//! fields, convex hulls). Other shapes are left to Coulomb with a warning.
//!
//! The law, per contact, is creep-law's rigid kernel (`creep_law::rigid::ball_creep`: Kalker's
//! steady creepage at Hertz's contact radius, Kalker's lateral coefficient, spin creep and its
//! twisting moment, the implicit solve; equations and sources in its docs). SI units
//! throughout.

mod hooks;
mod material;
mod plugin;
pub mod scenes;
mod state;

pub use hooks::CreepHooks;
pub use material::{CreepMaterial, Fidelity};
pub use plugin::CreepAvianPlugin;
pub use state::{ContactInfo, CreepSettings, CreepState, CreepWarning, StepCounts};

/// The plugin, the hooks, the material and the state.
pub mod prelude {
    pub use crate::{
        CreepAvianPlugin, CreepHooks, CreepMaterial, CreepSettings, CreepState, CreepWarning,
        Fidelity, StepCounts,
    };
}

/// The README's quick start, compiled and run as a doc-test.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
