//! The rigid hook's wheel path (crate::wheel, docs/ARCHITECTURE.md §2): a cylinder on a flat
//! collider gets one contact record and one slip target for its whole manifold, with Carter's
//! line-contact law or, for a crowned wheel, the elliptic contact's 3-D law. Called from
//! [`crate::CreepHooks`]' `modify_solver_contacts` (crate::rigid), whose implicit per-contact
//! solve it shares.

use creep_law::kinematics::contact_rates;
use creep_law::{PairMaterial, Surface, Vec3};
use rapier3d::prelude::*;

use crate::convert::{inverse_mass, motion, v3, vf};
use crate::creep3d::{LawCache, RollFrame, solve_translation};
use crate::registry::Fidelity;
use crate::rigid::{CreepSettings, StepCounts, pair_fidelity, solver_tangents};
use crate::store::{ContactKey, ContactStore};
use crate::wheel::{Crowns, WheelContact, carter_creepage, line_half_width};

/// What the wheel path needs of the hook's call.
pub(crate) struct WheelCtx<'a> {
    pub(crate) colliders: (ColliderHandle, ColliderHandle),
    pub(crate) handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
    pub(crate) materials: (
        &'a crate::registry::CreepMaterial,
        &'a crate::registry::CreepMaterial,
    ),
    pub(crate) bodies: &'a RigidBodySet,
    pub(crate) colliders_set: &'a ColliderSet,
    pub(crate) dt: f64,
    pub(crate) settings: &'a CreepSettings,
}

/// The wheel path of the hook (crate::wheel): one record and one slip target for the whole
/// manifold of a cylinder (`side` 0: collider 1, 1: collider 2) on a flat collider. Returns
/// false when the collider is not a wheel (the caller then falls back to Coulomb).
pub(crate) fn wheel_manifold(
    ctx: &WheelCtx,
    rigid: &mut ModifiableManifold,
    side: usize,
    store: &mut ContactStore,
    counts: &mut StepCounts,
    laws: &mut LawCache,
    crowns: &mut Crowns,
) -> bool {
    let (c1, c2) = ctx.colliders;
    let (h1, h2) = ctx.handles;
    let (m1, m2) = ctx.materials;
    let wc = if side == 0 { c1 } else { c2 };
    let n_contacts = rigid.solver_contacts.len();
    let Some(co) = ctx.colliders_set.get(wc) else {
        return false;
    };
    let Some(cyl) = co.shape().as_cylinder() else {
        return false;
    };
    let radius = f64::from(cyl.radius);
    let wheel_surface = Surface::Sphere(radius);
    let (s1, s2) = if side == 0 {
        (wheel_surface, Surface::Plane)
    } else {
        (Surface::Plane, wheel_surface)
    };
    let mu = f64::from(*rigid.friction);
    let Ok(pair) =
        PairMaterial::new(&m1.material, &m2.material, s1, s2).and_then(|p| p.with_friction(mu))
    else {
        counts.coulomb_unsupported += n_contacts;
        return true;
    };
    let Some(wheel) = crowns.wheel(wc, co, pair.e_star) else {
        return false;
    };
    let fidelity = pair_fidelity(m1.fidelity, m2.fidelity);
    if fidelity == Fidelity::Coulomb {
        counts.coulomb_requested += n_contacts;
        return true;
    }
    let dt = ctx.dt;
    let n = v3(*rigid.normal);
    // The whole manifold: total normal force, contact centre.
    let key = ContactKey {
        collider1: c1,
        collider2: c2,
        feature1: u32::MAX,
        feature2: u32::MAX,
    };
    let rec = store.touch(key);
    let n_prev = if rec.normal == Vec3::ZERO {
        n
    } else {
        rec.normal
    };
    let (t1, t2) = solver_tangents(n_prev);
    let (mut impulse, mut tangent, mut centre, mut count) = (0.0, Vec3::ZERO, Vec3::ZERO, 0.0);
    for sc in rigid.solver_contacts.iter() {
        let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
        let Some(point) = rigid.manifold.points.get(cid) else {
            continue;
        };
        impulse += f64::from(point.data.impulse);
        let ti = point.data.tangent_impulse;
        tangent += t1 * f64::from(ti.x) + t2 * f64::from(ti.y);
        centre += (v3(sc.anchor1) + v3(sc.anchor2)) * 0.5;
        count += 1.0;
    }
    rec.bodies = (h1, h2);
    rec.torque = Vec3::ZERO;
    rec.spin_torque = Vec3::ZERO;
    rec.normal = n;
    let p_force = impulse / dt;
    rec.p = p_force;
    if !(count > 0.0) {
        rec.q_used = Vec3::ZERO;
        rec.target = Vec3::ZERO;
        return true;
    }
    let c = centre * (1.0 / count);
    let p_motion = motion(ctx.bodies, h1, c - n, s1);
    let q_motion = motion(ctx.bodies, h2, c + n, s2);
    let rates = contact_rates(&p_motion, &q_motion, c, n);
    // The wheel's frame: x along the heading n x axle, with the rolling.
    let heading = n.cross(wheel.axle).try_normalize();
    let frame = heading.map(|h| {
        let x = if h.dot(rates.v_roll) > 0.0 { -h } else { h };
        RollFrame { x, y: n.cross(x) }
    });
    let roll = frame.map_or(0.0, |f| rates.v_roll.dot(f.x).abs());
    let Some(frame) = frame.filter(|_| p_force > 0.0 && roll > 0.0 && mu > 0.0) else {
        rec.q_used = Vec3::ZERO;
        rec.target = Vec3::ZERO;
        counts.coulomb_auto += n_contacts;
        return true;
    };
    let mu_p = mu * p_force;
    let g = pair.g;
    // The law along x and the lateral ratio (module docs of crate::wheel).
    let (law3, line) = match wheel.contact {
        WheelContact::Crowned { a1, b1 } => {
            let s = p_force.cbrt();
            let (a, b) = (a1 * s, b1 * s);
            let Some(law3) = laws.get(a / b, pair.nu.clamp(0.0, 0.5)).copied() else {
                counts.coulomb_unsupported += n_contacts;
                rec.q_used = Vec3::ZERO;
                rec.target = Vec3::ZERO;
                return true;
            };
            (Some((law3, a * b)), None)
        }
        WheelContact::Line { width } => (
            None,
            Some(line_half_width(p_force, width, radius, pair.e_star)),
        ),
    };
    let creepage = |q: f64| -> f64 {
        match (law3, line) {
            (Some((law3, c2)), _) => {
                let f = (q / mu_p).clamp(0.0, 1.0 - 1e-9);
                law3.creepages_for_force(f, 0.0).map_or(0.0, |(x, _)| x) * mu_p / (g * c2)
            }
            (None, Some(a)) => carter_creepage(q, mu_p, p_force, a, radius),
            _ => 0.0,
        }
    };
    let (slope0, r) = match (law3, line) {
        (Some((law3, c2)), _) => {
            let k = law3.coefficients();
            (1.0 / (g * c2 * k.c11), k.c11 / k.c22)
        }
        (None, Some(a)) => (a / (2.0 * radius * p_force), 1.0 / (1.0 - pair.nu)),
        _ => (0.0, 1.0),
    };
    if fidelity == Fidelity::Auto && creepage(mu_p) * roll < ctx.settings.auto_tolerance {
        counts.coulomb_auto += n_contacts;
        rec.q_used = Vec3::ZERO;
        rec.target = Vec3::ZERO;
        return true;
    }
    let q_meas = tangent.reject(n) * (1.0 / dt);
    let tau_prev = rec.target.reject(n);
    let probe = (q_meas + tau_prev).try_normalize().unwrap_or(frame.x);
    let inv_m = inverse_mass(ctx.bodies, [h1, h2], vf(c), vf(probe), vf(probe));
    let q_star = if inv_m > 0.0 {
        q_meas + tau_prev * (1.0 / (inv_m * dt))
    } else {
        q_meas
    };
    let noise = crate::gap::solver_noise_force(&p_motion, &q_motion, c, inv_m, dt);
    if !(q_star.length() > noise) {
        rec.q_used = Vec3::ZERO;
        rec.target = Vec3::ZERO;
        counts.coulomb_auto += n_contacts;
        return true;
    }
    let k = if inv_m > 0.0 {
        roll / (inv_m * dt)
    } else {
        0.0
    };
    let (q_t, ux, uy) = solve_translation(frame.split(q_star), k, r, mu_p, slope0, &creepage);
    let f = creepage(q_t);
    let (cx, cy) = (f * ux, f * r * uy);
    let q_used = frame.join(q_t * ux, q_t * uy);
    let target = frame.join(cx, cy) * roll;
    rec.q_used = q_used;
    rec.target = target;
    counts.creep += n_contacts;
    counts.creep_power += q_used.dot(target).max(0.0);
    for sc in rigid.solver_contacts.iter_mut() {
        sc.tangent_velocity += vf(target);
    }
    true
}
