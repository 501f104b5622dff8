//! One Rapier step of a settled 4,096-sphere pile, with and without the creep plugin, in the
//! same run and from the same settled state (DESIGN.md §4: a collider with
//! `MODIFY_SOLVER_CONTACTS` takes its pairs out of Rapier's contact recycling).
//!
//! Variants, each a copy of one settled world:
//! * `plain`: no hooks, no `MODIFY_SOLVER_CONTACTS` flag (plain `PhysicsWorld::step`, with the
//!   plugin's integration parameters: Coulomb friction, no clustering);
//! * `flag_only`: the same flags as the settled plugin world (`MODIFY_SOLVER_CONTACTS` where
//!   the activation left it on) but Rapier's no-op hooks `()`;
//! * `plugin_auto`: every collider registered, `Fidelity::Auto` (the default), with the default
//!   activation speed (bodies slower than 1e-2 m/s keep their hooks off and their recycling);
//! * `plugin_auto_always_on`: the same with `activation_speed = 0` (every hook on);
//! * `plugin_creep`: every collider registered, `Fidelity::Creep` (every contact on the creep
//!   path);
//! * `plugin_coulomb`: every collider registered, `Fidelity::Coulomb`: the hook is called and
//!   does its bookkeeping but leaves the friction alone; against `plain` this separates the
//!   lost recycling from the hook's own work.
//!
//! `cargo bench -p creep-rapier --bench pile -- --warm-up-time 2 --measurement-time 10`

use std::time::Instant;

use creep_law::Material;
use creep_rapier::{
    CreepHooks, CreepMaterial, CreepSettings, CreepWorld, Fidelity, MaterialRegistry, clone_physics,
};
use criterion::{Criterion, criterion_group, criterion_main};
use rapier3d::prelude::*;

const N: usize = 16; // 16^3 = 4,096 balls
const R: f32 = 0.05;

/// 4,096 glass balls (5 cm) dropped as a 16^3 lattice into a 1.8 m x 1.8 m box of fixed cuboid
/// walls, every collider registered, stepped at 1/60 s until settled. Sleeping is off, so the
/// settled pile keeps being simulated (a sleeping pile costs nothing, with or without hooks).
fn settled_pile() -> CreepWorld {
    let mut w = CreepWorld::new(1.0 / 60.0, CreepSettings::default()).unwrap();
    let mat = CreepMaterial::new(Material::glass());
    let half = 0.9f32;
    let wall = 0.1f32;
    w.insert(
        RigidBodyBuilder::fixed().translation(Vector::new(0.0, -wall, 0.0)),
        ColliderBuilder::cuboid(half + 2.0 * wall, wall, half + 2.0 * wall),
        Some(mat),
    );
    for (x, z, hx, hz) in [
        (half + wall, 0.0, wall, half),
        (-half - wall, 0.0, wall, half),
        (0.0, half + wall, half, wall),
        (0.0, -half - wall, half, wall),
    ] {
        w.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(x, 2.0, z)),
            ColliderBuilder::cuboid(hx, 2.0, hz),
            Some(mat),
        );
    }
    let spacing = 2.0 * R * 1.1;
    let offset = -(N as f32 - 1.0) * spacing / 2.0;
    for i in 0..N {
        for j in 0..N {
            for k in 0..N {
                // A small deterministic jitter so the lattice collapses into a pile.
                let jit = ((i * 7 + j * 13 + k * 29) % 11) as f32 * 1e-3;
                let p = Vector::new(
                    offset + i as f32 * spacing + jit,
                    R + 0.01 + j as f32 * spacing,
                    offset + k as f32 * spacing - jit,
                );
                w.insert(
                    RigidBodyBuilder::dynamic().translation(p).can_sleep(false),
                    ColliderBuilder::ball(R).density(2500.0),
                    Some(mat),
                );
            }
        }
    }
    let t0 = Instant::now();
    let steps = 400;
    for _ in 0..steps {
        w.step().unwrap();
    }
    let max_v = w
        .physics
        .bodies
        .iter()
        .map(|(_, b)| b.linvel().length())
        .fold(0.0f32, f32::max);
    eprintln!(
        "pile: settled {steps} steps in {:.1} s; max speed {max_v:.2e} m/s; {} live contact records",
        t0.elapsed().as_secs_f64(),
        w.hooks.live_contacts()
    );
    w
}

/// A copy of `w` whose colliders are all registered at `fidelity`.
fn with_fidelity(w: &CreepWorld, fidelity: Fidelity) -> CreepWorld {
    let mut reg = MaterialRegistry::new();
    for (h, _) in w.physics.colliders.iter() {
        if let Some(m) = w.hooks.registry().get(h) {
            reg.insert(h, m.with_fidelity(fidelity));
        }
    }
    CreepWorld::from_parts(
        clone_physics(&w.physics),
        CreepHooks::new(reg, *w.hooks.settings()).unwrap(),
    )
    .unwrap()
}

/// A copy of `w` without the plugin: no `MODIFY_SOLVER_CONTACTS` flags, stepped without hooks.
fn plain(w: &CreepWorld) -> PhysicsWorld {
    let mut p = clone_physics(&w.physics);
    let handles: Vec<ColliderHandle> = p.colliders.iter().map(|(h, _)| h).collect();
    for h in handles {
        p.colliders[h].set_active_hooks(ActiveHooks::empty());
    }
    p
}

/// Writes every collider's hook flags back through `ColliderSet::index_mut`, which marks the
/// collider modified: `plain` must do this to clear its flags, and a world whose every collider
/// was modified once steps measurably slower afterwards (measured: plain 47.9 ms against 31.3 ms
/// for the untouched `flag_only` copy), so every variant gets the same treatment.
fn touch_all(p: &mut PhysicsWorld) {
    let handles: Vec<ColliderHandle> = p.colliders.iter().map(|(h, _)| h).collect();
    for h in handles {
        let flags = p.colliders[h].active_hooks();
        p.colliders[h].set_active_hooks(flags);
    }
}

fn bench(c: &mut Criterion) {
    let w = settled_pile();
    let mut plain = plain(&w);
    let mut flag_only = clone_physics(&w.physics);
    let mut auto = with_fidelity(&w, Fidelity::Auto);
    let mut creep = with_fidelity(&w, Fidelity::Creep);
    let mut coulomb = with_fidelity(&w, Fidelity::Coulomb);
    let mut auto_on = with_fidelity(&w, Fidelity::Auto);
    for p in [
        &mut flag_only,
        &mut auto.physics,
        &mut creep.physics,
        &mut coulomb.physics,
        &mut auto_on.physics,
    ] {
        touch_all(p);
    }
    let settings = CreepSettings {
        activation_speed: 0.0,
        ..*w.hooks.settings()
    };
    auto_on.hooks = CreepHooks::new(auto_on.hooks.registry().clone(), settings).unwrap();
    // A few steps so that every copy has rebuilt its workspace (and `plain` its recycling).
    for _ in 0..5 {
        plain.step();
        flag_only.step();
        auto.step().unwrap();
        creep.step().unwrap();
        coulomb.step().unwrap();
        auto_on.step().unwrap();
    }
    let counts = auto.step().unwrap();
    eprintln!("plugin_auto counts: {counts:?}");
    let counts = creep.step().unwrap();
    eprintln!("plugin_creep counts: {counts:?}");
    interleaved(&mut plain, &mut auto);
    let mut g = c.benchmark_group("pile_4096_step");
    g.sample_size(15);
    g.bench_function("plain", |b| b.iter(|| plain.step()));
    g.bench_function("flag_only", |b| b.iter(|| flag_only.step()));
    g.bench_function("plugin_auto", |b| b.iter(|| auto.step().unwrap()));
    g.bench_function("plugin_creep", |b| b.iter(|| creep.step().unwrap()));
    g.bench_function("plugin_coulomb", |b| b.iter(|| coulomb.step().unwrap()));
    g.bench_function("plugin_auto_always_on", |b| {
        b.iter(|| auto_on.step().unwrap())
    });
    g.finish();
}

/// The overhead ratio measured side by side: `plain` and `plugin_auto` stepped alternately,
/// 2 x 150 steps, so that the machine's load drifts hit both alike; prints the medians and
/// the median of the per-pair ratios.
fn interleaved(plain: &mut PhysicsWorld, auto: &mut CreepWorld) {
    let (mut tp, mut ta, mut ratio) = (vec![], vec![], vec![]);
    for i in 0..300 {
        let time = |f: &mut dyn FnMut()| {
            let t0 = Instant::now();
            f();
            t0.elapsed().as_secs_f64()
        };
        // Alternate which goes first.
        let (p, a) = if i % 2 == 0 {
            let p = time(&mut || plain.step());
            (
                p,
                time(&mut || {
                    auto.step().unwrap();
                }),
            )
        } else {
            let a = time(&mut || {
                auto.step().unwrap();
            });
            (time(&mut || plain.step()), a)
        };
        tp.push(p);
        ta.push(a);
        ratio.push(a / p);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    let (mp, ma, mr) = (median(&mut tp), median(&mut ta), median(&mut ratio));
    eprintln!(
        "interleaved, 300 pairs: plain {:.2} ms, plugin_auto {:.2} ms (medians); overhead ratio {:.3} (median of pair ratios), {:.3} (ratio of medians)",
        mp * 1e3,
        ma * 1e3,
        mr,
        ma / mp
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
