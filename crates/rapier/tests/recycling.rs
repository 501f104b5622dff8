//! The hook and Rapier's contact recycling: a pair whose hooks go off keeps clean solver
//! contacts, and the per-manifold records follow the manifolds.

use creep_law::Material;
use creep_rapier::*;
use rapier3d::prelude::*;

/// Horizontal push on the ball \[N\]: rolling with a tangential load (the friction force is
/// (2/7) of it, far below mu m g), so the contact creeps. In free rolling there is no load and
/// no creep target.
const PUSH: f32 = 50.0;

/// A 0.1 m steel ball rolling at `v` m/s along +x on a steel ground (both `Auto`), pushed
/// along +x by [`PUSH`].
fn rolling_ball(v: f32) -> (CreepWorld, RigidBodyHandle, ColliderHandle) {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel().with_friction(0.5).unwrap());
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(1000.0, 0.5, 10.0).friction(0.5),
        Some(steel),
    );
    let (ball, co) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.1, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -v / 0.1))
            .can_sleep(false),
        ColliderBuilder::ball(0.1).friction(0.5),
        Some(steel),
    );
    w.physics.bodies[ball].add_force(Vector::new(PUSH, 0.0, 0.0), true);
    (w, ball, co)
}

/// The largest `|tangent_velocity|` over the solver contacts of the world.
fn max_target(w: &CreepWorld) -> f32 {
    let mut m = 0.0f32;
    for pair in w.physics.narrow_phase.contact_pairs() {
        for man in pair.manifolds() {
            for sc in &man.data.solver_contacts {
                m = m.max(sc.tangent_velocity.length());
            }
        }
    }
    m
}

#[test]
fn a_pair_whose_hooks_go_off_keeps_no_stale_target() {
    let (mut w, ball, co) = rolling_ball(1.0);
    for _ in 0..20 {
        w.step().unwrap();
    }
    // Rolling under a load: the hook writes the creep target.
    assert!(max_target(&w) > 0.0, "{}", max_target(&w));
    assert!(w.hooks().live_contacts() > 0);
    // The ball stops (and is no longer pushed): below the activation speed, both sides quiet.
    let rb = w.physics.bodies.get_mut(ball).unwrap();
    rb.reset_forces(true);
    rb.set_linvel(Vector::ZERO, true);
    rb.set_angvel(Vector::ZERO, true);
    let c = w.step().unwrap();
    // The clearing step: hooks still on, contacts left as Rapier built them.
    assert!(c.quiet > 0, "{c:?}");
    assert_eq!(c.creep, 0, "{c:?}");
    assert!(
        w.physics.colliders[co]
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    );
    assert_eq!(max_target(&w), 0.0);
    for _ in 0..5 {
        let c = w.step().unwrap();
        assert_eq!(c.hooks_on, 0, "{c:?}");
        // Hooks off: Rapier recycles (or rebuilds) the pair's solver contacts; none carries
        // the last creep target or gap correction.
        assert_eq!(max_target(&w), 0.0);
        assert!(
            !w.physics.colliders[co]
                .active_hooks()
                .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
        );
    }
    assert_eq!(w.hooks().live_contacts(), 0);
    // Set rolling (and pushed) again: the hook comes back on and writes targets again.
    let rb = w.physics.bodies.get_mut(ball).unwrap();
    rb.add_force(Vector::new(PUSH, 0.0, 0.0), true);
    rb.set_linvel(Vector::new(1.0, 0.0, 0.0), true);
    rb.set_angvel(Vector::new(0.0, 0.0, -10.0), true);
    for _ in 0..3 {
        w.step().unwrap();
    }
    assert!(max_target(&w) > 0.0);
    assert!(w.hooks().live_contacts() > 0);
}

#[test]
fn records_follow_their_manifolds_across_steps() {
    // A creeping contact keeps its record (the normal of the last step is written, its last
    // target carried) from step to step, through the manifold's slot.
    let (mut w, _, co) = rolling_ball(2.0);
    let mut last = None;
    for step in 0..30 {
        w.step().unwrap();
        let recs = w.hooks().records();
        assert_eq!(recs.len(), 1, "step {step}");
        let (k, r) = recs[0];
        assert!(k.collider1 == co || k.collider2 == co);
        assert!(r.normal.length() > 0.99);
        if let Some(k0) = last {
            assert_eq!(k, k0, "the contact's identity is stable");
        }
        assert_eq!(w.hooks().record(&k), Some(r));
        last = Some(k);
    }
}
