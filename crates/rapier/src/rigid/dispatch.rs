//! Rapier's call into the rigid hooks: `modify_solver_contacts` sorts each manifold to its path
//! (compliant, quiet, ball, wheel, Coulomb) and applies the rotation-gap correction;
//! `modify_recycled_solver_contacts` (feature `rapier-patched`) refreshes a recycled ball
//! manifold's slip targets. Both read a manifold's pair through one preamble ([`PairView`]).
//!
//! # Cost
//! Rapier calls the full-update hook for every manifold of a hooked pair, also for those with
//! no solver contact (the bodies' shapes within the broad phase's margin but apart by more than
//! the prediction distance: about three in four of a poured pile's manifolds). Such a manifold
//! has nothing to rewrite, so the hook leaves it at once unless a cylinder is on it (a wheel:
//! the wheel path may add the patch contact, module `wheel`): a collider's bad friction and an
//! unregistered partner are reported from the pair's first solver contact on.

use std::sync::atomic::Ordering;
use std::sync::{Mutex, MutexGuard};

use creep_law::Surface;
use rapier3d::prelude::*;

#[cfg(feature = "rapier-patched")]
use super::ball::recycled_ball_manifold;
use super::ball::{BallManifold, ball_manifold};
use super::hooks::{CreepHooks, Shard, quiet_collider, shard_of};
use super::wheel::{WheelCtx, wheel_manifold};
use crate::convert::{body_motion, v3, vf};
use crate::gap::rotation_gap_correction;
use crate::shape::{FlatShape, SupportedShape, wheel_collider};
use creep_law::rigid::RigidPairCache;

use crate::registry::{CreepMaterial, Fidelity, Regime, RollingResistance};

/// A manifold's pair as both hooks read it once it is a rigid pair of two registered
/// colliders, not quiet and with something to rewrite ([`CreepHooks::pair_view`]).
struct PairView<'a> {
    /// The two colliders' materials.
    materials: (&'a CreepMaterial, &'a CreepMaterial),
    /// The pair's fidelity (`Regime::pair`).
    fidelity: Fidelity,
    /// The contact law's surfaces (`SupportedShape::rigid_surface`).
    laws: (Option<Surface>, Option<Surface>),
    /// The rotation-gap correction's surfaces (`SupportedShape::gap_surface`).
    gaps: (Option<Surface>, Option<Surface>),
    /// The bodies, looked up once per manifold.
    bodies: [Option<&'a RigidBody>; 2],
    /// Whether a side is a triangle mesh or a heightfield (its contacts with a ball may
    /// coincide: `crate::store::CoincidentLoad`).
    on_mesh: bool,
}

/// Why [`CreepHooks::pair_view`] leaves a manifold to its caller as it is.
enum Skip {
    /// Counted or nothing to do.
    Done,
    /// A compliant pair: the compliant regime applies its forces itself, so the solver gets
    /// no contact.
    Compliant,
}

impl PhysicsHooks for CreepHooks {
    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        let (c1, c2) = (context.collider1, context.collider2);
        let (h1, h2) = (context.rigid_body1, context.rigid_body2);
        let bodies = context.bodies;
        let colliders = context.colliders;
        let Some(rigid) = context.rigid_mut() else {
            return;
        };
        let n_contacts = rigid.solver_contacts.len();
        if !self.prepared {
            // Stepped without the step owner: leave the contact to Rapier, and say so at the
            // next step (PluginError::HookOutsideStep).
            self.outside.fetch_add(n_contacts.max(1), Ordering::Relaxed);
            return;
        }
        let (co1, co2) = (colliders.get(c1), colliders.get(c2));
        if n_contacts == 0 && !wheel_collider(co1) && !wheel_collider(co2) {
            // Nothing to rewrite and no wheel to give a patch contact (module docs): the
            // checks below would change nothing for this manifold.
            return;
        }
        let shard = &self.shards[shard_of(c1, c2)];
        // Both colliders' friction (a registered collider's is checked before the step, its
        // partner's only here): the step returns PluginError::Friction, and the pair is
        // solved without friction meanwhile so that no NaN reaches the bodies.
        for (handle, co) in [(c1, co1), (c2, co2)] {
            if let Some(co) = co
                && !(co.friction().is_finite() && co.friction() >= 0.0)
            {
                lock(shard).bad_friction = Some((handle, co.friction()));
                *rigid.friction = 0.0;
                return;
            }
        }
        let view = match self.pair_view(shard, (c1, c2), (h1, h2), (co1, co2), bodies, n_contacts) {
            Ok(view) => view,
            Err(Skip::Compliant) => {
                rigid.solver_contacts.clear();
                return;
            }
            Err(Skip::Done) => return,
        };
        // Only this pair's shard (never a global lock: crate docs of `SHARDS`).
        let mut shard = lock(shard);
        let Shard {
            store,
            counts,
            laws,
            crowns,
            pairs,
            ..
        } = &mut *shard;
        let PairView {
            materials: (m1, m2),
            fidelity,
            laws: (law1, law2),
            gaps: (gap1, gap2),
            bodies: rbs,
            on_mesh,
        } = view;
        let mu = f64::from(*rigid.friction);
        // The patched Rapier (feature `rapier-patched`) reads no rotation gap on a ball:
        // nothing to correct (crate::gap).
        let gap_substeps = (self.settings.anchor_drift_correction
            && !cfg!(feature = "rapier-patched"))
        .then_some(self.substeps);
        let ball = self.ball_of(
            (c1, c2),
            (h1, h2),
            (m1, m2),
            (law1, law2),
            mu,
            rbs,
            bodies,
            pairs,
            fidelity,
            gap_substeps,
            on_mesh,
        );
        if let Some(manifold) = ball {
            // (The rotation-gap correction below is done there, contact by contact, on the
            // same motions as the creep.)
            ball_manifold(&manifold, rigid, store, counts);
            return;
        }
        if self.settings.anchor_drift_correction {
            // Every registered pair, whatever its shapes and fidelity: Rapier's rotation gap
            // (see `rotation_gap`) is the engine's, not creep's.
            let n = v3(*rigid.normal);
            let dt = self.dt;
            let flat = Surface::Plane;
            for sc in rigid.solver_contacts.iter_mut() {
                let (a1, a2) = (v3(sc.anchor1), v3(sc.anchor2));
                let p_motion = body_motion(rbs[0], a1 - n, gap1.unwrap_or(flat));
                let q_motion = body_motion(rbs[1], a2 + n, gap2.unwrap_or(flat));
                let (c, b) =
                    rotation_gap_correction(&p_motion, a1, &q_motion, a2, n, dt, self.substeps);
                sc.dist -= c as f32;
                sc.tangent_velocity += vf(n * b);
            }
        }
        // A cylinder on a flat collider: a wheel (module `wheel`).
        let wheel_side = match (law1, law2) {
            (None, Some(Surface::Plane)) => Some(0),
            (Some(Surface::Plane), None) => Some(1),
            _ => None,
        };
        if let Some(side) = wheel_side {
            let ctx = WheelCtx {
                colliders: (c1, c2),
                handles: (h1, h2),
                materials: (m1, m2),
                bodies,
                colliders_set: colliders,
                dt: self.dt,
                prediction: self.prediction,
                gap_substeps: self
                    .settings
                    .anchor_drift_correction
                    .then_some(self.substeps),
                settings: &self.settings,
                fidelity,
                consts: pairs.get(&m1.material, &m2.material, mu, self.settings.creep_model),
            };
            if wheel_manifold(&ctx, rigid, side, store, counts, laws, crowns) {
                return;
            }
        }
        count_coulomb(counts, (law1, law2), n_contacts);
    }
    /// A recycled step's hook (feature `rapier-patched`; the colliders that opt in are set by
    /// [`CreepHooks::update_activation`]): a ball manifold gets this step's slip targets on
    /// the solver contacts kept from the pair's last full update (module `ball`), as on a full
    /// update; any other manifold keeps what the full update wrote (its rotation-gap correction
    /// is zero on the patched engine, and wheels do not opt in) and is counted as there.
    #[cfg(feature = "rapier-patched")]
    fn modify_recycled_solver_contacts(&self, context: &mut RecycledContactModificationContext) {
        let (c1, c2) = (context.collider1, context.collider2);
        let (h1, h2) = (context.rigid_body1, context.rigid_body2);
        let (bodies, colliders, manifold) = (context.bodies, context.colliders, context.manifold);
        let contacts = &mut context.solver_contacts;
        let n_contacts = contacts.len();
        if !self.prepared {
            self.outside.fetch_add(n_contacts.max(1), Ordering::Relaxed);
            return;
        }
        let shard = &self.shards[shard_of(c1, c2)];
        let co = (colliders.get(c1), colliders.get(c2));
        // (A compliant pair has no solver contacts, so it is never called here.)
        let Ok(view) = self.pair_view(shard, (c1, c2), (h1, h2), co, bodies, n_contacts) else {
            return;
        };
        let mut shard = lock(shard);
        let Shard {
            store,
            counts,
            pairs,
            ..
        } = &mut *shard;
        let ball = self.ball_of(
            (c1, c2),
            (h1, h2),
            view.materials,
            view.laws,
            f64::from(manifold.data.friction),
            view.bodies,
            bodies,
            pairs,
            view.fidelity,
            None,
            view.on_mesh,
        );
        if let Some(m) = ball {
            recycled_ball_manifold(&m, manifold, contacts, store, counts);
            return;
        }
        count_coulomb(counts, view.laws, n_contacts);
    }
}

/// Counts a manifold that keeps Rapier's Coulomb friction for want of a supported pair of
/// shapes.
fn count_coulomb(
    counts: &mut super::counts::StepCounts,
    laws: (Option<Surface>, Option<Surface>),
    n_contacts: usize,
) {
    let is_sphere = |s: Surface| matches!(s, Surface::Sphere(_));
    match laws {
        (Some(s1), Some(s2)) if !is_sphere(s1) && !is_sphere(s2) => {
            // Two flat sides (a box on a box or on a mesh): Hertz needs a curved one.
            counts.coulomb_no_sphere += n_contacts;
        }
        // No supported shape, or a ball pair the law refuses (a bad radius or friction).
        _ => counts.coulomb_unsupported += n_contacts,
    }
}

/// Locks a shard of the hooks' state (a poisoned lock is taken as it is, as everywhere in the
/// hooks).
fn lock(shard: &Mutex<Shard>) -> MutexGuard<'_, Shard> {
    shard.lock().unwrap_or_else(|e| e.into_inner())
}

impl CreepHooks {
    /// The preamble both hooks share (module docs), which locks the pair's shard only to count
    /// or report: the pair's materials (an unregistered
    /// collider's pair is counted and left to Coulomb, and reported once with
    /// [`crate::CreepSettings::warn_unregistered`]), its regime (a compliant pair is
    /// [`Skip::Compliant`]), a pair of quiet colliders (counted, left as Rapier built it), then
    /// the shapes and the bodies. (A manifold without solver contacts and without a wheel never
    /// gets here: `modify_solver_contacts` leaves it at once, and Rapier calls
    /// `modify_recycled_solver_contacts` only with solver contacts.)
    #[inline]
    fn pair_view<'a>(
        &'a self,
        shard: &Mutex<Shard>,
        (c1, c2): (ColliderHandle, ColliderHandle),
        (h1, h2): (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
        (co1, co2): (Option<&'a Collider>, Option<&'a Collider>),
        bodies: &'a RigidBodySet,
        n_contacts: usize,
    ) -> Result<PairView<'a>, Skip> {
        let (Some(m1), Some(m2)) = (self.registry.get(c1), self.registry.get(c2)) else {
            let mut shard = lock(shard);
            shard.counts.coulomb_unregistered += n_contacts;
            if self.settings.warn_unregistered {
                let (stranger, known) = if self.registry.get(c1).is_some() {
                    (c2, c1)
                } else {
                    (c1, c2)
                };
                if self.registry.get(known).is_some() && shard.unregistered_seen.insert(stranger) {
                    shard.unregistered.push((stranger, known));
                }
            }
            return Err(Skip::Done);
        };
        // A pair with a compliant collider is the compliant regime's (`Regime::pair`), which
        // applies its forces itself.
        let Regime::Rigid(fidelity) = m1.regime.pair(m2.regime) else {
            return Err(Skip::Compliant);
        };
        if quiet_collider(co1) && quiet_collider(co2) {
            // Both below the activation speed: plain Rapier contacts (as with the hook off),
            // rebuilt clean before Rapier starts recycling them.
            if n_contacts > 0 {
                lock(shard).counts.quiet += n_contacts;
            }
            return Err(Skip::Done);
        }
        // The shapes (one typed-shape call per collider): the contact law's surfaces and, for
        // Rapier's rotation gap, a wheel (cylinder) turning about its axle like a sphere of its
        // radius (module `crowns`).
        let shape1 = co1.and_then(crate::shape::supported_shape);
        let shape2 = co2.and_then(crate::shape::supported_shape);
        let mesh = |s: Option<SupportedShape>| {
            matches!(
                s,
                Some(SupportedShape::Flat(
                    FlatShape::TriMesh | FlatShape::HeightField
                ))
            )
        };
        Ok(PairView {
            materials: (m1, m2),
            fidelity,
            laws: (
                shape1.and_then(|s| s.rigid_surface()),
                shape2.and_then(|s| s.rigid_surface()),
            ),
            gaps: (
                shape1.map(|s| s.gap_surface()),
                shape2.map(|s| s.gap_surface()),
            ),
            bodies: [
                h1.and_then(|h| bodies.get(h)),
                h2.and_then(|h| bodies.get(h)),
            ],
            on_mesh: mesh(shape1) || mesh(shape2),
        })
    }

    /// The ball path's view of a manifold (module `ball`) when a ball is on either side of a
    /// supported shape and the law takes the pair, with the pair's constants computed once per
    /// pair of materials (`creep_law::rigid::RigidPairCache`); `None` otherwise.
    #[allow(clippy::too_many_arguments)]
    fn ball_of<'a>(
        &self,
        colliders: (ColliderHandle, ColliderHandle),
        handles: (Option<RigidBodyHandle>, Option<RigidBodyHandle>),
        (m1, m2): (&CreepMaterial, &CreepMaterial),
        laws: (Option<Surface>, Option<Surface>),
        mu: f64,
        bodies: [Option<&'a RigidBody>; 2],
        body_set: &'a RigidBodySet,
        pairs: &'a mut RigidPairCache,
        fidelity: Fidelity,
        gap_substeps: Option<usize>,
        on_mesh: bool,
    ) -> Option<BallManifold<'a>> {
        let is_sphere = |s: Surface| matches!(s, Surface::Sphere(_));
        let (s1, s2, consts, pair) = match laws {
            (Some(s1), Some(s2)) if is_sphere(s1) || is_sphere(s2) => pairs
                .get(&m1.material, &m2.material, mu, self.settings.creep_model)
                .and_then(|k| k.pair_for(s1, s2).map(|p| (s1, s2, k, p)))?,
            _ => return None,
        };
        let rolling = match (m1.rolling, m2.rolling) {
            (RollingResistance::Torque(m), _) | (_, RollingResistance::Torque(m)) => Some(m),
            _ => None,
        };
        Some(BallManifold {
            colliders,
            handles,
            bodies,
            body_set,
            surfaces: (s1, s2),
            pair,
            consts,
            fidelity,
            rolling,
            dt: self.dt,
            gap_substeps,
            auto_tolerance: (fidelity == Fidelity::Auto).then_some(self.settings.auto_tolerance),
            on_mesh,
        })
    }
}
