//! One Rapier step of a settled pile, with and without the creep plugin, in the same run and
//! from the same settled state (docs/ARCHITECTURE.md §6: a collider with `MODIFY_SOLVER_CONTACTS` takes its
//! pairs out of Rapier's contact recycling). The piles are `creep_scenes::pile`'s, the ones
//! `creep report`'s scale section times.
//!
//! Group `pile_4096_step`: the dropped 16^3 pile (`pile::dropped`), variants, each a copy of one
//! settled world:
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
//! Group `pile_scale_step`: the scale study's stacked piles (`pile::SCALE_SIDES`: 1,005, 4,184,
//! 16,301 and 64,349 spheres), `plain` and `plugin_auto` each. `CREEP_PILE_SIZES=1005,4184`
//! limits the sizes built (the 64k pile takes about a minute to settle); `CREEP_PILE_SIZES=none`
//! skips the group.
//!
//! `cargo bench -p creep-scenes --bench pile -- --warm-up-time 2 --measurement-time 10`

use creep_rapier::{CreepSettings, Fidelity};
use creep_scenes::pile::{self, Pile};
use criterion::{Criterion, criterion_group, criterion_main};

fn bench_4096(c: &mut Criterion) {
    let p = pile::dropped(16).expect("dropped pile");
    eprintln!(
        "pile: settled {} steps in {:.1} s; max speed {:.2e} m/s; {} live contact records",
        p.settle_steps,
        p.settle_seconds,
        p.max_speed,
        p.world.hooks().live_contacts()
    );
    let w = &p.world;
    let settings = *w.hooks().settings();
    let copy = |f: Fidelity, s: CreepSettings| pile::with_fidelity(w, f, s).expect("copy");
    let mut plain = pile::plain(w);
    let mut flag_only = creep_rapier::clone_physics(&w.physics);
    let mut auto = copy(Fidelity::Auto, settings);
    let mut creep = copy(Fidelity::Creep, settings);
    let mut coulomb = copy(Fidelity::Coulomb, settings);
    let mut auto_on = copy(
        Fidelity::Auto,
        CreepSettings {
            activation_speed: 0.0,
            ..settings
        },
    );
    for p in [
        &mut flag_only,
        &mut auto.physics,
        &mut creep.physics,
        &mut coulomb.physics,
        &mut auto_on.physics,
    ] {
        pile::touch_all(p);
    }
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
    report_interleaved(
        "dropped 4096",
        &pile::interleaved(&mut plain, &mut auto, 300).unwrap(),
    );
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

fn report_interleaved(label: &str, t: &pile::Interleaved) {
    eprintln!(
        "{label}: interleaved, {} pairs: plain {:.3} ms, plugin_auto {:.3} ms (medians); ratio {:.3} (median of pair ratios), {:.3} (ratio of medians); {} active contact pairs; hooks on {}",
        t.pairs,
        t.plain * 1e3,
        t.plugin * 1e3,
        t.ratio,
        t.plugin / t.plain,
        t.contacts,
        t.hooks_on
    );
}

/// The sizes `CREEP_PILE_SIZES` asks for (all by default).
fn sizes() -> Vec<usize> {
    let all = pile::SCALE_SIDES;
    match std::env::var("CREEP_PILE_SIZES") {
        Ok(v) => all
            .into_iter()
            .filter(|&n| {
                let count = pile::stacked_count(n, pile::SCALE_LAYERS).to_string();
                v.split(',').any(|s| s.trim() == count)
            })
            .collect(),
        Err(_) => all.to_vec(),
    }
}

fn bench_scale(c: &mut Criterion) {
    for n in sizes() {
        let p: Pile =
            pile::stacked(n, pile::SCALE_LAYERS, pile::SCALE_SETTLE_STEPS).expect("stacked pile");
        eprintln!(
            "stacked pile of {}: settled {} steps in {:.1} s; max speed {:.2e} m/s",
            p.spheres, p.settle_steps, p.settle_seconds, p.max_speed
        );
        let (mut plain, mut auto) = pile::plain_and_auto(&p).expect("copies");
        report_interleaved(
            &format!("stacked {}", p.spheres),
            &pile::interleaved(&mut plain, &mut auto, 10).unwrap(),
        );
        let mut g = c.benchmark_group(format!("pile_scale_step/{}", p.spheres));
        g.sample_size(10);
        g.bench_function("plain", |b| b.iter(|| plain.step()));
        g.bench_function("plugin_auto", |b| b.iter(|| auto.step().unwrap()));
        g.finish();
    }
}

criterion_group!(benches, bench_4096, bench_scale);
criterion_main!(benches);
