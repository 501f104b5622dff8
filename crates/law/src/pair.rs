//! The pure pair-force kernel of the soft-sphere (DEM) hosts: one function,
//! [`pair_force`], that takes the two bodies' state, the pair's constants, the contact's history
//! and the time step, and returns the force and torques, updating the history in place and
//! reporting the energy terms. The compliant regime of creep-rapier and the creep-dem engine
//! both call it, so their forces on the same configuration agree to rounding; a LAMMPS pair
//! style can call it through a C ABI (the history is a flat `[f64]`, see
//! [`ContactHistory::write`] / [`ContactHistory::read`]). [`cheap_sphere_block`] and
//! [`exact_sphere_block`] step [`LANES`] sphere-sphere contacts at once (vector
//! instructions), the same bits as [`pair_force`] lane by lane; [`cheap_sphere_block_lanes`]
//! and [`exact_sphere_block_lanes`] hand their outputs lane by lane ([`SphereForceLanes`]).
//!
//! # The law (all in f64)
//! Bodies p and q, unit normal `n` from p to q, overlap `delta`, contact point `c` in the middle
//! of the overlap (DESIGN §2 conventions: `Q` is the tangential force on p from q).
//! * Normal: Hertz `P_e = (4/3) E* sqrt(R*) delta^(3/2)` (Johnson 1985, §4.2) plus the damping of
//!   Tsuji, Tanaka & Ishida (1992), `alpha sqrt(m* k_H) delta^(1/4) delta_dot`, with `alpha`
//!   chosen so that the impact rebounds with the pair's restitution `e` exactly
//!   ([`damping::damping_coefficient`]); the total is never attractive (`P >= 0`).
//! * Tangential: a [`TangentialLaw`], a generic parameter (monomorphised, no dynamic dispatch per
//!   contact):
//!   - [`Exact`]: Cattaneo-Mindlin with load-history memory and Kuhn's (2011) creep term,
//!     creep-law's [`CreepState`](crate::CreepState) (the compliant regime's physics);
//!   - [`Cheap`]: an incremental no-slip spring of Mindlin's initial stiffness `k_t = 8 G* a`
//!     (Mindlin 1949), scaled back onto the Coulomb limit `mu P_e` when the trial force exceeds
//!     it (LAMMPS' `granular` `tangential mindlin/force`), with the same creep term
//!     `F_ss(|Q|/(mu P)) Q/|Q| |du_roll|` subtracted from the displacement.
//!
//!   Both are fed `du_disp = v_disp dt` and `du_roll = v_roll dt` (Kuhn & Bagi 2004 rates,
//!   [`contact_rates`](crate::kinematics::contact_rates)) at the contact radius `a = sqrt(R* delta)`; without creep
//!   ([`PairConstants::creep`] `None`) no rolling displacement is fed: plain Coulomb-Mindlin.
//! * The tangential history lives in a tangent basis `(t1, t2)` carried by the contact: each
//!   step the basis turns about the normal with the pair's mean spin `(w_p + w_q) . n / 2` and
//!   follows the normal onto its new tangent plane, by projection for the small turns of a DEM
//!   step (the smallest rotation taking the last normal to the new one to second order in the
//!   turn, see `kernel::carry_tangent`; the rotation itself beyond a 45-degree turn), then is
//!   re-orthonormalised, so the stored 2-D force follows the contact as a rigid body.
//! * Optional contact-torque rolling resistance (creep-law [`rolling_torque`]).
//!
//! # Energy bookkeeping
//! [`PairForces::dissipation`] holds the step's dissipated energies (damping, slip, creep,
//! rolling) and the truncation energy; the stored energies are
//! [`ContactHistory::elastic_energy`]. Balance over a run: work of the contact forces = change
//! of the stored energy + dissipation - truncation (as creep-rapier's `CompliantEnergy`).
//!
//! [`rolling_torque`]: crate::rolling_torque

mod block;
mod constants;
pub mod damping;
mod history;
mod kernel;
mod tiers;

pub use block::{
    LANES, SphereForceLanes, SphereForces, SphereLanes, SpherePair, WallForceLanes, WallLanes,
    WallSphere, block_supports, cheap_sphere_block, cheap_sphere_block_lanes, exact_sphere_block,
    exact_sphere_block_lanes, wall_block_lanes,
};
pub use constants::{ContactGeometry, PairBody, PairConstants};
pub use damping::{MIN_RESTITUTION, damping_coefficient};
pub use history::ContactHistory;
pub(crate) use kernel::finite;
pub use kernel::{PairDissipation, PairForces, pair_force, release, rotate_about, rotate_to};
pub(crate) use tiers::kuhn_creepage;
pub use tiers::{Cheap, CheapHistory, Exact, TangentialLaw, TangentialStep};

#[cfg(test)]
mod tests;
