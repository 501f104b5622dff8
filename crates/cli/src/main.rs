//! The `creep` command-line tool.
mod ref_cmd;

use clap::{Parser, Subcommand};

/// Creep-friction: rolling resistance that is physically right.
#[derive(Debug, Parser)]
#[command(name = "creep", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Reference solutions (closed forms, FASTSIM, boundary elements) as CSV.
    #[command(subcommand, name = "ref")]
    Ref(ref_cmd::RefCommand),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let result = match &cli.command {
        None => Ok(()),
        Some(Command::Ref(cmd)) => ref_cmd::run(cmd, &mut out),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::from(2)
        }
    }
}
