//! A seam for forces from outside the engine (e.g. rigid bodies of a Rapier world acting as
//! boundaries of the granular bed, docs/ARCHITECTURE.md): [`Dem::step_with`] calls an
//! [`ExternalForces`] once per step, after the pair and wall forces, at the same positions and
//! half-step velocities the pair kernel saw, so the forces it adds enter velocity Verlet's
//! second half-kick exactly like contact forces.

use creep_law::Vec3;

use crate::{Dem, DemError, TangentialLaw};

/// The particles as the engine holds them during a force evaluation, in the engine's (cell)
/// order: index `k` is not the particle id, `ids[k]` is. Forces and torques added here act in
/// this step. SI units: m, m/s, rad/s, kg, N, N m.
#[derive(Debug)]
pub struct ExternalView<'a> {
    /// Time at the end of this step \[s\].
    pub time: f64,
    /// The step \[s\].
    pub dt: f64,
    /// Particle ids, by engine index.
    pub ids: &'a [u32],
    /// Centres \[m\] (wrapped into the periodic box, if any).
    pub positions: &'a [Vec3],
    /// Half-step velocities \[m/s\].
    pub velocities: &'a [Vec3],
    /// Half-step angular velocities \[rad/s\].
    pub angular_velocities: &'a [Vec3],
    /// Radii \[m\].
    pub radii: &'a [f64],
    /// Masses \[kg\].
    pub masses: &'a [f64],
    /// Material ids (indices into the engine's [`crate::MaterialTable`]).
    pub materials: &'a [u32],
    /// Forces \[N\]: add to them.
    pub forces: &'a mut [Vec3],
    /// Torques \[N m\]: add to them.
    pub torques: &'a mut [Vec3],
}

/// Forces from outside the engine, added once per step (see [`Dem::step_with`]).
pub trait ExternalForces {
    /// Adds this step's external forces and torques. An error stops the step before the
    /// second half-kick (the state is then mid-step; the caller should discard the engine).
    fn add_forces(&mut self, view: ExternalView<'_>) -> Result<(), DemError>;

    /// Whether [`ExternalForces::add_forces`] may add anything (default `true`). `false` lets
    /// the engine's parallel step (the `parallel` feature) sum the contact forces and apply
    /// the second half-kick in one pass over the particles, without the call in between.
    fn adds_forces(&self) -> bool {
        true
    }
}

/// No external forces: [`Dem::step`] is `step_with(&mut NoExternal)`.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoExternal;

impl ExternalForces for NoExternal {
    #[inline]
    fn add_forces(&mut self, _view: ExternalView<'_>) -> Result<(), DemError> {
        Ok(())
    }
    #[inline]
    fn adds_forces(&self) -> bool {
        false
    }
}

impl<T: TangentialLaw> Dem<T> {
    /// The view handed to an [`ExternalForces`] during a step.
    pub(crate) fn external_view(&mut self, dt: f64) -> ExternalView<'_> {
        ExternalView {
            time: self.time + dt,
            dt,
            ids: &self.id,
            positions: &self.x,
            velocities: &self.v,
            angular_velocities: &self.w,
            radii: &self.r,
            masses: &self.mass,
            materials: &self.mat,
            forces: &mut self.f,
            torques: &mut self.t,
        }
    }
}
