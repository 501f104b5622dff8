//! A pair's contact geometry from its Rapier colliders (ball-ball, wall-ball), in the kernel's form.

use creep_law::pair::ContactGeometry;
use creep_law::{Surface, Vec3};
use rapier3d::prelude::*;

use super::geometry::{self, Frame, Touch};
use crate::hooks::v3;

/// The compliant surface of a collider ([`crate::supported_shape`]: balls, cuboids and
/// half-spaces), or `None`.
pub(super) fn surface(co: &Collider) -> Option<Surface> {
    crate::shape::supported_shape(co).and_then(|s| s.compliant_surface())
}

/// Centre of a collider in f64 \[m\].
pub(super) fn centre(co: &Collider) -> Vec3 {
    Frame::of(co.position()).t
}

/// Geometry of a supported pair (ball-ball, wall-ball, ball-wall), normal from collider 1 to 2.
pub(super) fn touch_of(co1: &Collider, co2: &Collider) -> Option<Touch> {
    let wall = |co: &Collider, ball_centre: Vec3, r: f64| {
        let frame = Frame::of(co.position());
        if let Some(cub) = co.shape().as_cuboid() {
            geometry::cuboid_sphere(&frame, v3(cub.half_extents), ball_centre, r)
        } else if let Some(hs) = co.shape().as_halfspace() {
            geometry::halfspace_sphere(&frame, v3(hs.normal), ball_centre, r)
        } else {
            None
        }
    };
    match (co1.shape().as_ball(), co2.shape().as_ball()) {
        (Some(b1), Some(b2)) => geometry::sphere_sphere(
            centre(co1),
            f64::from(b1.radius),
            centre(co2),
            f64::from(b2.radius),
        ),
        (None, Some(b2)) => wall(co1, centre(co2), f64::from(b2.radius)),
        (Some(b1), None) => wall(co2, centre(co1), f64::from(b1.radius)).map(Touch::flipped),
        (None, None) => None,
    }
}

/// The kernel's geometry of a touch.
pub(super) fn touch_geometry(t: &Touch) -> ContactGeometry {
    ContactGeometry {
        normal: t.normal,
        point: t.point,
        overlap: t.overlap,
    }
}
