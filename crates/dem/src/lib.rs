//! # creep-dem
//!
//! A soft-sphere DEM engine for creep-friction, built the way the fast codes (LAMMPS,
//! LIGGGHTS) are, in f64:
//!
//! * per-property arrays (positions, velocities, angular velocities, forces, torques, radii,
//!   masses, material ids), re-sorted by cell at every neighbour rebuild for locality;
//! * a cell grid and a *half* neighbour list with a skin, rebuilt only when some particle has
//!   moved more than half the skin (or a particle and a wall together more than the skin);
//!   the contact history sits beside the list (CSR: `start[i]..start[i+1]`), and is carried
//!   over by partner id only at a rebuild; no hashing in the inner loop;
//! * per material pair constants ([`creep_law::pair::PairConstants`]: combined moduli, damping
//!   from restitution, friction, the steady creep law) computed once, in a small table indexed
//!   by material ids ([`MaterialTable`]);
//! * the pair force is creep-law's pure kernel [`creep_law::pair::pair_force`], with the
//!   tangential tier a generic parameter ([`creep_law::pair::Exact`]: Cattaneo-Mindlin memory
//!   with Kuhn's creep; [`creep_law::pair::Cheap`]: incremental `8 G* a` spring, rescaled at
//!   `mu P`, plus creep), monomorphised; the serial force loop runs the cheap tier's touching
//!   sphere pairs four at a time ([`creep_law::pair::cheap_sphere_block_lanes`]: vector
//!   instructions, the same bits as the one-contact kernel) and adds each lane's outputs to
//!   the particles as it comes, the one-contact kernel's entries in their places, so every
//!   sum keeps the list's order (the exact tier runs the one-contact kernel entry by entry:
//!   its time is in the memory update of each contact);
//! * velocity Verlet (Swope et al. 1982) for translation and rotation (spheres: isotropic
//!   inertia `I = (2/5) m r^2`), the contact forces evaluated at the half-step velocities as in
//!   LAMMPS;
//! * plane walls (any number; moving with a prescribed velocity, e.g. the servo-controlled
//!   walls of a triaxial box, with the force on each wall reported) and periodic boundaries per
//!   axis (minimum image);
//! * with the `parallel` feature and [`DemConfig::parallel`], the step runs on rayon's threads
//!   in three regions (kick and drift; every contact's kernel, its output to a buffer; per
//!   particle the sum of its contacts' outputs in list order, the order in which the serial loop
//!   adds them, then the second half-kick), energies and counts summed per block of particles
//!   in both, and the neighbour list is built per block of particles at rebuilds: results are
//!   the same bits as the serial loop's, run to run and for any number of threads;
//! * the force loops compiled three times, for the target's baseline and (x86-64) with AVX2
//!   and FMA, and with AVX-512F and AVX-512VL too (32 vector registers), the widest taken at
//!   run time where the CPU has it ([`Kernels`]): the same bits.
//!
//! Conventions are creep-law's: in a pair the particle with the smaller id is body p, the
//! normal points from p to q; for a wall contact the wall is p, its normal points into the
//! domain. SI units throughout.
// No unsafe code but the calls of the AVX2 and AVX-512 copies of the force loops (`kernels`),
// allowed there.
#![deny(unsafe_code)]
#![allow(clippy::neg_cmp_op_on_partial_ord)]
// Loops index several per-particle arrays at once (structure of arrays) on purpose.
#![allow(clippy::needless_range_loop)]

pub mod checkpoint;
mod config;
pub mod dump;
mod engine;
mod external;
mod grid;
mod kernels;
mod material;
mod measure;
mod neighbour;
#[cfg(feature = "parallel")]
mod par;
mod probe;
mod step;

pub use config::{DemConfig, DemError, Particle, Wall};
pub use external::{ExternalForces, ExternalView, NoExternal};
pub use kernels::{KERNELS_ENV, Kernels};
pub use material::MaterialTable;
pub use measure::{ContactView, DemCounts, DemEnergy};
pub use probe::{ContactForce, ContactLoad};
#[cfg(feature = "parallel")]
pub(crate) use step::tally;

use creep_law::Vec3;
use creep_law::pair::ContactHistory;

pub use creep_law::pair::{Cheap, Exact, TangentialLaw};

/// The engine, generic over the tangential tier `T` ([`Exact`] or [`Cheap`]).
#[derive(Debug, Clone)]
pub struct Dem<T: TangentialLaw> {
    cfg: DemConfig,
    table: MaterialTable,
    // Per-particle arrays, in cell order.
    x: Vec<Vec3>,
    v: Vec<Vec3>,
    w: Vec<Vec3>,
    f: Vec<Vec3>,
    t: Vec<Vec3>,
    r: Vec<f64>,
    mass: Vec<f64>,
    inv_m: Vec<f64>,
    inv_i: Vec<f64>,
    mat: Vec<u32>,
    id: Vec<u32>,
    /// Index of each id.
    index: Vec<u32>,
    /// Positions at the last rebuild.
    x_build: Vec<Vec3>,
    walls: Vec<Wall>,
    wall_build: Vec<Vec3>,
    wall_force: Vec<Vec3>,
    // Half neighbour list (CSR) with the histories beside it.
    nl_start: Vec<u32>,
    nl_j: Vec<u32>,
    nl_h: Vec<ContactHistory<T>>,
    // Wall lists: (wall, particle) entries with their histories.
    wl_k: Vec<u32>,
    wl_i: Vec<u32>,
    wl_h: Vec<ContactHistory<T>>,
    grid: grid::Grid,
    energy: DemEnergy,
    counts: DemCounts,
    time: f64,
    steps: u64,
    /// The compiled copy of the force loops this engine runs.
    kernels: Kernels,
    #[cfg(feature = "parallel")]
    par: par::Buffers,
}

/// Runs `f` on a rayon pool of `threads` threads (the engines it steps with
/// [`DemConfig::parallel`] use them). Without the `parallel` feature only `threads == 1` runs.
pub fn with_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> Result<R, DemError> {
    if threads == 0 {
        return Err(DemError::Parameter {
            name: "threads",
            value: 0.0,
            why: "at least one thread",
        });
    }
    #[cfg(feature = "parallel")]
    {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|_| DemError::Parameter {
                name: "threads",
                value: threads as f64,
                why: "rayon could not start the pool",
            })?;
        Ok(pool.install(f))
    }
    #[cfg(not(feature = "parallel"))]
    {
        if threads == 1 {
            Ok(f())
        } else {
            Err(DemError::Parameter {
                name: "threads",
                value: threads as f64,
                why: "more than one thread needs creep-dem's `parallel` feature",
            })
        }
    }
}
