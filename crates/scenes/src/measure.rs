//! Shared measuring tools.

use rapier3d::math::Rotation;
use rapier3d::prelude::*;

/// Why a scene could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SceneError {
    /// The plugin refused the world or a setting.
    #[error(transparent)]
    Plugin(#[from] creep_rapier::PluginError),
    /// A material parameter was refused.
    #[error(transparent)]
    Law(#[from] creep_law::LawError),
    /// A scene parameter outside its range.
    #[error("{0}")]
    Parameter(String),
}

/// Accumulates a body's rotation about a fixed axis from its orientation increments \[rad\]
/// (robust to the velocity offsets a substepping solver leaves at the end of a step).
#[derive(Debug, Clone, Copy, Default)]
pub struct RollingMeter {
    last: Option<Rotation>,
    /// Accumulated angle about the axis \[rad\].
    pub angle: f64,
}

impl RollingMeter {
    /// Adds the rotation since the last call, about `axis` (unit).
    pub fn update(&mut self, rotation: Rotation, axis: Vector) {
        if let Some(last) = self.last {
            let dq = rotation * last.inverse();
            let (v, w) = (Vector::new(dq.x, dq.y, dq.z), dq.w);
            // Angle of the increment about the axis: 2 atan2(v . axis, w).
            self.angle += 2.0 * f64::from(v.dot(axis)).atan2(f64::from(w));
        }
        self.last = Some(rotation);
    }
}

/// Checks a positive, finite scene parameter.
pub(crate) fn positive(name: &str, v: f64) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(SceneError::Parameter(format!(
            "{name} must be finite and > 0, got {v}"
        )))
    }
}

/// Mass of a uniform solid sphere, `rho (4/3) pi R^3` \[kg\], from its density `rho` [kg/m^3] and
/// radius `R` \[m\].
pub fn sphere_mass(density: f64, radius: f64) -> f64 {
    density * 4.0 / 3.0 * std::f64::consts::PI * radius.powi(3)
}
