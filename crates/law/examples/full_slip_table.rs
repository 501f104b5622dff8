//! Writes `crates/law/src/steady3d/full_slip_data.rs`, the table of the loads of full slip
//! (module `creep_law::steady3d::full_slip`): every row `a/b` and grid direction by
//! quadrature (`rigid_slip_loads`, 240 x 960 points).
//!
//! `cargo run --release -p creep-law --example full_slip_table`
use creep_law::steady3d::full_slip::{NU, NV, ROWS, node_direction, rigid_slip_frame, row_ab};
use std::fmt::Write;

/// Quadrature steps in the polar angle (`4 N` around).
const N: usize = 240;
const OUT: &str = "crates/law/src/steady3d/full_slip_data.rs";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut s = String::new();
    writeln!(
        s,
        "//! The loads of full slip per row `a/b` and direction (module `full_slip`). DO NOT EDIT:\n\
         //! written by `cargo run --release -p creep-law --example full_slip_table` (quadrature,\n\
         //! {N} x {} points).\n\n\
         // Computed loads, not approximations of named constants.\n\
         #![allow(clippy::approx_constant)]\n\n\
         use super::full_slip::{{ROWS as N_ROWS, Row}};\n\n\
         /// The rows, `a/b = 10^((k - 12)/12)`.\n\
         #[rustfmt::skip]\n\
         pub(super) static ROWS: [Row; N_ROWS] = [",
        4 * N
    )?;
    for k in 0..ROWS {
        let ab = row_ab(k);
        writeln!(s, "    // a/b = {ab:.6}\n    [")?;
        for i in 0..NU {
            let mut line = String::from("       ");
            for j in 0..NV {
                let l = rigid_slip_frame(ab, node_direction(i, j), N);
                let f = |v: f64| {
                    let t = format!("{v:.6}");
                    if t == "-0.000000" {
                        "0.000000".to_string()
                    } else {
                        t
                    }
                };
                write!(line, " [{}, {}, {}],", f(l[0]), f(l[1]), f(l[2]))?;
            }
            writeln!(s, "{line}")?;
        }
        writeln!(s, "    ],")?;
        eprintln!("row {k} (a/b {ab:.4}) done");
    }
    writeln!(s, "];")?;
    std::fs::write(OUT, s)?;
    eprintln!("wrote {OUT}");
    Ok(())
}
