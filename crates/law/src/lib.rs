//! # creep-law
//!
//! Engine-free contact mechanics for *creep-friction* (Kuhn 2011).
#![forbid(unsafe_code)]

pub mod error;
pub mod creep;
pub mod hertz;
pub mod kalker;
pub mod kinematics;
pub mod material;
pub mod mindlin;
pub mod rolling_torque;
pub mod vector;

pub use error::LawError;
pub use material::{FrictionCombine, Material, PairMaterial, Surface};
pub use creep::{CreepState, CreepStep};
pub use mindlin::{MindlinState, MindlinStep};
pub use vector::{Vec2, Vec3};
