//! A ball on a ball or on a flat surface: a circular Hertz contact with the pair's steady law
//! along the rolling direction, Kalker's `C22` across it and spin creep (parent module docs).

use super::{
    CoulombReason, ForceCreepage, RigidContact, RigidCreep, RigidPair, RollFrame, creeping,
    force_estimate, solver_noise_force, spin_above_noise, translate,
};
use crate::kinematics::contact_rates;
use crate::material::PairMaterial;
use crate::vector::Vec3;
use crate::{hertz, kalker};

/// The creep slip target of one ball contact (parent module docs).
///
/// * `pair`: the contact's pair ([`RigidPair::pair_for`] of the two surfaces, at least one a
///   sphere; its `mu` is the contact's friction coefficient);
/// * `consts`: the pair's constants (the same [`RigidPair`]);
/// * `contact`: what the engine has at the contact ([`RigidContact`]; its bodies' surfaces are
///   not read, the pair's radius is);
/// * `inv_mass(d)`: the contact's inverse effective mass along the unit tangent `d` \[1/kg\],
///   `sum over dynamic bodies of 1/m + (r x d) . I^-1 (r x d)` (`r` from the body's centre of
///   mass to the contact point; called once).
///
/// Contacts without load, rolling or friction, auto contacts below their tolerance and loads
/// within the solver's rounding are left to Coulomb ([`CoulombReason`]).
pub fn ball_creep(
    pair: &PairMaterial,
    consts: &RigidPair,
    contact: &RigidContact,
    inv_mass: impl Fn(Vec3) -> f64,
) -> RigidCreep {
    let mu = pair.mu;
    let dt = contact.dt;
    let n = contact.normal;
    let p_force = contact.normal_impulse / dt;
    if let Some(out) = RigidCreep::unloaded(p_force, mu) {
        return out;
    }
    let (p, q) = (&contact.p, &contact.q);
    let rates = contact_rates(p, q, contact.point, n);
    let roll = rates.v_roll.length();
    if !(roll > 0.0) {
        return RigidCreep::coulomb(CoulombReason::NotRolling);
    }
    let a = hertz::contact_radius(pair, p_force);
    let mu_p = mu * p_force;
    if let Some(tolerance) = contact.auto_tolerance {
        // The largest creep slip, at full utilisation.
        let bound = kalker::steady_creepage(1.0, mu_p, pair.g, a, pair.c11) * roll;
        if bound < tolerance {
            return RigidCreep::coulomb(CoulombReason::BelowTolerance);
        }
    }
    let (q_star, inv_m) = force_estimate(contact, Vec3::X, inv_mass);
    let noise = solver_noise_force(p, q, contact.point, inv_m, dt);
    let k = if inv_m > 0.0 {
        roll / (inv_m * dt)
    } else {
        0.0
    };
    let Some(frame) = RollFrame::new(rates.v_roll, n) else {
        return RigidCreep::coulomb(CoulombReason::NotRolling);
    };
    let Some(law3) = consts.law3.as_ref() else {
        return RigidCreep::coulomb(CoulombReason::OutsideTable);
    };
    let w_scale = p.angular_velocity.length() + q.angular_velocity.length();
    let w_twist = spin_above_noise(rates.w_twist, w_scale);
    // The spin's lateral force (normalised spin creepage phi_n = phi G a^3/(mu P)).
    let phi_n = w_twist / roll * pair.g * a * a * a / mu_p;
    let spin = if phi_n != 0.0 {
        law3.loads(0.0, 0.0, phi_n)
    } else {
        Default::default()
    };
    let q_s = frame.y * (spin.fy * mu_p);
    let q_star_t = q_star - q_s;
    if !(q_star_t.length() > noise) {
        return RigidCreep::coulomb(CoulombReason::BelowNoise);
    }
    // The capacity left to the translation, and its law.
    let mu_t = (mu_p - spin.fy.abs() * mu_p).max(0.0);
    let law = consts.law;
    let law_t = ForceCreepage::new(law, mu_t, pair.g, a);
    let creepage = |q: f64| law_t.at(q);
    let slope0 = law.creepage_for_force(1.0, f64::INFINITY, pair.g, a);
    let t = translate(
        &frame, q_star_t, q_s, k, consts.r, mu_t, roll, slope0, creepage,
    );
    // Kalker's twisting moment on p about n.
    let mz = if phi_n != 0.0 || t.cy != 0.0 {
        let scale = pair.g * a * a / mu_p;
        law3.loads(t.cx * scale, t.cy * scale, phi_n).mz * mu_p * a
    } else {
        0.0
    };
    creeping(&t, n, mz, w_twist)
}
