//! The regime's settings ([`CompliantSettings`]) and the Rayleigh time-step check.

use creep_law::CreepModel;

use crate::error::PluginError;

/// Default largest `dt / T_R` (Rayleigh time step) [-]; DEM practice is 0.1-0.3.
pub const DEFAULT_RAYLEIGH_FRACTION: f64 = 0.2;

/// Relative slack of the Rayleigh check [-]: four f32 ulps, the rounding of `dt` and of the
/// radii that Rapier stores as f32, so a step set to exactly the fraction passes.
pub(super) const RAYLEIGH_ROUNDING: f64 = 4.0 * f32::EPSILON as f64;

/// What to do when `dt` exceeds the safe fraction of the Rayleigh time step.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum RayleighCheck {
    /// Return [`PluginError::RayleighTimeStep`] (default).
    #[default]
    Error,
    /// Step anyway and flag it in [`CompliantCounts::rayleigh_exceeded`](super::CompliantCounts::rayleigh_exceeded).
    Warn,
    /// Do not check.
    Off,
}

/// Settings of the compliant regime.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompliantSettings {
    /// Largest `dt / T_R` accepted [-], in (0, 1]; default [`DEFAULT_RAYLEIGH_FRACTION`].
    pub rayleigh_fraction: f64,
    /// What exceeding it does.
    pub rayleigh_check: RayleighCheck,
    /// Kuhn's creep term on (default) or off (plain Coulomb-Mindlin).
    pub creep: bool,
    /// Steady (and transient) creep law of the creep term (default Kuhn's, Kalker's `F_ss`).
    pub creep_model: CreepModel,
}

impl Default for CompliantSettings {
    fn default() -> Self {
        Self {
            rayleigh_fraction: DEFAULT_RAYLEIGH_FRACTION,
            rayleigh_check: RayleighCheck::Error,
            creep: true,
            creep_model: CreepModel::Kuhn,
        }
    }
}

impl CompliantSettings {
    /// Validates the settings.
    pub fn validate(&self) -> Result<(), PluginError> {
        if !(self.rayleigh_fraction > 0.0 && self.rayleigh_fraction <= 1.0) {
            return Err(PluginError::Setting {
                name: "rayleigh_fraction",
                value: self.rayleigh_fraction,
                why: "must be in (0, 1] [-]",
            });
        }
        Ok(())
    }
}
