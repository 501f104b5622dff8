//! The per-collider creep material: a Bevy component wrapping creep-rapier's
//! [`creep_rapier::CreepMaterial`] (one definition of the fields and builders; the component
//! derefs to it).

use bevy::prelude::*;
use creep_law::Material;
use creep_law::rolling_torque::RollingModel;
use creep_rapier::{Fidelity, Regime};
use std::ops::{Deref, DerefMut};

/// Opts a collider entity (one with a bevy_rapier3d `Collider`) in to creep-friction. The fields
/// are creep-rapier's (reached through `Deref`/`DerefMut`, e.g. `m.regime = ...`):
///
/// - `material`: shear modulus G \[Pa\], Poisson's ratio nu \[-\] and density rho \[kg/m^3\]
///   (creep-law's validated [`Material`]). The friction coefficient mu is **not** taken from the
///   material: the collider's bevy_rapier3d `Friction` component supplies it (Rapier's combine
///   rule applies; Rapier's default is 0.5), so Coulomb and creep-friction see the same mu.
/// - `regime`: [`Regime::Rigid`] (Rapier's contact solve) at a [`Fidelity`]: Coulomb (Rapier's
///   own response), `Auto` (creep where its slip speed bound exceeds
///   [`creep_rapier::CreepSettings::auto_tolerance`]) or `Creep` (always); a pair uses the
///   lower of its two colliders' (Coulomb < Auto < Creep). Or [`Regime::Compliant`]
///   ([`CreepMaterial::compliant`]): soft-sphere forces (balls, cuboid and half-space walls),
///   which a pair gets as soon as one of its colliders is compliant ([`Regime::pair`]).
/// - `crown`: a wheel's crown radius \[m\] (`None`: a flat tread, line contact).
/// - `rolling`: contact-torque rolling resistance (Ai et al. 2011 types A, B, C), the other
///   category of rolling resistance, for comparison; a pair uses the first collider's that is
///   not `None`.
///
/// Density: when the entity has no `ColliderMassProperties`, the plugin gives the collider
/// `ColliderMassProperties::Density(rho)` from this material; a `ColliderMassProperties` of
/// your own wins.
///
/// Shapes ([`creep_rapier::supported_shape`]): a ball is a sphere; a cuboid, half-space,
/// triangle mesh, heightfield or convex polyhedron is flat at the contact; a cylinder rolling on
/// a flat collider is a wheel (Carter's line contact, or Hertz's ellipse with a crown:
/// [`CreepMaterial::with_crown`]). Any other shape (capsule, cone, compound, a ball with
/// non-uniform scale) draws a warning and stays Coulomb.
/// Both colliders of a pair need a `CreepMaterial`; a contact with a collider that has none
/// draws a warning (once per collider) and stays Coulomb.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct CreepMaterial(pub creep_rapier::CreepMaterial);

impl CreepMaterial {
    /// A material in the rigid regime with `Fidelity::Auto` and no rolling torque.
    pub fn new(material: Material) -> Self {
        Self(creep_rapier::CreepMaterial::new(material))
    }
    /// A material in the rigid regime at `fidelity`, with no rolling torque.
    pub fn rigid(material: Material, fidelity: Fidelity) -> Self {
        Self(creep_rapier::CreepMaterial::rigid(material, fidelity))
    }
    /// A material in the compliant regime ([`Regime::Compliant`]), with no rolling torque.
    pub fn compliant(material: Material) -> Self {
        Self(creep_rapier::CreepMaterial::compliant(material))
    }
    /// Steel (creep-law's [`Material::steel`]), `Fidelity::Auto`.
    pub fn steel() -> Self {
        Self::new(Material::steel())
    }
    /// Glass (creep-law's [`Material::glass`]), `Fidelity::Auto`.
    pub fn glass() -> Self {
        Self::new(Material::glass())
    }
    /// Rubber (creep-law's [`Material::rubber`]), `Fidelity::Auto`.
    pub fn rubber() -> Self {
        Self::new(Material::rubber())
    }
    /// This material in the rigid regime at `fidelity` (whatever its regime was).
    pub fn with_fidelity(self, fidelity: Fidelity) -> Self {
        Self(self.0.with_fidelity(fidelity))
    }
    /// This material in another regime.
    pub fn with_regime(self, regime: Regime) -> Self {
        Self(self.0.with_regime(regime))
    }
    /// This material on a wheel with a crown of radius `crown` \[m\] (finite, > 0): the tread's
    /// profile across the wheel, for Hertz's elliptic contact with spin creep instead of
    /// Carter's line contact (creep-rapier's `CreepMaterial::crown`). Read for cylinder
    /// colliders only.
    pub fn with_crown(self, crown: f64) -> Self {
        Self(self.0.with_crown(crown))
    }
    /// This material with a contact-torque rolling model.
    pub fn with_rolling(self, model: RollingModel) -> Self {
        Self(self.0.with_rolling(model))
    }
    /// The density rho \[kg/m^3\], as the `f32` Rapier uses.
    pub fn density(&self) -> f32 {
        self.0.material.density() as f32
    }
    /// The same material in creep-rapier's form (what the plugin registers).
    pub fn to_rapier(&self) -> creep_rapier::CreepMaterial {
        self.0
    }
}

impl Deref for CreepMaterial {
    type Target = creep_rapier::CreepMaterial;
    fn deref(&self) -> &Self::Target {
        &self.0
    }
}

impl DerefMut for CreepMaterial {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
    }
}

impl From<creep_rapier::CreepMaterial> for CreepMaterial {
    fn from(m: creep_rapier::CreepMaterial) -> Self {
        Self(m)
    }
}

impl From<CreepMaterial> for creep_rapier::CreepMaterial {
    fn from(m: CreepMaterial) -> Self {
        m.0
    }
}
