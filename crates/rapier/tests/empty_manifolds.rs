//! Which colliders skip the hook on manifolds without solver contacts (feature
//! `rapier-patched`: `ActiveHooks::SKIP_EMPTY_SOLVER_CONTACTS`): a moving ball does, a wheel
//! (whose pairs with a flat collider may get a patch contact there) and a flat collider do
//! not, and the flag goes off with the hook.

#![cfg(feature = "rapier-patched")]

use creep_law::Material;
use creep_rapier::*;
use rapier3d::prelude::*;

const SKIP: ActiveHooks = ActiveHooks::SKIP_EMPTY_SOLVER_CONTACTS;
const MODIFY: ActiveHooks = ActiveHooks::MODIFY_SOLVER_CONTACTS;

#[test]
fn only_moving_balls_skip_empty_manifolds() {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let steel = CreepMaterial::new(Material::steel());
    let (_, ground) = w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        ColliderBuilder::cuboid(5.0, 0.5, 5.0),
        Some(steel),
    );
    let (_, ball) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.1, 0.0))
            .linvel(Vector::new(1.0, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -10.0)),
        ColliderBuilder::ball(0.1),
        Some(steel),
    );
    let (_, wheel) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(2.0, 0.3, 0.0))
            .rotation(Vector::new(std::f32::consts::FRAC_PI_2, 0.0, 0.0))
            .linvel(Vector::new(1.0, 0.0, 0.0)),
        ColliderBuilder::cylinder(0.05, 0.3),
        Some(steel),
    );
    let (resting, resting_co) = w.insert(
        RigidBodyBuilder::dynamic().translation(Vector::new(-2.0, 0.1, 0.0)),
        ColliderBuilder::ball(0.1),
        Some(steel),
    );
    w.step().unwrap();
    let flags = |w: &CreepWorld, c: ColliderHandle| w.physics.colliders[c].active_hooks();
    assert!(
        flags(&w, ball).contains(MODIFY | SKIP),
        "{:?}",
        flags(&w, ball)
    );
    assert!(flags(&w, wheel).contains(MODIFY), "{:?}", flags(&w, wheel));
    assert!(!flags(&w, wheel).contains(SKIP), "{:?}", flags(&w, wheel));
    assert!(
        !flags(&w, ground).intersects(MODIFY | SKIP),
        "{:?}",
        flags(&w, ground)
    );
    assert!(
        !flags(&w, resting_co).intersects(SKIP),
        "{:?}",
        flags(&w, resting_co)
    );

    // Stopped, the ball's hook goes off (after its clearing step) and the flag with it.
    w.physics.bodies[resting].set_linvel(Vector::ZERO, true);
    let b = w.physics.colliders[ball].parent().unwrap();
    w.physics.bodies[b].set_linvel(Vector::ZERO, true);
    w.physics.bodies[b].set_angvel(Vector::ZERO, true);
    w.physics.bodies[b].set_gravity_scale(0.0, true);
    for _ in 0..2 {
        w.step().unwrap();
    }
    assert!(
        !flags(&w, ball).intersects(MODIFY | SKIP),
        "{:?}",
        flags(&w, ball)
    );
}
