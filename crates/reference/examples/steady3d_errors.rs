//! The error table of creep-law's fast 3-D steady law (`creep_law::steady3d`) against the
//! boundary-element table `data/steady3d_bem.csv` (module `creep_reference::steady3d`), or
//! against another table in the same format given with `--table FILE` (for instance the
//! validation table `data/steady3d_bem_validation.csv`, off the fitted nodes): markdown on
//! stdout, and the per-case CSV to the file given as the first other argument, if any.
//!
//! With `--blend`, the previous round's law between rows is graded instead
//! (`Steady3d::two_row_blend`: two rows' loads blended; the same law at the rows).
//!
//! `cargo run --release -p creep-reference --example steady3d_errors [-- [--blend] [--table FILE] [errors.csv]]`
use creep_law::steady3d::Steady3d;
use creep_reference::steady3d::{error_markdown, law_errors_of, read_csv, table};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let mut points = None;
    let mut out = None;
    let mut blend = false;
    while let Some(a) = args.next() {
        if a == "--blend" {
            blend = true;
        } else if a == "--table" {
            let path = args.next().ok_or("--table needs a file")?;
            points = Some(read_csv(&std::fs::read_to_string(path)?)?);
        } else {
            out = Some(a);
        }
    }
    let points = match points {
        Some(p) => p,
        None => table()?,
    };
    let errors = if blend {
        law_errors_of(&points, Steady3d::two_row_blend)?
    } else {
        law_errors_of(&points, Steady3d::new)?
    };
    print!("{}", error_markdown(&errors));
    if let Some(path) = out {
        let mut csv = String::from(
            "ab,nu,kind,force_err,force_at_xi,force_at_eta,force_at_phi,moment_err,moment_at_xi,moment_at_eta,moment_at_phi\n",
        );
        for e in &errors {
            csv.push_str(&format!(
                "{},{},{},{:.5},{},{},{},{:.5},{},{},{}\n",
                e.ab,
                e.nu,
                e.kind.name(),
                e.force,
                e.force_at[0],
                e.force_at[1],
                e.force_at[2],
                e.moment,
                e.moment_at[0],
                e.moment_at[1],
                e.moment_at[2]
            ));
        }
        std::fs::write(path, csv)?;
    }
    Ok(())
}
