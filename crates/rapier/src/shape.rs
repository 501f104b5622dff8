//! Which collider shapes the plugin models, and how: the one answer that the rigid hook, the
//! compliant regime and the Bevy plugin all read ([`supported_shape`]).
//!
//! | shape | rigid regime | compliant regime |
//! |---|---|---|
//! | ball | a sphere (Hertz's circular contact) | a sphere |
//! | cuboid, half-space | flat at the contact | a wall |
//! | triangle mesh, heightfield, convex polyhedron | flat at the contact | - |
//! | cylinder | a wheel on a flat collider: Carter's line contact, or Hertz's ellipse with a crown radius ([`crate::CreepMaterial::with_crown`]) | - |
//!
//! A rigid contact creeps when one side is a ball and the other any supported shape but a
//! wheel, or when one side is a wheel and the other flat. Other pairs (two flat colliders, a
//! wheel on a ball or on a wheel) and other shapes (capsules, cones, compounds, ...) keep
//! Rapier's Coulomb friction; they are counted in [`crate::StepCounts`].

use creep_law::Surface;
use rapier3d::parry::shape::TypedShape;
use rapier3d::prelude::Collider;

use crate::registry::Regime;

/// A flat collider of the rigid regime (flat at the contact: infinite radius, the face's
/// normal is Rapier's contact normal; a contact with a mesh's edge or vertex is taken as a face
/// contact).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FlatShape {
    /// `ColliderBuilder::cuboid` (also a compliant wall).
    Cuboid,
    /// `ColliderBuilder::halfspace` (also a compliant wall).
    HalfSpace,
    /// `ColliderBuilder::trimesh`.
    TriMesh,
    /// `ColliderBuilder::heightfield`.
    HeightField,
    /// `ColliderBuilder::convex_hull` / `convex_mesh` (a convex floor).
    ConvexPolyhedron,
}

/// How the plugin models a collider's shape ([`supported_shape`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportedShape {
    /// A ball of radius `radius` \[m\]: Hertz's circular contact (rigid and compliant regimes).
    Ball {
        /// Radius \[m\].
        radius: f64,
    },
    /// A flat collider (rigid regime; cuboids and half-spaces also compliant).
    Flat(FlatShape),
    /// A cylinder, a wheel in the rigid regime when it rolls on its round face on a flat
    /// collider (crate module `wheel`): Carter's line contact of length `width`, or, with a
    /// crown radius ([`crate::CreepMaterial::with_crown`]), Hertz's ellipse with the curvature
    /// sums `1/radius` and `1/crown`. Rapier's cylinder has its axis (the axle) along the
    /// collider's local `y`. Hold a wheel upright through its axle (module docs of the crate:
    /// "Wheels").
    Wheel {
        /// Rolling radius \[m\] (the cylinder's radius).
        radius: f64,
        /// Contact length along the axle \[m\] (twice the cylinder's half-height).
        width: f64,
    },
}

/// The shapes the plugin models, in words (for warnings and errors).
pub const SUPPORTED_SHAPES: &str = "balls; cuboids, half-spaces, triangle meshes, heightfields \
     and convex polyhedra (flat at the contact); cylinders rolling on a flat collider (wheels: \
     line contact, or crowned with CreepMaterial::with_crown). The compliant regime takes \
     balls, cuboids and half-spaces";

impl SupportedShape {
    /// The contact surface the rigid regime's Hertz contact uses for a ball or a flat collider
    /// (a sphere of the ball's radius, a plane); `None` for a wheel, whose contact is its own
    /// (line or ellipse, crate module `wheel`).
    pub fn rigid_surface(&self) -> Option<Surface> {
        match *self {
            Self::Ball { radius } => Some(Surface::Sphere(radius)),
            Self::Flat(_) => Some(Surface::Plane),
            Self::Wheel { .. } => None,
        }
    }

    /// The surface the rigid hook's rotation-gap correction (crate module `gap`) uses: a wheel
    /// turns about its axle like a sphere of its radius.
    pub(crate) fn gap_surface(&self) -> Surface {
        match *self {
            Self::Ball { radius } => crate::gap::ball_gap_surface(radius),
            Self::Wheel { radius, .. } => Surface::Sphere(radius),
            Self::Flat(_) => Surface::Plane,
        }
    }

    /// The surface of the compliant regime (balls; cuboids and half-spaces as walls), or `None`
    /// for a shape it does not model.
    pub fn compliant_surface(&self) -> Option<Surface> {
        match *self {
            Self::Ball { radius } => Some(Surface::Sphere(radius)),
            Self::Flat(FlatShape::Cuboid | FlatShape::HalfSpace) => Some(Surface::Plane),
            _ => None,
        }
    }

    /// Whether a collider of this shape can take part in contacts of `regime`: every shape
    /// in the rigid regime (at any fidelity), balls, cuboids and half-spaces in the compliant
    /// one.
    pub fn supports(&self, regime: Regime) -> bool {
        match regime {
            Regime::Compliant => self.compliant_surface().is_some(),
            Regime::Rigid(_) => true,
        }
    }

    /// Whether this is a wheel.
    pub fn is_wheel(&self) -> bool {
        matches!(self, Self::Wheel { .. })
    }

    /// Whether the rigid regime models a contact between shapes `self` and `other`: a ball
    /// against a ball or a flat collider, or a wheel on a flat collider. Two flat colliders
    /// (Hertz's contact needs a curved side), a wheel on a ball or a wheel are Coulomb.
    pub fn rigid_pair(&self, other: &SupportedShape) -> bool {
        use SupportedShape::*;
        matches!(
            (self, other),
            (Ball { .. }, Ball { .. } | Flat(_))
                | (Flat(_), Ball { .. } | Wheel { .. })
                | (Wheel { .. }, Flat(_))
        )
    }
}

/// How the plugin models `collider`'s shape, or `None` for a shape it does not model (its
/// contacts keep Rapier's Coulomb friction): the one list (module docs) read by the rigid hook,
/// the compliant regime and the Bevy plugin. One virtual call (the typed shape).
pub fn supported_shape(collider: &Collider) -> Option<SupportedShape> {
    Some(match collider.shape().as_typed_shape() {
        TypedShape::Ball(ball) => SupportedShape::Ball {
            radius: f64::from(ball.radius),
        },
        TypedShape::Cuboid(_) => SupportedShape::Flat(FlatShape::Cuboid),
        TypedShape::HalfSpace(_) => SupportedShape::Flat(FlatShape::HalfSpace),
        TypedShape::TriMesh(_) => SupportedShape::Flat(FlatShape::TriMesh),
        TypedShape::HeightField(_) => SupportedShape::Flat(FlatShape::HeightField),
        TypedShape::ConvexPolyhedron(_) => SupportedShape::Flat(FlatShape::ConvexPolyhedron),
        TypedShape::Cylinder(c) => SupportedShape::Wheel {
            radius: f64::from(c.radius),
            width: 2.0 * f64::from(c.half_height),
        },
        _ => return None,
    })
}

/// Whether [`supported_shape`] makes `collider` a [`SupportedShape::Wheel`] (a cylinder),
/// `false` without a collider: one virtual call (the shape's type), cheaper than the typed
/// shape, for the rigid hook's exit from a manifold without contacts.
#[inline]
pub(crate) fn wheel_collider(collider: Option<&Collider>) -> bool {
    collider
        .is_some_and(|co| co.shape().shape_type() == rapier3d::parry::shape::ShapeType::Cylinder)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::registry::Fidelity;
    use rapier3d::prelude::*;

    #[test]
    fn each_shape_is_classified_once() {
        let ball = supported_shape(&ColliderBuilder::ball(0.1).build()).unwrap();
        assert_eq!(
            ball,
            SupportedShape::Ball {
                radius: 0.1f32 as f64
            }
        );
        assert_eq!(ball.rigid_surface(), Some(Surface::Sphere(0.1f32 as f64)));
        assert!(ball.supports(Regime::Compliant));
        let cuboid = supported_shape(&ColliderBuilder::cuboid(1.0, 0.1, 1.0).build()).unwrap();
        assert_eq!(cuboid, SupportedShape::Flat(FlatShape::Cuboid));
        assert_eq!(cuboid.compliant_surface(), Some(Surface::Plane));
        let hs = supported_shape(
            &ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y)).build(),
        )
        .unwrap();
        assert_eq!(hs, SupportedShape::Flat(FlatShape::HalfSpace));
        let verts = vec![
            Vector::new(-1.0, 0.0, -1.0),
            Vector::new(1.0, 0.0, -1.0),
            Vector::new(0.0, 0.0, 1.0),
        ];
        let mesh = ColliderBuilder::trimesh(verts.clone(), vec![[0, 1, 2]])
            .unwrap()
            .build();
        let mesh = supported_shape(&mesh).unwrap();
        assert_eq!(mesh, SupportedShape::Flat(FlatShape::TriMesh));
        assert!(!mesh.supports(Regime::Compliant) && mesh.supports(Regime::Rigid(Fidelity::Creep)));
        let mut hull = verts;
        hull.push(Vector::new(0.0, -1.0, 0.0));
        let hull = supported_shape(&ColliderBuilder::convex_hull(&hull).unwrap().build()).unwrap();
        assert_eq!(hull, SupportedShape::Flat(FlatShape::ConvexPolyhedron));
        let wheel = supported_shape(&ColliderBuilder::cylinder(0.02, 0.3).build()).unwrap();
        assert_eq!(
            wheel,
            SupportedShape::Wheel {
                radius: 0.3f32 as f64,
                width: 2.0 * (0.02f32 as f64)
            }
        );
        assert_eq!(wheel.rigid_surface(), None);
        assert!(wheel.is_wheel() && !wheel.supports(Regime::Compliant));
        assert!(supported_shape(&ColliderBuilder::capsule_y(0.1, 0.1).build()).is_none());
        assert!(supported_shape(&ColliderBuilder::cone(0.1, 0.1).build()).is_none());
    }

    /// The hook's cheap wheel test agrees with the classification on every shape builder.
    #[test]
    fn wheel_collider_agrees_with_supported_shape() {
        let colliders = [
            ColliderBuilder::ball(0.1).build(),
            ColliderBuilder::cuboid(1.0, 0.1, 1.0).build(),
            ColliderBuilder::cylinder(0.02, 0.3).build(),
            ColliderBuilder::round_cylinder(0.02, 0.3, 0.01).build(),
            ColliderBuilder::capsule_y(0.1, 0.1).build(),
            ColliderBuilder::cone(0.1, 0.1).build(),
            ColliderBuilder::halfspace(rapier3d::na::Unit::new_unchecked(Vector::Y)).build(),
        ];
        for co in &colliders {
            assert_eq!(
                wheel_collider(Some(co)),
                supported_shape(co).is_some_and(|s| s.is_wheel()),
                "{:?}",
                co.shape().shape_type()
            );
        }
        assert!(!wheel_collider(None));
    }

    #[test]
    fn pairs_the_rigid_regime_models() {
        let ball = SupportedShape::Ball { radius: 0.1 };
        let flat = SupportedShape::Flat(FlatShape::TriMesh);
        let wheel = SupportedShape::Wheel {
            radius: 0.3,
            width: 0.05,
        };
        for (a, b, want) in [
            (ball, ball, true),
            (ball, flat, true),
            (flat, ball, true),
            (wheel, flat, true),
            (flat, wheel, true),
            (flat, flat, false),
            (wheel, ball, false),
            (ball, wheel, false),
            (wheel, wheel, false),
        ] {
            assert_eq!(a.rigid_pair(&b), want, "{a:?} {b:?}");
        }
    }
}
