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
    if extra {
        writeln!(out, "creepage,fx,fx_over_mu_p,lateral,spin,fy,mz")?;
    } else {
        writeln!(out, "creepage,fx,fx_over_mu_p")?;
    }
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
            writeln!(out, "{xi},{fx},{ratio},{},{},{fy},{mz}", c.lateral, c.spin)?;
        } else {
            writeln!(out, "{xi},{fx},{ratio}")?;
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
    writeln!(out, "step,rolled,creepage,fx_over_mu_p")?;
    for r in records {
        writeln!(
            out,
            "{},{},{},{}",
            r.step, r.rolled, r.creepage, r.fx_over_mu_p
        )?;
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
    writeln!(out, "branch,q_over_mu_p,shift")?;
    for i in 0..=args.points {
        let q = qs * i as f64 / k;
        writeln!(out, "loading,{},{}", q / c.mu_p(), m.loading_shift(q)?)?;
    }
    for i in 1..=args.points {
        let q = qs - 2.0 * qs * i as f64 / k;
        writeln!(
            out,
            "unloading,{},{}",
            q / c.mu_p(),
            m.unloading_shift(qs, q)?
        )?;
    }
    for i in 1..=args.points {
        let q = -qs + 2.0 * qs * i as f64 / k;
        writeln!(
            out,
            "reloading,{},{}",
            q / c.mu_p(),
            m.reloading_shift(qs, q)?
        )?;
    }
    Ok(())
}

fn run_carter(args: &CarterArgs, out: &mut dyn Write) -> Result<(), Box<dyn std::error::Error>> {
    let c = Carter::new(args.a, args.r, args.mu)?;
    writeln!(out, "q_over_mu_p,creepage,stick_half_width_over_a")?;
    for &s in &args.ratios {
        writeln!(out, "{s},{},{}", c.creepage(s)?, Carter::stick_ratio(s)?)?;
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
    }
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
        let mut v = with("steady", &["--creepage", "1e-4"]);
        v[2] = "-1".into(); // a < 0
        assert!(call(&v).is_err());
    }
}
