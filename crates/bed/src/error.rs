//! The coupling's errors.

use creep_dem::DemError;
use rapier3d::prelude::{ColliderHandle, RigidBodyHandle};

/// Errors of the coupling.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BedError {
    /// The DEM engine refused a step or a parameter.
    #[error(transparent)]
    Dem(#[from] DemError),
    /// An invalid parameter.
    #[error("{name} = {value} is invalid: {why}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// Why it was refused.
        why: &'static str,
    },
    /// The collider is not in the collider set.
    #[error("collider {0:?} is not in the collider set")]
    MissingCollider(ColliderHandle),
    /// The body of a boundary is not in the body set any more.
    #[error("rigid body {0:?} of a boundary is not in the body set")]
    MissingBody(RigidBodyHandle),
    /// The collider's shape is not one the bed supports.
    #[error(
        "collider {collider:?} has a {shape} shape; the bed supports balls, cuboids, cylinders, convex hulls and trimeshes"
    )]
    Shape {
        /// The collider.
        collider: ColliderHandle,
        /// Its shape type, as parry names it.
        shape: String,
    },
    /// The game step is not a whole number of DEM steps.
    #[error("the game step {rigid} s is not a whole number of DEM steps of {dem} s")]
    StepRatio {
        /// Rapier's step \[s\].
        rigid: f64,
        /// The engine's step \[s\].
        dem: f64,
    },
    /// A body's pose or velocity is not finite.
    #[error("rigid body {0:?} has a non-finite pose or velocity")]
    NonFinite(RigidBodyHandle),
}
