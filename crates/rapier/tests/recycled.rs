//! The hook on contacts Rapier recycles (feature `rapier-patched`: the engine keeps recycling
//! for hooked pairs that opt in, and the hook rewrites a recycled contact's slip target).

#![cfg(feature = "rapier-patched")]

use creep_law::Material;
use creep_rapier::diagnostics::ContactKey;
use creep_rapier::*;
use rapier3d::prelude::*;

/// Horizontal push on the ball \[N\]: rolling under a tangential load, so the contact creeps.
const PUSH: f32 = 0.5;
/// The ball's radius \[m\].
const R: f32 = 0.1;
/// Steel's density \[kg/m^3\] (`Material::steel`).
const RHO: f32 = 7850.0;

/// A 0.1 m steel ball rolling at `v` m/s along +x on a fixed steel block (both `Creep`), pushed
/// along +x by [`PUSH`]; `recycle_distance` is Rapier's normalized contact recycling distance
/// (0: never recycled).
fn pushed_ball(v: f32, recycle_distance: f32) -> (CreepWorld, RigidBodyHandle) {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    w.physics
        .integration_parameters
        .normalized_contact_recycle_distance = recycle_distance;
    let steel = CreepMaterial::new(Material::steel().with_friction(0.5).unwrap())
        .with_fidelity(Fidelity::Creep);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)),
        // A small ground: Rapier bounds a pair's drift by its rotation times the colliders'
        // extent, so a large one would keep the pair from being recycled.
        ColliderBuilder::cuboid(0.5, 0.5, 0.5).friction(0.5),
        Some(steel),
    );
    let (ball, _) = w.insert(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, R, 0.0))
            .linvel(Vector::new(v, 0.0, 0.0))
            .angvel(Vector::new(0.0, 0.0, -v / R))
            .can_sleep(false),
        ColliderBuilder::ball(R).friction(0.5),
        Some(steel),
    );
    w.physics.bodies[ball].add_force(Vector::new(PUSH, 0.0, 0.0), true);
    (w, ball)
}

/// The solver contacts of the world with the slip target of their records: `(tangent
/// velocity, the record's target rounded to f32)`.
fn targets(w: &CreepWorld) -> Vec<(Vector, Vector)> {
    let mut out = Vec::new();
    for pair in w.physics.narrow_phase.contact_pairs() {
        for man in pair.manifolds() {
            for sc in &man.data.solver_contacts {
                let cid = (sc.contact_id[0] & !NEW_CONTACT_BIT) as usize;
                let point = &man.points[cid];
                let key = ContactKey {
                    collider1: pair.collider1,
                    collider2: pair.collider2,
                    feature1: point.fid1.0,
                    feature2: point.fid2.0,
                };
                let rec = w.hooks().record(&key).expect("a live record per contact");
                let t = rec.target;
                out.push((
                    sc.tangent_velocity,
                    Vector::new(t.x as f32, t.y as f32, t.z as f32),
                ));
            }
        }
    }
    out
}

#[test]
fn recycled_contacts_carry_this_steps_target() {
    // 0.02-0.03 m/s: slow enough for the plugin to opt in (`|v| + |w| R` below 0.1 m/s); the
    // ball turns 0.3 degrees and moves 0.5 mm a step, so Rapier recycles the pair for several
    // steps between full updates (its drift bound: the ball's rotation times the block's
    // extent, 0.87 m, within 0.05 m).
    let (mut w, ball) = pushed_ball(0.02, 0.05);
    let (mut recycled_steps, mut rewritten) = (0, 0);
    let mut last = None;
    for step in 0..120 {
        if step == 60 {
            // Reverse the push: the slip target reverses, on recycled steps too.
            let rb = w.physics.bodies.get_mut(ball).unwrap();
            rb.reset_forces(true);
            rb.add_force(Vector::new(-PUSH, 0.0, 0.0), true);
        }
        let c = w.step().unwrap();
        if step == 0 {
            // A new contact carries no load yet: Coulomb.
            continue;
        }
        assert_eq!(c.creep, 1, "step {step}: {c:?}");
        let t = targets(&w);
        assert_eq!(t.len(), 1, "step {step}");
        let (tv, target) = t[0];
        // Every step, full update or recycled: the solver contact carries this step's target.
        assert_eq!(
            tv, target,
            "step {step} (recycled contacts: {})",
            c.recycled
        );
        assert!(target.length() > 0.0, "step {step}");
        if c.recycled > 0 {
            recycled_steps += 1;
            if last.is_some_and(|l: Vector| l != tv) {
                rewritten += 1;
            }
        }
        last = Some(tv);
    }
    // Recycled on most steps, and the target changed on recycled steps (a kept solver contact
    // would have carried its last full update's).
    println!("{recycled_steps} recycled steps of 120, target rewritten on {rewritten}");
    assert!(
        recycled_steps >= 80,
        "{recycled_steps} recycled steps of 120"
    );
    assert!(
        rewritten >= 80,
        "target rewritten on {rewritten} recycled steps"
    );
}

#[test]
fn recycling_keeps_the_rolling_closed_form() {
    // A ball pushed at its centre by F rolls with a = F / (m + I / R^2) = 5 F / (7 m), creep
    // or not (the creep force is the rolling constraint's). Over 1 s from 0.02 m/s, with the
    // pair recycled and with it fully updated every step.
    let m = RHO * 4.0 / 3.0 * std::f32::consts::PI * R * R * R;
    let expected = 0.02 + 5.0 * PUSH / (7.0 * m);
    let mut v = [0.0f32; 2];
    let mut recycled = [0usize; 2];
    for (i, distance) in [0.05, 0.0].into_iter().enumerate() {
        let (mut w, ball) = pushed_ball(0.02, distance);
        for _ in 0..60 {
            recycled[i] += w.step().unwrap().recycled;
        }
        v[i] = w.physics.bodies[ball].linvel().x;
    }
    println!("recycled contacts {recycled:?}, v {v:?} m/s, closed form {expected} m/s");
    assert!(recycled[0] > 40 && recycled[1] == 0, "{recycled:?}");
    for vi in v {
        assert!(
            (vi - expected).abs() < 1.0e-3 * expected,
            "v {vi} m/s, closed form {expected} m/s"
        );
    }
    assert!(
        (v[0] - v[1]).abs() < 5.0e-5,
        "recycled {} m/s, full updates {} m/s",
        v[0],
        v[1]
    );
}
