//! Per-collider creep materials. The registry is keyed by `ColliderHandle` (never the collider's
//! `user_data`, which bevy_rapier uses for its `Entity`), so the same core serves plain Rapier
//! and Bevy.
//!
//! A collider's [`Regime`] says which of the plugin's two contact models solves its pairs:
//! Rapier's contact solve with creep-friction at a [`Fidelity`] (the rigid regime), or the
//! plugin's own soft-sphere forces (the compliant regime). [`Regime::pair`] is the one rule
//! that gives a pair its regime.

use creep_law::Material;
use rapier3d::prelude::ColliderHandle;

/// How much creep-friction a rigid-regime collider (or pair) asks for. The order
/// `Coulomb < Auto < Creep` is the pairing order: a pair uses the lower of its two colliders'
/// (`a.min(b)`, [`Regime::pair`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default)]
pub enum Fidelity {
    /// Plain Coulomb friction (Rapier's own response).
    Coulomb,
    /// Creep-friction where it matters: a contact whose creep slip-speed bound
    /// `F_ss(1) |v_roll|` is below `tolerance` [m/s] is left to Coulomb.
    #[default]
    Auto,
    /// Creep-friction on every contact.
    Creep,
}

/// Which contact model solves a collider's pairs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Regime {
    /// Rapier's contact solve, with creep-friction at this fidelity (the rigid hooks).
    Rigid(Fidelity),
    /// Compliant (soft-sphere DEM) contact: the collider takes part in no Rapier contact solve
    /// (the plugin sets its solver groups to none and its hook off, so its pairs keep Rapier's
    /// contact recycling); [`crate::compliant`] applies Hertz-Mindlin-creep forces to every pair
    /// it forms (balls, and cuboids and half-spaces as walls:
    /// [`crate::SupportedShape::compliant_surface`]).
    Compliant,
}

impl Default for Regime {
    /// `Rigid(Fidelity::Auto)`.
    fn default() -> Self {
        Self::Rigid(Fidelity::default())
    }
}

impl From<Fidelity> for Regime {
    fn from(fidelity: Fidelity) -> Self {
        Self::Rigid(fidelity)
    }
}

impl Regime {
    /// The regime of a pair of colliders: rigid at the lower of the two fidelities
    /// (Coulomb < Auto < Creep) when both colliders are rigid; compliant as soon as one of them
    /// is compliant.
    ///
    /// A mixed pair (one rigid, one compliant collider) is therefore a compliant contact: the
    /// rigid hook gives it no solver contact, and the compliant regime applies its forces with
    /// both colliders' materials, friction and restitution, counted in
    /// [`crate::CompliantCounts::contacts`] like any compliant contact. That is how a compliant
    /// ball meets a wall registered in the rigid regime. What the compliant regime cannot model
    /// (a shape other than a ball, cuboid or half-space; two walls; a pair whose materials it
    /// refuses) it passes through and counts in [`crate::CompliantCounts::unsupported`]; so
    /// does a compliant collider's unregistered partner.
    pub fn pair(self, other: Regime) -> Regime {
        match (self, other) {
            (Regime::Rigid(a), Regime::Rigid(b)) => Regime::Rigid(a.min(b)),
            (Regime::Compliant, _) | (_, Regime::Compliant) => Regime::Compliant,
        }
    }
    /// The fidelity of a rigid-regime collider; `None` for a compliant one.
    pub fn fidelity(self) -> Option<Fidelity> {
        match self {
            Regime::Rigid(fidelity) => Some(fidelity),
            Regime::Compliant => None,
        }
    }
    /// Whether this is the compliant regime.
    pub fn is_compliant(self) -> bool {
        self == Regime::Compliant
    }
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
    /// The contact model of this collider's pairs: rigid at a fidelity, or compliant; a pair's
    /// is [`Regime::pair`] of its two colliders'.
    pub regime: Regime,
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
    /// A material in the rigid regime with `Fidelity::Auto` and no rolling torque.
    pub fn new(material: Material) -> Self {
        Self::rigid(material, Fidelity::Auto)
    }
    /// A material in the rigid regime at `fidelity`, with no rolling torque.
    pub fn rigid(material: Material, fidelity: Fidelity) -> Self {
        Self {
            material,
            regime: Regime::Rigid(fidelity),
            rolling: RollingResistance::None,
            crown: None,
        }
    }
    /// A material in the compliant regime ([`Regime::Compliant`]), with no rolling torque.
    pub fn compliant(material: Material) -> Self {
        Self {
            regime: Regime::Compliant,
            ..Self::new(material)
        }
    }
    /// This material in the rigid regime at `fidelity` (whatever its regime was).
    pub fn with_fidelity(self, fidelity: Fidelity) -> Self {
        self.with_regime(Regime::Rigid(fidelity))
    }
    /// This material in another regime.
    pub fn with_regime(mut self, regime: Regime) -> Self {
        self.regime = regime;
        self
    }
    /// Whether this material is in the compliant regime.
    pub fn is_compliant(&self) -> bool {
        self.regime.is_compliant()
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
    /// Registered colliders in the compliant regime (the compliant regime runs only with
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
            Some((_, old)) => self.compliant -= usize::from(old.is_compliant()),
        }
        self.compliant += usize::from(material.is_compliant());
    }
    /// Forgets a collider (call when removing it; unknown colliders fall back to Coulomb).
    pub fn remove(&mut self, collider: ColliderHandle) -> Option<CreepMaterial> {
        let slot = self.slots.get_mut(collider.into_raw_parts().0 as usize)?;
        if slot.is_some_and(|(h, _)| h == collider) {
            self.len -= 1;
            let m = slot.take().map(|(_, m)| m);
            self.compliant -= usize::from(m.is_some_and(|m| m.is_compliant()));
            m
        } else {
            None
        }
    }
    /// The material of a collider, if registered, to change anything but its regime.
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
                self.compliant -= usize::from(m.is_compliant());
            }
        }
    }
    /// Number of registered colliders in the compliant regime.
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Every pair of regimes: two rigid colliders pair at the lower fidelity
    /// (Coulomb < Auto < Creep), a compliant collider makes the pair compliant; the rule is
    /// symmetric.
    #[test]
    fn pairing_rule_over_all_combinations() {
        use Fidelity::{Auto, Coulomb, Creep};
        use Regime::{Compliant, Rigid};
        let all = [Rigid(Coulomb), Rigid(Auto), Rigid(Creep), Compliant];
        let expected = |a: Regime, b: Regime| match (a, b) {
            (Compliant, _) | (_, Compliant) => Compliant,
            (Rigid(Coulomb), _) | (_, Rigid(Coulomb)) => Rigid(Coulomb),
            (Rigid(Auto), _) | (_, Rigid(Auto)) => Rigid(Auto),
            (Rigid(Creep), Rigid(Creep)) => Rigid(Creep),
        };
        for a in all {
            for b in all {
                assert_eq!(a.pair(b), expected(a, b), "{a:?} with {b:?}");
                assert_eq!(a.pair(b), b.pair(a), "{a:?} with {b:?}");
            }
        }
        assert!(Coulomb < Auto && Auto < Creep);
        assert_eq!(Regime::default(), Rigid(Auto));
        assert_eq!(Rigid(Creep).fidelity(), Some(Creep));
        assert_eq!(Compliant.fidelity(), None);
    }

    /// The constructors and the registry's count of compliant colliders.
    #[test]
    fn constructors_and_compliant_count() {
        let steel = Material::steel();
        assert_eq!(
            CreepMaterial::new(steel).regime,
            Regime::Rigid(Fidelity::Auto)
        );
        assert_eq!(
            CreepMaterial::rigid(steel, Fidelity::Creep),
            CreepMaterial::new(steel).with_fidelity(Fidelity::Creep)
        );
        let soft = CreepMaterial::compliant(steel);
        assert!(soft.is_compliant() && soft.regime.fidelity().is_none());
        assert_eq!(
            soft.with_fidelity(Fidelity::Coulomb).regime,
            Regime::Rigid(Fidelity::Coulomb)
        );
        let mut reg = MaterialRegistry::new();
        let (a, b) = (
            ColliderHandle::from_raw_parts(0, 0),
            ColliderHandle::from_raw_parts(1, 0),
        );
        reg.insert(a, soft);
        reg.insert(b, CreepMaterial::new(steel));
        assert_eq!(reg.compliant_len(), 1);
        reg.insert(a, CreepMaterial::new(steel)); // replaced by a rigid one
        assert_eq!(reg.compliant_len(), 0);
        reg.insert(b, soft);
        reg.retain(|h, _| h != b);
        assert_eq!((reg.len(), reg.compliant_len()), (1, 0));
    }
}
