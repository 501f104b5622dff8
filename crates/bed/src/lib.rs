//! # creep-bed
//!
//! A granular bed ([`creep_dem::Dem`], f64 soft spheres) coupled both ways to the rigid bodies
//! of a Rapier 0.36 world (f32): chosen colliders (balls, cuboids, cylinders, convex hulls,
//! trimeshes) are moving boundaries of the bed. Every grain touching a boundary gets the same
//! contact law as a grain pair, creep-law's kernel [`creep_law::pair::pair_force`] (Hertz +
//! Tsuji damping + Cattaneo-Mindlin with Kuhn's creep), with the boundary as body p (normal
//! from the boundary to the grain, docs/ARCHITECTURE.md §4); the equal and opposite force and
//! its moment go to the rigid body, and are handed to Rapier for its step.
//!
//! ## Co-simulation: the sub-stepping rule
//!
//! One game step `Dt` (Rapier's `IntegrationParameters::dt`) is `K = Dt / dt` DEM steps, `dt`
//! the engine's [`creep_dem::DemConfig::dt`]; `K` must be a whole number (within `1e-9`
//! relative, else [`BedError::StepRatio`]). [`Bed::step`] runs the `K` sub-steps *before*
//! Rapier's step, then applies the exchanged impulses to the bodies (`apply_impulse`,
//! `apply_torque_impulse`); the caller then steps Rapier. Within the game step:
//!
//! * **held constant**: each boundary body's linear and angular velocity (`v_b`, `w_b`, read
//!   from Rapier at the start of the step, f32 -> f64), its mass, and its shape; the body
//!   moves *kinematically* through the sub-steps: centre of mass `x(t) = x_0 + v_b t`,
//!   orientation `R(t) = exp(w_b t) R_0` (the exact constant-velocity motion), `t` from the
//!   start of the game step;
//! * **exchanged**: the impulse of the grain forces on the body. The grains are integrated by
//!   velocity Verlet, in which the force `F_s` computed at sub-step `s` is applied half at the
//!   end of `s` and half at the start of `s + 1`; the body receives exactly the same weights:
//!   `J = (dt/2) F_0 + dt (F_1 + ... + F_{K-1}) + (dt/2) F_K` (`F_0`: the last sub-step of the
//!   previous game step), and the angular impulse about the world origin
//!   `A = sum_s w_s (x_s x F_s + tau_s)` with the same weights. Rapier receives the linear
//!   impulse `J` and the torque impulse `A - x_0 x J` about the centre of mass at the start of
//!   the step (Rapier's symplectic Euler step changes the body's moment of momentum about the
//!   origin by exactly `x_0 x J`). So the grains' momentum change and the body's are equal
//!   and opposite at every game-step boundary, up to rounding; the body's state itself is
//!   Rapier's f32.
//!
//! **The error.** The body's velocity is frozen at `v_b` while the grains see it, and Rapier
//! then integrates it with the new velocity `v_b + J/m` (symplectic Euler): per game step the
//! body's pose seen by the grains lags Rapier's by `(J/m) Dt = a Dt^2` (`a` the body's
//! acceleration by the grains), and the work the grains did on the body, `J . v_b`, falls
//! short of the body's kinetic energy change by `|J|^2 / (2 m)` = `m a^2 Dt^2 / 2`. Both are
//! first order in `Dt` over a fixed time (like symplectic Euler for a rigid body in Rapier
//! itself), independent of the DEM step `dt`, and vanish for a body the grains barely
//! accelerate (`m a` small against the body's inertia). For a body at rest on the bed the
//! mean force and the weight balance exactly in the mean (momentum is exchanged exactly);
//! what `Dt` adds is a jitter of the body's pose of order `g Dt^2`. Choose `Dt` so that
//! `a Dt^2` is small against the grain overlaps (`~1e-3` of the grain radius).
//!
//! ## Finding the contacts
//!
//! Per boundary a candidate list of grains (engine index, id and the contact's history, side
//! by side: a small CSR-like list, no hashing): the grains whose centres were inside the
//! boundary's axis-aligned box grown by their radius plus a skin ([`BedConfig::skin`]) at the
//! last refresh. The lists are refreshed (an `O(n)` scan per boundary) when the largest grain
//! displacement since the last refresh plus the largest displacement of a boundary's surface
//! (translation of the centre of mass plus rotation angle times the boundary's bounding
//! radius) exceeds the skin; the histories are carried over by grain id through a scratch
//! array indexed by id. The engine re-sorts its grains at its own neighbour rebuilds; a
//! candidate whose index no longer holds its id is re-indexed (an `O(n)` id -> index table).
//! Per sub-step the cost is `O(n)` (the displacement check) plus the closest-point queries of
//! the candidates.
//!
//! Closest points and penetration: closed forms in f64 for balls (a sphere-sphere contact,
//! the boundary's radius as its curvature), cuboids and cylinders (the nearest face, edge or
//! rim; inside, the shallowest face); parry's `project_local_point` (f32, in the collider's
//! frame, the grain's centre relative to the collider's origin) for convex hulls and trimeshes.
//! All but balls are flat at the contact (`Surface::Plane`): the grains are assumed small
//! against the boundary's radii of curvature (a cylinder's rim and a cuboid's edge are seen
//! as a plane through the nearest point, normal along the centre-to-point line). A trimesh
//! tells inside from outside only if built with `TriMeshFlags::ORIENTED`; otherwise a grain
//! whose centre crosses the surface is pushed out on the side it is on.
//!
//! ## What the bed does not do
//!
//! Boundaries do not see the engine's periodic images; grain-boundary contacts between two
//! boundaries (rigid-rigid contacts) are Rapier's business; a boundary's body is a single
//! Rapier body (multibody joints are fine, the impulse goes to the body the collider is
//! attached to); the engine must be stepped only through [`Bed::step`] (a step without the
//! boundary forces would drop the pending half-kick of the exchange).
#![forbid(unsafe_code)]
// `!(x > 0.0)` is meant: it is true for NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Loops index several per-grain arrays at once (structure of arrays) on purpose.
#![allow(clippy::needless_range_loop)]

mod bed;
mod boundary;
mod config;
mod convert;
pub mod cost;
mod energy;
mod error;
mod geometry;
pub mod scene;
pub mod wheel;

pub use bed::Bed;
pub use boundary::BoundarySet;
pub use config::BedConfig;
pub use energy::{BoundaryEnergy, Exchange};
pub use error::BedError;
pub use geometry::BoundaryShape;
