//! The cost of the plugin on a poured pile: `n^3` glass spheres fall into a box and settle;
//! plain Avian, the plugin at `Fidelity::Auto` and the plugin with creep on every contact step
//! from the same state, in turn each step (the order rotating), 1/60 s, Avian's 6 substeps.
//! Prints the medians of the per-step ratios plugin / plain.
//!
//! `cargo run --release -p creep-avian --example pile_bench --ignore-rust-version -- [--n 1000] [--steps 300]`

use std::time::Instant;

use creep_avian::Fidelity;
use creep_avian::scenes::{Run, pile_app, step};

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    if v.is_empty() {
        return f64::NAN;
    }
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |name: &str, default: usize| {
        args.iter()
            .position(|a| a == name)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse::<usize>().ok())
            .unwrap_or(default)
    };
    let n = (arg("--n", 1000) as f64).cbrt().round().max(1.0) as usize;
    let steps = arg("--steps", 300);
    let mut apps = [
        pile_app(n, Run::Plain),
        pile_app(n, Run::Plugin(Fidelity::Auto)),
        pile_app(n, Run::Plugin(Fidelity::Creep)),
    ];
    let (mut ra, mut rc, mut tp) = (vec![], vec![], vec![]);
    let mut creep_contacts = 0;
    for i in 0..steps {
        let mut t = [0.0; 3];
        for k in 0..3 {
            let which = (i + k) % 3;
            let t0 = Instant::now();
            step(&mut apps[which]);
            t[which] = t0.elapsed().as_secs_f64();
        }
        tp.push(t[0]);
        ra.push(t[1] / t[0]);
        rc.push(t[2] / t[0]);
        if let Some(s) = apps[2].world().get_resource::<creep_avian::CreepState>() {
            creep_contacts = creep_contacts.max(s.counts().creep);
        }
    }
    println!(
        "moving pile in Avian: {} spheres, {steps} steps of 1/60 s from release, 6 substeps; plain Avian median step {:.3} ms; most creep contacts in a step {creep_contacts}",
        n * n * n,
        1e3 * median(&mut tp)
    );
    println!(
        "median per-step ratio plugin / plain: Auto {:.3}, creep on every contact {:.3}",
        median(&mut ra),
        median(&mut rc)
    );
}
