//! A scene, built once per fidelity, and the run that steps it and records its [`Trace`]
//! (with the paired Coulomb twin of every step).

use creep_rapier::{CreepHooks, CreepWorld, Fidelity, MaterialRegistry, clone_physics};
use rapier3d::prelude::*;

use super::*;
use crate::measure::SceneError;

/// A scene, built once per fidelity.
pub(super) struct Scene {
    pub(super) w: CreepWorld,
    /// Dynamic bodies whose energy is counted.
    pub(super) dynamic: Vec<RigidBodyHandle>,
    /// The V-incline: the ball and the field's magnitude `m g sin(theta)` \[N\].
    pub(super) vee: Option<(RigidBodyHandle, f64)>,
    /// `F_ss` of the ball's contact as a function of `|Q|` \[N\] (V-incline scenes).
    pub(super) f_ss: Option<Box<dyn Fn(f64) -> f64>>,
    /// The body the ball rolls on, if dynamic (slip is measured relative to it).
    pub(super) support: Option<RigidBodyHandle>,
    /// Radius of the measured ball \[m\].
    pub(super) radius: f64,
    /// The creep is measured only while the ball's amplitude in the V (its position plus its
    /// kinetic energy over the field's magnitude) is at least this \[m\] (see the spin case).
    pub(super) min_amplitude: f64,
}

/// What a run measured.
#[derive(Debug, Default, Clone)]
pub struct Trace {
    /// Mechanical energy after each step \[J\].
    pub energy: Vec<f64>,
    /// Energy before the first step \[J\].
    pub e0: f64,
    /// Largest `|q_used| / (mu p)` over the plugin's records.
    pub q_ratio: f64,
    /// Largest `|tangent impulse| / (mu normal impulse)` over Rapier's contact points.
    pub rapier_ratio: f64,
    /// Largest loop gain reported.
    pub max_gain: f64,
    /// Number of contact-steps that took the creep path.
    pub creep_contacts: usize,
    /// Creep energy the plugin booked, `sum creep_power dt` \[J\].
    pub creep_energy: f64,
    /// Signed slip sum `W` over the measuring window \[m\] (V-incline scenes).
    pub slip: f64,
    /// Rolled distance `sum |dx|` over the measuring window \[m\].
    pub path: f64,
    /// Creep slip the plugin added, step by step against the twin stepped at Coulomb fidelity
    /// from the same state, signed like `slip` \[m\].
    pub paired_slip: f64,
    /// Kalker's prediction of `slip`, `sum F_ss((2/7) |F|) |dx|` \[m\].
    pub predicted: f64,
    /// Largest `|v|` of any body [m/s].
    pub max_speed: f64,
    /// Largest energy of a step minus that of the same step at Coulomb fidelity from the same
    /// state, relative to E0 (see `run::run`).
    pub paired_excess: f64,
    /// The step of `paired_excess`.
    pub paired_at: usize,
    /// Largest `paired_excess` minus 4 times the creep energy the plugin booked in that step or
    /// the one before, relative to E0 (see `common_verdicts`).
    pub paired_beyond_lag: f64,
    /// Largest running sum of the paired excesses, relative to E0: the plugin's net energy
    /// contribution along the run.
    pub paired_cumulative: f64,
    /// Steps run (fewer than asked when a non-finite state stopped the run).
    pub steps: usize,
    /// Non-finite states, forces or counts, Rapier quarantines, and friction forces without a
    /// normal force: the first one's description (the run stops there).
    pub broken: Option<String>,
}

pub(super) fn f(v: f32) -> f64 {
    f64::from(v)
}

/// The pair's friction coefficient (both colliders use the default `Average` combine rule).
pub(super) fn pair_mu(w: &CreepWorld, c1: ColliderHandle, c2: ColliderHandle) -> f64 {
    let c = &w.physics.colliders;
    0.5 * (f(c[c1].friction()) + f(c[c2].friction()))
}

/// The same hooks with every registered collider at `Fidelity::Coulomb` (fresh contact store:
/// the Coulomb path reads none of it).
pub(super) fn coulomb_hooks(w: &CreepWorld) -> Result<CreepHooks, SceneError> {
    let mut reg = MaterialRegistry::new();
    for (h, _) in w.physics.colliders.iter() {
        if let Some(m) = w.hooks().registry().get(h) {
            reg.insert(h, m.with_fidelity(Fidelity::Coulomb));
        }
    }
    Ok(CreepHooks::new(reg, *w.hooks().settings())?)
}

/// Whether a body's state is finite.
pub(super) fn finite_body(rb: &RigidBody) -> bool {
    rb.translation().is_finite()
        && rb.linvel().is_finite()
        && rb.angvel().is_finite()
        && rb.rotation().is_finite()
}

/// Runs the scene `steps` steps; the slip sum covers the steps from `measure_from` on. A
/// non-finite state stops the run and is recorded in [`Trace::broken`].
///
/// Paired energy check: before every step the world is copied, and the copy is stepped with
/// the plugin at `Fidelity::Coulomb` from the same state: the run's energy after the step minus
/// the copy's is the energy the plugin's creep added in that step, which must not be positive
/// (beyond 1e-6 of E0). This compares the two models on the same state, so it does not suffer
/// from the two runs' trajectories drifting apart (a run-against-run comparison at equal time
/// is dominated by the engine's own, phase-dependent losses).
pub(super) fn run(
    mut s: Scene,
    steps: usize,
    measure_from: usize,
) -> Result<(Trace, Scene), SceneError> {
    let mut t = Trace {
        paired_excess: f64::NEG_INFINITY,
        paired_beyond_lag: f64::NEG_INFINITY,
        paired_cumulative: f64::NEG_INFINITY,
        ..Default::default()
    };
    let mut sum_excess = 0.0;
    let mut booked_prev = 0.0f64;
    let x0: Vec<Vector> = s
        .dynamic
        .iter()
        .map(|&b| s.w.physics.bodies[b].center_of_mass())
        .collect();
    apply_vee(&mut s);
    t.e0 = energy(&s.w.physics, &s.dynamic, s.vee, &x0);
    let dt = f(s.w.physics.integration_parameters.dt);
    let ball = s.vee.map(|v| v.0);
    for step in 0..steps {
        let fx = apply_vee(&mut s);
        let before = ball.map(|b| {
            let rb = &s.w.physics.bodies[b];
            let sup = s.support.map(|h| s.w.physics.bodies[h].translation().x);
            (*rb.rotation(), rb.translation().x, sup.unwrap_or(0.0))
        });
        let mut twin = CreepWorld::from_parts(clone_physics(&s.w.physics), coulomb_hooks(&s.w)?)?;
        let counts = s.w.step()?;
        twin.step()?;
        t.steps = step + 1;
        // No NaN anywhere, and none neutralised by Rapier's quarantine either.
        if !s.w.physics.quarantine().is_empty() {
            t.broken = Some(format!(
                "Rapier quarantined non-finite state at step {step}"
            ));
            break;
        }
        if !s
            .dynamic
            .iter()
            .all(|&b| finite_body(&s.w.physics.bodies[b]))
        {
            t.broken = Some(format!("non-finite state at step {step}"));
            break;
        }
        for &b in &s.dynamic {
            t.max_speed = t.max_speed.max(f(s.w.physics.bodies[b].linvel().length()));
        }
        if !(counts.creep_power.is_finite() && counts.max_loop_gain.is_finite()) {
            t.broken = Some(format!("non-finite counts at step {step}: {counts:?}"));
            break;
        }
        t.max_gain = t.max_gain.max(counts.max_loop_gain);
        t.creep_contacts += counts.creep;
        t.creep_energy += counts.creep_power * dt;
        // |Q| <= mu P for the force the plugin used.
        for (k, r) in s.w.hooks().records() {
            if !(r.q_used.x.is_finite() && r.q_used.y.is_finite() && r.q_used.z.is_finite()) {
                t.broken = Some(format!("non-finite q_used at step {step}"));
            } else if r.p > 0.0 {
                let ratio = r.q_used.length() / (pair_mu(&s.w, k.collider1, k.collider2) * r.p);
                t.q_ratio = t.q_ratio.max(ratio);
            } else if r.q_used.length() != 0.0 {
                // No normal force: the plugin must not use any friction force.
                t.broken = Some(format!("Q without P at step {step}"));
            }
        }
        if t.broken.is_some() {
            break;
        }
        // ... and for Rapier's own total impulses of the step.
        for pair in s.w.physics.narrow_phase.contact_pairs() {
            let mu = pair_mu(&s.w, pair.collider1, pair.collider2);
            for m in pair.manifolds() {
                for pt in &m.points {
                    let n = f(pt.data.impulse);
                    if n > 0.0 && mu > 0.0 {
                        let ti = pt.data.tangent_impulse;
                        let tq = f(ti.x).hypot(f(ti.y));
                        t.rapier_ratio = t.rapier_ratio.max(tq / (mu * n));
                    }
                }
            }
        }
        let e = energy(&s.w.physics, &s.dynamic, s.vee, &x0);
        let e_twin = energy(&twin.physics, &s.dynamic, s.vee, &x0);
        let excess = (e - e_twin) / t.e0.abs();
        if excess > t.paired_excess {
            t.paired_excess = excess;
            t.paired_at = step;
        }
        let booked = counts.creep_power * dt / t.e0.abs();
        t.paired_beyond_lag = t
            .paired_beyond_lag
            .max(excess - 4.0 * booked.max(booked_prev));
        booked_prev = booked;
        sum_excess += excess;
        t.paired_cumulative = t.paired_cumulative.max(sum_excess);
        t.energy.push(e);
        // Slip of the ball's contact point along x, signed by the incline force.
        if let (Some(b), Some((q_old, x_old, sup_old))) = (ball, before)
            && step >= measure_from
            && amplitude(&s) >= s.min_amplitude
        {
            let rb = &s.w.physics.bodies[b];
            let dq = *rb.rotation() * q_old.inverse();
            let dtheta = f(dq.to_scaled_axis().z);
            let sup = s.support.map(|h| s.w.physics.bodies[h].translation().x);
            let dx = f(rb.translation().x - x_old) - f(sup.unwrap_or(0.0) - sup_old);
            t.slip += fx.signum() * (dx + s.radius * dtheta);
            t.path += dx.abs();
            // The same step at Coulomb fidelity from the same state (the twin).
            let tb = &twin.physics.bodies[b];
            let dq_t = *tb.rotation() * q_old.inverse();
            let sup_t = s.support.map(|h| twin.physics.bodies[h].translation().x);
            let dx_t = f(tb.translation().x - x_old) - f(sup_t.unwrap_or(0.0) - sup_old);
            t.paired_slip += fx.signum()
                * ((dx + s.radius * dtheta) - (dx_t + s.radius * f(dq_t.to_scaled_axis().z)));
            if let Some(f_ss) = &s.f_ss {
                t.predicted += f_ss(2.0 / 7.0 * fx.abs()) * dx.abs();
            }
        }
    }
    Ok((t, s))
}

/// The ball's amplitude in the V \[m\]: `|x| + E_kin / (m g sin(theta))`, the distance from
/// the bottom at which it would stop without losses (0 without a V).
pub(super) fn amplitude(s: &Scene) -> f64 {
    let Some((b, mag)) = s.vee else {
        return 0.0;
    };
    let rb = &s.w.physics.bodies[b];
    let w = rb.angvel();
    let iw = rb.mass_properties().effective_angular_inertia() * w;
    let ke = 0.5 * f(rb.mass()) * f(rb.linvel().length_squared()) + 0.5 * f(w.dot(iw));
    f(rb.translation().x).abs() + ke / mag
}

/// A run's numbers, one line.
pub(super) fn summary(label: &str, which: &str, t: &Trace) -> String {
    let e_end = t.energy.last().copied().unwrap_or(f64::NAN) / t.e0;
    format!(
        "{label} [{which}]: E0 {:.4e} J, E_end/E0 {e_end:.4}; paired step: max (E - E_coulomb)/E0 {:+.3e} (step {}), beyond the one-step lag {:+.3e}, cumulative {:+.3e}; max |Q|/(mu P): plugin {:.6}, Rapier {:.6}; max loop gain {:.3e}; creep contact-steps {}; creep energy booked {:.4e} J; max speed {:.3} m/s",
        t.e0,
        t.paired_excess,
        t.paired_at,
        t.paired_beyond_lag,
        t.paired_cumulative,
        t.q_ratio,
        t.rapier_ratio,
        t.max_gain,
        t.creep_contacts,
        t.creep_energy,
        t.max_speed
    )
}
