//! # creep-bevy
//!
//! Creep-friction (Kuhn 2011) for Bevy, over bevy_rapier3d 0.37: a thin adapter around
//! creep-rapier's rigid-regime hooks, in the manner of bevy_rapier3d itself (components that
//! mirror the core's types one to one, a `SystemParam` for the physics hooks).
//!
//! - [`CreepFrictionPlugin`]: registers materials, wraps bevy_rapier3d's step with
//!   creep-rapier's pipeline, sets each new context's integration parameters (one solver
//!   substep by default: [`SolverPreset::Rolling`]), warns and falls back to Coulomb on misuse.
//! - [`CreepPhysicsHooks`]: the hooks to give `RapierPhysicsPlugin` ([`CreepRapierPlugin`]).
//! - [`CreepMaterial`]: the per-collider component (G, nu, density; fidelity; rolling torque;
//!   a wheel's crown). The collider's `Friction` supplies mu.
//! - [`CreepFriction`]: the resource with the settings, the last step's counts and the
//!   warnings ([`CreepWarning`]).
//! - [`prelude`]: all of the above in one `use creep_bevy::prelude::*;`.
//!
//! The quick start is `examples/quick_start.rs` (the crate README's, line for line): a steel
//! floor and a 0.1 m steel ball launched rolling at 5 m/s, one Rapier step of 1/60 s per
//! frame; `tests/quick_start.rs` runs it headless (the ball keeps 0.999 of its energy over
//! 10 s and its height within 0.1 mm).
//!
//! The plugin needs one Rapier step per run of its schedule (`TimestepMode::Fixed` or
//! `Variable` with `substeps: 1`).
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
    CompliantSettings, CreepSettings, Fidelity, Regime, RollingResistance, SolverPreset, StepCounts,
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
        CompliantSettings, CreepSettings, Fidelity, Regime, RollingResistance, SolverPreset,
        StepCounts,
    };
}
