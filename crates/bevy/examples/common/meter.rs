//! The angle meter: a body's rotation about a fixed axis accumulated from its orientation.

use bevy::prelude::*;

/// Accumulates a body's rotation about a fixed axis from its orientation increments [rad]
/// (creep-scenes' `RollingMeter` for Bevy's `Quat`: robust to the wrap-around of a
/// quaternion's angle).
#[derive(Debug, Clone, Copy, Default)]
pub struct AngleMeter {
    last: Option<Quat>,
    /// Accumulated angle about the axis [rad].
    pub angle: f64,
}

impl AngleMeter {
    /// Adds the rotation since the last call about `axis` (unit): `2 atan2(v . axis, w)` of
    /// the increment `q last^-1`.
    pub fn update(&mut self, rotation: Quat, axis: Vec3) {
        if let Some(last) = self.last {
            let dq = rotation * last.inverse();
            let v = Vec3::new(dq.x, dq.y, dq.z);
            self.angle += 2.0 * f64::from(v.dot(axis)).atan2(f64::from(dq.w));
        }
        self.last = Some(rotation);
    }
}
