//! Error of Kuhn's/Kalker's closed-form steady creepage F_ss (crate creep-law) against the
//! boundary-element steady creepage, by Poisson ratio, at force ratios up to 0.98.
//! Usage: `fss_error [GRID]` (default 32).
use creep_reference::bem::{SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use std::time::Instant;

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(32);
    let ratios = [
        0.02, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95, 0.98,
    ];
    println!("grid,nu,q_over_mu_p,xi_n_bem,xi_n_fss,rel_err");
    let mut summary = Vec::new();
    for nu in [0.0, 0.25, 0.5] {
        let t0 = Instant::now();
        let c = CircularContact::normalised(nu).unwrap();
        let mut s = SteadySolver::new(c, SolverOptions::with_grid(n)).unwrap();
        let (mut max, mut sum2) = (0.0f64, 0.0);
        for &r in &ratios {
            let (xi, _) = s.solve_force(r).unwrap();
            let fss = creep_law::kalker::steady_creepage_n(r, nu);
            let e = fss / xi - 1.0;
            max = max.max(e.abs());
            sum2 += e * e;
            println!("{n},{nu},{r},{xi:.6},{fss:.6},{e:+.4}");
        }
        let rms = (sum2 / ratios.len() as f64).sqrt();
        summary.push((nu, max, rms, t0.elapsed().as_secs_f64()));
    }
    println!("# grid,nu,max_rel_err,rms_rel_err,seconds");
    for (nu, max, rms, t) in summary {
        println!("# {n},{nu},{max:.4},{rms:.4},{t:.2}");
    }
}
