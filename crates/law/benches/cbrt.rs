//! The cube root in Kalker's `F_ss` (`[1 - (1 - s)^(1/3)]`): creep-law's [`kalker::cbrt`]
//! (Evans' algorithm) against the system libm's `f64::cbrt`, and Kalker's normalised creepage
//! with each, side by side: the variants alternate in every round (so the machine's load hits
//! both alike; CPU time of the thread, not wall-clock time) and the medians over the rounds are printed with their ratio.
//!
//! Run: `cargo bench -p creep-law --bench cbrt` (`-- ROUNDS` to change the 11 rounds).

use std::hint::black_box;
use std::time::Instant;

use creep_law::kalker;

/// CPU time of this thread \[ns\] (Linux: `/proc/thread-self/schedstat`, whose first field is
/// the time on a CPU), so that other jobs' load does not enter; wall-clock time elsewhere.
fn cpu_ns(start: Instant) -> f64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .unwrap_or_else(|| start.elapsed().as_secs_f64() * 1e9)
}

/// Passes over the arguments per measurement: 5e6 calls, tens of milliseconds, long against
/// the scheduler tick at which the kernel updates the thread's CPU time.
const REPS: usize = 500;

/// CPU nanoseconds per call of `f` over `xs` (summed, so no call can be skipped).
fn ns_per_call(xs: &[f64], f: impl Fn(f64) -> f64) -> f64 {
    let origin = Instant::now();
    let t0 = cpu_ns(origin);
    let mut acc = 0.0;
    for _ in 0..REPS {
        for &x in xs {
            acc += f(black_box(x));
        }
    }
    black_box(acc);
    (cpu_ns(origin) - t0) / (REPS * xs.len()) as f64
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let rounds: usize = std::env::args()
        .skip(1)
        .find_map(|a| a.parse().ok())
        .unwrap_or(11);
    // The creep law's arguments: 1 - s for force ratios s in [0, 1).
    let xs: Vec<f64> = (0..10_000)
        .map(|i| 1.0 - (i as f64 + 0.5) / 10_000.0)
        .collect();
    let c11 = kalker::c11(0.2);
    let (mut ours, mut libm, mut fss_new, mut fss_old) = (vec![], vec![], vec![], vec![]);
    for _ in 0..rounds {
        ours.push(ns_per_call(&xs, kalker::cbrt));
        libm.push(ns_per_call(&xs, f64::cbrt));
        // Kalker's creepage as evaluated now, and the former libm form `1 - (1 - s)^(1/3)`.
        fss_new.push(ns_per_call(&xs, |x| {
            kalker::steady_creepage_n(1.0 - x, 0.2)
        }));
        fss_old.push(ns_per_call(&xs, |x| {
            let s = (1.0 - x).clamp(0.0, 1.0);
            3.0 / c11 * (1.0 - (1.0 - s).cbrt())
        }));
    }
    let (a, b, c, d) = (median(ours), median(libm), median(fss_new), median(fss_old));
    println!("median over {rounds} interleaved rounds, ns per call:");
    println!(
        "  kalker::cbrt {a:.2}   f64::cbrt (libm) {b:.2}   ratio {:.2}",
        b / a
    );
    println!(
        "  F_ss now {c:.2}   F_ss with libm, 1 - c form {d:.2}   ratio {:.2}",
        d / c
    );
}
