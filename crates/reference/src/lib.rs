//! # creep-reference
//!
//! Exact and numerical references for *creep-friction* (Kuhn 2011): closed forms, Kalker's
//! simplified theory FASTSIM, and a boundary-element solver of Kalker's exact theory.
#![forbid(unsafe_code)]

pub mod error;
pub mod influence;

pub use error::RefError;
pub mod bem;
pub mod contact;
pub mod grid;
