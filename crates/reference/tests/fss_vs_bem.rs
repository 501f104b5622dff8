//! Kuhn's steady creepage `F_ss` (Kalker 2000's closed form, crate `creep-law`) graded against the
//! boundary-element solution of Kalker's exact theory (this crate), by Poisson ratio.
//!
//! For each force ratio `s = Q/(mu P)` the exact theory's creepage is found by a force-prescribed
//! steady solve; the relative error of `F_ss` is `F_ss(s)/xi_bem(s) - 1`. The table is written to
//! `$CARGO_TARGET_TMPDIR/fss_vs_bem.csv` and printed (see it with `--nocapture`). The grid here is
//! small to keep the debug test fast; the closing note of the reference crate quotes the same
//! table at N = 64 (`cargo run --release -p creep-reference --example fss_error 64`).

use creep_reference::bem::{SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use std::fmt::Write as _;

const RATIOS: [f64; 13] = [
    0.02, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98,
];

#[test]
fn fss_against_bem_steady_curve() {
    let grid = 16;
    let mut csv = String::from("grid,nu,q_over_mu_p,xi_n_bem,xi_n_fss,rel_err\n");
    let mut summary = String::from("grid,nu,max_rel_err,rms_rel_err\n");
    for nu in [0.0, 0.25, 0.5] {
        let contact = CircularContact::normalised(nu).unwrap();
        let mut solver = SteadySolver::new(contact, SolverOptions::with_grid(grid)).unwrap();
        let mut errors = Vec::new();
        for s in RATIOS {
            let (xi_bem, out) = solver.solve_force(s).unwrap();
            assert!((out.fx - s).abs() < 1e-8);
            let xi_fss = creep_law::kalker::steady_creepage_n(s, nu);
            let e = xi_fss / xi_bem - 1.0;
            writeln!(csv, "{grid},{nu},{s},{xi_bem:.6},{xi_fss:.6},{e:.5}").unwrap();
            errors.push(e);
        }
        let max = errors.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let rms = (errors.iter().map(|e| e * e).sum::<f64>() / errors.len() as f64).sqrt();
        writeln!(summary, "{grid},{nu},{max:.4},{rms:.4}").unwrap();

        // What the comparison establishes (tolerances cover the grid error at N = 16, about
        // +1.6 % in C11, see `bem::steady` tests):
        // 1. in the linear range F_ss agrees with the exact theory to within a few percent
        //    (it is built on Kalker's C11);
        assert!(errors[1].abs() < 0.04, "nu={nu}: {errors:?}");
        // 2. F_ss over-estimates the exact creepage at every force ratio, and the more so the
        //    closer to full slip (the cubic law saturates later than the exact theory);
        assert!(errors.iter().all(|&e| e > 0.0), "nu={nu}: {errors:?}");
        assert!(
            errors.windows(2).skip(1).all(|w| w[1] >= w[0] - 1e-3),
            "nu={nu}"
        );
        // 3. the error stays below 20 % up to Q/(mu P) = 0.98.
        assert!(max < 0.2, "nu={nu}: max {max}");
    }
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR"));
    std::fs::write(dir.join("fss_vs_bem.csv"), &csv).unwrap();
    std::fs::write(dir.join("fss_vs_bem_summary.csv"), &summary).unwrap();
    println!("{csv}\n{summary}");
}
