//! Scenes of a granular bed coupled both ways to a Rapier world (crate `creep-bed`: a creep-dem
//! bed whose boundaries are Rapier colliders), here so that tests, the CLI, benches and demos
//! run one scenario code: the resting sphere (the bed carries a rigid sphere's weight), the
//! driven wheel on sand (sinkage, drawbar pull and torque against slip, with and without creep
//! at the grain contacts) and the coupling's cost against the bed alone. The scenes themselves
//! live in creep-bed (`creep_bed::scene`, `creep_bed::wheel`, `creep_bed::cost`), which knows
//! only creep-dem, creep-law and Rapier; this module re-exports them.

pub use creep_bed::cost::{CostReport, coupling_cost};
pub use creep_bed::scene::{
    BedSpec, RestingReport, RestingSphere, highest_under, resting_sphere, surface_height,
};
pub use creep_bed::wheel::{
    Drive, Driving, Landed, Progress, SettledBed, WheelOnSand, WheelRow, WheelSteady, settle,
    steady, surface_level, sweep,
};
pub use creep_bed::{Bed, BedConfig, BedError};
