//! # creep-scenes
//!
//! The scenarios of the project, each a function that builds a Rapier world with the
//! creep-friction plugin, runs it, and returns measurements next to their closed-form
//! expectation. Tests, the `creep` CLI, benchmarks and demos call the same code.
#![forbid(unsafe_code)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod bed;
pub mod cue_ball;
pub mod free_rolling;
pub mod friction_drive;
pub mod hard_cases;
pub mod impact;
pub mod incline;
mod measure;
pub mod pile;
pub mod repose;
pub mod robot;
pub mod rolling_ball;
pub mod rolling_effect;
pub mod stats;
pub mod triaxial;
pub mod wheels;
pub mod wheels_spin;

pub use measure::{RollingMeter, SceneError, sphere_mass};
