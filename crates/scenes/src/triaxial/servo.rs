//! The servo-controlled walls.

use super::stress::Stress;

/// Share of a wall's stress error the servo corrects per step (the servo of Itasca's PFC,
/// e.g. Cundall & Strack's walls: the wall speed `alpha (sigma - p0) A / (K tau)` with `K` the
/// summed normal stiffness of its contacts would remove the error `alpha` per time `tau` if
/// the packing were a spring; `tau` is the step in the compaction). With the stiffness of a Hertz packing, the stress lag of a wall
/// moving at `v` is `~ 1.5 v tau / (alpha delta)` of p0, `delta` the overlap of the wall's
/// balls and `tau` the time the share is removed in: about 2 % while the default test's packing
/// dilates (lateral walls at ~0.035 m/s, `delta` ~4e-5 m, `tau` 5.1 µs). Measured on the full
/// default shear (docs/results/triaxial-timestep): the lateral stress is 1.5 % above p0 on
/// average (2.15 % at most). With `tau` the step, as it was in the shear until the `triaxdt`
/// branch and still is in the compaction, the lag grows with the step: 1.9 % at 0.25 T_R,
/// 2.3 % at 0.3 T_R; the shear now uses `TriaxialParams::servo_time` (the step at 0.2 T_R,
/// whatever the step): 1.51 % at 0.3 T_R.
const SERVO_ALPHA: f64 = 0.3;

impl Stress {
    /// The servo speed of wall `k` (outwards, m/s) towards `p0`, capped at `cap` [m/s],
    /// removing [`SERVO_ALPHA`] of the error per `tau` \[s\] (the time step in the compaction,
    /// `TriaxialParams::servo_time` in the shear).
    pub(super) fn servo(&self, k: usize, p0: f64, tau: f64, cap: f64) -> f64 {
        let axis = k / 2;
        let area = self.dims[(axis + 1) % 3] * self.dims[(axis + 2) % 3];
        let v = if self.stiffness[k] > 0.0 {
            SERVO_ALPHA * (self.each[k] - p0) * area / (self.stiffness[k] * tau)
        } else {
            -cap // nothing touches: close in
        };
        v.clamp(-cap, cap)
    }
}
