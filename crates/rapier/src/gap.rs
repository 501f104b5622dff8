//! Rapier's rotation gap: the solver tracks a contact point as a point fixed in each body, so
//! a rolling sphere's tracked point turns away from its lowest point within a step and the
//! solver reads a spurious gap `R (1 - cos(omega t))` (the ball sinks, then is pushed back:
//! energy is lost). The hook can write a constant (`dist`) and a rate (the normal component of
//! `tangent_velocity`) into the solver contact; Rapier reads the gap at `n + 1` instants of a
//! step (`n = num_solver_iterations`: the biased passes at `j h`, `j < n`, the relaxation passes
//! at `j h`, `j >= 1`, `h = dt / n`).
//!
//! * One substep: two instants, which a constant and a rate follow **exactly**
//!   ([`rotation_gap_correction`]; it also never exceeds the gap, so it never pushes bodies
//!   apart and adds no energy). The fast-rolling matrix passes there.
//! * More substeps (Rapier's default is 4): no correction a hook can write meets the
//!   fast-rolling bounds (measured on the 108-case matrix of creep-scenes'
//!   `hard_cases::fast_rolling`, 10 s, spin cap lifted where stated). What a hook can write
//!   into a `SolverContact` reaches the gap reading only as `dist` (a constant) and the normal
//!   part of `tangent_velocity` (a rate); the anchors cannot help, because Rapier derives from
//!   them one point per contact that is both the tracked point and the lever arm of the
//!   normal and friction rows (`ContactData::solver_dp1`, the midpoint of the two surfaces),
//!   and a rolling ball's lever arm must be `R' n`. The readings `e_j` at `t_j = j h`,
//!   `j = 0..=n`, grow like `R' (omega t)^2 / 2` (at 5 m/s and 1/60 s: 2.2 mm a substep), so
//!   every line misses by millimetres somewhere. Lines tried (plain Rapier: worst loss 0.99 of
//!   E0, sinking 8.6 mm): the gap's mean over the substep midpoints (the one kept; worst
//!   gain 7.7e-3 of E0, rise 45 mm with the cap; loss 0.16 and rise 41 mm with it lifted);
//!   the line kept below every reading (cap lifted: no rise, a gain only at 20 m/s and 1/30 s,
//!   1.67 rad a substep, where the readings stop being convex; but sinking 0.1..13 mm and a
//!   loss up to 7e-3, and at 20 m/s and 1/30 s a loss of 0.33 and 0.15 m of sinking on the
//!   plane, a fall through the mesh); a minimax line through all five readings and one
//!   through the four biased readings (rises up to 33 mm with the cap lifted, 55 mm with it
//!   kept). None meets the bounds in more than 3 of 108 cases, and every one but the mean
//!   fails the hard-case matrix's paired energy bound, cap lifted or not (the line below: the
//!   1/30 s V-incline by 5.1e-6 of E0, the column of ten spinning spheres by 1.2e-5; the
//!   minimax lines: 5.8e-6..1.1e-5 and 6.7e-6..1.5e-5; no correction: the column by 3.1e-4),
//!   so the mean stays, and the spin cap stays on (`lift_rotation_cap` acts at one substep
//!   only). For fast-rolling balls at game steps use one substep (the plugin's default,
//!   `SolverPreset::Rolling`).
//! * What would meet them at 4 substeps: one unilateral row per secant of the readings (the
//!   largest of `n` lines follows a convex sequence of `n + 1` readings exactly), i.e. the
//!   solver contact duplicated `n` times with the lines `(c_k, b_k)` through `(t_k, e_k)` and
//!   `(t_{k+1}, e_{k+1})`, each lowered below all readings. Measured with the spin cap lifted:
//!   loss and height bounds met in 54 of the 72 plane and mesh cases (no rise, sinking at most
//!   65 um, wherever the turn per substep is at most 0.42 rad), the gain bound in 15 (gains up
//!   to 1.2e-3 of E0, the warm start below). Not shipped: the duplicates share
//!   one manifold point, where Rapier keeps the warm start and the step's impulses (the last
//!   row written wins), so the `P` and `Q` the creep hook reads are one row's and the warm
//!   start is applied `n` times: the hard-case matrix fails (creep 0.02..0.34 of Kalker's
//!   `F_ss`, a column of spheres drifting 0.29 m). It needs Rapier to keep impulses per solver
//!   contact, or a hook that may add manifold points (the experiment is
//!   `docs/experiments/substep-secant-rows.patch` in the repository).
//!
//! With one substep the correction is also not what limits a free ball's energy: Rapier
//! clamps the relaxed reading at zero overlap, so scaling the correction by 1.001 changes
//! nothing, and the drift that remains (up to 2e-5 of E0 over 10 s in the fast-rolling matrix)
//! is plain Rapier's own: a slow ball whose gap stays inside the overlap gains 1.8e-4..1.0e-3
//! of E0 in 60 s without the plugin, bit for bit as with it (creep-scenes'
//! `plain_rapier_gains_energy_in_slow_free_rolling`).
//!
//! With the feature `rapier-patched` (Rapier 0.36.1 with the patch series in `upstream/rapier/`),
//! the engine follows a ball's separation by the motion of its centre, so a ball reads no
//! rotation gap at any substep count and the plugin corrects none ([`ball_gap_surface`]); a
//! wheel (a cylinder) is still tracked by a body-fixed point and keeps its correction.

use creep_law::kinematics::BodyMotion;
use creep_law::{Surface, Vec3};

/// The surface a ball of `radius` \[m\] presents to the rotation-gap correction: a sphere (its
/// body-fixed contact anchor turns away from its lowest point), or, with the feature
/// `rapier-patched`, a plane: the patched engine tracks the ball's centre, which the rotation
/// does not move, so there is no gap to correct.
pub(crate) fn ball_gap_surface(radius: f64) -> Surface {
    if cfg!(feature = "rapier-patched") {
        Surface::Plane
    } else {
        Surface::Sphere(radius)
    }
}

/// Mean spurious change of the separation along `n` caused by a body's contact anchor riding
/// with the body's rotation through the solver substeps (the correction used with more than
/// one substep: module docs): the anchor `a` (world, at the start
/// of the step) turns about the centre of mass by `w t`; its normal component changes by
/// `(Rot(w t) r - r) . n`, `r = a - x` (Rodrigues' rotation formula), which the solver reads as
/// a gap (or overlap) although the surface of a sphere does not move. Averaged over the
/// substep midpoints `t = (k - 1/2) dt / n`, `k = 1..n`, in closed form (two sine-cosine
/// evaluations instead of one per substep). Zero for a body that does not turn.
fn mean_substep_gap(body: &BodyMotion, a: Vec3, n: Vec3, dt: f64, substeps: usize) -> f64 {
    let w = body.angular_velocity;
    let wl = w.length();
    if !(wl > 0.0) || !matches!(body.surface, Surface::Sphere(_)) {
        return 0.0;
    }
    let axis = w * (1.0 / wl);
    let r = a - body.position;
    // Means of cos and sin of phi_k = (k + 1/2) h over k = 0..n-1, h = |w| dt / n, in closed
    // form (sum of a geometric series of e^{i phi_k}): sum = e^{i n h / 2} sin(n h / 2) / sin(h / 2).
    let count = substeps.max(1) as f64;
    let h = wl * dt / count;
    let (sh, ch) = (0.5 * count * h).sin_cos();
    let s_half = (0.5 * h).sin();
    let ratio = if s_half != 0.0 {
        sh / (count * s_half)
    } else {
        1.0
    };
    let (mean_cos, mean_sin) = (ch * ratio, sh * ratio);
    // Rodrigues: Rot(phi) r - r = (cos phi - 1) (r - axis (axis . r)) + sin phi (axis x r).
    let r_perp = r - axis * axis.dot(r);
    (r_perp * (mean_cos - 1.0) + axis.cross(r) * mean_sin).dot(n)
}

/// Largest number of substeps the rotation-gap correction resolves (more are treated as this
/// many: the correction then stays on the safe side only approximately).
const MAX_GAP_SUBSTEPS: usize = 64;

/// Spurious change of the separation along `n` that Rapier reads after `j` substeps because
/// the solver tracks a body's contact point as a point fixed in the body: the point `a` (world,
/// at the start of the step) turns about the centre of mass with the body, although the surface
/// of a sphere does not move. Rapier (0.36, `integrate_linearized`) turns a body by
/// `phi = 2 atan(|w| h / 2)` per substep of length `h` (the quaternion `(1, w h / 2)`
/// normalised), so after `j` substeps the change along `n` is `(Rot(j phi) r - r) . n`,
/// `r = a - x` (Rodrigues' rotation formula). Zero for a body that does not turn or is not a
/// sphere.
fn rotation_gap(body: &BodyMotion, a: Vec3, n: Vec3, h: f64, j: usize) -> f64 {
    let w = body.angular_velocity;
    let wl = w.length();
    if !(wl > 0.0) || !matches!(body.surface, Surface::Sphere(_)) {
        return 0.0;
    }
    let axis = w * (1.0 / wl);
    let r = a - body.position;
    let phi = 2.0 * (0.5 * wl * h).atan() * j as f64;
    let (sn, cs) = phi.sin_cos();
    // Rodrigues: Rot(phi) r - r = (cos phi - 1) (r - axis (axis . r)) + sin phi (axis x r).
    let r_perp = r - axis * axis.dot(r);
    (r_perp * (cs - 1.0) + axis.cross(r) * sn).dot(n)
}

/// The correction of Rapier's rotation gap for one contact: `(c, b)` such that the solver's
/// separation reading `dist - c - b t` at the solve times `t_j = j h` (`j = 0..=n`, `h = dt /
/// n`: the biased passes at `j < n`, the relaxation passes at `j >= 1`) removes the spurious gap
/// `e_j = g2_j - g1_j` ([`rotation_gap`] of body 2 minus body 1's) as closely as a line can,
/// **never beyond it**: `c + b t_j <= e_j` for every `j`, so the solver never reads an overlap
/// that is not there and never pushes the bodies apart (the correction adds no energy). Of the
/// lines through two consecutive points `(t_j, e_j), (t_{j+1}, e_{j+1})`, each lowered until it
/// lies below all points, the one with the smallest largest residual `max_j (e_j - c - b t_j)`
/// is used. For `n = 1` the correction is exact. `c` is subtracted from the contact's `dist`
/// (Rapier bakes it into the anchors) and `b n` added to its `tangent_velocity` (whose normal
/// component moves the tracked point of body 1 along `n` at `b`, and enters no velocity target:
/// rapier3d 0.36 `ContactWithCoulombFrictionBuilder::update`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn rotation_gap_correction(
    p: &BodyMotion,
    a1: Vec3,
    q: &BodyMotion,
    a2: Vec3,
    n: Vec3,
    dt: f64,
    substeps: usize,
) -> (f64, f64) {
    if substeps > 1 {
        // A line cannot follow the gap through more than two instants: with Rapier's substeps
        // the correction is the gap's mean over the substeps (module docs).
        let c = mean_substep_gap(q, a2, n, dt, substeps) - mean_substep_gap(p, a1, n, dt, substeps);
        return (c, 0.0);
    }
    let count = substeps.clamp(1, MAX_GAP_SUBSTEPS);
    let h = dt / count as f64;
    let mut e = [0.0f64; MAX_GAP_SUBSTEPS + 1];
    let mut any = false;
    for (j, ej) in e.iter_mut().enumerate().take(count + 1) {
        *ej = rotation_gap(q, a2, n, h, j) - rotation_gap(p, a1, n, h, j);
        any |= *ej != 0.0;
    }
    if !any {
        return (0.0, 0.0);
    }
    let e = &e[..=count];
    let mut best = (0.0, 0.0, f64::INFINITY);
    for k in 0..count {
        let b = (e[k + 1] - e[k]) / h;
        let mut c = e[k] - b * (k as f64 * h);
        // Lower the line below every point.
        let over = e
            .iter()
            .enumerate()
            .map(|(j, ej)| c + b * (j as f64 * h) - ej)
            .fold(0.0f64, f64::max);
        c -= over;
        let residual = e
            .iter()
            .enumerate()
            .map(|(j, ej)| ej - c - b * (j as f64 * h))
            .fold(0.0f64, f64::max);
        if residual < best.2 {
            best = (c, b, residual);
        }
    }
    (best.0, best.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mean_substep_gap_closed_form_equals_the_substep_average() {
        let body = BodyMotion {
            position: Vec3::new(0.1, 0.2, -0.3),
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::new(3.0, -24.0, 7.0),
            surface: Surface::Sphere(0.1),
        };
        let n = Vec3::new(0.2, 0.9, -0.1).try_normalize().unwrap();
        let a = body.position - n * 0.1 + Vec3::new(0.01, 0.0, 0.02);
        for (dt, substeps) in [(1.0 / 60.0, 4), (1.0 / 30.0, 1), (1.0 / 240.0, 8)] {
            // Direct average of (Rot(w t_k) r - r) . n over the substep midpoints.
            let w = body.angular_velocity;
            let axis = w.try_normalize().unwrap();
            let r = a - body.position;
            let mut sum = 0.0;
            for k in 0..substeps {
                let phi = w.length() * (k as f64 + 0.5) * dt / substeps as f64;
                let (sn, cs) = phi.sin_cos();
                let rot = r * cs + axis.cross(r) * sn + axis * (axis.dot(r) * (1.0 - cs));
                sum += (rot - r).dot(n);
            }
            let direct = sum / substeps as f64;
            let closed = mean_substep_gap(&body, a, n, dt, substeps);
            assert!(
                (closed - direct).abs() <= 1e-15 + 1e-12 * direct.abs(),
                "{closed} vs {direct}"
            );
        }
    }

    #[test]
    fn ball_gap_surface_is_a_plane_only_for_the_patched_rapier() {
        let expected = if cfg!(feature = "rapier-patched") {
            Surface::Plane
        } else {
            Surface::Sphere(0.1)
        };
        assert_eq!(ball_gap_surface(0.1), expected);
    }

    #[test]
    fn rotation_gap_correction_stays_below_the_gap_and_is_exact_for_one_substep() {
        let ball = BodyMotion {
            position: Vec3::new(0.0, 0.1, 0.0),
            velocity: Vec3::new(5.0, 0.0, 0.0),
            angular_velocity: Vec3::new(0.0, 0.0, -50.0),
            surface: Surface::Sphere(0.1),
        };
        let ground = BodyMotion {
            position: Vec3::new(0.0, -1.0, 0.0),
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            surface: Surface::Plane,
        };
        // Ball = body 1, normal from the ball to the ground.
        let n = Vec3::new(0.0, -1.0, 0.0);
        let a = Vec3::ZERO;
        for (dt, substeps) in [(1.0 / 30.0, 1usize), (1.0 / 60.0, 1), (1.0 / 120.0, 1)] {
            let (c, b) = rotation_gap_correction(&ball, a, &ground, a, n, dt, substeps);
            let h = dt / substeps as f64;
            let mut worst = 0.0f64;
            for j in 0..=substeps {
                let e = -rotation_gap(&ball, a, n, h, j);
                let d = c + b * j as f64 * h;
                // The ball's contact point rises with the rotation: a spurious gap (> 0).
                if j > 0 {
                    assert!(e > 0.0, "{e}");
                }
                assert!(d <= e + 1e-15, "j {j}: correction {d} beyond the gap {e}");
                worst = worst.max(e - d);
            }
            if substeps == 1 {
                assert!(worst < 1e-15, "{worst}");
            }
        }
    }
}
