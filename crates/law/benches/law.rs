//! Criterion benchmarks of the per-contact hot path: one creep-friction update (Kuhn's rule on the
//! Cattaneo-Mindlin memory) and one Kuhn & Bagi kinematics evaluation.
//!
//! Run: `cargo bench -p creep-law --bench law`

use std::hint::black_box;

use creep_law::kinematics::{BodyMotion, contact_rates};
use creep_law::{
    CreepInput, CreepLaw, CreepModel, CreepState, Material, MindlinState, PairMaterial, SteadyLaw,
    Surface, Vec2, Vec3, hertz, kalker,
};
use criterion::{Criterion, criterion_group, criterion_main};

/// Glass beads of 1 mm radius at 1 N: a DEM-sized contact.
fn pair() -> PairMaterial {
    let m = Material::glass();
    PairMaterial::new(&m, &m, Surface::Sphere(1e-3), Surface::Sphere(1e-3)).unwrap()
}

fn bench_updates(c: &mut Criterion) {
    let pair = pair();
    let p = 1.0;
    let a = hertz::contact_radius(&pair, p);
    let ds = 3.0 * pair.mu * p / (16.0 * pair.g_star * a);
    let xi = kalker::steady_creepage(0.6, pair.mu * p, pair.g, a, pair.c11);
    let dr = a * 1e-3;
    let law = CreepLaw::kuhn(pair);

    // Steady rolling at 0.6 mu P is stationary, so updating one state repeatedly measures the
    // real per-step cost (no state copy inside the timed loop).
    let mut rolling = CreepState::new();
    rolling.update(&law, CreepInput::new(p, Vec2::ZERO, Vec2::ZERO));
    for _ in 0..20_000 {
        rolling.update(
            &law,
            CreepInput::new(p, Vec2::new(xi * dr, 0.0), Vec2::new(dr, 0.0)),
        );
    }
    c.bench_function("creep_update/steady_rolling", |b| {
        b.iter(|| {
            rolling.update(
                black_box(&law),
                CreepInput::new(
                    black_box(p),
                    black_box(Vec2::new(xi * dr, 0.0)),
                    black_box(Vec2::new(dr, 0.0)),
                ),
            )
        })
    });
    // The same, with the contact radius given (DEM: a = sqrt(R* delta), no cube root).
    c.bench_function("creep_update/steady_rolling_radius_given", |b| {
        b.iter(|| {
            rolling.update(
                black_box(&law),
                CreepInput::new(
                    black_box(p),
                    black_box(Vec2::new(xi * dr, 0.0)),
                    black_box(Vec2::new(dr, 0.0)),
                )
                .with_radius(black_box(a)),
            )
        })
    });
    // Micro-oscillation in the stick range without rolling (a settled packing).
    let mut stuck = CreepState::new();
    stuck.update(&law, CreepInput::new(p, Vec2::ZERO, Vec2::ZERO));
    stuck.update(
        &law,
        CreepInput::new(p, Vec2::new(0.2 * ds, 0.0), Vec2::ZERO),
    );
    c.bench_function("creep_update/stick_oscillating", |b| {
        let mut sign = 1.0;
        b.iter(|| {
            sign = -sign;
            stuck.update(
                black_box(&law),
                CreepInput::new(
                    black_box(p),
                    black_box(Vec2::new(sign * 1e-6 * ds, 0.0)),
                    Vec2::ZERO,
                ),
            )
        })
    });
    // A deep load memory (nested cycles) and a turning path with varying P: the slow case. The
    // state is copied in per iteration (criterion's batched mode), which is included.
    let mut deep = CreepState::new();
    deep.update(&law, CreepInput::new(p, Vec2::ZERO, Vec2::ZERO));
    let mut d = 0.0;
    for k in 0..12 {
        let t = if k % 2 == 0 { 0.9 } else { -0.9 } * ds * 0.7f64.powi(k);
        deep.update(&law, CreepInput::new(p, Vec2::new(t - d, 0.0), Vec2::ZERO));
        d = t;
    }
    c.bench_function("creep_update/deep_memory_turning_incl_copy", |b| {
        b.iter_batched_ref(
            || deep,
            |st| {
                st.update(
                    black_box(&law),
                    CreepInput::new(
                        black_box(p * 1.001),
                        black_box(Vec2::new(1e-3 * ds, 2e-3 * ds)),
                        black_box(Vec2::new(dr, dr)),
                    ),
                )
            },
            criterion::BatchSize::SmallInput,
        )
    });
    let mut plain = MindlinState::new();
    plain.update(&pair, p, Vec2::ZERO);
    plain.update(&pair, p, Vec2::new(0.3 * ds, 0.0));
    c.bench_function("mindlin_update/stick_oscillating", |b| {
        let mut sign = 1.0;
        b.iter(|| {
            sign = -sign;
            plain.update(
                black_box(&pair),
                black_box(p),
                black_box(Vec2::new(sign * 1e-6 * ds, 0.0)),
            )
        })
    });
    c.bench_function("kalker/steady_creepage", |b| {
        b.iter(|| kalker::steady_creepage(black_box(0.6), black_box(0.5), pair.g, a, pair.c11))
    });
    c.bench_function("hertz/contact_radius", |b| {
        b.iter(|| hertz::contact_radius(&pair, black_box(p)))
    });
}

fn bench_kinematics(c: &mut Criterion) {
    let r = 1e-3;
    let p = BodyMotion {
        position: Vec3::ZERO,
        velocity: Vec3::new(0.1, 0.2, -0.1),
        angular_velocity: Vec3::new(3.0, -1.0, 2.0),
        surface: Surface::Sphere(r),
    };
    let q = BodyMotion {
        position: Vec3::new(2.0 * r, 0.0, 0.0),
        velocity: Vec3::new(-0.1, 0.0, 0.3),
        angular_velocity: Vec3::new(-1.0, 4.0, 0.5),
        surface: Surface::Sphere(r),
    };
    c.bench_function("kinematics/contact_rates", |b| {
        b.iter(|| {
            contact_rates(
                black_box(&p),
                black_box(&q),
                black_box(Vec3::new(r, 0.0, 0.0)),
                black_box(Vec3::X),
            )
        })
    });
}

/// The steady laws side by side (run: `cargo bench -p creep-law --bench law -- steady_law`):
/// Kalker's F_ss and the fitted law, from `nu` each call and with the coefficients precomputed,
/// forward and inverse; and the creep update of each tier in steady rolling.
fn bench_steady_laws(c: &mut Criterion) {
    let pair = pair();
    let nu = pair.nu;
    // A spread of force ratios, so that no branch predictor or constant folding helps.
    let ss: Vec<f64> = (0..64).map(|i| (i as f64 + 0.5) / 64.0).collect();
    let mut i = 0usize;
    let mut next = move || {
        i = (i + 1) & 63;
        i
    };
    c.bench_function("steady_law/kuhn_fss_nu", |b| {
        b.iter(|| kalker::steady_creepage_n(black_box(ss[next()]), black_box(nu)))
    });
    c.bench_function("steady_law/fitted_nu", |b| {
        b.iter(|| {
            SteadyLaw::new(CreepModel::Fitted, black_box(nu)).creepage_n(black_box(ss[next()]))
        })
    });
    let kuhn = SteadyLaw::new(CreepModel::Kuhn, nu);
    let fitted = SteadyLaw::new(CreepModel::Fitted, nu);
    c.bench_function("steady_law/kuhn_fss_c11_given", |b| {
        b.iter(|| black_box(&kuhn).creepage_n(black_box(ss[next()])))
    });
    c.bench_function("steady_law/fitted_precomputed", |b| {
        b.iter(|| black_box(&fitted).creepage_n(black_box(ss[next()])))
    });
    let xk: Vec<f64> = ss.iter().map(|&s| kuhn.creepage_n(s)).collect();
    let xf: Vec<f64> = ss.iter().map(|&s| fitted.creepage_n(s)).collect();
    c.bench_function("steady_law/kuhn_inverse", |b| {
        b.iter(|| black_box(&kuhn).force_ratio(black_box(xk[next()])))
    });
    c.bench_function("steady_law/fitted_inverse", |b| {
        b.iter(|| black_box(&fitted).force_ratio(black_box(xf[next()])))
    });
    let p = 1.0;
    let a = hertz::contact_radius(&pair, p);
    let dr = a * 1e-3;
    for model in CreepModel::ALL {
        let law = CreepLaw::new(pair, model);
        let xi = law
            .steady()
            .creepage_for_force(0.6 * pair.mu * p, pair.mu * p, pair.g, a);
        let mut st = CreepState::new();
        st.update(&law, CreepInput::new(p, Vec2::ZERO, Vec2::ZERO));
        for _ in 0..20_000 {
            st.update(
                &law,
                CreepInput::new(p, Vec2::new(xi * dr, 0.0), Vec2::new(dr, 0.0)),
            );
        }
        c.bench_function(&format!("steady_law/creep_update_{}", model.name()), |b| {
            b.iter(|| {
                st.update(
                    black_box(&law),
                    CreepInput::new(
                        black_box(p),
                        black_box(Vec2::new(xi * dr, 0.0)),
                        black_box(Vec2::new(dr, 0.0)),
                    ),
                )
            })
        });
    }
}

criterion_group!(benches, bench_updates, bench_kinematics, bench_steady_laws);
criterion_main!(benches);
