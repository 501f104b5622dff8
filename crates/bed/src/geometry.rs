//! Closest points of a grain's centre on a boundary, in the collider's frame.

use creep_law::Surface;
use rapier3d::glamx::{DVec3, Vec3 as FVec3};
use rapier3d::parry::shape::{SharedShape, TypedShape};

/// The shape of a boundary, in the collider's frame (SI units, m).
#[derive(Clone)]
pub enum BoundaryShape {
    /// A ball of `radius` \[m\] centred on the collider's origin (closed form, f64).
    Ball {
        /// Radius \[m\].
        radius: f64,
    },
    /// A box of half extents `half` \[m\] centred on the origin (closed form, f64).
    Cuboid {
        /// Half extents \[m\].
        half: DVec3,
    },
    /// A cylinder about the local y axis (parry's convention): `half_height`, `radius` \[m\]
    /// (closed form, f64).
    Cylinder {
        /// Half height \[m\].
        half_height: f64,
        /// Radius \[m\].
        radius: f64,
    },
    /// A convex hull or a trimesh: parry's point projection (f32).
    Parry(SharedShape),
}

impl core::fmt::Debug for BoundaryShape {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Ball { radius } => write!(f, "Ball {{ radius: {radius} }}"),
            Self::Cuboid { half } => write!(f, "Cuboid {{ half: {half:?} }}"),
            Self::Cylinder {
                half_height,
                radius,
            } => write!(
                f,
                "Cylinder {{ half_height: {half_height}, radius: {radius} }}"
            ),
            Self::Parry(s) => write!(f, "Parry({:?})", s.shape_type()),
        }
    }
}

/// The nearest point of a boundary's surface to a grain centre, in the collider's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// Nearest surface point \[m\].
    pub point: DVec3,
    /// Unit outward normal at it, towards the grain centre when outside [-].
    pub normal: DVec3,
}

impl BoundaryShape {
    /// The bed's view of a parry shape; `None` for shapes it does not support.
    pub fn from_shape(shape: &SharedShape) -> Option<Self> {
        match shape.as_typed_shape() {
            TypedShape::Ball(b) => Some(Self::Ball {
                radius: f64::from(b.radius),
            }),
            TypedShape::Cuboid(c) => Some(Self::Cuboid {
                half: DVec3::new(
                    f64::from(c.half_extents.x),
                    f64::from(c.half_extents.y),
                    f64::from(c.half_extents.z),
                ),
            }),
            TypedShape::Cylinder(c) => Some(Self::Cylinder {
                half_height: f64::from(c.half_height),
                radius: f64::from(c.radius),
            }),
            TypedShape::ConvexPolyhedron(_) | TypedShape::TriMesh(_) => {
                Some(Self::Parry(shape.clone()))
            }
            _ => None,
        }
    }

    /// The surface the contact law sees: a ball's curvature; flat otherwise.
    #[inline]
    pub fn surface(&self) -> Surface {
        match self {
            Self::Ball { radius } => Surface::Sphere(*radius),
            _ => Surface::Plane,
        }
    }

    /// The shape's bounding box in its frame (mins, maxs) \[m\].
    pub fn local_aabb(&self) -> (DVec3, DVec3) {
        match self {
            Self::Ball { radius } => (DVec3::splat(-radius), DVec3::splat(*radius)),
            Self::Cuboid { half } => (-*half, *half),
            Self::Cylinder {
                half_height,
                radius,
            } => {
                let h = DVec3::new(*radius, *half_height, *radius);
                (-h, h)
            }
            Self::Parry(s) => {
                let a = s.compute_local_aabb();
                let f = |v: FVec3| DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z));
                (f(a.mins), f(a.maxs))
            }
        }
    }

    /// The nearest surface point to the grain centre `p` (collider frame) when the grain of
    /// radius `r` may touch (the centre within `r` of the surface, or inside); `None` when
    /// apart or when no normal is defined (a centre exactly on the surface of a parry shape).
    #[inline]
    pub(crate) fn closest(&self, p: DVec3, r: f64) -> Option<Hit> {
        match self {
            Self::Ball { radius } => {
                let d = p.length();
                if d >= radius + r || !(d > 0.0) {
                    return None;
                }
                let n = p / d;
                Some(Hit {
                    point: n * *radius,
                    normal: n,
                })
            }
            Self::Cuboid { half } => cuboid(*half, p, r),
            Self::Cylinder {
                half_height,
                radius,
            } => cylinder(*half_height, *radius, p, r),
            Self::Parry(s) => {
                let (lo, hi) = self.local_aabb();
                let out = (lo - p).max(p - hi).max(DVec3::ZERO);
                if out.length_squared() >= r * r {
                    return None;
                }
                let q = FVec3::new(p.x as f32, p.y as f32, p.z as f32);
                let proj = s.project_local_point(q, false);
                let cp = DVec3::new(
                    f64::from(proj.point.x),
                    f64::from(proj.point.y),
                    f64::from(proj.point.z),
                );
                let diff = p - cp;
                let d = diff.length();
                if !(d > 0.0) {
                    return None;
                }
                if !proj.is_inside && d >= r {
                    return None;
                }
                let n = if proj.is_inside { -diff / d } else { diff / d };
                Some(Hit {
                    point: cp,
                    normal: n,
                })
            }
        }
    }
}

/// Box of half extents `he`: outside, the nearest point of the box (face, edge or corner) and
/// the direction to the centre; inside, the shallowest face.
#[inline]
fn cuboid(he: DVec3, p: DVec3, r: f64) -> Option<Hit> {
    let q = p.clamp(-he, he);
    let diff = p - q;
    let d2 = diff.length_squared();
    if d2 > 0.0 {
        if d2 >= r * r {
            return None;
        }
        let d = d2.sqrt();
        return Some(Hit {
            point: q,
            normal: diff / d,
        });
    }
    // Inside (or on the surface): the face with the smallest gap.
    let gap = he - p.abs();
    let axis = if gap.x <= gap.y && gap.x <= gap.z {
        0
    } else if gap.y <= gap.z {
        1
    } else {
        2
    };
    let s = if p[axis] >= 0.0 { 1.0 } else { -1.0 };
    let mut normal = DVec3::ZERO;
    normal[axis] = s;
    let mut point = p;
    point[axis] = s * he[axis];
    Some(Hit { point, normal })
}

/// Cylinder about y (half height `hh`, radius `rc`): outside, the nearest point of the side,
/// cap or rim; inside, the nearer of the side and the caps.
#[inline]
fn cylinder(hh: f64, rc: f64, p: DVec3, r: f64) -> Option<Hit> {
    let rho = (p.x * p.x + p.z * p.z).sqrt();
    let u = if rho > 0.0 {
        DVec3::new(p.x / rho, 0.0, p.z / rho)
    } else {
        DVec3::X
    };
    if rho > rc || p.y.abs() > hh {
        let q = u * rho.min(rc) + DVec3::Y * p.y.clamp(-hh, hh);
        let diff = p - q;
        let d2 = diff.length_squared();
        if d2 >= r * r || !(d2 > 0.0) {
            return None;
        }
        return Some(Hit {
            point: q,
            normal: diff / d2.sqrt(),
        });
    }
    let side = rc - rho;
    let cap = hh - p.y.abs();
    if side <= cap {
        Some(Hit {
            point: u * rc + DVec3::Y * p.y,
            normal: u,
        })
    } else {
        let s = if p.y >= 0.0 { 1.0 } else { -1.0 };
        Some(Hit {
            point: DVec3::new(p.x, s * hh, p.z),
            normal: DVec3::Y * s,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cuboid_faces_edges_and_inside() {
        let he = DVec3::new(1.0, 2.0, 3.0);
        // Above the top face.
        let h = cuboid(he, DVec3::new(0.5, 2.1, 0.0), 0.2).unwrap();
        assert_eq!(h.normal, DVec3::Y);
        assert!((h.point - DVec3::new(0.5, 2.0, 0.0)).length() < 1e-15);
        // Too far.
        assert!(cuboid(he, DVec3::new(0.5, 2.3, 0.0), 0.2).is_none());
        // Off an edge: the normal points from the edge to the centre.
        let h = cuboid(he, DVec3::new(1.1, 2.1, 0.0), 0.2).unwrap();
        assert!((h.normal - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-12);
        // Inside, nearest to the +x face.
        let h = cuboid(he, DVec3::new(0.95, 0.0, 0.0), 0.2).unwrap();
        assert_eq!(h.normal, DVec3::X);
        assert!((h.point.x - 1.0).abs() < 1e-15);
    }

    #[test]
    fn cylinder_side_cap_rim_and_inside() {
        let (hh, rc) = (0.5, 1.0);
        let h = cylinder(hh, rc, DVec3::new(0.0, 0.0, 1.05), 0.1).unwrap();
        assert!((h.normal - DVec3::Z).length() < 1e-15);
        assert!((h.point - DVec3::new(0.0, 0.0, 1.0)).length() < 1e-15);
        let h = cylinder(hh, rc, DVec3::new(0.3, 0.55, 0.0), 0.1).unwrap();
        assert_eq!(h.normal, DVec3::Y);
        let h = cylinder(hh, rc, DVec3::new(1.05, 0.55, 0.0), 0.1).unwrap();
        assert!((h.normal - DVec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-12);
        // Inside near the side.
        let h = cylinder(hh, rc, DVec3::new(0.0, 0.0, -0.98), 0.1).unwrap();
        assert!((h.normal + DVec3::Z).length() < 1e-15);
        assert!(cylinder(hh, rc, DVec3::new(0.0, 0.0, 1.2), 0.1).is_none());
    }

    #[test]
    fn convex_hull_agrees_with_the_cuboid_closed_form() {
        let he = DVec3::new(0.1, 0.2, 0.3);
        let pts: Vec<FVec3> = [-1.0f32, 1.0]
            .iter()
            .flat_map(|&x| {
                [-1.0f32, 1.0].iter().flat_map(move |&y| {
                    [-1.0f32, 1.0]
                        .iter()
                        .map(move |&z| FVec3::new(0.1 * x, 0.2 * y, 0.3 * z))
                })
            })
            .collect();
        let hull = BoundaryShape::from_shape(&SharedShape::convex_hull(&pts).unwrap()).unwrap();
        for p in [
            DVec3::new(0.0, 0.205, 0.01),
            DVec3::new(0.104, 0.0, -0.1),
            DVec3::new(0.0, 0.0, 0.29),
            DVec3::new(0.103, 0.203, 0.0),
        ] {
            let a = hull.closest(p, 0.01).unwrap();
            let b = cuboid(he, p, 0.01).unwrap();
            assert!((a.point - b.point).length() < 1e-6, "{p:?}");
            assert!((a.normal - b.normal).length() < 1e-4, "{p:?}");
        }
    }
}
