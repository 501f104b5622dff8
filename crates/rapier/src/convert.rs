//! Conversions between Rapier (f32, glam) and creep-law (f64) quantities, and the bodies'
//! motion and effective masses at a contact.

use creep_law::kinematics::BodyMotion;
use creep_law::{Surface, Vec3};
use rapier3d::prelude::*;

/// A Rapier (f32) vector in creep-law's f64 vector.
pub(crate) fn v3(v: Vector) -> Vec3 {
    Vec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}

/// A creep-law f64 vector rounded to Rapier's f32.
pub(crate) fn vf(v: Vec3) -> Vector {
    Vector::new(v.x as f32, v.y as f32, v.z as f32)
}

/// Motion of a body at the contact (a missing body is at rest at `fallback`).
pub(crate) fn body_motion(
    body: Option<&RigidBody>,
    fallback: Vec3,
    surface: Surface,
) -> BodyMotion {
    match body {
        Some(rb) => BodyMotion {
            position: v3(rb.center_of_mass()),
            velocity: v3(rb.linvel()),
            angular_velocity: v3(rb.angvel()),
            surface,
        },
        None => BodyMotion {
            position: fallback,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            surface,
        },
    }
}

/// [`body_motion`] of a body of `bodies` by handle.
pub(crate) fn motion(
    bodies: &RigidBodySet,
    handle: Option<RigidBodyHandle>,
    fallback: Vec3,
    surface: Surface,
) -> BodyMotion {
    body_motion(handle.and_then(|h| bodies.get(h)), fallback, surface)
}

/// Inverse effective mass of a contact between the unit directions `t` and `u` at `point`:
/// `sum_i [t . M_i^-1 u + (r_i x t) . I_i^-1 (r_i x u)]` over the dynamic bodies [1/kg] (the
/// Delassus operator of the contact; `t = u` gives the inverse mass along `t`).
pub(crate) fn inverse_mass(
    bodies: &RigidBodySet,
    handles: [Option<RigidBodyHandle>; 2],
    point: Vector,
    t: Vector,
    u: Vector,
) -> f64 {
    inverse_mass_of(handles.map(|h| h.and_then(|h| bodies.get(h))), point, t, u)
}

/// [`inverse_mass`] of bodies already looked up (the rigid hook looks them up once per
/// manifold).
#[inline]
pub(crate) fn inverse_mass_of(
    bodies: [Option<&RigidBody>; 2],
    point: Vector,
    t: Vector,
    u: Vector,
) -> f64 {
    let mut inv = 0.0;
    for rb in bodies.into_iter().flatten() {
        if !rb.is_dynamic() {
            continue;
        }
        let mp = rb.mass_properties();
        let r = point - rb.center_of_mass();
        let (rt, ru) = (r.cross(t), r.cross(u));
        inv += f64::from((mp.effective_inv_mass * t).dot(u))
            + f64::from(rt.dot(mp.effective_world_inv_inertia * ru));
    }
    inv
}

/// Inverse effective rotational inertia of the pair about the unit axis `w` [1/(kg m^2)].
pub(crate) fn inverse_rotational_inertia(
    bodies: &RigidBodySet,
    handles: [Option<RigidBodyHandle>; 2],
    w: Vector,
) -> f64 {
    let mut inv = 0.0;
    for h in handles {
        let Some(rb) = h.and_then(|h| bodies.get(h)) else {
            continue;
        };
        if rb.is_dynamic() {
            inv += f64::from(w.dot(rb.mass_properties().effective_world_inv_inertia * w));
        }
    }
    inv
}

/// The friction basis of Rapier's Coulomb contact constraint for a manifold of normal `n`
/// (rapier3d 0.36 `compute_tangent_contact_directions`: `t1 = orthonormal_vector(-n)`, the
/// branchless basis of Duff et al. 2017, `t2 = -n x t1`); `ContactData::tangent_impulse` is in it
/// (public so that scenes reading Rapier's friction impulses use the same basis).
pub fn solver_tangents(n: Vec3) -> (Vec3, Vec3) {
    let d = -n;
    let sign = 1f64.copysign(d.z);
    let a = -1.0 / (sign + d.z);
    let b = d.x * d.y * a;
    let t1 = Vec3::new(b, sign + d.y * d.y * a, -d.y);
    (t1, d.cross(t1))
}
