//! Per-collider creep materials. The registry is keyed by `ColliderHandle` (never the collider's
//! `user_data`, which bevy_rapier uses for its `Entity`), so the same core serves plain Rapier
//! and Bevy.

use creep_law::{Material, Surface};
use rapier3d::prelude::{Collider, ColliderHandle};

/// The fidelity a collider (or pair) asks for.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Fidelity {
    /// Plain Coulomb friction (Rapier's own response).
    Coulomb,
    /// Creep-friction on every contact.
    Creep,
    /// Creep-friction where it matters: a contact whose creep slip-speed bound
    /// `F_ss(1) |v_roll|` is below `tolerance` [m/s] is left to Coulomb.
    #[default]
    Auto,
    /// Compliant (soft-sphere DEM) contact: the collider takes part in no Rapier contact solve
    /// (the plugin sets its solver groups to none and its hook off, so its pairs keep Rapier's
    /// contact recycling); [`crate::compliant`] applies Hertz-Mindlin-creep forces to every pair
    /// it forms. Both colliders of a pair must be registered (an unregistered partner is passed
    /// through and counted in `CompliantCounts::unsupported`).
    Compliant,
}

/// Contact-torque rolling resistance (the talk's other category), per collider.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum RollingResistance {
    /// None (creep-friction alone).
    #[default]
    None,
    /// A contact-torque model from creep-law (Ai et al. 2011 types A, B, C).
    Torque(creep_law::rolling_torque::RollingModel),
}

/// What the plugin knows of one collider.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepMaterial {
    /// Elastic properties (G, nu) and density. The density sets the collider's mass when the
    /// collider is inserted through [`crate::CreepWorld::insert`] (or creep-bevy) with Rapier's
    /// default density (1 kg/m^3; a collider given its own density or mass keeps it).
    /// **Friction:** the one coefficient the plugin uses is the collider's
    /// (`ColliderBuilder::friction`, Rapier's combine rule between the two colliders); the
    /// material's `friction` is not read by the rigid regime (set the collider's from it, e.g.
    /// `.friction(material.friction() as f32)`). A NaN, infinite or negative collider friction
    /// is refused by the step ([`crate::PluginError::Friction`]).
    pub material: Material,
    /// Requested fidelity; a pair uses the lower of its two colliders' (Coulomb < Auto < Creep).
    pub fidelity: Fidelity,
    /// Contact-torque rolling resistance; a pair uses the first collider's that is not `None`.
    pub rolling: RollingResistance,
    /// A wheel's crown radius \[m\] (finite, > 0; read for cylinder colliders only, crate
    /// [`crate::SupportedShape::Wheel`]): the radius of the tread's profile across the wheel,
    /// giving Hertz's elliptic contact with the curvature sums `1/R` and `1/crown` and spin
    /// creep. `None` (default): a flat tread, Carter's line contact. A bad radius is refused by
    /// the step ([`crate::PluginError::Setting`]).
    pub crown: Option<f64>,
}

impl CreepMaterial {
    /// A material with `Fidelity::Auto` and no rolling torque.
    pub fn new(material: Material) -> Self {
        Self {
            material,
            fidelity: Fidelity::Auto,
            rolling: RollingResistance::None,
            crown: None,
        }
    }
    /// This material with another fidelity.
    pub fn with_fidelity(mut self, fidelity: Fidelity) -> Self {
        self.fidelity = fidelity;
        self
    }
    /// This material with a wheel's crown radius \[m\] ([`CreepMaterial::crown`]).
    pub fn with_crown(mut self, crown: f64) -> Self {
        self.crown = Some(crown);
        self
    }
    /// Refuses a crown radius that is not finite and > 0.
    pub fn validate(&self) -> Result<(), crate::PluginError> {
        match self.crown {
            Some(rc) if !(rc.is_finite() && rc > 0.0) => Err(crate::PluginError::Setting {
                name: "CreepMaterial::crown",
                value: rc,
                why: "a wheel's crown radius must be finite and > 0 [m]",
            }),
            _ => Ok(()),
        }
    }
    /// This material with a contact-torque rolling model.
    pub fn with_rolling(mut self, model: creep_law::rolling_torque::RollingModel) -> Self {
        self.rolling = RollingResistance::Torque(model);
        self
    }
}

/// Materials keyed by collider handle, addressed by the handle's index (no hashing on the
/// hook path): slot `i` holds the material of the live collider with index `i`, with its handle
/// to check the generation.
#[derive(Debug, Clone, Default)]
pub struct MaterialRegistry {
    slots: Vec<Option<(ColliderHandle, CreepMaterial)>>,
    len: usize,
    /// Registered colliders with `Fidelity::Compliant` (the compliant regime runs only with
    /// some; kept so that a step need not scan the registry to know).
    compliant: usize,
}

impl MaterialRegistry {
    /// An empty registry.
    pub fn new() -> Self {
        Self::default()
    }
    /// Registers (or replaces) a collider's material. A material left under the same index by
    /// an older generation (a collider Rapier removed) is replaced.
    pub fn insert(&mut self, collider: ColliderHandle, material: CreepMaterial) {
        let i = collider.into_raw_parts().0 as usize;
        if i >= self.slots.len() {
            self.slots.resize(i + 1, None);
        }
        match self.slots[i].replace((collider, material)) {
            None => self.len += 1,
            Some((_, old)) => self.compliant -= usize::from(old.fidelity == Fidelity::Compliant),
        }
        self.compliant += usize::from(material.fidelity == Fidelity::Compliant);
    }
    /// Forgets a collider (call when removing it; unknown colliders fall back to Coulomb).
    pub fn remove(&mut self, collider: ColliderHandle) -> Option<CreepMaterial> {
        let slot = self.slots.get_mut(collider.into_raw_parts().0 as usize)?;
        if slot.is_some_and(|(h, _)| h == collider) {
            self.len -= 1;
            let m = slot.take().map(|(_, m)| m);
            self.compliant -= usize::from(m.is_some_and(|m| m.fidelity == Fidelity::Compliant));
            m
        } else {
            None
        }
    }
    /// The material of a collider, if registered, to change anything but its fidelity.
    pub(crate) fn get_mut(&mut self, collider: ColliderHandle) -> Option<&mut CreepMaterial> {
        match self.slots.get_mut(collider.into_raw_parts().0 as usize) {
            Some(Some((h, m))) if *h == collider => Some(m),
            _ => None,
        }
    }
    /// The material of a collider, if registered.
    #[inline]
    pub fn get(&self, collider: ColliderHandle) -> Option<&CreepMaterial> {
        match self.slots.get(collider.into_raw_parts().0 as usize) {
            Some(Some((h, m))) if *h == collider => Some(m),
            _ => None,
        }
    }
    /// Number of registered colliders.
    pub fn len(&self) -> usize {
        self.len
    }
    /// Iterates over the registered colliders, in the order of their handles' indices.
    pub fn iter(&self) -> impl Iterator<Item = (&ColliderHandle, &CreepMaterial)> {
        self.slots
            .iter()
            .filter_map(|s| s.as_ref().map(|(h, m)| (h, m)))
    }
    /// Keeps only the colliders for which `keep` is true (no allocation).
    pub fn retain(&mut self, mut keep: impl FnMut(ColliderHandle, &CreepMaterial) -> bool) {
        for slot in &mut self.slots {
            if let Some((h, m)) = *slot
                && !keep(h, &m)
            {
                *slot = None;
                self.len -= 1;
                self.compliant -= usize::from(m.fidelity == Fidelity::Compliant);
            }
        }
    }
    /// Number of registered colliders with `Fidelity::Compliant`.
    pub fn compliant_len(&self) -> usize {
        self.compliant
    }
    /// Whether no collider is registered.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// A collider handle as `{index}v{generation}` (errors and warnings).
pub(crate) fn handle_name(collider: ColliderHandle) -> String {
    let (i, g) = collider.into_raw_parts();
    format!("{i}v{g}")
}

/// Refuses a friction coefficient that is NaN, infinite or negative.
pub(crate) fn check_friction(
    collider: ColliderHandle,
    value: f32,
) -> Result<(), crate::PluginError> {
    if value.is_finite() && value >= 0.0 {
        Ok(())
    } else {
        Err(crate::PluginError::Friction {
            collider: handle_name(collider),
            value: f64::from(value),
        })
    }
}

/// The contact surface a collider presents to the compliant regime (a ball a sphere, a cuboid
/// or half-space a plane), or `None`: [`crate::supported_shape`]'s
/// [`crate::SupportedShape::compliant_surface`].
pub fn surface_of(collider: &Collider) -> Option<Surface> {
    crate::shape::supported_shape(collider).and_then(|s| s.compliant_surface())
}

/// The contact surface a collider presents to the rigid regime's Hertz contact (a ball a
/// sphere; a cuboid, half-space, triangle mesh, heightfield or convex polyhedron a plane), or
/// `None` (a cylinder, whose wheel contact is its own, or an unsupported shape):
/// [`crate::supported_shape`]'s [`crate::SupportedShape::rigid_surface`]. To ask whether
/// the plugin models a collider at all (wheels included), use [`crate::supported_shape`].
pub fn rigid_surface_of(collider: &Collider) -> Option<Surface> {
    crate::shape::supported_shape(collider).and_then(|s| s.rigid_surface())
}

/// The lower of two fidelities (Coulomb < Auto < Creep), except that a `Compliant` collider
/// makes the pair compliant (it takes part in no Rapier contact solve).
pub(crate) fn pair_fidelity(a: Fidelity, b: Fidelity) -> Fidelity {
    use Fidelity::*;
    match (a, b) {
        (Coulomb, _) | (_, Coulomb) => Coulomb,
        (Auto, _) | (_, Auto) => Auto,
        (Compliant, _) | (_, Compliant) => Compliant,
        _ => Creep,
    }
}
