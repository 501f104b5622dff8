//! Feature `parallel`: Rapier calls the rigid hook from several threads at once. The hooks'
//! state is sharded by collider pair (no global lock) and the contacts' moments are applied in
//! key order, so a pile steps to the same bits on one thread and on several.
//!
//! Run with `cargo test -p creep-rapier --features parallel --test parallel`.
#![cfg(feature = "parallel")]

use creep_law::Material;
use creep_rapier::*;
use rapier3d::prelude::*;

/// A `side^3` lattice of 5 cm glass balls with spin dropped into a box (creep on every contact,
/// so that every ball contact takes the 3-D path with spin and the moments are applied).
fn pile(side: usize) -> CreepWorld {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let glass = CreepMaterial::new(Material::glass()).with_fidelity(Fidelity::Creep);
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.1, 0.0)),
        ColliderBuilder::cuboid(1.0, 0.1, 1.0),
        Some(glass),
    );
    for (x, z, hx, hz) in [
        (0.5, 0.0, 0.1, 0.5),
        (-0.5, 0.0, 0.1, 0.5),
        (0.0, 0.5, 0.5, 0.1),
        (0.0, -0.5, 0.5, 0.1),
    ] {
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(x, 1.0, z)),
            ColliderBuilder::cuboid(hx, 1.0, hz),
            Some(glass),
        );
    }
    let spacing = 0.11;
    let offset = -(side as f32 - 1.0) * spacing / 2.0;
    for i in 0..side {
        for j in 0..side {
            for k in 0..side {
                let jit = ((i * 7 + j * 13 + k * 29) % 11) as f32 * 1e-3;
                w.insert(
                    RigidBodyBuilder::dynamic()
                        .translation(Vector::new(
                            offset + i as f32 * spacing + jit,
                            0.06 + j as f32 * spacing,
                            offset + k as f32 * spacing - jit,
                        ))
                        .angvel(Vector::new(0.0, 3.0 * (i as f32 - 1.0), 1.0))
                        .can_sleep(false),
                    ColliderBuilder::ball(0.05).density(2500.0),
                    Some(glass),
                );
            }
        }
    }
    w
}

/// Every body's pose and velocities, as bits, and the integer counts of each step.
fn run(threads: usize, steps: usize) -> (Vec<[u32; 13]>, Vec<[usize; 6]>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut w = pile(4);
        let mut counts = Vec::new();
        for _ in 0..steps {
            let c = w.step().unwrap();
            counts.push([
                c.creep,
                c.coulomb_auto,
                c.coulomb_no_sphere,
                c.coulomb_unsupported,
                c.quiet,
                c.hooks_on,
            ]);
        }
        let states = w
            .physics
            .bodies
            .iter()
            .map(|(_, b)| {
                let (p, q, v, a) = (b.translation(), b.rotation(), b.linvel(), b.angvel());
                [
                    p.x, p.y, p.z, q.x, q.y, q.z, q.w, v.x, v.y, v.z, a.x, a.y, a.z,
                ]
                .map(f32::to_bits)
            })
            .collect();
        (states, counts)
    })
}

#[test]
fn one_thread_and_several_give_the_same_bits() {
    let steps = 90;
    let (one, counts_one) = run(1, steps);
    // The scene does creep (3-D path, with spin) on many contacts.
    assert!(counts_one.iter().map(|c| c[0]).sum::<usize>() > 1000);
    for threads in [2, 4] {
        let (many, counts_many) = run(threads, steps);
        assert_eq!(counts_one, counts_many, "{threads} threads: counts");
        assert!(one == many, "{threads} threads: the bodies' states differ");
    }
}
