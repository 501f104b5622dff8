//! # creep-law
//!
//! Engine-free contact mechanics for *creep-friction* (Kuhn 2011).
#![forbid(unsafe_code)]
// `!(x > 0.0)` is used on purpose: it is true for NaN too, which is how inputs are sanitised.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod creep;
pub mod elliptic;
pub mod error;
pub mod hertz;
pub mod kalker;
pub mod kalker3d;
pub mod kinematics;
pub mod material;
pub mod mindlin;
pub mod pair;
pub mod rigid;
pub mod rolling_torque;
pub mod root;
pub mod steady3d;
pub mod steady_law;
pub mod steady_table;
pub mod transient_law;
pub mod vector;

pub use creep::{CreepInput, CreepLaw, CreepState, CreepStep};
pub use error::LawError;
pub use material::{FrictionCombine, Material, PairMaterial, Surface};
pub use mindlin::{MindlinState, MindlinStep};
pub use steady_law::{CreepModel, SteadyLaw};
pub use vector::{Vec2, Vec3};
