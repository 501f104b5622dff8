//! `creep ref ...`: the reference solvers of crate `creep-reference`, as CSV on stdout.
//! (Owned by the reference-solver work; placeholder until it lands.)

use clap::Subcommand;

/// Reference solutions (closed forms, FASTSIM, boundary elements), printed as CSV.
#[derive(Debug, Subcommand)]
pub enum RefCommand {
    /// Placeholder.
    Todo,
}

/// Runs one `creep ref` subcommand, writing CSV to `out`.
pub fn run(cmd: &RefCommand, out: &mut dyn std::io::Write) -> Result<(), Box<dyn std::error::Error>> {
    let _ = (cmd, out);
    Err("not implemented yet".into())
}
