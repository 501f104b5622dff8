//! The bed: the engine and its boundaries stepped together.

use creep_dem::{Dem, TangentialLaw};
use creep_law::Vec3;
use rapier3d::glamx::DVec3;
use rapier3d::prelude::{ColliderHandle, ColliderSet, RigidBodySet};

use crate::convert::{fv, gv, lv};
use crate::{BedConfig, BedError, BoundaryEnergy, BoundarySet};

/// A granular bed and its Rapier boundaries: the engine and the [`BoundarySet`], stepped
/// together (module docs: the sub-stepping rule).
#[derive(Debug, Clone)]
pub struct Bed<T: TangentialLaw> {
    dem: Dem<T>,
    set: BoundarySet<T>,
    /// Cumulative impulses handed to Rapier: linear, angular about the world origin.
    given: (DVec3, DVec3),
}

impl<T: TangentialLaw> Bed<T> {
    /// A bed around `dem` with no boundaries yet.
    pub fn new(dem: Dem<T>, cfg: BedConfig) -> Result<Self, BedError> {
        let set = BoundarySet::new(cfg, dem.table().clone(), dem.len())?;
        Ok(Self {
            dem,
            set,
            given: (DVec3::ZERO, DVec3::ZERO),
        })
    }

    /// Adds `collider` (of the given engine material id) as a boundary; returns its index.
    pub fn add_boundary(
        &mut self,
        collider: ColliderHandle,
        material: usize,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<usize, BedError> {
        self.set.add(collider, material, bodies, colliders)
    }

    /// The engine.
    pub fn dem(&self) -> &Dem<T> {
        &self.dem
    }
    /// The boundaries.
    pub fn boundaries(&self) -> &BoundarySet<T> {
        &self.set
    }

    /// Number of DEM sub-steps in a game step of `dt_rigid` \[s\].
    pub fn substeps(&self, dt_rigid: f64) -> Result<usize, BedError> {
        let dt = self.dem.config().dt;
        let k = dt_rigid / dt;
        let kr = k.round();
        if !(k.is_finite() && kr >= 1.0 && (k - kr).abs() <= 1e-9 * k) {
            return Err(BedError::StepRatio {
                rigid: dt_rigid,
                dem: dt,
            });
        }
        Ok(kr as usize)
    }

    /// One game step of `dt_rigid` \[s\] (Rapier's `dt`): the DEM sub-steps with the bodies
    /// moving at their current Rapier velocities, then the impulses applied to the bodies. Call
    /// Rapier's step right after.
    pub fn step(&mut self, dt_rigid: f64, bodies: &mut RigidBodySet) -> Result<(), BedError> {
        let k = self.substeps(dt_rigid)?;
        self.set.begin(self.dem.time(), bodies)?;
        for _ in 0..k {
            self.dem.step_with(&mut self.set)?;
        }
        let dt = self.dem.config().dt;
        self.set.finish(dt_rigid, dt);
        for b in &self.set.boundaries {
            let Some(h) = b.body else { continue };
            let rb = bodies.get_mut(h).ok_or(BedError::MissingBody(h))?;
            let j = gv(b.last.impulse);
            let tau = gv(b.last.torque_impulse);
            self.given.0 += j;
            self.given.1 += tau + b.com0.cross(j);
            if rb.is_dynamic() {
                rb.apply_impulse(fv(j), true);
                rb.apply_torque_impulse(fv(tau), true);
            }
        }
        Ok(())
    }

    /// Cumulative impulses handed to the Rapier bodies since the bed was built, in f64:
    /// linear \[N s\] and angular about the world origin \[N m s\] (before Rapier's f32).
    pub fn impulses_given(&self) -> (Vec3, Vec3) {
        (lv(self.given.0), lv(self.given.1))
    }

    /// Energy of the grain-boundary contacts.
    pub fn boundary_energy(&self) -> BoundaryEnergy {
        self.set.energy(&self.dem)
    }
}
