//! # creep-law
//!
//! Engine-free contact mechanics for *creep-friction* (Kuhn 2011).
#![forbid(unsafe_code)]

pub mod error;
pub mod hertz;
pub mod kalker;
pub mod material;
pub mod mindlin;
pub mod vector;

pub use error::LawError;
pub use material::{FrictionCombine, Material, PairMaterial, Surface};
pub use mindlin::MindlinState;
pub use vector::{Vec2, Vec3};
