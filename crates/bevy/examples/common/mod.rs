//! Shared by the desktop demos (feature `render`): command-line options (`--screenshot`,
//! `--frames`), the window, an orbit camera, the on-screen panel, a live plot drawn into a
//! texture, the physics schedule (a fixed number of Rapier steps per frame, so that a run of N
//! frames is reproducible), frame timing and the keys every demo shares.
//!
//! Keys: Space pauses, `.` steps once while paused, `+`/`-` change the physics steps per frame,
//! R resets (the demo's own reset), Esc quits. Mouse: left drag orbits, wheel zooms.

#![allow(dead_code, unused_imports)] // each demo uses a part (of the items and of the modules)

mod app;
mod args;
mod meter;
mod plot;

pub use app::*;
pub use args::*;
pub use meter::*;
pub use plot::*;
