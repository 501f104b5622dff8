//! The plugin's contacts as Bevy-side values (entities, world points, forces, slips): what the
//! gizmos draw and what a demo shows on screen (e.g. colour by contact state).

use bevy::prelude::*;
use bevy_rapier3d::prelude::{RapierContextColliders, RapierContextSimulation};
use rapier3d::prelude::ColliderHandle;

use crate::state::CreepFriction;

/// What a contact did in the last step. Rigid regime: `Creep` when the plugin set a creep slip
/// target. Compliant regime: `Slip` at the Coulomb limit, otherwise `Creep` while the contact
/// carries a tangential force (Cattaneo-Mindlin partial slip, with Kuhn's creep term when it
/// rolls), `Stick` without one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ContactState {
    /// No creep slip: Rapier's Coulomb response (rolling without slip, or sticking).
    Stick,
    /// Creep: the contact transmits a force below `mu P` and slips by the creep law.
    Creep,
    /// At the Coulomb limit (`|Q| >= mu P` within 1e-3): gross sliding.
    Slip,
}

/// One contact point of the plugin's colliders, world frame, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CreepContact {
    /// Collider entity of body p (Rapier's collider1).
    pub collider1: Entity,
    /// Collider entity of body q (Rapier's collider2).
    pub collider2: Entity,
    /// Contact point \[m\]: rigid regime, the narrow phase's point on collider 1's surface as of
    /// the start of the last step (it trails a moving body by up to `v dt`); compliant regime,
    /// the middle of the overlap.
    pub point: Vec3,
    /// Unit normal from p to q [-].
    pub normal: Vec3,
    /// Normal force P \[N\] (the last step's; >= 0).
    pub normal_force: f32,
    /// Tangential force on p from q \[N\] (q gets the opposite).
    pub force: Vec3,
    /// Creep slip velocity of q's surface against p's, `v_disp` [m/s] (the rigid regime's
    /// target; zero for compliant contacts, whose slip is not a velocity target).
    pub slip: Vec3,
    /// Stick, creep or slip.
    pub state: ContactState,
}

impl CreepFriction {
    /// The live contacts of the plugin's colliders in the served context: the rigid regime's
    /// records (with their world points from the narrow phase) and the compliant regime's
    /// touching contacts. Allocates; meant for display and measurement, once a frame.
    pub fn creep_contacts(
        &self,
        sim: &RapierContextSimulation,
        colliders: &RapierContextColliders,
    ) -> Vec<CreepContact> {
        let entity = |h: ColliderHandle| {
            colliders
                .colliders
                .get(h)
                .and_then(|c| Entity::try_from_bits(c.user_data as u64))
        };
        let mut out = Vec::new();
        for (key, rec) in self.pipeline.hooks.records() {
            let (Some(e1), Some(e2), Some(co1)) = (
                entity(key.collider1),
                entity(key.collider2),
                colliders.colliders.get(key.collider1),
            ) else {
                continue;
            };
            let Some(pair) = sim.narrow_phase.contact_pair(key.collider1, key.collider2) else {
                continue;
            };
            let found = pair.manifolds().iter().find_map(|m| {
                m.points
                    .iter()
                    .find(|p| p.fid1.0 == key.feature1 && p.fid2.0 == key.feature2)
                    .map(|p| (m, p))
            });
            let Some((manifold, point)) = found else {
                continue;
            };
            let force = vec3(rec.q_used);
            let slip = vec3(rec.target);
            let mu_p = f64::from(manifold.data.friction) * rec.p;
            let state = if slip == Vec3::ZERO {
                ContactState::Stick
            } else if mu_p > 0.0 && rec.q_used.length() >= (1.0 - 1e-3) * mu_p {
                ContactState::Slip
            } else {
                ContactState::Creep
            };
            out.push(CreepContact {
                collider1: e1,
                collider2: e2,
                point: co1.position().transform_point(point.local_p1),
                normal: manifold.data.normal,
                normal_force: rec.p as f32,
                force,
                slip,
                state,
            });
        }
        for (&(c1, c2), c) in self.pipeline.compliant.contacts() {
            let (Some(e1), Some(e2)) = (entity(c1), entity(c2)) else {
                continue;
            };
            if !(c.overlap > 0.0) {
                continue;
            }
            out.push(CreepContact {
                collider1: e1,
                collider2: e2,
                point: vec3(c.point),
                normal: vec3(c.normal),
                normal_force: c.normal_force as f32,
                force: vec3(c.tangential_force),
                slip: Vec3::ZERO,
                state: if c.sliding {
                    ContactState::Slip
                } else if c.tangential_force.length() > 0.0 {
                    ContactState::Creep
                } else {
                    ContactState::Stick
                },
            });
        }
        out
    }
}

fn vec3(v: creep_law::Vec3) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}
