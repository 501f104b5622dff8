//! What the plugin reports without failing the step: [`CreepWarning`]s, each given once (in the
//! [`crate::StepCounts::warnings`] of the step in which it is first seen), so that a setup
//! that silently falls back to plain Rapier says so.

use rapier3d::prelude::{ColliderHandle, RigidBodyHandle};

use crate::registry::handle_name;

/// Turn of a registered ball or wheel in one step \[rad\] above which, with more than one
/// solver substep, Rapier's rotation gap matters (crate module `gap`): the solver reads the gap
/// `R (1 - cos(omega t))` at several instants of the step, which no correction a hook can write
/// follows; at 0.4 rad a step (a 0.1 m ball at 2.4 m/s, 1/60 s, 4 substeps) the ball sinks
/// 0.33 mm with the plugin's correction, at 0.83 rad (5 m/s) it floats 2.2 mm and loses 17 % of
/// its energy in one second. 0.2 rad keeps the spurious gap of the step, `R (1 - cos 0.2)`, at
/// 2 % of the radius.
pub const ROTATION_GAP_TURN: f64 = 0.2;

/// Something the plugin reports once, without failing the step (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum CreepWarning {
    /// A registered ball or wheel turned more than [`ROTATION_GAP_TURN`] in a step while
    /// `IntegrationParameters::num_solver_iterations` is above 1: Rapier's rotation gap makes it
    /// float or sink and lose energy, and its spin stays capped at 45 degrees a step.
    RotationGap {
        /// The ball's or wheel's collider.
        collider: ColliderHandle,
        /// Its rim speed `|omega| R` \[m/s\].
        rim_speed: f64,
        /// Its turn in the step `|omega| dt` \[rad\].
        turn: f64,
        /// The solver substeps of the step.
        substeps: usize,
    },
    /// A collider the registry does not know touches a registered one: their contacts stay
    /// Rapier's Coulomb friction (opt out: `CreepSettings::warn_unregistered`).
    Unregistered {
        /// The unregistered collider.
        collider: ColliderHandle,
        /// The registered collider it touches (the first seen).
        touching: ColliderHandle,
    },
    /// The world has colliders but none is registered: every contact is plain Rapier.
    NothingRegistered {
        /// Colliders in the world.
        colliders: usize,
    },
    /// Rapier quarantined a body whose state went non-finite (NaN or infinite): it is disabled
    /// (`Quarantine` of rapier3d; `RigidBody::set_enabled(true)` re-enables it).
    Quarantined {
        /// The body.
        body: RigidBodyHandle,
    },
}

impl std::fmt::Display for CreepWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::RotationGap {
                collider,
                rim_speed,
                turn,
                substeps,
            } => write!(
                f,
                "collider {} rolls at {rim_speed:.3} m/s ({turn:.3} rad a step) with \
                 num_solver_iterations = {substeps}: Rapier's rotation gap makes it float or \
                 sink and lose energy; set IntegrationParameters::num_solver_iterations = 1 \
                 (CreepSettings::solver = SolverPreset::Rolling, the default of CreepWorld::new \
                 and configure_parameters)",
                handle_name(*collider)
            ),
            Self::Unregistered { collider, touching } => write!(
                f,
                "collider {} touches the registered collider {} but is not registered: their \
                 contacts stay Coulomb (register it with a CreepMaterial, or set \
                 CreepSettings::warn_unregistered = false)",
                handle_name(*collider),
                handle_name(*touching)
            ),
            Self::NothingRegistered { colliders } => write!(
                f,
                "none of the world's {colliders} colliders is registered: every contact is plain \
                 Rapier (register colliders with CreepWorld::insert(.., Some(material)) or \
                 CreepPipeline::registry_mut().insert(handle, material))"
            ),
            Self::Quarantined { body } => {
                let (i, g) = body.into_raw_parts();
                write!(
                    f,
                    "Rapier quarantined body {i}v{g}: its state went non-finite (NaN or \
                     infinite) and it is disabled (check its size, mass and speed)"
                )
            }
        }
    }
}

/// Colliders already warned about, by collider index (no hashing): each warning once.
#[derive(Debug, Clone, Default)]
pub(crate) struct WarnedSet {
    slots: Vec<Option<ColliderHandle>>,
}

impl WarnedSet {
    /// Marks `collider`; true if it was not marked before.
    pub fn insert(&mut self, collider: ColliderHandle) -> bool {
        let i = collider.into_raw_parts().0 as usize;
        if i >= self.slots.len() {
            self.slots.resize(i + 1, None);
        }
        if self.slots[i] == Some(collider) {
            return false;
        }
        self.slots[i] = Some(collider);
        true
    }
}
