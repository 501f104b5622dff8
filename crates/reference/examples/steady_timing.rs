//! Times steady-state solves of the boundary-element solver at several grid sizes.
use creep_reference::bem::{Creepage, SolverOptions, SteadySolver};
use creep_reference::contact::CircularContact;
use std::time::Instant;

fn main() {
    let grids: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let grids = if grids.is_empty() {
        vec![16, 32, 40, 64]
    } else {
        grids
    };
    for nu in [0.0, 0.25, 0.5] {
        let c = CircularContact::normalised(nu).unwrap();
        for &n in &grids {
            let t0 = Instant::now();
            let mut s = SteadySolver::new(c, SolverOptions::with_grid(n)).unwrap();
            let setup = t0.elapsed().as_secs_f64();
            // Linear limit: tiny creepage.
            let xi = 1e-6;
            let t1 = Instant::now();
            let out = s.solve(Creepage::longitudinal(xi)).unwrap();
            let lin = t1.elapsed().as_secs_f64();
            let c11 = out.fx / xi;
            let mut line = format!(
                "nu={nu} N={n} elems={} setup={setup:.4}s linear: C11={c11:.4} sweeps={} t={lin:.4}s |",
                s.grid().len(),
                out.sweeps
            );
            for xin in [0.1, 0.3, 0.6] {
                s.reset();
                let t2 = Instant::now();
                let out = s.solve(Creepage::longitudinal(xin)).unwrap();
                line += &format!(
                    " xi_n={xin}: Q={:.5} sw={} t={:.4}s slip={:.2} |",
                    out.fx,
                    out.sweeps,
                    t2.elapsed().as_secs_f64(),
                    out.traction.slip_fraction()
                );
            }
            println!("{line}");
        }
    }
}
