//! # creep-bevy
//!
//! Creep-friction (Kuhn 2011) for Bevy, over bevy_rapier3d 0.37: a thin adapter around
//! creep-rapier's rigid-regime hooks, in the manner of bevy_rapier3d itself (components that
//! mirror the core's types one to one, a `SystemParam` for the physics hooks).
//!
//! - [`CreepFrictionPlugin`]: registers materials, wraps bevy_rapier3d's step with
//!   creep-rapier's `begin_step` / `update_activation` / `end_step`, checks the integration
//!   parameters, warns and falls back to Coulomb on misuse.
//! - [`CreepPhysicsHooks`]: the hooks to give `RapierPhysicsPlugin` ([`CreepRapierPlugin`]).
//! - [`CreepMaterial`]: the per-collider component (G, nu, density; fidelity; rolling torque).
//!   The collider's `Friction` supplies mu.
//! - [`CreepFriction`]: the resource with the settings and the last step's counts.
//!
//! ```no_run
//! use bevy::prelude::*;
//! use bevy_rapier3d::prelude::*;
//! use creep_bevy::{CreepFrictionPlugin, CreepMaterial, CreepPhysicsHooks};
//! # let mut app = App::new();
//! app.add_plugins((RapierPhysicsPlugin::<CreepPhysicsHooks>::default(), CreepFrictionPlugin::default()));
//! # let mut commands: Commands = unimplemented!();
//! commands.spawn((RigidBody::Dynamic, Collider::ball(0.1), Friction::coefficient(0.5), CreepMaterial::steel()));
//! ```
//!
//! The plugin needs one Rapier step per run of its schedule (`TimestepMode::Fixed` or
//! `Variable` with `substeps: 1`); at the time steps of games (1/60 s) Rapier's own rolling
//! error is larger than the creepage of steel, so use 1/240 s where the absolute slip matters
//! (see creep-rapier's `hooks` module docs).
//!
//! Headless: the crate uses Bevy with `default-features = false` (`std`, `bevy_log`) and
//! bevy_rapier3d with `dim3` only, so its tests run with `MinimalPlugins`, no window, no GPU.
#![forbid(unsafe_code)]
#![warn(missing_docs)]
#![allow(clippy::neg_cmp_op_on_partial_ord)] // `!(x > 0.0)` also refuses NaN, on purpose
#![allow(clippy::type_complexity)] // Bevy queries

pub mod contacts;
#[cfg(feature = "gizmos")]
pub mod gizmos;
pub mod hooks;
pub mod material;
pub mod plugin;
pub mod state;

pub use contacts::{ContactState, CreepContact};
pub use creep_rapier::{
    CompliantSettings, CreepSettings, Fidelity, RollingResistance, SolverPreset, StepCounts,
};
#[cfg(feature = "gizmos")]
pub use gizmos::CreepGizmos;
pub use hooks::{CreepPhysicsHooks, CreepRapierPlugin};
pub use material::CreepMaterial;
pub use plugin::CreepFrictionPlugin;
pub use state::{CreepFriction, CreepWarning};

/// What an app needs, in one `use creep_bevy::prelude::*;` next to `bevy::prelude::*` and
/// `bevy_rapier3d::prelude::*`: the plugins, the components, the resource and its settings.
pub mod prelude {
    pub use crate::contacts::{ContactState, CreepContact};
    #[cfg(feature = "gizmos")]
    pub use crate::gizmos::CreepGizmos;
    pub use crate::hooks::{CreepPhysicsHooks, CreepRapierPlugin};
    pub use crate::material::CreepMaterial;
    pub use crate::plugin::CreepFrictionPlugin;
    pub use crate::state::{CreepFriction, CreepWarning};
    pub use creep_law::Material;
    pub use creep_law::rolling_torque::RollingModel;
    pub use creep_rapier::{
        CompliantSettings, CreepSettings, Fidelity, RollingResistance, SolverPreset, StepCounts,
    };
}
