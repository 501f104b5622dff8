//! The talk's drained triaxial compression of a dense packing of spheres, in the compliant
//! (soft-sphere DEM) regime of creep-rapier, once with Coulomb-Mindlin contacts and once with
//! Kuhn's creep-friction, from the same packing.
//!
//! # The test
//! 1. **Generation**: `n^3` spheres (4,096 by default) on a cubic lattice with a small random
//!    jitter, radii uniform in `[r (1 - s), r (1 + s)]` (default `s = 0.2`: a 1.5:1 size ratio,
//!    enough to prevent crystallisation), no initial overlap, zero gravity, inside six
//!    frictionless walls (kinematic cuboids; friction 0 with Rapier's `Min` combine rule, so the
//!    ball-wall pairs are frictionless whatever the balls' friction).
//! 2. **Isotropic compaction**: frictionless balls (`mu = 0`, which gives the densest random
//!    packing the walls can make), all six walls servo-controlled to the confining pressure
//!    `p0`, until every wall stress is within 1 % of `p0` and the packing's kinetic energy has
//!    decayed (see [`compact`]).
//! 3. **Shear** (drained, constant lateral stress): the balls get their friction `mu`; the top
//!    and bottom walls approach at a constant axial strain rate, the four lateral walls keep
//!    `p0` by servo control, to 20 % axial strain; run twice from the same packing, with
//!    `CompliantSettings::creep` off (Coulomb-Mindlin) and on (Kuhn 2011's creep-friction).
//!
//! # Quasi-static
//! The strain rate comes from the inertial number `I = eps_dot d sqrt(rho / p0)` (GDR MiDi 2004,
//! eq. 3; `d` the mean diameter): default `I = 8e-4`; below ~1e-3 the response is rate
//! independent (GDR MiDi 2004; da Cruz et al. 2005). The time step is a fraction of the Rayleigh time of the smallest ball (the
//! compliant regime's check, creep-law `hertz::rayleigh_time_step`): 0.2 in the generation
//! and the compaction (`rayleigh_fraction`: the packing depends on it), 0.3 in the shears
//! (`shear_rayleigh_fraction`: the shears at 0.3 reproduce those at 0.2 within 0.07 deg and
//! 0.25 %, docs/results/triaxial-timestep). The number of steps of a shear is
//! `0.2 / (eps_dot dt)`, which grows as `sqrt(G / p0)`: the default material is a
//! softened glass (G = 29 MPa, `G / p0 = 290`), with overlaps of ~2 % of the diameter. DEM
//! practice softens the particles (e.g. Thornton 2000 used a reduced modulus) because the
//! quasi-static response depends on stiffness only through the overlap.
//!
//! # Stress
//! * Walls: `sigma_i = (F_i+ + F_i-) / (2 A_i)` with `F` the normal forces on the two walls of
//!   axis `i` and `A_i` the current face area.
//! * Contacts (Love 1927, Weber 1966; Christoffersen, Mehrabadi & Nemat-Nasser 1981):
//!   `sigma = -(1/V) sum_particles sum_contacts (x_c - x_p) (x) f_c`, `V` the box volume,
//!   compression positive. In static equilibrium the two agree exactly (up to the contact
//!   points lying half an overlap inside the walls); their difference measures the packing's
//!   inertia.
//!
//! Axial strain `eps_a = (H0 - H) / H0`, volumetric strain `eps_v = (V0 - V) / V0` (compression
//! positive: dilation makes it fall), `p = (sigma_1 + 2 sigma_3) / 3`, `q = sigma_1 - sigma_3`
//! with `sigma_3` the mean lateral stress. Peak friction angle `sin phi = (sigma_1 - sigma_3) /
//! (sigma_1 + sigma_3)`; dilatancy rate `D = -d eps_v / d eps_a` and angle
//! `sin psi = D / (2 + D)` (triaxial compression, e.g. Bolton 1986).

mod dem;
mod params;
mod protocol;
mod report;
mod run;
mod servo;
mod specimen;
mod stress;

pub use dem::{DemSpecimen, SHEAR_SKIN, compact_dem, shear_dem};
pub use params::{SERVO_RAYLEIGH_FRACTION, TriaxialConfig, TriaxialEngine, TriaxialParams};
pub use protocol::{CompactionSummary, ShearRun, compact, compact_observed, shear, shear_observed};
pub use report::{
    CSV_HEADER, ShearSummary, TriaxialRow, time_compliant_steps, time_dem_steps,
    time_plain_rapier_steps,
};
pub use run::{Boundary, DemRun, Outcome, Phase, RUN_KIND, RunError, RunHooks};
pub use specimen::{GENERATOR, Specimen, dem_engine, dem_engine_tiled};
pub use stress::CREEPING;
