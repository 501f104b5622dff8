//! The rigid hook's ball path (crate::rigid, docs/ARCHITECTURE.md §2): the creep slip target of
//! every solver contact of a manifold with a ball on at least one side, with the 3-D law of
//! crate::creep3d. Called from [`crate::CreepHooks`]' `modify_solver_contacts` with what the
//! manifold shares, looked up once per manifold: the two bodies, the pair's constants
//! (crate::pair_cache), the fidelity and the rolling model.
//!
//! # Cost
//! Per contact: the record (one hash lookup in the shard's store), the bodies' motion at the
//! contact (shared by the rotation-gap correction and the creep), Kuhn & Bagi's rates, Hertz's
//! radius, the effective mass along the force, and the implicit solve. Contacts that carry no
//! load (a new contact, a separating one) leave before the rates and the solve.
//!
//! A planar shortcut was tried and is not used: with no spin creep and a lateral load within
//! the solver's noise floor (crate::gap's `solver_noise_force`), solve the contact as circular
//! along `Q*` (the rigid regime's 2-D solve before the 3-D law, bit for bit). Contacts near
//! the floor then switch between the two solves from step to step, and the hard-case matrix's
//! 1:1000 light-ball-on-heavy-slab case failed its paired energy check (excess beyond the
//! one-step lag 2.5e-5 of E0 against the bound 1e-6; 1.0e-7 with the 3-D solve alone). In the
//! poured pile almost every contact spins, so the shortcut would have saved little there.

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::{PairMaterial, Surface, Vec3, hertz, kalker};
use rapier3d::geometry::NEW_CONTACT_BIT;
use rapier3d::prelude::*;

use crate::convert::{body_motion, inverse_mass_of, v3, vf};
use crate::gap::rotation_gap_correction;
use crate::registry::Fidelity;
use crate::rigid::{CreepSettings, StepCounts, solver_tangents};
use crate::rolling::rolling_torque;
use crate::store::{ContactKey, ContactStore};
use creep_law::rigid::RigidPair as PairConsts;
use creep_law::rigid::{RollFrame, solve_translation};

/// Rounding ulps of the bodies' angular speeds below which a relative spin about the normal is
/// taken as f32 noise (no spin creep): the solver resolves angular velocities to about
/// `eps_f32 |w|`; 16 as for the tangential load's floor (crate::gap). Without it the noise
/// spin of straight rolling drove the spin terms and the hard-case matrix's mass-ratio case
/// exceeded its paired energy bound by 1.2 %.
pub(crate) const SPIN_NOISE_ULPS: f64 = 16.0;

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
    pub consts: &'a PairConsts,
    /// The pair's fidelity.
    pub fidelity: Fidelity,
    /// The pair's contact-torque model.
    pub rolling: Option<creep_law::rolling_torque::RollingModel>,
    /// Time step \[s\].
    pub dt: f64,
    /// The solver substeps when the rotation-gap correction is on (crate::gap), else `None`.
    pub gap_substeps: Option<usize>,
    /// The hooks' settings.
    pub settings: &'a CreepSettings,
}

/// The creep slip targets of one ball manifold (module docs).
pub(crate) fn ball_manifold(
    m: &BallManifold,
    rigid: &mut ModifiableManifold,
    store: &mut ContactStore,
    counts: &mut StepCounts,
) {
    let (c1, c2) = m.colliders;
    let (h1, h2) = m.handles;
    let (s1, s2) = m.surfaces;
    let pair = &m.pair;
    let mu = pair.mu;
    let dt = m.dt;
    let n = v3(*rigid.normal);
    for sc in rigid.solver_contacts.iter_mut() {
        let (a1, a2) = (v3(sc.anchor1), v3(sc.anchor2));
        let p_motion = body_motion(m.bodies[0], a1 - n, s1);
        let q_motion = body_motion(m.bodies[1], a2 + n, s2);
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
        let key = ContactKey {
            collider1: c1,
            collider2: c2,
            feature1: point.fid1.0,
            feature2: point.fid2.0,
        };
        let c = (a1 + a2) * 0.5;
        let rec = store.touch(key);
        rec.bodies = (h1, h2);
        let p_force = f64::from(point.data.impulse) / dt;
        rec.p = p_force;
        let n_prev_step = rec.normal;
        rec.normal = n;
        rec.torque = Vec3::ZERO;
        rec.spin_torque = Vec3::ZERO;
        let creeps = m.fidelity != Fidelity::Coulomb;
        if m.rolling.is_none() {
            // Fast exits before the contact's rates, which nothing below needs then.
            if !creeps {
                counts.coulomb_requested += 1;
                rec.target = Vec3::ZERO;
                continue;
            }
            if !(p_force > 0.0 && mu > 0.0) {
                // No load (a new contact: no impulse yet, or one that separates) or
                // frictionless: nothing creeps.
                rec.q_used = Vec3::ZERO;
                counts.coulomb_auto += 1;
                rec.target = Vec3::ZERO;
                continue;
            }
        }
        let rates = contact_rates(&p_motion, &q_motion, c, n);
        let roll = rates.v_roll.length();

        // Contact-torque rolling resistance (computed here, applied in end_step).
        if let Some(model) = m.rolling {
            counts.rolling_torque += 1;
            rec.torque = rolling_torque(
                &model,
                rec,
                m.body_set,
                (h1, h2),
                pair,
                p_force,
                rates.w_roll,
                n,
                dt,
            );
        }

        if !creeps {
            counts.coulomb_requested += 1;
            rec.target = Vec3::ZERO;
            continue;
        }
        if !(p_force > 0.0) || !(roll > 0.0) || !(mu > 0.0) {
            // New contact (no impulse yet), no rolling, or frictionless: nothing creeps.
            rec.q_used = Vec3::ZERO;
            counts.coulomb_auto += 1;
            rec.target = Vec3::ZERO;
            continue;
        }
        let a = hertz::contact_radius(pair, p_force);
        let mu_p = mu * p_force;
        let bound = kalker::steady_creepage(1.0, mu_p, pair.g, a, pair.c11) * roll;
        if m.fidelity == Fidelity::Auto && bound < m.settings.auto_tolerance {
            counts.coulomb_auto += 1;
            rec.q_used = Vec3::ZERO;
            rec.target = Vec3::ZERO;
            continue;
        }
        // Measured friction force of the last step, on body 1: the step's total tangent
        // impulse in the solver's tangent basis, built from the normal of that step.
        // (`warmstart_tangent_world` holds the last substep only and reads zero on most
        // rolling steps: a direction taken from it never follows a reversal.)
        let ti = point.data.tangent_impulse;
        let n_prev = if n_prev_step == Vec3::ZERO {
            n
        } else {
            n_prev_step
        };
        let (t1, t2) = solver_tangents(n_prev);
        let q_meas = (t1 * f64::from(ti.x) + t2 * f64::from(ti.y)).reject(n) * (1.0 / dt);
        // Local implicit solve of the creep relation (crate::rigid): the force the solver
        // would transmit for a target tau is Q* - (m_t/dt) tau, with
        // Q* = Q_meas + (m_t/dt) tau_prev; tau = F_ss(|Q|/mu P) |v_roll| Q/|Q|.
        // Always the last target (dropping it makes the solve explicit: gain > 1 runs away).
        let tau_prev = rec.target.reject(n);
        let probe = (q_meas + tau_prev).try_normalize().unwrap_or(Vec3::X);
        let inv_m = inverse_mass_of(m.bodies, vf(c), vf(probe), vf(probe));
        let q_star = if inv_m > 0.0 {
            q_meas + tau_prev * (1.0 / (inv_m * dt))
        } else {
            q_meas
        };
        let noise = crate::gap::solver_noise_force(&p_motion, &q_motion, c, inv_m, dt);
        let k = if inv_m > 0.0 {
            roll / (inv_m * dt)
        } else {
            0.0
        };
        let law = m.consts.law;
        let (Some(frame), Some(law3)) = (RollFrame::new(rates.v_roll, n), m.consts.law3.as_ref())
        else {
            rec.q_used = Vec3::ZERO;
            rec.target = Vec3::ZERO;
            counts.coulomb_auto += 1;
            continue;
        };
        // A relative spin within the f32 rounding of the bodies' angular velocities is
        // noise, not spin (as the tangential load's floor, crate::gap): no spin creep.
        let w_twist = spin_above_noise(&p_motion, &q_motion, rates.w_twist);
        let r = m.consts.r;
        // 3-D creep (crate::creep3d): the spin's lateral force, the anisotropic implicit solve
        // of the translation, the twisting moment.
        let phi_n = w_twist / roll * pair.g * a * a * a / mu_p;
        let spin = if phi_n != 0.0 {
            law3.loads(0.0, 0.0, phi_n)
        } else {
            Default::default()
        };
        let q_s = frame.y * (spin.fy * mu_p);
        let q_star_t = q_star - q_s;
        if !(q_star_t.length() > noise) {
            rec.q_used = Vec3::ZERO;
            rec.target = Vec3::ZERO;
            counts.coulomb_auto += 1;
            continue;
        }
        let mu_t = (mu_p - spin.fy.abs() * mu_p).max(0.0);
        let creepage = |q: f64| law.creepage_for_force(q, mu_t, pair.g, a);
        let slope0 = law.creepage_for_force(1.0, f64::INFINITY, pair.g, a);
        let (q_t, ux, uy) = solve_translation(frame.split(q_star_t), k, r, mu_t, slope0, &creepage);
        let dq = 1e-6 * mu_t;
        let gain =
            k * (creepage((q_t + dq).min(mu_t)) - creepage((q_t - dq).max(0.0))) / (2.0 * dq);
        counts.max_loop_gain = counts.max_loop_gain.max(gain);
        let f = creepage(q_t);
        let (cx, cy) = (f * ux, f * r * uy);
        let q_used = frame.join(q_t * ux, q_t * uy) + q_s;
        rec.q_used = q_used;
        let target = frame.join(cx, cy) * roll;
        rec.target = target;
        // Twisting moment on p about n (Kalker's Mz), applied after the step as an angular
        // impulse that never reverses the relative spin (crate::rolling).
        let mz = if phi_n != 0.0 || cy != 0.0 {
            let scale = pair.g * a * a / mu_p;
            law3.loads(cx * scale, cy * scale, phi_n).mz * mu_p * a
        } else {
            0.0
        };
        rec.spin_torque = n * (-mz);
        counts.creep += 1;
        counts.creep_power += (q_used.dot(target) + mz * w_twist).max(0.0);
        sc.tangent_velocity += vf(target);
    }
}

/// The relative spin about the normal `w_twist` \[rad/s\], or 0 when it is within
/// [`SPIN_NOISE_ULPS`] f32 ulps of the bodies' angular speeds (noise, not spin).
#[inline]
pub(crate) fn spin_above_noise(p: &BodyMotion, q: &BodyMotion, w_twist: f64) -> f64 {
    let w_scale = p.angular_velocity.length() + q.angular_velocity.length();
    if w_twist.abs() > SPIN_NOISE_ULPS * f64::from(f32::EPSILON) * w_scale {
        w_twist
    } else {
        0.0
    }
}
