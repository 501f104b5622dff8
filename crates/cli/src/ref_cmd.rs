//! `creep ref ...`: the reference solvers of crate `creep-reference`, as CSV on stdout.
//!
//! Physical inputs are SI: contact radius `a` [m], normal force `P` [N], combined shear modulus
//! `G` [Pa] and Poisson ratio `nu` of the pair (Kalker's combination, see
//! `creep_reference::material::Pair`), friction coefficient `mu`. Creepage is the rigid slip
//! velocity of body q relative to body p over the rolling speed; forces are on body p; the
//! rolling direction is `x` (see `creep_reference::bem`).

use clap::{Args, Subcommand, ValueEnum};
use creep_reference::bem::{
    Creepage, SolverOptions, SteadySolver, TransientInput, transient_hold_creepage,
    transient_hold_force,
};
use creep_reference::carter::Carter;
use creep_reference::contact::CircularContact;
use creep_reference::fastsim::{FastsimOptions, fastsim};
use creep_reference::mindlin::Mindlin;
use std::io::Write;

use crate::output::CsvWriter;

/// Reference solutions (closed forms, FASTSIM, boundary elements), printed as CSV.
#[derive(Debug, Subcommand)]
pub enum RefCommand {
    /// Steady rolling: tangential force against creepage (boundary elements or FASTSIM).
    /// Header `creepage,fx,fx_over_mu_p`, plus `,lateral,spin,fy,mz` when `--lateral` or
    /// `--spin` is given.
    Steady(SteadyArgs),
    /// Transient rolling from zero traction, holding the force or the creepage (boundary
    /// elements). Header `step,rolled,creepage,fx_over_mu_p`.
    Transient(TransientArgs),
    /// Cattaneo-Mindlin / Mindlin-Deresiewicz closed forms at constant P: a loading, unloading
    /// and reloading cycle. Header `branch,q_over_mu_p,shift`.
    Mindlin(MindlinArgs),
    /// Carter's 2-D steady rolling of cylinders (closed form). Header
    /// `q_over_mu_p,creepage,stick_half_width_over_a`.
    Carter(CarterArgs),
    /// Boundary-element tables for the creep-law tiers, and the fit of creep-law's steady law.
    #[command(subcommand)]
    Fit(FitCommand),
}

/// `creep ref fit ...`: generators of the checked-in tables (normalised units: a = G = mu P = 1).
#[derive(Debug, Subcommand)]
pub enum FitCommand {
    /// Steady curves by boundary elements on grids N/2 and N at the node and check Poisson
    /// ratios, their Richardson extrapolation 2 f(N) - f(N/2), and the fitted steady law's
    /// coefficients as creep-law's `steady_table.rs`.
    Steady(FitSteadyArgs),
    /// Transient curves (held force, held creepage at Q/(mu P) = 0.3, 0.6, 0.9) by boundary
    /// elements on grids N/2 and N, as CSV.
    Transient(FitTransientArgs),
}

/// Arguments of `creep ref fit steady`.
#[derive(Debug, Args)]
pub struct FitSteadyArgs {
    /// Elements across the contact diameter of the fine grid N (the coarse one is N/2), in
    /// [8, 256].
    #[arg(long, default_value_t = 64)]
    grid: usize,
    /// Worker threads (one Poisson ratio per thread).
    #[arg(long, default_value_t = 2)]
    threads: usize,
    /// Read the boundary-element curves from this CSV instead of solving (refit only).
    #[arg(long)]
    from: Option<std::path::PathBuf>,
    /// Write the boundary-element curves (CSV) here.
    #[arg(long)]
    data: Option<std::path::PathBuf>,
    /// Write the Rust table here (default: stdout).
    #[arg(long)]
    out: Option<std::path::PathBuf>,
    /// Largest force ratio fitted, in (0.5, 1).
    #[arg(long, default_value_t = 0.99)]
    s_max: f64,
}

/// Arguments of `creep ref fit transient`.
#[derive(Debug, Args)]
pub struct FitTransientArgs {
    /// Elements across the contact diameter of the fine grid N (the coarse one is N/2), in
    /// [8, 256].
    #[arg(long, default_value_t = 32)]
    grid: usize,
    /// Rolled distance per step, in contact radii (> 0; 2/N is the fine grid's element side).
    #[arg(long, default_value_t = 0.0625)]
    dq: f64,
    /// Steps per curve, in [1, 100000].
    #[arg(long, default_value_t = 64)]
    steps: usize,
    /// Poisson ratios, each in [0, 0.5].
    #[arg(long, value_delimiter = ',', default_value = "0,0.25,0.5")]
    nu: Vec<f64>,
    /// Worker threads.
    #[arg(long, default_value_t = 2)]
    threads: usize,
    /// Write the CSV here (default: stdout).
    #[arg(long)]
    out: Option<std::path::PathBuf>,
}

/// The circular contact shared by the 3-D commands.
#[derive(Debug, Args)]
pub struct ContactArgs {
    /// Contact radius a [m] (> 0).
    #[arg(long, allow_negative_numbers = true)]
    a: f64,
    /// Normal force P [N] (> 0).
    #[arg(long, allow_negative_numbers = true)]
    p: f64,
    /// Combined shear modulus G [Pa] (> 0).
    #[arg(long, allow_negative_numbers = true)]
    g: f64,
    /// Combined Poisson ratio nu, in [0, 0.5].
    #[arg(long, allow_negative_numbers = true)]
    nu: f64,
    /// Friction coefficient mu (> 0).
    #[arg(long, allow_negative_numbers = true)]
    mu: f64,
}

impl ContactArgs {
    fn contact(&self) -> Result<CircularContact, creep_reference::RefError> {
        CircularContact::new(self.a, self.p, self.g, self.nu, self.mu)
    }
}

/// Which steady-state model to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SteadyMethod {
    /// Boundary elements, Kalker's exact theory.
    Bem,
    /// Kalker's simplified theory (FASTSIM).
    Fastsim,
}

/// Arguments of `creep ref steady`.
#[derive(Debug, Args)]
pub struct SteadyArgs {
    #[command(flatten)]
    contact: ContactArgs,
    /// Longitudinal creepages, comma separated [dimensionless].
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        allow_negative_numbers = true
    )]
    creepage: Vec<f64>,
    /// Lateral creepage: one value for all rows, or one per creepage [dimensionless].
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    lateral: Vec<f64>,
    /// Spin creepage: one value for all rows, or one per creepage [1/m].
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    spin: Vec<f64>,
    /// Elements across the contact diameter (boundary elements), in [4, 256].
    #[arg(long, default_value_t = 32)]
    grid: usize,
    /// Model: bem (exact theory) or fastsim (simplified theory).
    #[arg(long, value_enum, default_value_t = SteadyMethod::Bem)]
    method: SteadyMethod,
}

/// Arguments of `creep ref transient`.
#[derive(Debug, Args)]
pub struct TransientArgs {
    #[command(flatten)]
    contact: ContactArgs,
    /// Hold the longitudinal force at this ratio Q/(mu P), in (-1, 1).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "hold_creepage")]
    hold_force: Option<f64>,
    /// Hold this longitudinal creepage [dimensionless].
    #[arg(long, allow_negative_numbers = true)]
    hold_creepage: Option<f64>,
    /// Rolling distance per step DX [m] (> 0; the element side, about 2a/N, reproduces the
    /// steady discretisation).
    #[arg(long, allow_negative_numbers = true)]
    step: f64,
    /// Number of steps, in [1, 1000000].
    #[arg(long)]
    steps: usize,
    /// Elements across the contact diameter, in [4, 256].
    #[arg(long, default_value_t = 24)]
    grid: usize,
}

/// Arguments of `creep ref mindlin`.
#[derive(Debug, Args)]
pub struct MindlinArgs {
    #[command(flatten)]
    contact: ContactArgs,
    /// Turning point of the cycle Q*/(mu P), in (0, 1].
    #[arg(long, default_value_t = 0.8)]
    amplitude: f64,
    /// Points per branch, in [1, 100000].
    #[arg(long, default_value_t = 20)]
    points: usize,
}

/// Arguments of `creep ref carter`.
#[derive(Debug, Args)]
pub struct CarterArgs {
    /// Contact half-width a [m] (> 0).
    #[arg(long)]
    a: f64,
    /// Relative radius R [m] (1/R = 1/R1 + 1/R2, > 0).
    #[arg(long)]
    r: f64,
    /// Friction coefficient mu (> 0).
    #[arg(long)]
    mu: f64,
    /// Force ratios Q/(mu P), comma separated, each in [-1, 1].
    #[arg(
        long,
        value_delimiter = ',',
        required = true,
        allow_negative_numbers = true
    )]
    ratios: Vec<f64>,
}

/// Picks element `i` of a broadcast list (empty: 0; one value: for all rows).
fn pick(list: &[f64], i: usize, name: &str, n: usize) -> Result<f64, Box<dyn std::error::Error>> {
    match list.len() {
        0 => Ok(0.0),
        1 => Ok(list[0]),
        m if m == n => Ok(list[i]),
        m => Err(format!("--{name} has {m} values: give one, or one per creepage ({n})").into()),
    }
}

fn run_steady(args: &SteadyArgs, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    let contact = args.contact.contact()?;
    let extra = !args.lateral.is_empty() || !args.spin.is_empty();
    let n = args.creepage.len();
    let mut solver = match args.method {
        SteadyMethod::Bem => Some(SteadySolver::new(
            contact,
            SolverOptions::with_grid(args.grid),
        )?),
        SteadyMethod::Fastsim => None,
    };
    let header: &[&str] = if extra {
        &[
            "creepage",
            "fx",
            "fx_over_mu_p",
            "lateral",
            "spin",
            "fy",
            "mz",
        ]
    } else {
        &["creepage", "fx", "fx_over_mu_p"]
    };
    let mut w = CsvWriter::new(out, header)?;
    for (i, &xi) in args.creepage.iter().enumerate() {
        let c = Creepage {
            longitudinal: xi,
            lateral: pick(&args.lateral, i, "lateral", n)?,
            spin: pick(&args.spin, i, "spin", n)?,
        };
        let (fx, fy, mz) = match solver.as_mut() {
            Some(s) => {
                let o = s.solve(c)?;
                (o.fx, o.fy, o.mz)
            }
            None => {
                let o = fastsim(&contact, c, &FastsimOptions::default())?;
                (o.fx, o.fy, o.mz)
            }
        };
        let ratio = fx / contact.mu_p();
        if extra {
            w.row(&[&xi, &fx, &ratio, &c.lateral, &c.spin, &fy, &mz])?;
        } else {
            w.row(&[&xi, &fx, &ratio])?;
        }
    }
    Ok(())
}

fn run_transient(
    args: &TransientArgs,
    out: &mut dyn Write,
) -> Result<(), Box<dyn std::error::Error>> {
    let input = TransientInput {
        contact: args.contact.contact()?,
        options: SolverOptions::with_grid(args.grid),
        step: args.step,
        steps: args.steps,
    };
    let records = match (args.hold_force, args.hold_creepage) {
        (Some(r), None) => transient_hold_force(&input, r)?,
        (None, Some(x)) => transient_hold_creepage(&input, Creepage::longitudinal(x))?,
        _ => return Err("give exactly one of --hold-force RATIO or --hold-creepage X".into()),
    };
    let mut w = CsvWriter::new(out, &["step", "rolled", "creepage", "fx_over_mu_p"])?;
    for r in records {
        w.row(&[&r.step, &r.rolled, &r.creepage, &r.fx_over_mu_p])?;
    }
    Ok(())
}

fn run_mindlin(args: &MindlinArgs, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    let c = args.contact.contact()?;
    // Quasi-identical pair: G* = G / (2 (2 - nu)) with Kalker's combined G, nu.
    let m = Mindlin::new(c.mu_p(), c.g() / (2.0 * (2.0 - c.nu())), c.a())?;
    if args.amplitude.is_nan() || args.amplitude <= 0.0 || args.amplitude > 1.0 {
        return Err(format!("--amplitude {} must be in (0, 1]", args.amplitude).into());
    }
    if !(1..=100_000).contains(&args.points) {
        return Err(format!("--points {} must be in [1, 100000]", args.points).into());
    }
    let qs = args.amplitude * c.mu_p();
    let k = args.points as f64;
    let mut w = CsvWriter::new(out, &["branch", "q_over_mu_p", "shift"])?;
    for i in 0..=args.points {
        let q = qs * i as f64 / k;
        w.row(&[&"loading", &(q / c.mu_p()), &m.loading_shift(q)?])?;
    }
    for i in 1..=args.points {
        let q = qs - 2.0 * qs * i as f64 / k;
        w.row(&[&"unloading", &(q / c.mu_p()), &m.unloading_shift(qs, q)?])?;
    }
    for i in 1..=args.points {
        let q = -qs + 2.0 * qs * i as f64 / k;
        w.row(&[&"reloading", &(q / c.mu_p()), &m.reloading_shift(qs, q)?])?;
    }
    Ok(())
}

fn run_carter(args: &CarterArgs, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    let c = Carter::new(args.a, args.r, args.mu)?;
    let mut w = CsvWriter::new(out, &["q_over_mu_p", "creepage", "stick_half_width_over_a"])?;
    for &s in &args.ratios {
        w.row(&[&s, &c.creepage(s)?, &Carter::stick_ratio(s)?])?;
    }
    Ok(())
}

/// Runs one `creep ref` subcommand, writing CSV to `out`.
pub fn run(cmd: &RefCommand, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    match cmd {
        RefCommand::Steady(a) => run_steady(a, out),
        RefCommand::Transient(a) => run_transient(a, out),
        RefCommand::Mindlin(a) => run_mindlin(a, out),
        RefCommand::Carter(a) => run_carter(a, out),
        RefCommand::Fit(FitCommand::Steady(a)) => run_fit_steady(a, out),
        RefCommand::Fit(FitCommand::Transient(a)) => run_fit_transient(a, out),
    }
}

/// Today's date (UTC) as `YYYY-MM-DD`, from the system clock (days-to-civil conversion of
/// Hinnant, "chrono-Compatible Low-Level Date Algorithms").
fn today() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0) as i64;
    let z = secs.div_euclid(86_400) + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}-{m:02}-{d:02}")
}

fn check_grid(grid: usize) -> Result<(), Box<dyn std::error::Error>> {
    if (8..=256).contains(&grid) {
        Ok(())
    } else {
        Err(format!("--grid {grid} must be in [8, 256]").into())
    }
}

fn write_to(
    path: &Option<std::path::PathBuf>,
    text: &str,
    out: &mut dyn Write,
) -> Result<(), Box<dyn std::error::Error>> {
    match path {
        Some(p) => crate::output::write(p, text)?,
        None => out.write_all(text.as_bytes())?,
    }
    Ok(())
}

fn run_fit_steady(
    args: &FitSteadyArgs,
    out: &mut dyn Write,
) -> Result<(), Box<dyn std::error::Error>> {
    use creep_reference::fit;
    if !(args.s_max > 0.5 && args.s_max < 1.0) {
        return Err(format!("--s-max {} must be in (0.5, 1)", args.s_max).into());
    }
    let (curves, source) = match &args.from {
        Some(path) => (
            fit::read_steady_csv(&std::fs::read_to_string(path)?)?,
            format!("read from {}", path.display()),
        ),
        None => {
            check_grid(args.grid)?;
            let mut nus = fit::FIT_NUS.to_vec();
            nus.extend(fit::CHECK_NUS);
            let c = fit::steady_curves(&nus, args.grid, args.threads)?;
            let flat: Vec<_> = c.into_iter().flatten().collect();
            let csv = format!(
                "# Steady rolling of the circular contact, boundary elements (creep-reference bem), normalised\n\
                 # units (a = G = mu P = 1). Grids N = {} and {}; `ext` = Richardson 2 f(N) - f(N/2).\n\
                 # Generated {} by: creep ref fit steady --grid {} --data FILE\n{}",
                args.grid / 2,
                args.grid,
                today(),
                args.grid,
                fit::steady_csv(&flat)
            );
            if let Some(p) = &args.data {
                crate::output::write(p, &csv)?;
            }
            (
                flat,
                format!("solved at N = {} and {}", args.grid / 2, args.grid),
            )
        }
    };
    let nodes: Vec<_> = fit::FIT_NUS
        .iter()
        .map(|nu| {
            curves
                .iter()
                .find(|c| c.grid == "ext" && c.nu == *nu)
                .cloned()
                .ok_or_else(|| format!("no extrapolated curve at node nu = {nu}"))
        })
        .collect::<Result<_, _>>()?;
    let f = fit::fit_steady(&nodes, args.s_max)?;
    let prov = format!(
        "Boundary-element curves {source}; fit and table generated {} by\n\
         `creep ref fit steady --from crates/reference/data/steady_bem.csv --out crates/law/src/steady_table.rs`\n\
         (the curves themselves: `creep ref fit steady --grid 64 --data crates/reference/data/steady_bem.csv`,\n\
         grids N = 32 and 64, Richardson extrapolation 2 f(64) - f(32) of C11, x_sat and the creepage at\n\
         each force ratio; Poisson-ratio nodes {:?}).",
        today(),
        fit::FIT_NUS
    );
    write_to(&args.out, &fit::rust_table(&f, &prov), out)
}

fn run_fit_transient(
    args: &FitTransientArgs,
    out: &mut dyn Write,
) -> Result<(), Box<dyn std::error::Error>> {
    use creep_reference::fit::{self, TransientCase};
    check_grid(args.grid)?;
    if !(args.dq > 0.0 && args.dq.is_finite()) {
        return Err(format!("--dq {} must be finite and > 0", args.dq).into());
    }
    if !(1..=100_000).contains(&args.steps) {
        return Err(format!("--steps {} must be in [1, 100000]", args.steps).into());
    }
    let cases: Vec<TransientCase> = [0.3, 0.6, 0.9]
        .iter()
        .map(|&r| TransientCase::HoldForce(r))
        .chain(
            [0.3, 0.6, 0.9]
                .iter()
                .map(|&r| TransientCase::HoldCreepage(r)),
        )
        .collect();
    let c = fit::transient_curves(
        &args.nu,
        &cases,
        args.grid,
        args.dq,
        args.steps,
        args.threads,
    )?;
    let flat: Vec<_> = c.into_iter().flatten().collect();
    let nus: Vec<String> = args.nu.iter().map(f64::to_string).collect();
    let csv = format!(
        "# Transient rolling from zero traction, boundary elements (creep-reference bem), normalised\n\
         # units (a = G = mu P = 1), rolled distance dq = {} a per step, grids N = {} and {}.\n\
         # Generated {} by: creep ref fit transient --grid {} --dq {} --steps {} --nu {}\n{}",
        args.dq,
        args.grid / 2,
        args.grid,
        today(),
        args.grid,
        args.dq,
        args.steps,
        nus.join(","),
        fit::transient_csv(&flat)
    );
    write_to(&args.out, &csv, out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Debug, Parser)]
    struct Wrapper {
        #[command(subcommand)]
        cmd: RefCommand,
    }

    fn run_args(args: &[&str]) -> Result<String, Box<dyn std::error::Error>> {
        let w = Wrapper::try_parse_from(std::iter::once("ref").chain(args.iter().copied()))?;
        let mut out = Vec::new();
        run(&w.cmd, &mut out)?;
        Ok(String::from_utf8(out)?)
    }

    const CONTACT: [&str; 10] = [
        "--a", "1e-4", "--p", "10", "--g", "80e9", "--nu", "0.3", "--mu", "0.3",
    ];

    fn with(cmd: &str, rest: &[&str]) -> Vec<String> {
        let mut v = vec![cmd.to_string()];
        v.extend(CONTACT.iter().map(|s| s.to_string()));
        v.extend(rest.iter().map(|s| s.to_string()));
        v
    }

    fn call(v: &[String]) -> Result<String, Box<dyn std::error::Error>> {
        run_args(&v.iter().map(String::as_str).collect::<Vec<_>>())
    }

    #[test]
    fn steady_prints_the_csv() {
        let s = call(&with(
            "steady",
            &["--creepage", "0,1e-4,-1e-4", "--grid", "8"],
        ))
        .unwrap();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines[0], "creepage,fx,fx_over_mu_p");
        assert_eq!(lines.len(), 4);
        let row: Vec<f64> = lines[2].split(',').map(|v| v.parse().unwrap()).collect();
        assert!(row[1] > 0.0 && (row[2] - row[1] / 3.0).abs() < 1e-12);
        let s = call(&with(
            "steady",
            &["--creepage", "1e-4", "--spin", "5", "--grid", "8"],
        ))
        .unwrap();
        assert!(s.starts_with("creepage,fx,fx_over_mu_p,lateral,spin,fy,mz\n"));
        let s = call(&with(
            "steady",
            &["--creepage", "1e-4", "--method", "fastsim"],
        ))
        .unwrap();
        assert_eq!(s.lines().count(), 2);
    }

    #[test]
    fn transient_mindlin_and_carter_print_their_csv() {
        let s = call(&with(
            "transient",
            &[
                "--hold-force",
                "0.5",
                "--step",
                "2.5e-5",
                "--steps",
                "3",
                "--grid",
                "8",
            ],
        ))
        .unwrap();
        let lines: Vec<&str> = s.lines().collect();
        assert_eq!(lines[0], "step,rolled,creepage,fx_over_mu_p");
        assert_eq!(lines.len(), 4);
        let ratio: f64 = lines[3].rsplit(',').next().unwrap().parse().unwrap();
        assert!((ratio - 0.5).abs() < 1e-6, "{ratio}");
        let s = call(&with("mindlin", &["--points", "2"])).unwrap();
        assert!(s.starts_with("branch,q_over_mu_p,shift\nloading,0,0\n"));
        assert_eq!(s.lines().count(), 1 + 3 + 2 + 2);
        let s = run_args(&[
            "carter", "--a", "1e-3", "--r", "0.05", "--mu", "0.3", "--ratios", "0,1",
        ])
        .unwrap();
        assert_eq!(
            s,
            "q_over_mu_p,creepage,stick_half_width_over_a\n0,0,1\n1,0.005999999999999999,0\n"
        );
    }

    #[test]
    fn fit_transient_and_refit_run_on_small_grids() {
        let s = run_args(&[
            "fit",
            "transient",
            "--grid",
            "8",
            "--dq",
            "0.25",
            "--steps",
            "2",
            "--nu",
            "0.25",
        ])
        .unwrap();
        let curves = creep_reference::fit::read_transient_csv(&s).unwrap();
        assert_eq!(curves.len(), 12);
        assert!(curves.iter().all(|c| c.rolled.len() == 2));
        // Refit from the checked-in steady curves reproduces the checked-in table's numbers.
        let data = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../reference/data/steady_bem.csv"
        );
        let table = run_args(&["fit", "steady", "--from", data]).unwrap();
        // Read at run time from the workspace (not `include_str!`, which would make the
        // published crate depend on a file outside it).
        let table_rs = concat!(env!("CARGO_MANIFEST_DIR"), "/../law/src/steady_table.rs");
        let checked_in = &std::fs::read_to_string(table_rs).unwrap();
        // Every number of the constants, in order (insensitive to rustfmt's layout).
        let consts = |t: &str| -> Vec<f64> {
            t.lines()
                .filter(|l| !l.trim_start().starts_with("//"))
                .flat_map(|l| {
                    l.split(|c: char| !(c.is_ascii_alphanumeric() || c == '.' || c == '-'))
                })
                .filter_map(|w| w.parse::<f64>().ok())
                .collect()
        };
        assert!(consts(checked_in).len() > 50);
        assert_eq!(consts(&table), consts(checked_in));
    }

    #[test]
    fn bad_inputs_are_errors_not_panics() {
        assert!(call(&with("steady", &["--creepage", "1e-4", "--grid", "2"])).is_err());
        assert!(
            call(&with(
                "steady",
                &["--creepage", "1e-4", "--lateral", "1,2,3"]
            ))
            .is_err()
        );
        assert!(call(&with("transient", &["--step", "1e-5", "--steps", "3"])).is_err());
        assert!(call(&with("mindlin", &["--amplitude", "1.5"])).is_err());
        assert!(run_args(&["fit", "steady", "--grid", "4"]).is_err());
        assert!(run_args(&["fit", "steady", "--s-max", "1.5"]).is_err());
        assert!(run_args(&["fit", "transient", "--dq", "0"]).is_err());
        let mut v = with("steady", &["--creepage", "1e-4"]);
        v[2] = "-1".into(); // a < 0
        assert!(call(&v).is_err());
    }
}
