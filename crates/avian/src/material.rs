//! The [`CreepMaterial`] component: a collider's elastic material and its fidelity.

use bevy::prelude::*;
use creep_law::Material;

/// How a contact of a creep collider is solved.
///
/// A pair's fidelity is the lower of its two colliders' (`Coulomb` < `Auto` < `Creep`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default, Reflect)]
pub enum Fidelity {
    /// Avian's own Coulomb friction, untouched.
    Coulomb,
    /// Creep where it is larger than [`crate::CreepAvianPlugin::with_auto_tolerance`] (the
    /// saturated creep slip `F_ss(1) |v_roll|`, m/s), Coulomb elsewhere.
    #[default]
    Auto,
    /// Creep on every loaded rolling contact.
    Creep,
}

/// The elastic material of a collider (shear modulus, Poisson ratio, density, friction), read
/// by the creep hooks. Adding it to a collider turns on Avian's contact modification hook for
/// that collider (`ActiveCollisionHooks::MODIFY_CONTACTS`).
///
/// The friction coefficient used by the law is the manifold's (Avian's [`avian3d::prelude::Friction`]
/// combined by its rule); the material's own `mu` is not used, so a scene sets friction once,
/// in Avian.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct CreepMaterial {
    /// Elastic constants and density.
    pub material: Material,
    /// How this collider's contacts are solved.
    pub fidelity: Fidelity,
}

impl CreepMaterial {
    /// A creep material with [`Fidelity::Auto`].
    pub fn new(material: Material) -> Self {
        Self {
            material,
            fidelity: Fidelity::Auto,
        }
    }
    /// Structural steel (creep-law's [`Material::steel`]).
    pub fn steel() -> Self {
        Self::new(Material::steel())
    }
    /// Soda-lime glass (creep-law's [`Material::glass`]).
    pub fn glass() -> Self {
        Self::new(Material::glass())
    }
    /// This material with another fidelity.
    pub fn with_fidelity(self, fidelity: Fidelity) -> Self {
        Self { fidelity, ..self }
    }
    /// Density \[kg/m^3\] as Avian's `f32`.
    pub fn density(&self) -> f32 {
        self.material.density() as f32
    }
}
