//! The leap-frog corrected mechanical energy (module docs of [`super`], "Energy").

use rapier3d::prelude::*;

use super::*;

/// The leap-frog corrected mechanical energy (module docs) of `dynamic` in `p`; `x0`: the
/// bodies' initial centres, `vee`: the V-incline field.
pub(super) fn energy(
    p: &PhysicsWorld,
    dynamic: &[RigidBodyHandle],
    vee: Option<(RigidBodyHandle, f64)>,
    x0: &[Vector],
) -> f64 {
    let h = f(p.integration_parameters.dt) / p.integration_parameters.num_solver_iterations as f64;
    let g = p.gravity;
    let mut e = 0.0;
    for (i, &b) in dynamic.iter().enumerate() {
        let rb = &p.bodies[b];
        let m = f(rb.mass());
        let com = rb.center_of_mass();
        let v = rb.linvel();
        let mut force = g * rb.mass();
        let w = rb.angvel();
        let iw = rb.mass_properties().effective_angular_inertia() * w;
        e += 0.5 * m * f(v.length_squared()) + 0.5 * f(w.dot(iw));
        e -= m * f(g.dot(com - x0[i]));
        if let Some((vb, mag)) = vee
            && vb == b
        {
            e += mag * f(com.x).abs();
            force += rb.user_force();
        }
        e += 0.5 * h * f(force.dot(v));
    }
    e
}
