//! Criterion benchmarks of the fast 3-D steady law (`creep_law::steady3d`) against Kuhn's `F_ss`
//! (Kalker's closed form, `creep_law::kalker`), each timed over the same batch of 64 inputs per
//! iteration (so the reported time is per 64 evaluations).
//!
//! Run: `cargo bench -p creep-law --bench steady3d` (results: docs/CREEP3D.md).

use std::hint::black_box;

use creep_law::steady3d::Steady3d;
use creep_law::{SteadyLaw, kalker};
use criterion::{Criterion, criterion_group, criterion_main};

const BATCH: usize = 64;

fn inputs() -> Vec<[f64; 3]> {
    (0..BATCH)
        .map(|i| {
            let t = i as f64 * 0.37;
            [0.4 * t.sin(), 0.3 * (1.3 * t).cos(), 0.8 * (0.7 * t).sin()]
        })
        .collect()
}

fn bench_steady3d(c: &mut Criterion) {
    let nu = 0.25;
    let kuhn = SteadyLaw::Kuhn {
        c11: kalker::c11(nu),
    };
    let law = Steady3d::new(0.5, nu).unwrap();
    // Between the fitted nodes the spin force blends four nodes' shapes.
    let between = Steady3d::new(0.35, 0.125).unwrap();
    let x = inputs();
    let ratios: Vec<f64> = x.iter().map(|v| v[0].abs().min(0.99)).collect();
    let mut g = c.benchmark_group("steady3d");
    g.bench_function("fss_creepage_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for &s in black_box(&ratios) {
                acc += kuhn.creepage_n(s);
            }
            acc
        })
    });
    g.bench_function("fss_force_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for v in black_box(&x) {
                acc += kuhn.force_ratio(v[0]);
            }
            acc
        })
    });
    g.bench_function("steady3d_translation_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for v in black_box(&x) {
                let l = law.loads(v[0], v[1], 0.0);
                acc += l.fx + l.fy + l.mz;
            }
            acc
        })
    });
    g.bench_function("steady3d_with_spin_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for v in black_box(&x) {
                let l = law.loads(v[0], v[1], v[2]);
                acc += l.fx + l.fy + l.mz;
            }
            acc
        })
    });
    g.bench_function("steady3d_with_spin_between_nodes_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for v in black_box(&x) {
                let l = between.loads(v[0], v[1], v[2]);
                acc += l.fx + l.fy + l.mz;
            }
            acc
        })
    });
    g.bench_function("steady3d_inverse_x64", |b| {
        b.iter(|| {
            let mut acc = 0.0;
            for v in black_box(&x) {
                let (p, q) = law
                    .creepages_for_force(0.9 * v[0], 0.9 * v[1])
                    .unwrap_or((0.0, 0.0));
                acc += p + q;
            }
            acc
        })
    });
    g.finish();
}

criterion_group!(benches, bench_steady3d);
criterion_main!(benches);
