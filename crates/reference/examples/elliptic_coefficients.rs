//! Kalker's creep coefficients C11, C22, C23, C33 of elliptic contacts by the boundary elements,
//! on the grids given (elements across the shorter axis), with the Richardson extrapolation
//! `2 C(N) - C(N/2)` of the last two grids (the grid error is O(h)).
//!
//! `cargo run --release -p creep-reference --example elliptic_coefficients -- 16 32 [AB ...]`
//!
//! An argument is an axis ratio `a/b` if it is below 4 or contains a decimal point (`5.0`),
//! otherwise a grid.
use creep_reference::bem::{SolverOptions, elliptic_creep_coefficients};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    let mut grids: Vec<usize> = Vec::new();
    let mut abs: Vec<f64> = Vec::new();
    for s in &raw {
        let v = s.parse::<f64>()?;
        if v < 4.0 || s.contains('.') {
            abs.push(v);
        } else {
            grids.push(v as usize);
        }
    }
    if abs.is_empty() {
        abs = vec![1.0, 0.5, 0.2];
    }
    if grids.is_empty() {
        grids = vec![16, 32];
    }
    println!("ab,nu,grid,c11,c22,c23,c32,c33");
    for &ab in &abs {
        for nu in [0.0, 0.25, 0.5] {
            let mut last = Vec::new();
            for &n in &grids {
                let c = elliptic_creep_coefficients(nu, ab, SolverOptions::with_grid(n))?;
                println!(
                    "{ab},{nu},{n},{:.4},{:.4},{:.4},{:.4},{:.4}",
                    c.c11, c.c22, c.c23, c.c32, c.c33
                );
                last.push(c);
            }
            if last.len() >= 2 {
                let (p, q) = (last[last.len() - 2], last[last.len() - 1]);
                let r = |x: f64, y: f64| 2.0 * y - x;
                println!(
                    "{ab},{nu},rich,{:.4},{:.4},{:.4},{:.4},{:.4}",
                    r(p.c11, q.c11),
                    r(p.c22, q.c22),
                    r(p.c23, q.c23),
                    r(p.c32, q.c32),
                    r(p.c33, q.c33)
                );
            }
        }
    }
    Ok(())
}
