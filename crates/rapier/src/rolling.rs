//! Contact-torque rolling resistance (Ai et al. 2011 types A, B, C from creep-law): the torque
//! of a contact in a step, and its application as a capped angular impulse after the step.

use creep_law::rolling_torque::{RollingInput, RollingModel, epsd_rolling_inertia};
use creep_law::{PairMaterial, Surface, Vec3, hertz};
use rapier3d::prelude::*;

use crate::convert::{inverse_rotational_inertia, v3, vf};
use crate::store::ContactRecord;

/// Applies the contact's rolling torque and its spin-creep moment ([`apply_capped_impulse`]
/// each).
pub(crate) fn apply_rolling_impulse(bodies: &mut RigidBodySet, rec: &ContactRecord, dt: f64) {
    apply_capped_impulse(bodies, rec, rec.torque, dt);
    apply_capped_impulse(bodies, rec, rec.spin_torque, dt);
}

/// Applies `M dt` on body 2 and `-M dt` on body 1, shortened so that it brings the relative
/// angular velocity along `M` at most to zero, never past it (a torque that would speed the
/// relative rotation up is not applied).
fn apply_capped_impulse(bodies: &mut RigidBodySet, rec: &ContactRecord, torque: Vec3, dt: f64) {
    let Some(axis) = torque.try_normalize() else {
        return;
    };
    let handles = [rec.bodies.0, rec.bodies.1];
    let inv_i = inverse_rotational_inertia(bodies, handles, vf(axis));
    if !(inv_i > 0.0) {
        return;
    }
    // Current relative rolling rate along the torque axis (the torque opposes it).
    let w_of = |h: Option<RigidBodyHandle>, b: &RigidBodySet| {
        h.and_then(|h| b.get(h))
            .map(|rb| v3(rb.angvel()))
            .unwrap_or_default()
    };
    let w_rel = (w_of(rec.bodies.1, bodies) - w_of(rec.bodies.0, bodies)).dot(axis);
    let mut impulse = torque.length() * dt;
    if w_rel < 0.0 {
        impulse = impulse.min(-w_rel / inv_i);
    } else {
        return; // already reversed or stopped: no torque pushes it further
    }
    let j = vf(axis * impulse);
    for (handle, jj) in [(rec.bodies.1, j), (rec.bodies.0, -j)] {
        // Without waking the body: it took part in the step (its contact was solved), and a
        // wake-up would restart its sleep timer every step, so that a settled pile with creep
        // or a rolling torque on its contacts never slept. A body Rapier has just put to sleep
        // keeps its rest.
        if let Some(rb) = handle.and_then(|h| bodies.get_mut(h))
            && rb.is_dynamic()
            && !rb.is_sleeping()
        {
            rb.apply_torque_impulse(jj, false);
        }
    }
}

/// The contact-torque model's torque on body 2 for this step.
#[allow(clippy::too_many_arguments)]
pub(crate) fn rolling_torque(
    model: &RollingModel,
    rec: &mut ContactRecord,
    bodies: &RigidBodySet,
    handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    pair: &PairMaterial,
    p: f64,
    w_roll: Vec3,
    n: Vec3,
    dt: f64,
) -> Vec3 {
    let a = hertz::contact_radius(pair, p);
    // Each dynamic sphere contributes its mass, its inertia about a diameter (2/5) m r^2 and its
    // radius to Ai et al.'s (2011) rolling inertia; walls and fixed bodies contribute nothing.
    let term = |h: Option<RigidBodyHandle>, s: Surface| {
        let body = h.and_then(|h| bodies.get(h)).filter(|rb| rb.is_dynamic());
        match (body, s) {
            (Some(rb), Surface::Sphere(r)) => {
                let m = f64::from(rb.mass());
                (m, 0.4 * m * r * r, r)
            }
            _ => (f64::INFINITY, f64::INFINITY, 1.0),
        }
    };
    let (m1, i1, rr1) = term(handles.0, pair.surface_p);
    let (m2, i2, rr2) = term(handles.1, pair.surface_q);
    let input = RollingInput {
        p,
        r_star: pair.r_star,
        k_n: 2.0 * pair.e_star * a,
        w_roll,
        normal: n,
        dt,
        rolling_inertia: epsd_rolling_inertia(m1, i1, rr1, m2, i2, rr2),
    };
    model.torque(&mut rec.rolling, &input).torque
}
