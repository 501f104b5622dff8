//! # creep-reference
//!
//! Exact and numerical references for *creep-friction* (Kuhn 2011, "Rolling and friction in
//! discrete element simulations", EMI 2011 talk): the truth against which every model tier of the
//! project is graded.
//!
//! * Closed forms: [`hertz`] (Hertz contact), [`mindlin`] (Cattaneo-Mindlin loading and Mindlin &
//!   Deresiewicz unloading/reloading at constant normal force), [`carter`] (Carter's exact 2-D
//!   steady rolling), [`kalker_linear`] (Kalker's creep coefficients `C11`, `C22`, `C23` of the
//!   circular contact).
//! * [`fastsim`]: Kalker's simplified theory (FASTSIM) with longitudinal, lateral and spin
//!   creepage.
//! * [`bem`]: a boundary-element solver of Kalker's exact theory for quasi-identical bodies in
//!   circular Hertz contact (the method of Kalker's program CONTACT): steady rolling
//!   ([`bem::steady()`], [`bem::SteadySolver`]) and transient rolling or shift with the creepage or
//!   the force held ([`bem::transient_hold_creepage`], [`bem::transient_hold_force`],
//!   [`bem::mindlin_loading`]).
//!
//! Supporting modules: [`material`] (combined elastic constants), [`contact`] (the circular
//! contact solved numerically), [`grid`] (boundary-element grid), [`influence`] (Boussinesq and
//! Cerruti influence coefficients), [`error`] (typed errors), [`parallel`] (the project's one
//! thread pool, also used by the CLI).
//!
//! Sign conventions (see [`bem`]): traction and force on body p from body q; creepage is the rigid
//! slip velocity of q relative to p over the rolling speed; the contact moves in `+x` (leading
//! edge at `x = +a`). Then `Fx = G a^2 C11 xi` in the linear range and `Q . v_disp >= 0`.
#![forbid(unsafe_code)]

pub mod bem;
pub mod carter;
pub mod contact;
pub mod error;
pub mod fastsim;
pub mod fit;
pub mod grid;
pub mod hertz;
pub mod influence;
pub mod kalker_linear;
pub mod material;
pub mod mindlin;
pub mod parallel;
pub mod steady3d;
pub mod steady3d_far;
pub mod steady3d_map;
pub mod tiers;

pub use error::RefError;
