//! What the grain-boundary contacts stored and dissipated, and what a game step exchanged
//! with a body.

use creep_law::Vec3;

/// Energy bookkeeping of the grain-boundary contacts \[J\], as [`creep_dem::DemEnergy`]: the
/// elastic terms are the current stored energies, the others accumulate.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BoundaryEnergy {
    /// Hertz normal springs \[J\].
    pub normal_elastic: f64,
    /// Tangential springs \[J\].
    pub tangential_elastic: f64,
    /// Normal damping \[J\].
    pub damping: f64,
    /// Micro-slip and gross slip \[J\].
    pub slip: f64,
    /// Creep \[J\].
    pub creep: f64,
    /// Contact-torque rolling resistance \[J\].
    pub rolling: f64,
    /// Energy added by the tangential law's simplifications \[J\].
    pub truncation: f64,
}

impl BoundaryEnergy {
    /// Stored elastic energy \[J\].
    pub fn elastic(&self) -> f64 {
        self.normal_elastic + self.tangential_elastic
    }
    /// Net dissipated energy \[J\].
    pub fn dissipated(&self) -> f64 {
        self.damping + self.slip + self.creep + self.rolling - self.truncation
    }
}

/// What one game step exchanged with one boundary's body.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Exchange {
    /// Linear impulse of the grains on the body over the game step \[N s\].
    pub impulse: Vec3,
    /// Angular impulse about the body's centre of mass at the start of the step \[N m s\].
    pub torque_impulse: Vec3,
    /// `impulse / Dt`: the mean force of the grains on the body \[N\].
    pub mean_force: Vec3,
    /// `torque_impulse / Dt` \[N m\].
    pub mean_torque: Vec3,
    /// Touching grain contacts at the last sub-step.
    pub contacts: usize,
}
