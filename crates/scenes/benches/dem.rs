//! One step of the triaxial test's dense 4,096-sphere packing (compacted to 100 kPa, at rest):
//! compliant regime with Coulomb-Mindlin and with creep-friction, and plain Rapier with its own
//! rigid contacts for scale (`creep bench dem` prints particle-steps per second of the same).
//!
//! `cargo bench -p creep-scenes --bench dem` (the compaction before it takes about a minute).

use creep_scenes::triaxial::{Specimen, TriaxialParams, compact};
use criterion::{Criterion, criterion_group, criterion_main};

fn bench(c: &mut Criterion) {
    let mut s = Specimen::generate(TriaxialParams::default()).expect("default parameters");
    let summary = compact(&mut s, 2_000_000, &mut |_| {}).expect("compaction");
    eprintln!("compacted: {summary:?}");
    let mut coulomb = s.at_rest(false).expect("copy");
    let mut creep = s.at_rest(true).expect("copy");
    let mut plain = s.plain_rapier();
    let mut g = c.benchmark_group("dem_4096_step");
    g.sample_size(20);
    g.bench_function("compliant_coulomb_mindlin", |b| {
        b.iter(|| coulomb.step_at_rest().expect("step"))
    });
    g.bench_function("compliant_creep", |b| {
        b.iter(|| creep.step_at_rest().expect("step"))
    });
    g.bench_function("plain_rapier", |b| b.iter(|| plain.step()));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
