//! Wheels in the rigid regime: a cylinder collider rolling on its round face on a flat collider
//! (cuboid, half-space, mesh, heightfield, convex polyhedron) gets the creep law of its contact,
//! longitudinal and lateral (`creep_law::rigid::wheel_creep`); this module holds the wheels'
//! per-collider state (axle tracks, elliptic Hertz at unit load, a solver-contact template).
//!
//! # Geometry
//!
//! Rapier's cylinder has its axis along the collider's local `y`; the wheel's radius `R` is the
//! cylinder's, its width `L` twice the half-height. The rolling frame is the wheel's own: `x`
//! along the heading `n × e` (`e` the axle), oriented with the rolling, `y = n × x`; the rolling
//! speed is `V = |v_roll . x|` (Kuhn & Bagi's `v_roll` at the contact centre, the mean of the
//! manifold's solver contacts), so a wheel at slip angle `alpha` has `eta = tan(alpha)`.
//!
//! * **Crowned wheel** (a crown radius `R_c`: [`crate::CreepMaterial::with_crown`], or
//!   [`crate::CreepHooks::set_wheel_crown`] once registered): Hertz's elliptic contact with
//!   the curvature sums `1/R` and `1/R_c` and the 3-D law at its `a/b`, spin creep included.
//! * **Line contact** (no crown): Carter's two-dimensional solution; no spin creep. Not checked
//!   by a scene (creep-scenes' lateral scene runs a crowned wheel).
//!
//! The law of both is `creep_law::rigid::wheel_creep` (its module docs give the formulas and
//! their sources).
//!
//! # The patch contact
//!
//! Rapier's manifold of a cylinder on a flat collider has two to four points along the line of
//! contact, and its Coulomb solve limits each point's friction by `mu` times that point's own
//! normal impulse (rapier3d 0.36 `ContactWithCoulombFriction::solve`), the points solved one
//! after the other with their lever arms frozen at their own positions. Three collinear points
//! share the load in a statically indeterminate way: from 0.8 `mu P` one row saturated and the
//! Coulomb twin of a driven wheel slipped (creepage 9e-3 at 0.8 `mu P`, 4e-2 at 0.9), and a
//! wheel pushed sideways slid far beyond its creep target. The hook therefore solves an upright
//! wheel (`|axle . n| < 0.2`) as **one solver contact at the centre of its patch**
//! (module `wheel`, `patch_contact`: the point of the wheel's mid-plane rim nearest the floor,
//! with the manifold's separation fitted along the axle), for every fidelity (a Coulomb twin
//! has the same contact): its friction row acts where the law's patch is, with the limit
//! `mu P` of the whole wheel. The contact has no tilt stiffness (hold a wheel upright by its
//! axle: a joint, or locked tilt) and no Coulomb twisting friction.
//!
//! On a **cuboid or a half-space** the patch contact's normal and separation come from the two
//! shapes themselves, not from Rapier's manifold (module `wheel`, `ExactPatch`): the floor's
//! face under the wheel (the face whose slab the wheel's centre lies farthest outside of, its
//! line of contact on the face) and the distance of the wheel's mid-plane rim point from it.
//! Rapier's narrow phase computes a cylinder on a cuboid by GJK and EPA in f32 on the
//! Minkowski difference, whose support points are the cuboid's corners; on a 1000 m floor their
//! rounding exceeds the 5e-5 m a resting wheel overlaps by, and some steps came back with a
//! wrong normal and points 0.7-1.4 mm apart while the wheel overlapped: the wheel lost its
//! contact for one to five steps, then took an impact of 2-7 `m g dt` (a wheel sliding
//! sideways at `mu P` averaged 0.82-0.89 `mu P`; the robot's wheels lost contact too). When
//! Rapier's points are left without a solver contact the hook adds one by Rapier's own rule
//! (within the prediction distance now or after the step), named after the manifold point
//! with the largest impulse; a manifold without any point gets none. On other floors (meshes,
//! heightfields, convex polyhedra, a cuboid's edge) the patch takes Rapier's normal and fits
//! its separation along the axle from Rapier's points.
//!
//! **Spin**: a crowned wheel's patch has Kalker's spin creep as a ball's contact has
//! (`creep_law::rigid`): the lateral force of spin takes its share of `mu P` and the twisting moment
//! `Mz(xi_n, eta_n, phi_n)` of `Steady3d` is applied after the step (crate module `rolling`).
//! The relative spin is read from the wheel's axle turning between the hook calls of two steps
//! (`Crowns::axle_turn`), not from its angular velocity: a wheel on a joint takes the
//! post-step impulse alone and its joint shares it with the carrier only in the next solve. A
//! line-contact wheel (no elliptic law) and a tilted wheel (left on Rapier's points) have no
//! spin creep. Rapier's rotation gap (crate module `gap`) is corrected as for a sphere of the
//! wheel's radius; a fast wheel at long steps sinks and loses energy as in plain Rapier.

use creep_law::elliptic::elliptic_hertz;
use creep_law::rigid::WheelContact;
use rapier3d::prelude::*;

/// A wheel: a cylinder collider's radius, width and crown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Wheel {
    /// Rolling radius \[m\].
    pub radius: f64,
    /// Axle direction in the world (unit).
    pub axle: creep_law::Vec3,
    /// Its contact law's shape.
    pub contact: WheelContact,
}

/// A wheel's axle direction at the hook calls of two consecutive steps.
#[derive(Debug, Clone, Copy, PartialEq)]
struct AxleTrack {
    handle: ColliderHandle,
    /// The step (the contact store's generation) of `now`.
    step: u64,
    /// The axle at the hook call of the step before `step`, if the wheel was seen then.
    before: Option<creep_law::Vec3>,
    /// The axle at the hook call of `step`.
    now: creep_law::Vec3,
}

/// The wheels' per-collider state of the hook (by collider index, no hashing): axle tracks,
/// elliptic Hertz at unit load, a solver-contact template.
#[derive(Debug, Clone, Default)]
pub(crate) struct Crowns {
    /// The wheels' axles in the last two steps, by collider index (see [`Crowns::axle_turn`]).
    axles: Vec<Option<AxleTrack>>,
    /// Elliptic Hertz at unit load by `(kx, ky, E*)`: `(a1, b1)` (a short list).
    hertz: Vec<([f64; 3], (f64, f64))>,
    /// A copy of a solver contact Rapier built (see [`Crowns::solver_contact`]).
    template: Option<SolverContact>,
}

impl Crowns {
    /// The angle \[rad\] the wheel's axle turned about `n` over the last step (from the poses
    /// of the hook calls of steps `step - 1` and `step`), or `None` if the wheel was not seen in
    /// the step before. The poses follow the solver's velocities, which a wheel's joint keeps
    /// consistent with its axle's carrier; the angular velocity the hook sees also holds the
    /// spin-creep impulse the plugin applied to the wheel alone after the last step (crate
    /// module `rolling`), which a joint only shares out in the next solve.
    pub fn axle_turn(
        &mut self,
        collider: ColliderHandle,
        axle: creep_law::Vec3,
        n: creep_law::Vec3,
        step: u64,
    ) -> Option<f64> {
        let i = collider.into_raw_parts().0 as usize;
        if i >= self.axles.len() {
            self.axles.resize(i + 1, None);
        }
        let slot = &mut self.axles[i];
        let track = match *slot {
            Some(t) if t.handle == collider && t.step == step => t,
            Some(t) if t.handle == collider && t.step + 1 == step => AxleTrack {
                handle: collider,
                step,
                before: Some(t.now),
                now: axle,
            },
            _ => AxleTrack {
                handle: collider,
                step,
                before: None,
                now: axle,
            },
        };
        *slot = Some(track);
        let before = track.before?;
        Some(before.cross(track.now).dot(n).atan2(before.dot(track.now)))
    }

    /// Remembers a solver contact Rapier built for a wheel, the first time one is seen.
    pub fn keep_template(&mut self, sc: Option<&SolverContact>) {
        if self.template.is_none() {
            self.template = sc.copied();
        }
    }

    /// A solver contact with the given public fields, for a wheel manifold whose points Rapier
    /// left without one (module `wheel`'s exact patch contact), or `None` before any was
    /// seen. Rapier 0.36 has no public constructor of `SolverContact` (its one private field
    /// is SIMD padding, which the solver never reads), so the hook copies one Rapier built
    /// ([`Crowns::keep_template`]) and overwrites every public field.
    pub fn solver_contact(
        &self,
        contact_id: u32,
        anchor1: Vector,
        anchor2: Vector,
        dist: f32,
        tangent_velocity: Vector,
    ) -> Option<SolverContact> {
        let mut sc = self.template?;
        sc.contact_id = [contact_id];
        sc.anchor1 = anchor1;
        sc.anchor2 = anchor2;
        sc.dist = dist;
        sc.tangent_velocity = tangent_velocity;
        Some(sc)
    }

    /// The wheel of a cylinder collider (`None` for other shapes) of crown radius `crown`
    /// \[m\] (its material's; `None`: line contact), with the contact modulus `e_star` \[Pa\]
    /// of its pair for the elliptic contact.
    pub fn wheel(&mut self, co: &Collider, crown: Option<f64>, e_star: f64) -> Option<Wheel> {
        let cyl = co.shape().as_cylinder()?;
        let radius = f64::from(cyl.radius);
        let axle = crate::convert::v3(co.rotation() * Vector::Y);
        let contact = match crown {
            Some(rc) => {
                let key = [1.0 / radius, 1.0 / rc, e_star];
                let (a1, b1) = match self.hertz.iter().find(|(k, _)| *k == key) {
                    Some((_, v)) => *v,
                    None => {
                        let h = elliptic_hertz(key[0], key[1], 1.0, e_star).ok()?;
                        if self.hertz.len() >= 32 {
                            self.hertz.remove(0);
                        }
                        self.hertz.push((key, (h.a, h.b)));
                        (h.a, h.b)
                    }
                };
                WheelContact::Crowned { a1, b1 }
            }
            None => WheelContact::Line {
                width: 2.0 * f64::from(cyl.half_height),
            },
        };
        Some(Wheel {
            radius,
            axle,
            contact,
        })
    }
}
