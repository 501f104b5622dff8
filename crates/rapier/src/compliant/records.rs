//! What the regime reports and keeps: energy totals, per-step counts and the per-contact record.

use creep_law::rolling_torque::RollingState;
use creep_law::{CreepState, Vec3};
use rapier3d::prelude::*;

/// Energy bookkeeping of the compliant contacts \[J\]. The elastic terms are the current stored
/// energies; the others accumulate from the creation of the regime (or [`CompliantRegime::reset_energy`](super::CompliantRegime::reset_energy)).
/// Balance: work of the contact forces = change of `elastic()` + `dissipated()`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CompliantEnergy {
    /// Elastic energy in the Hertz normal springs, `(8/15) E* sqrt(R*) delta^(5/2)` summed \[J\].
    pub normal_elastic: f64,
    /// Elastic energy in the Cattaneo-Mindlin tangential springs (creep-law
    /// `MindlinState::elastic_energy`) summed \[J\].
    pub tangential_elastic: f64,
    /// Dissipated by the normal damping, `sum (P - P_e) delta_dot dt` \[J\].
    pub damping: f64,
    /// Dissipated by micro-slip and gross slip (creep-law `CreepStep::slip_dissipation`) \[J\].
    pub slip: f64,
    /// Dissipated by creep (`CreepStep::creep_dissipation`) \[J\].
    pub creep: f64,
    /// Dissipated by contact-torque rolling resistance (`RollingStep::dissipation`) \[J\].
    pub rolling: f64,
    /// Added by simplifying over-full Mindlin memories (`CreepStep::truncation_energy`) \[J\].
    pub truncation: f64,
}

impl CompliantEnergy {
    /// Stored elastic energy \[J\].
    pub fn elastic(&self) -> f64 {
        self.normal_elastic + self.tangential_elastic
    }
    /// Net dissipated energy \[J\] (dissipation minus truncation energy).
    pub fn dissipated(&self) -> f64 {
        self.damping + self.slip + self.creep + self.rolling - self.truncation
    }
}

/// What the compliant regime did in the last step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct CompliantCounts {
    /// Touching compliant contacts (overlap > 0).
    pub contacts: usize,
    /// Of which at the Coulomb limit (`|Q| >= mu P_e`, gross sliding).
    pub sliding: usize,
    /// Of which creeping (a non-zero creep displacement this step).
    pub creeping: usize,
    /// Compliant pairs skipped: shapes other than ball, cuboid, half-space, or two walls.
    pub unsupported: usize,
    /// Smallest Rayleigh time step of the compliant balls \[s\] (infinite if none).
    pub rayleigh_time_step: f64,
    /// Whether `dt > rayleigh_fraction T_R` (only with [`RayleighCheck::Warn`](super::RayleighCheck::Warn)).
    pub rayleigh_exceeded: bool,
    /// Largest `|v| dt` of a body with a compliant collider this step \[m\]. A contact cannot
    /// start unseen while twice this stays below `IntegrationParameters::prediction_distance()`
    /// (the broad phase pairs colliders closer than it).
    pub max_step_displacement: f64,
}

/// State of one compliant contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompliantContact {
    /// Cattaneo-Mindlin memory and creep state; its 2-D vectors are in `(t1, t2)`.
    pub state: CreepState,
    /// First tangent of the contact-following basis [-].
    pub t1: Vec3,
    /// Second tangent, `n x t1` [-].
    pub t2: Vec3,
    /// Unit normal from p to q [-].
    pub normal: Vec3,
    /// Contact point \[m\].
    pub point: Vec3,
    /// Overlap \[m\].
    pub overlap: f64,
    /// Normal force on q (along `n`) \[N\], damping included.
    pub normal_force: f64,
    /// Tangential force on p from q, world frame \[N\].
    pub tangential_force: Vec3,
    /// Contact-torque rolling state.
    pub rolling: RollingState,
    /// Whether the contact slid (Coulomb limit) this step.
    pub sliding: bool,
    /// Creep displacement of the step over the sliding displacement `|du_disp|` [-] (0 without
    /// creep; Kuhn's rule feeds `du_disp` minus the creep displacement to Cattaneo-Mindlin).
    pub creep_ratio: f64,
    /// Sliding velocity `v_disp` of the step (Kuhn & Bagi), world frame [m/s].
    pub v_disp: Vec3,
    /// Rolling velocity `v_roll` of the step (Kuhn & Bagi), world frame [m/s].
    pub v_roll: Vec3,
    pub(super) generation: u64,
}

/// Key of a compliant contact: the collider pair, in the narrow phase's order (balls, cuboids
/// and half-spaces are convex: one contact per pair).
pub type PairKey = (ColliderHandle, ColliderHandle);
