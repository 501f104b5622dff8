//! Criterion benchmarks of the fast 3-D steady law (`creep_law::steady3d`) against Kuhn's `F_ss`
//! (Kalker's closed form, `creep_law::kalker`), each timed over the same batch of 64 inputs per
//! iteration (so the reported time is per 64 evaluations).
//!
//! Before criterion's groups, a load-robust table: every variant's CPU time per evaluation
//! (the thread's CPU time from `/proc/thread-self/schedstat`, as the `cbrt` bench does), the
//! variants interleaved in every round, medians over the rounds and their ratios to `F_ss`.
//!
//! The table also times the previous law, `Steady3d::two_row_blend` (two rows' translations
//! between rows, their loads blended; at a row the same law), interleaved with the current one
//! in every round, so before/after is one run.
//!
//! Run: `cargo bench -p creep-law --bench steady3d` (results: docs/CREEP3D.md);
//! `-- --rounds-only` prints the table alone, `-- --rounds N` takes N rounds (default 11).
//!
//! `-- --count CASE [--blend] [--passes P]` evaluates one variant only (`CASE` 0-7: the
//! table's cases in order; `--blend`: `Steady3d::two_row_blend`; `CASE` `fss`: `F_ss`; `P`
//! passes over the 4096 inputs, default 20; `--far` in both modes: the inputs times ten, beyond
//! the law's box) in the function `count_batch`, for a load-free
//! instruction count per evaluation:
//! `valgrind --tool=callgrind --toggle-collect='*count_batch*' BENCH_BINARY --count 2`
//! (instructions of `count_batch` / (4096 P)). `-- --time CASE [--blend]` prints that
//! variant's CPU ns per evaluation alone (median of 3 measurements of 1000 passes), for
//! alternating two builds of this bench in one script (e.g. before and after a change).

use std::hint::black_box;
use std::time::Instant;

use creep_law::steady3d::Steady3d;
use creep_law::{SteadyLaw, kalker};
use criterion::{Criterion, criterion_group};

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

/// CPU time of this thread \[ns\] (Linux: `/proc/thread-self/schedstat`, whose first field is
/// the time on a CPU), so that other jobs' load does not enter; wall-clock time elsewhere.
fn cpu_ns(start: Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or_else(|| start.elapsed().as_secs_f64() * 1e9)
}

/// CPU nanoseconds per evaluation of `f` over `xs`, `reps` passes (summed, so no call can be
/// skipped).
fn ns_per_call(xs: &[[f64; 3]], reps: usize, f: &dyn Fn(&[f64; 3]) -> f64) -> f64 {
    let origin = Instant::now();
    let t0 = cpu_ns(origin);
    let mut acc = 0.0;
    for _ in 0..reps {
        for x in xs {
            acc += f(black_box(x));
        }
    }
    black_box(acc);
    (cpu_ns(origin) - t0) / (reps * xs.len()) as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The table's cases: name, `a/b`, `nu` (the last two in the boundary-element table's
/// coverage: `Steady3d::loads` interpolates it; "before" there is the fitted law).
const CASES: [(&str, f64, f64); 8] = [
    ("a/b 0.5, nu 0.25 (a node)", 0.5, 0.25),
    ("a/b 0.5, nu 0.125 (table, two nodes)", 0.5, 0.125),
    ("a/b 0.35, nu 0.125 (table, between a/b)", 0.35, 0.125),
    ("a/b 3, nu 0.375 (table, two nodes)", 3.0, 0.375),
    ("a/b 1.4, nu 0.125 (table, two nodes)", 1.4, 0.125),
    ("a/b 1, nu 0.3 (table node)", 1.0, 0.3),
    ("a/b 1, nu 0.4 (table, two nodes)", 1.0, 0.4),
    ("a/b 0.7, nu 0.3 (table, between a/b)", 0.7, 0.3),
];

/// 4096 inputs of the bench's distribution (creepages up to full slip, spins both ways).
fn table_inputs() -> Vec<[f64; 3]> {
    (0..4096)
        .map(|i| {
            let t = i as f64 * 0.37;
            [0.4 * t.sin(), 0.3 * (1.3 * t).cos(), 0.8 * (0.7 * t).sin()]
        })
        .collect()
}

/// The interleaved CPU-time table (module documentation).
fn cpu_table(rounds: usize) {
    let nu = 0.25;
    let kuhn = SteadyLaw::Kuhn {
        c11: kalker::c11(nu),
    };
    let xs = table_inputs();
    let laws: Vec<(&str, Steady3d, Steady3d)> = CASES
        .iter()
        .map(|&(name, ab, nu)| {
            (
                name,
                Steady3d::new(ab, nu).unwrap(),
                Steady3d::two_row_blend(ab, nu).unwrap(),
            )
        })
        .collect();
    // The thread CPU clock ticks at 4 ms on this VM (schedstat): 1000 passes over the 4096
    // inputs take 0.15-0.4 s per measurement, a resolution of 1-3 %.
    let reps = 1000;
    let fss = |v: &[f64; 3]| kuhn.creepage_n(v[0].abs().min(0.99));
    let mut t_fss = vec![];
    let mut t_tr = vec![vec![]; laws.len()];
    let mut t_sp = vec![vec![]; laws.len()];
    let mut t_old = vec![vec![]; laws.len()];
    let mut t_old_tr = vec![vec![]; laws.len()];
    let mut t_inv = vec![];
    for _ in 0..rounds {
        t_fss.push(ns_per_call(&xs, reps, &fss));
        for (k, (_, law, old)) in laws.iter().enumerate() {
            t_tr[k].push(ns_per_call(&xs, reps, &|v| {
                let l = law.loads(v[0], v[1], 0.0);
                l.fx + l.fy + l.mz
            }));
            t_old_tr[k].push(ns_per_call(&xs, reps, &|v| {
                let l = old.loads(v[0], v[1], 0.0);
                l.fx + l.fy + l.mz
            }));
            t_old[k].push(ns_per_call(&xs, reps, &|v| {
                let l = old.loads(v[0], v[1], v[2]);
                l.fx + l.fy + l.mz
            }));
            t_sp[k].push(ns_per_call(&xs, reps, &|v| {
                let l = law.loads(v[0], v[1], v[2]);
                l.fx + l.fy + l.mz
            }));
        }
        let law = &laws[0].1;
        t_inv.push(ns_per_call(&xs, reps, &|v| {
            let (p, q) = law
                .creepages_for_force(0.9 * v[0], 0.9 * v[1])
                .unwrap_or((0.0, 0.0));
            p + q
        }));
    }
    let f = median(t_fss);
    println!(
        "steady3d: CPU ns per evaluation, medians of {rounds} interleaved rounds (ratio to F_ss)"
    );
    println!("  F_ss (Kuhn, kalker::cbrt)            {f:7.2}");
    for (k, (name, _, _)) in laws.iter().enumerate() {
        let (a, b) = (median(t_tr[k].clone()), median(t_sp[k].clone()));
        let (oa, ob) = (median(t_old_tr[k].clone()), median(t_old[k].clone()));
        println!(
            "  {name:34} no spin {a:6.2} ({:.2}x)  with spin {b:6.2} ({:.2}x) | before: no spin {oa:6.2} ({:.2}x)  with spin {ob:6.2} ({:.2}x)",
            a / f,
            b / f,
            oa / f,
            ob / f
        );
    }
    let i = median(t_inv);
    println!(
        "  inverse at zero spin (a node)        {i:7.2} ({:.2}x)",
        i / f
    );
    // Construction (once per contact shape and pair): between rows the table (105 knots,
    // both rows' spin terms and three pure-spin evaluations each).
    let t0 = Instant::now();
    let n = 50;
    for k in 0..n {
        black_box(Steady3d::new(black_box(0.35 + 0.001 * k as f64), 0.125).unwrap());
    }
    let fit = t0.elapsed().as_secs_f64() / n as f64;
    let t0 = Instant::now();
    for k in 0..100 {
        black_box(Steady3d::new(black_box(0.5), 0.125 + 1e-3 * k as f64).unwrap());
    }
    let row = t0.elapsed().as_secs_f64() / 100.0;
    println!(
        "  Steady3d::new: between rows {:.1} us (wall), at a row {:.2} us; size {} bytes",
        fit * 1e6,
        row * 1e6,
        std::mem::size_of::<Steady3d>()
    );
}

/// One variant's evaluations over `xs`, `passes` times, out of line (the `--count` mode).
#[inline(never)]
fn count_batch(xs: &[[f64; 3]], passes: usize, f: &dyn Fn(&[f64; 3]) -> f64) -> f64 {
    let mut acc = 0.0;
    for _ in 0..passes {
        for x in xs {
            acc += f(black_box(x));
        }
    }
    acc
}

/// The inputs of the `--count` and `--time` modes: [`table_inputs`], times ten with `--far`
/// (beyond the law's box, `Steady3d::loads`).
fn mode_inputs() -> Vec<[f64; 3]> {
    let mut xs = table_inputs();
    if std::env::args().any(|a| a == "--far") {
        xs.iter_mut().for_each(|v| *v = v.map(|c| 10.0 * c));
    }
    xs
}

/// The `--count` mode (module documentation).
fn count_mode(case: &str, blend: bool, passes: usize) {
    let xs = mode_inputs();
    let acc = if case == "fss" {
        let kuhn = SteadyLaw::Kuhn {
            c11: kalker::c11(0.25),
        };
        count_batch(&xs, passes, &|v| kuhn.creepage_n(v[0].abs().min(0.99)))
    } else {
        let (name, ab, nu) = CASES[case.parse::<usize>().expect("--count CASE: 0-7 or fss")];
        let law = if blend {
            Steady3d::two_row_blend(ab, nu).unwrap()
        } else {
            Steady3d::new(ab, nu).unwrap()
        };
        println!("{name}, {}", if blend { "two_row_blend" } else { "new" });
        count_batch(&xs, passes, &|v| {
            let l = law.loads(v[0], v[1], v[2]);
            l.fx + l.fy + l.mz
        })
    };
    println!("{} evaluations (checksum {acc})", passes * xs.len());
}

/// The `--time` mode (module documentation): CPU ns per evaluation of one variant, the median
/// of 3 measurements of 1000 passes (for alternating two binaries in a script).
fn time_mode(case: &str, blend: bool) {
    let xs = mode_inputs();
    let (ab, nu) = if case == "fss" {
        (1.0, 0.25)
    } else {
        let c = CASES[case.parse::<usize>().expect("--time CASE: 0-7 or fss")];
        (c.1, c.2)
    };
    let law = if blend {
        Steady3d::two_row_blend(ab, nu).unwrap()
    } else {
        Steady3d::new(ab, nu).unwrap()
    };
    let kuhn = SteadyLaw::Kuhn {
        c11: kalker::c11(0.25),
    };
    let t: Vec<f64> = (0..3)
        .map(|_| {
            if case == "fss" {
                ns_per_call(&xs, 1000, &|v| kuhn.creepage_n(v[0].abs().min(0.99)))
            } else {
                ns_per_call(&xs, 1000, &|v| {
                    let l = law.loads(v[0], v[1], v[2]);
                    l.fx + l.fy + l.mz
                })
            }
        })
        .collect();
    println!("{:.2}", median(t));
}

criterion_group!(benches, bench_steady3d);

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(i) = args.iter().position(|a| a == "--count") {
        let passes = args
            .iter()
            .position(|a| a == "--passes")
            .and_then(|i| args.get(i + 1)?.parse().ok())
            .unwrap_or(20);
        let case = args.get(i + 1).map(String::as_str).unwrap_or("0");
        count_mode(case, args.iter().any(|a| a == "--blend"), passes);
        return;
    }
    if let Some(i) = args.iter().position(|a| a == "--time") {
        let case = args.get(i + 1).map(String::as_str).unwrap_or("0");
        time_mode(case, args.iter().any(|a| a == "--blend"));
        return;
    }
    let rounds_only = std::env::args().any(|a| a == "--rounds-only");
    let rounds = std::env::args()
        .position(|a| a == "--rounds")
        .and_then(|i| std::env::args().nth(i + 1)?.parse().ok())
        .unwrap_or(11);
    cpu_table(rounds);
    if !rounds_only {
        benches();
        Criterion::default().configure_from_args().final_summary();
    }
}
