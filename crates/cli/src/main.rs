//! The `creep` command-line tool: creep-friction contact laws and references, headless.
mod bench_cmd;
mod bench_pile;
mod figure_cmd;
mod law_cmd;
mod output;
mod plot;
mod progress;
mod ref_cmd;
mod report_cmd;
mod repose_cmd;
mod robot_cmd;
mod run_cmd;
mod triaxial_cmd;
mod wheel_cmd;

use clap::{Parser, Subcommand};

/// Creep-friction: rolling resistance that is physically right.
///
/// With no command, prints a short tour: the contact law (steady creep curve, a
/// Cattaneo-Mindlin cycle, Kuhn's transient build-up) and the Rapier scenarios.
#[derive(Debug, Parser)]
#[command(name = "creep", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// The short tour of the contact law (the default).
    Demo,
    /// The contact law (creep-law) as CSV.
    #[command(subcommand)]
    Law(law_cmd::LawCommand),
    /// Scenarios in Rapier with the creep-friction plugin, measured against closed forms.
    #[command(subcommand)]
    Run(run_cmd::RunCommand),
    /// Reference solutions (closed forms, FASTSIM, boundary elements) as CSV.
    #[command(subcommand, name = "ref")]
    Ref(ref_cmd::RefCommand),
    /// The speed-against-error report: REPORT.md, CSVs and plots (`report [--quick] [--out DIR]`).
    Report(report_cmd::ReportArgs),
    /// The talk's figures as CSV, SVG and PNG (e.g. `figure rolling-effect --out figures`).
    #[command(subcommand)]
    Figure(figure_cmd::FigureCommand),
    /// The talk's drained triaxial test of 4,096 spheres (compliant regime), Coulomb-Mindlin
    /// against creep-friction from the same packing: CSVs, plots, SUMMARY.md.
    Triaxial(triaxial_cmd::TriaxialArgs),
    /// Benchmarks (particle-steps per second of the DEM packing).
    #[command(subcommand)]
    Bench(bench_cmd::BenchCommand),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let result = match &cli.command {
        None | Some(Command::Demo) => {
            law_cmd::tour(&mut out).and_then(|()| run_cmd::tour(&mut out))
        }
        Some(Command::Run(cmd)) => run_cmd::run(cmd, &mut out),
        Some(Command::Law(cmd)) => law_cmd::run(cmd, &mut out),
        Some(Command::Ref(cmd)) => ref_cmd::run(cmd, &mut out),
        Some(Command::Report(args)) => report_cmd::run(args, &mut out),
        Some(Command::Figure(cmd)) => figure_cmd::run(cmd, &mut out),
        Some(Command::Triaxial(args)) => triaxial_cmd::run(args, &mut out),
        Some(Command::Bench(cmd)) => bench_cmd::run(cmd, &mut out),
    };
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::from(2)
        }
    }
}
