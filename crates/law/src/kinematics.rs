//! Kuhn & Bagi's objective contact kinematics: the relative (sliding) and rolling velocities of
//! two bodies at their contact (Kuhn & Bagi 2004, "Contact rolling and deformation in granular
//! media", Int. J. Solids Struct. 41, 5793-5820; the talk, slide "Eulerian kinematics
//! of a moving contact").
//!
//! Bodies p and q (p is Rapier's collider1); unit normal `n` from p to q; contact point `c`.
//! Material velocity of each surface at `c`: `u'_i = v_i + w_i x (c - x_i)`.
//! * Relative displacement rate: `v_disp = (u'_q - u'_p)_t`.
//! * Rolling rate: `v_roll = ((u'_q + u'_p)/2 - c')_t`, with `c'` the velocity of the contact
//!   point, which follows from the normal's rotation `n'`: for two spheres `n = (x_q - x_p)/d`, so
//!   `n' = (v_q - v_p)_t / d` and `c' = v_p + rho_p n'` (`rho_p` the distance from `x_p` to `c`
//!   along `n`), which is `c'_t = (R_q v_p + R_p v_q)/(R_p + R_q)` (docs/ARCHITECTURE.md §4) with the actual
//!   distances; for a plane the normal turns with the plane, `n' = w_plane x n`, and `c` stays
//!   under the sphere's centre.
//!
//! `_t` is the part in the tangent plane. All velocities in m/s, angular velocities in rad/s.
//! Note: a sphere *sliding* without rotation on a fixed plane has `|v_roll| = |v|/2`: the contact
//! point travels over the plane's material. Rolling is zero when the contact point moves with the
//! mean of the two surfaces, e.g. two equal spheres sliding symmetrically past each other.

use crate::material::Surface;
use crate::vector::Vec3;

/// The motion of one body and the shape of its surface at the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyMotion {
    /// Centre of mass (for a sphere, its centre) \[m\].
    pub position: Vec3,
    /// Linear velocity of the centre [m/s].
    pub velocity: Vec3,
    /// Angular velocity [rad/s].
    pub angular_velocity: Vec3,
    /// Surface shape at the contact.
    pub surface: Surface,
}

/// Contact rates in the tangent plane (3-D vectors orthogonal to the normal).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactRates {
    /// `v_disp = (u'_q - u'_p)_t` [m/s]: q's surface relative to p's.
    pub v_disp: Vec3,
    /// `v_roll = ((u'_q + u'_p)/2 - c')_t` [m/s] (Kuhn & Bagi 2004).
    pub v_roll: Vec3,
    /// Relative rolling angular velocity `(w_q - w_p)_t` [rad/s] (the quantity contact-torque
    /// rolling models resist; Iwashita & Oda 1998; Ai et al. 2011).
    pub w_roll: Vec3,
    /// Relative twisting angular velocity `((w_q - w_p) . n)` [rad/s].
    pub w_twist: f64,
}

impl BodyMotion {
    /// Material velocity of this body's surface at `point`: `v + w x (point - x)` [m/s].
    #[inline]
    pub fn velocity_at(&self, point: Vec3) -> Vec3 {
        self.velocity + self.angular_velocity.cross(point - self.position)
    }
}

/// Kuhn & Bagi (2004) contact rates of bodies `p` and `q` touching at `point` with unit normal
/// `normal` (from p to q). For two planes (no curved surface) the rolling rate is taken as zero.
/// Finite inputs give finite outputs.
#[inline]
pub fn contact_rates(p: &BodyMotion, q: &BodyMotion, point: Vec3, normal: Vec3) -> ContactRates {
    contact_rates_and_approach(p, q, point, normal).0
}

/// [`contact_rates`] and the approach rate `delta_dot = -(u'_q - u'_p) . n` \[m/s\] (the rate
/// at which the overlap grows), from the same two surface velocities: the soft-sphere pair
/// kernel (`crate::pair`) needs both.
#[inline(always)]
pub fn contact_rates_and_approach(
    p: &BodyMotion,
    q: &BodyMotion,
    point: Vec3,
    normal: Vec3,
) -> (ContactRates, f64) {
    let n = normal;
    let up = p.velocity_at(point);
    let uq = q.velocity_at(point);
    let v_disp = (uq - up).reject(n);
    let w_rel = q.angular_velocity - p.angular_velocity;
    let w_roll = w_rel.reject(n);
    let w_twist = w_rel.dot(n);
    let c_dot = match (p.surface, q.surface) {
        (Surface::Sphere(_), Surface::Sphere(_)) => {
            let rho_p = (point - p.position).dot(n);
            let rho_q = (q.position - point).dot(n);
            let d = rho_p + rho_q;
            // `finite`: `d.is_finite()` tested in the FP domain (see its docs).
            if d > 0.0 && crate::pair::finite(d) {
                // c' = v_p + rho_p n',  n' = (v_q - v_p)_t / d.
                p.velocity + (q.velocity - p.velocity) * (rho_p / d)
            } else {
                (up + uq) * 0.5
            }
        }
        (Surface::Plane, Surface::Sphere(_)) => {
            // c = x_q - rho_q n, n' = w_p x n.
            let rho_q = (q.position - point).dot(n);
            q.velocity - p.angular_velocity.cross(n) * rho_q
        }
        (Surface::Sphere(_), Surface::Plane) => {
            // c = x_p + rho_p n, n' = w_q x n.
            let rho_p = (point - p.position).dot(n);
            p.velocity + q.angular_velocity.cross(n) * rho_p
        }
        (Surface::Plane, Surface::Plane) => (up + uq) * 0.5,
    };
    let v_roll = ((up + uq) * 0.5 - c_dot).reject(n);
    let rates = ContactRates {
        v_disp,
        v_roll,
        w_roll,
        w_twist,
    };
    (rates, -(uq - up).dot(n))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(x: Vec3, v: Vec3, w: Vec3, r: f64) -> BodyMotion {
        BodyMotion {
            position: x,
            velocity: v,
            angular_velocity: w,
            surface: Surface::Sphere(r),
        }
    }

    #[test]
    fn pure_rolling_on_a_plane() {
        // Sphere of radius R on the fixed plane z = 0, rolling in +x: w = (0, v/R, 0).
        let (r, v) = (0.05, 2.0);
        let plane = BodyMotion {
            position: Vec3::ZERO,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            surface: Surface::Plane,
        };
        let ball = sphere(
            Vec3::new(0.3, 0.0, r),
            Vec3::new(v, 0.0, 0.0),
            Vec3::new(0.0, v / r, 0.0),
            r,
        );
        let k = contact_rates(&plane, &ball, Vec3::new(0.3, 0.0, 0.0), Vec3::Z);
        assert!(k.v_disp.length() < 1e-15);
        assert!((k.v_roll.length() - v).abs() < 1e-12);
        // Same with the plane as body q (normal from the ball to the plane).
        let k = contact_rates(&ball, &plane, Vec3::new(0.3, 0.0, 0.0), -Vec3::Z);
        assert!(k.v_disp.length() < 1e-15);
        assert!((k.v_roll.length() - v).abs() < 1e-12);
    }

    #[test]
    fn pure_sliding_of_equal_spheres() {
        // Equal spheres, centres on the x axis, sliding past each other along y without rotation.
        let r = 0.01;
        let p = sphere(Vec3::ZERO, Vec3::new(0.0, -0.5, 0.0), Vec3::ZERO, r);
        let q = sphere(
            Vec3::new(2.0 * r, 0.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
            Vec3::ZERO,
            r,
        );
        let k = contact_rates(&p, &q, Vec3::new(r, 0.0, 0.0), Vec3::X);
        assert!(k.v_roll.length() < 1e-15, "{:?}", k.v_roll);
        assert!((k.v_disp - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-15);
    }

    #[test]
    fn gears_on_fixed_centres() {
        let (r, w) = (0.02, 3.0);
        let p = sphere(Vec3::ZERO, Vec3::ZERO, Vec3::new(0.0, 0.0, w), r);
        let q = sphere(
            Vec3::new(2.0 * r, 0.0, 0.0),
            Vec3::ZERO,
            Vec3::new(0.0, 0.0, -w),
            r,
        );
        let k = contact_rates(&p, &q, Vec3::new(r, 0.0, 0.0), Vec3::X);
        assert!(k.v_disp.length() < 1e-15);
        assert!((k.v_roll.length() - w * r).abs() < 1e-15);
    }

    #[test]
    fn rigid_motion_of_the_pair_gives_zero() {
        // Any rigid motion V + W x x of both bodies, unequal spheres with overlap, and a plane.
        let vel = Vec3::new(0.3, -1.2, 0.7);
        let om = Vec3::new(-2.0, 0.5, 1.5);
        let rigid = |x: Vec3, s: Surface| BodyMotion {
            position: x,
            velocity: vel + om.cross(x),
            angular_velocity: om,
            surface: s,
        };
        let n = Vec3::new(1.0, 2.0, -0.5).try_normalize().unwrap();
        let (rp, rq) = (0.03, 0.01);
        let xp = Vec3::new(0.1, 0.2, 0.3);
        let xq = xp + n * (rp + rq - 1e-4);
        let c = xp + n * (rp - 0.5e-4);
        let k = contact_rates(
            &rigid(xp, Surface::Sphere(rp)),
            &rigid(xq, Surface::Sphere(rq)),
            c,
            n,
        );
        assert!(
            k.v_disp.length() < 1e-14 && k.v_roll.length() < 1e-14,
            "{k:?}"
        );
        assert!(k.w_roll.length() < 1e-14 && k.w_twist.abs() < 1e-14);
        // Plane p, sphere q.
        let xq = c + n * rq;
        let k = contact_rates(
            &rigid(xp, Surface::Plane),
            &rigid(xq, Surface::Sphere(rq)),
            c,
            n,
        );
        assert!(
            k.v_disp.length() < 1e-14 && k.v_roll.length() < 1e-14,
            "{k:?}"
        );
        // Sphere p, plane q.
        let xp2 = c - n * rp;
        let k = contact_rates(
            &rigid(xp2, Surface::Sphere(rp)),
            &rigid(xq, Surface::Plane),
            c,
            n,
        );
        assert!(
            k.v_disp.length() < 1e-14 && k.v_roll.length() < 1e-14,
            "{k:?}"
        );
    }

    #[test]
    fn sliding_ball_on_plane_rolls_the_plane() {
        let plane = BodyMotion {
            position: Vec3::ZERO,
            velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            surface: Surface::Plane,
        };
        let ball = sphere(
            Vec3::new(0.0, 0.0, 0.1),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::ZERO,
            0.1,
        );
        let k = contact_rates(&plane, &ball, Vec3::ZERO, Vec3::Z);
        assert!((k.v_disp - Vec3::X).length() < 1e-15);
        assert!((k.v_roll - Vec3::X * -0.5).length() < 1e-15);
    }
}
