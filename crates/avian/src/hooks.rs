//! [`CreepHooks`]: Avian's contact modification hook as a `SystemParam`.
//!
//! For each manifold of a pair with a ball on at least one side and a [`CreepMaterial`] on
//! both, the hook reads the first contact point (a ball's manifold has one), last step's normal
//! and tangential forces from the plugin's record ([`crate::CreepState`], filled after the
//! solver from Avian's contact constraints), the two bodies' motion at the contact and the
//! effective mass along the force, and sets the manifold's `tangent_velocity` to the creep slip
//! target (creep-law's rigid kernel, `creep_law::rigid::ball_creep`). Avian's solver then drives the relative surface velocity at the
//! contact, `v2 - v1`, to `-tangent_velocity` within the Coulomb limit `friction * P` of each
//! substep: creep slip within Coulomb friction's budget.
//!
//! Anything else (no material, another shape, an invalid material, `Fidelity::Coulomb`) is left
//! to Avian's Coulomb friction, with a warning for a bad setup.

use crate::material::{CreepMaterial, Fidelity};
use crate::state::{CreepState, CreepWarning, Inner, PairRecord, PointRecord};
use avian3d::parry::shape::ShapeType;
use avian3d::prelude::*;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use creep_law::Surface;
use creep_law::kinematics::BodyMotion;
use creep_law::rigid::{RigidContact, RigidPair, ball_creep};

/// creep-law's vector from Avian's.
#[inline]
pub(crate) fn v3(v: Vec3) -> creep_law::Vec3 {
    creep_law::Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// Avian's vector from creep-law's.
#[inline]
pub(crate) fn vf(v: creep_law::Vec3) -> Vec3 {
    Vec3::new(v.x as f32, v.y as f32, v.z as f32)
}

/// The contact surface of a collider: a ball's sphere, a flat shape's plane, else `None`.
pub(crate) fn surface_of(collider: &Collider) -> Option<Surface> {
    let shape = collider.shape_scaled();
    if let Some(ball) = shape.as_ball() {
        return Some(Surface::Sphere(f64::from(ball.radius)));
    }
    match shape.shape_type() {
        ShapeType::Cuboid
        | ShapeType::HalfSpace
        | ShapeType::TriMesh
        | ShapeType::HeightField
        | ShapeType::ConvexPolyhedron
        | ShapeType::Triangle => Some(Surface::Plane),
        _ => None,
    }
}

/// What the hook reads of a body.
type BodyData = (
    &'static RigidBody,
    &'static LinearVelocity,
    &'static AngularVelocity,
    &'static ComputedMass,
    &'static ComputedAngularInertia,
    &'static Rotation,
);

/// Creep-friction's collision hooks. Install them with
/// `PhysicsPlugins::default().with_collision_hooks::<CreepHooks>()` and add
/// [`crate::CreepAvianPlugin`].
#[derive(SystemParam)]
pub struct CreepHooks<'w, 's> {
    state: Res<'w, CreepState>,
    materials: Query<'w, 's, &'static CreepMaterial>,
    colliders: Query<'w, 's, &'static Collider>,
    bodies: Query<'w, 's, BodyData>,
    time: Res<'w, Time>,
}

/// A body's motion (the centre placed at `point - anchor`), its inverse mass and world
/// inverse inertia; a static or missing body is still with no inverse mass.
struct Body {
    velocity: creep_law::Vec3,
    angular_velocity: creep_law::Vec3,
    inv_mass: f32,
    inertia: Option<ComputedAngularInertia>,
}

impl CreepHooks<'_, '_> {
    fn body(&self, entity: Option<Entity>) -> Body {
        let still = Body {
            velocity: creep_law::Vec3::ZERO,
            angular_velocity: creep_law::Vec3::ZERO,
            inv_mass: 0.0,
            inertia: None,
        };
        let Some(Ok((rb, v, w, m, i, rot))) = entity.map(|e| self.bodies.get(e)) else {
            return still;
        };
        if rb.is_static() {
            return still;
        }
        let dynamic = rb.is_dynamic();
        Body {
            velocity: v3(v.0),
            angular_velocity: v3(w.0),
            inv_mass: if dynamic { m.inverse() } else { 0.0 },
            inertia: dynamic.then(|| i.rotated(rot.0)),
        }
    }
}

/// Inverse effective mass of the contact along unit `t` at anchors `r1`, `r2` \[1/kg\]:
/// `1/m1 + 1/m2 + (I1^-1 (r1 x t)) . (r1 x t) + (I2^-1 (r2 x t)) . (r2 x t)`.
fn inverse_mass_along(b1: &Body, r1: Vec3, b2: &Body, r2: Vec3, t: Vec3) -> f64 {
    let part = |b: &Body, r: Vec3| {
        let rt = r.cross(t);
        b.inv_mass + b.inertia.map_or(0.0, |i| (i.inverse() * rt).dot(rt))
    };
    f64::from(part(b1, r1) + part(b2, r2))
}

impl CollisionHooks for CreepHooks<'_, '_> {
    fn modify_contacts(&self, contacts: &mut ContactPair, _commands: &mut Commands) -> bool {
        let mut inner = self.state.lock();
        inner.hook_calls += 1;
        let (e1, e2) = (contacts.collider1, contacts.collider2);
        let points: usize = contacts.manifolds.iter().map(|m| m.points.len()).sum();
        let (m1, m2) = match (self.materials.get(e1), self.materials.get(e2)) {
            (Ok(a), Ok(b)) => (*a, *b),
            (Ok(_), Err(_)) => return setup(&mut inner, CreepWarning::MissingMaterial(e2), points),
            (Err(_), Ok(_)) => return setup(&mut inner, CreepWarning::MissingMaterial(e1), points),
            // Another plugin's hook flag: not ours.
            (Err(_), Err(_)) => return true,
        };
        let surface = |e: Entity| self.colliders.get(e).ok().and_then(surface_of);
        let (s1, s2) = match (surface(e1), surface(e2)) {
            (Some(a), Some(b)) => (a, b),
            (None, _) => return setup(&mut inner, CreepWarning::UnsupportedShape(e1), points),
            (_, None) => return setup(&mut inner, CreepWarning::UnsupportedShape(e2), points),
        };
        if s1 == Surface::Plane && s2 == Surface::Plane {
            // Two flat shapes: no rolling contact to creep (a box on a box).
            inner.current.coulomb_setup += points;
            return true;
        }
        let (b1, b2) = (self.body(contacts.body1), self.body(contacts.body2));
        let dt = self.time.delta_secs_f64();
        let settings = inner.settings;
        if m1.fidelity.min(m2.fidelity) == Fidelity::Coulomb {
            inner.current.coulomb_requested += points;
            return true;
        }
        let Some(first) = contacts.manifolds.first() else {
            return true;
        };
        let key = (
            m1.material,
            m2.material,
            first.friction,
            s1.radius() as f32,
            s2.radius() as f32,
        );
        // The pair's record and laws, built once per pair (again if its colliders, materials,
        // friction or radii change).
        let slot_ok = matches!(
            inner.slot(contacts.contact_id),
            Some(r) if r.colliders == (e1, e2) && r.key == key
        );
        if !slot_ok {
            let mu = f64::from(first.friction);
            let law = RigidPair::new(&m1.material, &m2.material, mu, settings.creep_model)
                .and_then(|consts| Some((consts.pair_for(s1, s2)?, consts)));
            if law.is_none() {
                inner.warn(CreepWarning::InvalidMaterial(
                    e1,
                    format!("friction {mu}, surfaces {s1:?} and {s2:?}"),
                ));
            }
            *inner.slot(contacts.contact_id) = Some(PairRecord {
                colliders: (e1, e2),
                bodies: (contacts.body1, contacts.body2),
                key,
                law,
                points: Vec::new(),
                harvested: true,
            });
        }
        let auto_tolerance =
            (m1.fidelity.min(m2.fidelity) == Fidelity::Auto).then_some(settings.auto_tolerance);
        let mut counts = inner.current;
        let Some(Some(rec)) = inner.records.get_mut(contacts.contact_id.0 as usize) else {
            return true;
        };
        let Some((pair, consts)) = rec.law else {
            counts.coulomb_setup += points;
            inner.current = counts;
            return true;
        };
        if rec.points.len() < contacts.manifolds.len() {
            rec.points
                .resize(contacts.manifolds.len(), PointRecord::default());
        }
        for (manifold, prev) in contacts.manifolds.iter_mut().zip(rec.points.iter_mut()) {
            // Balls: one point per manifold. Further points (none for a ball) stay Coulomb.
            counts.coulomb_auto += manifold.points.len().saturating_sub(1);
            let Some(point) = manifold.points.first() else {
                continue;
            };
            let n = v3(manifold.normal);
            let c = v3(point.point);
            let (a1, a2) = (point.anchor1, point.anchor2);
            let motion = |b: &Body, anchor: Vec3, s: Surface| BodyMotion {
                position: c - v3(anchor),
                velocity: b.velocity,
                angular_velocity: b.angular_velocity,
                surface: s,
            };
            let (p, q) = (motion(&b1, a1, s1), motion(&b2, a2, s2));
            let contact = RigidContact {
                normal: n,
                point: c,
                p,
                q,
                normal_impulse: prev.p * dt,
                tangent_impulse: prev.q_meas * dt,
                last_target: prev.target,
                dt,
                auto_tolerance,
            };
            let out = ball_creep(&pair, &consts, &contact, |d| {
                inverse_mass_along(&b1, a1, &b2, a2, vf(d))
            });
            prev.target = out.target;
            prev.q_used = out.force;
            prev.moment = out.moment;
            prev.normal = n;
            if out.creeps() {
                counts.creep += 1;
                counts.creep_power += out.power;
                counts.max_loop_gain = counts.max_loop_gain.max(out.loop_gain);
                // Avian drives v2 - v1 to -tangent_velocity.
                manifold.tangent_velocity = -vf(out.target);
            } else {
                counts.coulomb_auto += 1;
            }
        }
        inner.current = counts;
        true
    }
}

/// Leaves a pair to Coulomb for a bad setup: warns once, counts its points.
fn setup(inner: &mut Inner, w: CreepWarning, points: usize) -> bool {
    inner.warn(w);
    inner.current.coulomb_setup += points;
    true
}
