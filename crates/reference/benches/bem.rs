//! Speed of the boundary-element solver: one steady-state solve from zero traction at several
//! grid sizes (normalised contact, nu = 0.25, normalised creepage 0.3: about half the contact
//! slips), and one FASTSIM evaluation for comparison.
use creep_reference::bem::{Creepage, SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use creep_reference::fastsim::{FastsimOptions, fastsim};
use criterion::{Criterion, criterion_group, criterion_main};
use std::hint::black_box;

fn steady(c: &mut Criterion) {
    let contact = CircularContact::normalised(0.25).unwrap();
    let mut group = c.benchmark_group("bem_steady_solve");
    group.sample_size(10);
    for n in [16, 32, 40, 64] {
        let mut solver = SteadySolver::new(contact, SolverOptions::with_grid(n)).unwrap();
        group.bench_function(format!("grid_{n}"), |b| {
            b.iter(|| {
                solver.reset();
                black_box(solver.solve(Creepage::longitudinal(0.3)).unwrap().fx)
            })
        });
    }
    group.finish();
    c.bench_function("fastsim_100x100", |b| {
        b.iter(|| {
            black_box(
                fastsim(
                    &contact,
                    Creepage::longitudinal(0.3),
                    &FastsimOptions::default(),
                )
                .unwrap()
                .fx,
            )
        })
    });
}

criterion_group!(benches, steady);
criterion_main!(benches);
