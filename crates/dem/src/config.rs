//! The engine's settings, the particles and walls it starts from, and its errors.

use creep_law::{CreepModel, LawError, Vec3};

/// Errors of the engine's constructors and steps.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DemError {
    /// A law parameter was refused by creep-law.
    #[error(transparent)]
    Law(#[from] LawError),
    /// An invalid engine parameter.
    #[error("{name} = {value} is invalid: {why}")]
    Parameter {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// Why it was refused.
        why: &'static str,
    },
    /// A material id out of the table.
    #[error("material id {0} is not in the table")]
    Material(usize),
    /// The tangential tier does not implement the creep model.
    #[error("the {tier} tangential tier does not implement the creep model {model:?}")]
    Unsupported {
        /// Tier name.
        tier: &'static str,
        /// The creep model.
        model: Option<CreepModel>,
    },
    /// A particle's state became non-finite (the time step is too large for the stiffness).
    #[error("particle {0} has a non-finite position or velocity (time step too large?)")]
    NonFinite(usize),
}

/// One particle's initial state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Particle {
    /// Centre \[m\].
    pub position: Vec3,
    /// Velocity [m/s].
    pub velocity: Vec3,
    /// Angular velocity [rad/s].
    pub angular_velocity: Vec3,
    /// Radius \[m\], finite and > 0.
    pub radius: f64,
    /// Material id (index in the [`MaterialTable`](crate::MaterialTable)).
    pub material: usize,
}

/// A plane wall: the half-space behind `point` along `-normal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// A point on the plane \[m\].
    pub point: Vec3,
    /// Unit normal pointing into the domain [-].
    pub normal: Vec3,
    /// Velocity of the wall [m/s] (the plane moves by `velocity dt` each step).
    pub velocity: Vec3,
    /// Material id.
    pub material: usize,
}

impl Wall {
    /// The wall as the first body of a sphere's contact at `point` (the contact point on the
    /// plane): a rigid plane of infinite mass moving with the wall, not turning.
    #[inline(always)]
    pub(crate) fn body_at(&self, point: Vec3) -> creep_law::pair::PairBody {
        creep_law::pair::PairBody {
            position: point,
            velocity: self.velocity,
            angular_velocity: Vec3::ZERO,
            surface: creep_law::Surface::Plane,
            mass: f64::INFINITY,
        }
    }
}

/// Settings of the engine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DemConfig {
    /// Time step \[s\], finite and > 0.
    pub dt: f64,
    /// Neighbour-list skin \[m\], finite and > 0 (LAMMPS' default for granular runs is of the
    /// order of a tenth of the diameter).
    pub skin: f64,
    /// Periodic axes: `Some((lo, hi))` \[m\] makes axis `x`, `y` or `z` periodic with that box.
    pub periodic: [Option<(f64, f64)>; 3],
    /// Gravity [m/s^2].
    pub gravity: Vec3,
    /// Run the step (and the neighbour-list build) on rayon's threads, with the serial loop's
    /// results bit for bit (needs the `parallel` feature; ignored without).
    pub parallel: bool,
}

impl Default for DemConfig {
    fn default() -> Self {
        Self {
            dt: 1e-6,
            skin: 1e-4,
            periodic: [None; 3],
            gravity: Vec3::ZERO,
            parallel: false,
        }
    }
}
