//! Kalker's creep coefficients recovered by the boundary-element solver in the linear limit, per
//! grid size, with the time per linear solve (three solves per line).
use creep_reference::bem::{SolverOptions, creep_coefficients};
use std::time::Instant;

fn main() {
    let grids: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let grids = if grids.is_empty() {
        vec![16, 32, 64]
    } else {
        grids
    };
    println!("nu,grid,c11,c22,c23,c32,seconds_for_3_solves");
    for nu in [0.0, 0.25, 0.5] {
        for &n in &grids {
            let t0 = Instant::now();
            let c = creep_coefficients(nu, SolverOptions::with_grid(n)).unwrap();
            println!(
                "{nu},{n},{:.4},{:.4},{:.4},{:.4},{:.3}",
                c.c11,
                c.c22,
                c.c23,
                c.c32,
                t0.elapsed().as_secs_f64()
            );
        }
    }
}
