//! The rigid hook's ball path: the creep slip target of every solver contact of a manifold
//! with a ball on at least one side, one call of `creep_law::rigid::ball_creep` per contact.
//! Called from the dispatch (`modify_solver_contacts`) with what the manifold shares, looked up
//! once per manifold: the two bodies, the pair's constants, the fidelity and the rolling model.
//!
//! # Cost
//! Per manifold: the bodies' motions, read once (shared by the rotation-gap correction and the
//! creep of every contact). Per contact: the record (one hash lookup in the shard's store) and
//! the kernel (Kuhn & Bagi's rates, Hertz's radius, the effective mass along the force, the
//! implicit solve). Contacts that carry no load (a new contact, a separating one) leave the
//! kernel before the rates.
//!
//! A planar shortcut was tried and is not used: with no spin creep and a lateral load within
//! the solver's noise floor (`creep_law::rigid::solver_noise_force`), solve the contact as
//! circular along `Q*` (the rigid regime's 2-D solve before the 3-D law, bit for bit). Contacts
//! near the floor then switch between the two solves from step to step, and the hard-case
//! matrix's 1:1000 light-ball-on-heavy-slab case failed its paired energy check (excess beyond
//! the one-step lag 2.5e-5 of E0 against the bound 1e-6; 1.0e-7 with the 3-D solve alone). In
//! the poured pile almost every contact spins, so the shortcut would have saved little there.

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::rigid::{RigidContact, RigidPair, ball_creep};
use creep_law::{PairMaterial, Surface, Vec3};
use rapier3d::geometry::{ContactData, NEW_CONTACT_BIT};
use rapier3d::parry::query::TrackedContact;
use rapier3d::prelude::*;

use super::counts::StepCounts;
use crate::convert::{body_motion, inverse_mass_of, solver_tangents, v3, vf};
use crate::gap::rotation_gap_correction;
use crate::registry::Fidelity;
use crate::rolling::rolling_torque;
use crate::store::{ContactKey, ContactStore};

/// What the ball path shares over one manifold.
pub(crate) struct BallManifold<'a> {
    /// The manifold's colliders.
    pub colliders: (ColliderHandle, ColliderHandle),
    /// Their bodies' handles.
    pub handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    /// Their bodies, looked up once.
    pub bodies: [Option<&'a RigidBody>; 2],
    /// The body set (for the contact-torque rolling model).
    pub body_set: &'a RigidBodySet,
    /// The contact surfaces (at least one a sphere).
    pub surfaces: (Surface, Surface),
    /// The pair (this manifold's shapes and friction).
    pub pair: PairMaterial,
    /// The pair's laws.
    pub consts: &'a RigidPair,
    /// The pair's fidelity.
    pub fidelity: Fidelity,
    /// The pair's contact-torque model.
    pub rolling: Option<creep_law::rolling_torque::RollingModel>,
    /// Time step \[s\].
    pub dt: f64,
    /// The solver substeps when the rotation-gap correction is on (crate::gap), else `None`.
    pub gap_substeps: Option<usize>,
    /// [`crate::CreepSettings::auto_tolerance`] for an `Auto` pair, else `None`.
    pub auto_tolerance: Option<f64>,
    /// Whether the other side is a triangle mesh or a heightfield, whose contacts with a ball
    /// may coincide (`crate::store::CoincidentLoad`).
    pub on_mesh: bool,
}

/// The creep slip targets of one ball manifold (module docs).
pub(crate) fn ball_manifold(
    m: &BallManifold,
    rigid: &mut ModifiableManifold,
    store: &mut ContactStore,
    counts: &mut StepCounts,
) {
    let (s1, s2) = m.surfaces;
    let dt = m.dt;
    let n = v3(*rigid.normal);
    // The bodies' motions, read once per manifold (a side without a body is at rest at the
    // contact: `body_motion`'s fallback, per contact).
    let (p_body, q_body) = (
        m.bodies[0].map(|rb| body_motion(Some(rb), Vec3::ZERO, s1)),
        m.bodies[1].map(|rb| body_motion(Some(rb), Vec3::ZERO, s2)),
    );
    for sc in rigid.solver_contacts.iter_mut() {
        let (a1, a2) = (v3(sc.anchor1), v3(sc.anchor2));
        let p_motion = p_body.unwrap_or_else(|| body_motion(None, a1 - n, s1));
        let q_motion = q_body.unwrap_or_else(|| body_motion(None, a2 + n, s2));
        if let Some(substeps) = m.gap_substeps {
            // Rapier's rotation gap (crate::gap), on every contact of the pair whatever its
            // fidelity: the engine's error, not creep's.
            let (cg, b) = rotation_gap_correction(&p_motion, a1, &q_motion, a2, n, dt, substeps);
            sc.dist -= cg as f32;
            sc.tangent_velocity += vf(n * b);
        }
        let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
        let Some(point) = rigid.manifold.points.get(cid) else {
            continue;
        };
        let contact = BallContact {
            normal: n,
            point: (a1 + a2) * 0.5,
            p: p_motion,
            q: q_motion,
            subshapes: (rigid.manifold.subshape1, rigid.manifold.subshape2),
        };
        if let Some(target) = ball_contact(m, &contact, point, store, counts) {
            sc.tangent_velocity += vf(target);
        }
    }
}

/// The creep slip targets of one ball manifold that Rapier recycled this step (feature
/// `rapier-patched`: `ActiveHooks::RECYCLE_MODIFIED_SOLVER_CONTACTS`): the solver contacts are
/// those of the pair's last full update, localized, so the contact point is rebuilt as the
/// solver rebuilds it (the lever arms `solver_dp1/dp2` frozen at that update, from each body's
/// current centre of mass, or in world space for a world-attached side) and the normal is the
/// manifold's, frozen with them. Each contact's `tangent_velocity` is rewritten with this
/// step's target, as [`ball_manifold`] would set it on a full update (the patched engine needs
/// no rotation-gap correction on a ball, so the target is all it holds).
#[cfg(feature = "rapier-patched")]
pub(crate) fn recycled_ball_manifold(
    m: &BallManifold,
    manifold: &ContactManifold,
    contacts: &mut rapier3d::pipeline::RecycledSolverContacts,
    store: &mut ContactStore,
    counts: &mut StepCounts,
) {
    let (s1, s2) = m.surfaces;
    let n = v3(manifold.data.normal);
    let rel_dom = manifold.data.relative_dominance;
    // Rapier localizes a side's anchors in its body's centre-of-mass frame when that side is
    // not dominance-superior (pair_update.rs, "Localize solver contacts"); the lever arm is
    // then relative to the centre of mass, else a world point.
    let com1 = m.bodies[0]
        .filter(|_| rel_dom <= 0)
        .map(|rb| v3(rb.center_of_mass()));
    let com2 = m.bodies[1]
        .filter(|_| rel_dom >= 0)
        .map(|rb| v3(rb.center_of_mass()));
    let (p_body, q_body) = (
        m.bodies[0].map(|rb| body_motion(Some(rb), Vec3::ZERO, s1)),
        m.bodies[1].map(|rb| body_motion(Some(rb), Vec3::ZERO, s2)),
    );
    counts.recycled += contacts.len();
    for i in 0..contacts.len() {
        let cid = (contacts.as_slice()[i].contact_id[0] & !NEW_CONTACT_BIT) as usize;
        let Some(point) = manifold.points.get(cid) else {
            continue;
        };
        let c1 = com1.unwrap_or(Vec3::ZERO) + v3(point.data.solver_dp1);
        let c2 = com2.unwrap_or(Vec3::ZERO) + v3(point.data.solver_dp2);
        let c = (c1 + c2) * 0.5;
        let contact = BallContact {
            normal: n,
            point: c,
            p: p_body.unwrap_or_else(|| body_motion(None, c - n, s1)),
            q: q_body.unwrap_or_else(|| body_motion(None, c + n, s2)),
            subshapes: (manifold.subshape1, manifold.subshape2),
        };
        let target = ball_contact(m, &contact, point, store, counts);
        contacts.set_tangent_velocity(i, target.map_or(Vector::ZERO, vf));
    }
}

/// The features of a contact in its [`ContactKey`]: Rapier's feature ids, or on a triangle
/// mesh or heightfield (`on_mesh`) the manifold's parts (`subshapes`, its `subshape1/2`: the
/// triangle, and 0 on the ball's side). There each manifold is one triangle with one contact
/// of the ball, and its feature ids are the triangle's own (vertex, edge or face 0-2): they
/// would give two triangles' contacts one key, and one contact a new key each time the ball
/// passes from a triangle's face to its edge.
#[inline]
pub(crate) fn contact_features(
    fids: (u32, u32),
    subshapes: (u32, u32),
    on_mesh: bool,
) -> (u32, u32) {
    if on_mesh { subshapes } else { fids }
}

/// One contact of a ball manifold as the law reads it.
struct BallContact {
    /// The manifold's normal (from body 1 to body 2).
    normal: Vec3,
    /// The contact point \[m\] (world).
    point: Vec3,
    /// Body 1's motion.
    p: BodyMotion,
    /// Body 2's motion.
    q: BodyMotion,
    /// The manifold's parts of composite shapes (`subshape1`, `subshape2`).
    subshapes: (u32, u32),
}

/// One contact of a ball manifold: its record, the contact-torque rolling moment, the kernel's
/// creep (booked in `counts`). Returns the slip target to add to the contact's
/// `tangent_velocity` when the contact creeps.
fn ball_contact(
    m: &BallManifold,
    contact: &BallContact,
    point: &TrackedContact<ContactData>,
    store: &mut ContactStore,
    counts: &mut StepCounts,
) -> Option<Vec3> {
    let (c1, c2) = m.colliders;
    let (h1, h2) = m.handles;
    let dt = m.dt;
    let (n, c) = (contact.normal, contact.point);
    let (feature1, feature2) =
        contact_features((point.fid1.0, point.fid2.0), contact.subshapes, m.on_mesh);
    let key = ContactKey {
        collider1: c1,
        collider2: c2,
        feature1,
        feature2,
    };
    // A contact on a mesh: listed for the next step's grouping, and its group's load from the
    // last solve (`crate::store::CoincidentLoad`).
    let coincident = if m.on_mesh {
        store.on_meshes.push((key, c));
        if store.coincident.is_empty() {
            None
        } else {
            store.coincident.remove(&key)
        }
    } else {
        None
    };
    let rec = store.touch(key);
    rec.bodies = (h1, h2);
    let normal_impulse = f64::from(point.data.impulse);
    let p_force = normal_impulse / dt;
    rec.p = p_force;
    let n_prev = std::mem::replace(&mut rec.normal, n);
    rec.torque = Vec3::ZERO;
    rec.spin_torque = Vec3::ZERO;
    // Contact-torque rolling resistance (computed here, applied after the step).
    if let Some(model) = m.rolling {
        let rates = contact_rates(&contact.p, &contact.q, c, n);
        counts.rolling_torque += 1;
        rec.torque = rolling_torque(
            &model,
            rec,
            m.body_set,
            (h1, h2),
            &m.pair,
            p_force,
            rates.w_roll,
            n,
            dt,
        );
    }
    if m.fidelity == Fidelity::Coulomb {
        counts.coulomb_requested += 1;
        rec.target = Vec3::ZERO;
        return None;
    }
    // A contact without load (about half of a moving pile's solver contacts) or without
    // friction: the kernel's first answer (`RigidCreep::unloaded`), asked here before the
    // contact's friction impulse and the kernel's input are built. (A contact on a mesh is
    // solved from its coincident group's load, below.)
    let unloaded = match coincident {
        None => creep_law::rigid::RigidCreep::unloaded(p_force, m.pair.mu),
        Some(_) => None,
    };
    if let Some(out) = unloaded {
        counts.book(&out, 1);
        rec.set_creep(&out);
        return None;
    }
    // Last step's friction impulse on body 1: in the solver's tangent basis of that step's
    // normal. (`warmstart_tangent_world` holds the last substep only and reads zero on
    // most rolling steps: a direction taken from it never follows a reversal.)
    let (t1, t2) = solver_tangents(if n_prev == Vec3::ZERO { n } else { n_prev });
    let ti = point.data.tangent_impulse;
    let mut rigid_contact = RigidContact {
        normal: n,
        point: c,
        p: contact.p,
        q: contact.q,
        normal_impulse,
        tangent_impulse: t1 * f64::from(ti.x) + t2 * f64::from(ti.y),
        last_target: rec.target,
        dt,
        auto_tolerance: m.auto_tolerance,
    };
    // A contact that coincided with others in the last solve (a ball on a shared edge of a
    // mesh) is solved from the group's load: the same target for every member, and this
    // member's share of the group's moment and power.
    let mut share = 1.0;
    if let Some(g) = coincident.filter(|g| g.normal_impulse > 0.0) {
        share = (normal_impulse / g.normal_impulse).clamp(0.0, 1.0);
        rigid_contact.normal_impulse = g.normal_impulse;
        rigid_contact.tangent_impulse = g.tangent_impulse;
        rigid_contact.last_target = g.target;
    }
    let mut out = ball_creep(&m.pair, m.consts, &rigid_contact, |d| {
        inverse_mass_of(m.bodies, vf(c), vf(d), vf(d))
    });
    if share != 1.0 {
        out.moment = out.moment * share;
        out.power *= share;
    }
    counts.book(&out, 1);
    rec.set_creep(&out);
    out.creeps().then_some(out.target)
}
