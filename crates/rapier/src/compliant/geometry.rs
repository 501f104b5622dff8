//! Contact geometry of the compliant regime, in f64 from the colliders' (f32) poses: sphere on
//! sphere, sphere on cuboid and sphere on half-space, analytically (no parry query, whose f32
//! arithmetic would round an overlap of a few micrometres at a position of a metre).

use creep_law::Vec3;
use rapier3d::prelude::Pose;

/// A rigid frame in f64: `x -> q x q^-1 + t`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Frame {
    /// Translation \[m\].
    pub t: Vec3,
    /// Unit quaternion `[x, y, z, w]` [-].
    pub q: [f64; 4],
}

impl Frame {
    /// The frame of a collider pose.
    pub fn of(pose: &Pose) -> Self {
        let t = pose.translation;
        let q = pose.rotation.to_array();
        Self {
            t: Vec3::new(f64::from(t.x), f64::from(t.y), f64::from(t.z)),
            q: q.map(f64::from),
        }
    }
    /// Rotates `v` by the frame's rotation (`v + 2 w (u x v) + 2 u x (u x v)`).
    pub fn rotate(&self, v: Vec3) -> Vec3 {
        rotate(self.q, v)
    }
    /// Rotates `v` by the inverse rotation.
    pub fn unrotate(&self, v: Vec3) -> Vec3 {
        rotate([-self.q[0], -self.q[1], -self.q[2], self.q[3]], v)
    }
}

fn rotate(q: [f64; 4], v: Vec3) -> Vec3 {
    let u = Vec3::new(q[0], q[1], q[2]);
    let t = u.cross(v) * 2.0;
    v + t * q[3] + u.cross(t)
}

/// Where and how deep two surfaces touch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Touch {
    /// Unit normal from body p to body q [-].
    pub normal: Vec3,
    /// Contact point: the middle of the overlap along the normal \[m\].
    pub point: Vec3,
    /// Overlap (approach) `delta` \[m\]; negative when apart.
    pub overlap: f64,
}

impl Touch {
    /// The same contact seen from the other body (normal reversed).
    pub fn flipped(self) -> Self {
        Self {
            normal: -self.normal,
            ..self
        }
    }
}

/// Sphere p (centre `xp`, radius `rp`) and sphere q: `n = (x_q - x_p)/|x_q - x_p|`,
/// `delta = r_p + r_q - |x_q - x_p|`, point at `x_p + n (r_p - delta/2)`. `None` for coincident
/// centres.
pub(crate) fn sphere_sphere(xp: Vec3, rp: f64, xq: Vec3, rq: f64) -> Option<Touch> {
    let d = xq - xp;
    let dist = d.length();
    let normal = d.try_normalize()?;
    let overlap = rp + rq - dist;
    Some(Touch {
        normal,
        point: xp + normal * (rp - 0.5 * overlap),
        overlap,
    })
}

/// Cuboid p (frame, half-extents \[m\]) and sphere q: normal from the cuboid's closest surface
/// point towards the centre (out of the nearest face when the centre is inside the cuboid).
pub(crate) fn cuboid_sphere(frame: &Frame, half: Vec3, xq: Vec3, rq: f64) -> Option<Touch> {
    let c = frame.unrotate(xq - frame.t);
    let h = [half.x, half.y, half.z];
    let cl = [c.x, c.y, c.z];
    let clamped: [f64; 3] = std::array::from_fn(|i| cl[i].clamp(-h[i], h[i]));
    let outside = (0..3).any(|i| cl[i].abs() > h[i]);
    let (closest, n_local, dist) = if outside {
        let closest = Vec3::new(clamped[0], clamped[1], clamped[2]);
        let d = c - closest;
        (closest, d.try_normalize()?, d.length())
    } else {
        // Centre inside: leave through the nearest face.
        let i = (0..3)
            .min_by(|&a, &b| (h[a] - cl[a].abs()).total_cmp(&(h[b] - cl[b].abs())))
            .unwrap_or(0);
        let s = 1f64.copysign(cl[i]);
        let mut e = [0.0; 3];
        e[i] = s;
        let mut p = cl;
        p[i] = s * h[i];
        (
            Vec3::new(p[0], p[1], p[2]),
            Vec3::new(e[0], e[1], e[2]),
            -(h[i] - cl[i].abs()),
        )
    };
    let overlap = rq - dist;
    let normal = frame.rotate(n_local);
    let closest = frame.rotate(closest) + frame.t;
    Some(Touch {
        normal,
        point: closest - normal * (0.5 * overlap),
        overlap,
    })
}

/// Half-space p (frame, outward unit normal in its local frame) and sphere q.
pub(crate) fn halfspace_sphere(frame: &Frame, n_local: Vec3, xq: Vec3, rq: f64) -> Option<Touch> {
    let normal = frame.rotate(n_local).try_normalize()?;
    let dist = (xq - frame.t).dot(normal);
    let overlap = rq - dist;
    let closest = xq - normal * dist;
    Some(Touch {
        normal,
        point: closest - normal * (0.5 * overlap),
        overlap,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_round_trip_and_known_turn() {
        // 90 degrees about z: x -> y.
        let s = std::f64::consts::FRAC_1_SQRT_2;
        let f = Frame {
            t: Vec3::ZERO,
            q: [0.0, 0.0, s, s],
        };
        let v = f.rotate(Vec3::X);
        assert!((v - Vec3::Y).length() < 1e-15);
        let w = Vec3::new(0.3, -1.0, 2.0);
        assert!((f.unrotate(f.rotate(w)) - w).length() < 1e-15);
    }

    #[test]
    fn shapes() {
        let t = sphere_sphere(Vec3::ZERO, 1.0, Vec3::new(1.9, 0.0, 0.0), 1.0).unwrap();
        assert!((t.overlap - 0.1).abs() < 1e-15 && (t.point.x - 0.95).abs() < 1e-15);
        let f = Frame {
            t: Vec3::new(0.0, -1.0, 0.0),
            q: [0.0, 0.0, 0.0, 1.0],
        };
        let half = Vec3::new(5.0, 1.0, 5.0);
        let t = cuboid_sphere(&f, half, Vec3::new(0.5, 0.49, 0.0), 0.5).unwrap();
        assert!((t.normal - Vec3::Y).length() < 1e-15);
        assert!((t.overlap - 0.01).abs() < 1e-15);
        assert!((t.point - Vec3::new(0.5, -0.005, 0.0)).length() < 1e-15);
        // Centre inside the box: out through the top face.
        let t = cuboid_sphere(&f, half, Vec3::new(0.5, -0.1, 0.0), 0.5).unwrap();
        assert!((t.normal - Vec3::Y).length() < 1e-15 && (t.overlap - 0.6).abs() < 1e-15);
        let t = halfspace_sphere(&f, Vec3::Y, Vec3::new(0.0, -0.6, 0.0), 0.5).unwrap();
        assert!((t.overlap - 0.1).abs() < 1e-15);
    }
}
