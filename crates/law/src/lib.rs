//! # creep-law
//!
//! Engine-free contact mechanics for *creep-friction* (Kuhn 2011).
#![forbid(unsafe_code)]

pub mod kalker;
