//! `creep triaxial [--quick] [--out DIR] [--config FILE]`: the talk's drained triaxial test
//! (creep-scenes `triaxial`), sheared with Coulomb-Mindlin and with creep-friction from the same
//! packing; writes CSVs, plots, a summary and the parameters it ran with (`params.toml`, which
//! `--config` reads back to repeat the run).

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Instant;

use creep_dem::dump::Snapshots;
use creep_dem::{Dem, Exact};
use creep_scenes::SceneError;
use creep_scenes::triaxial::{
    Boundary, CSV_HEADER, CompactionSummary, DemRun, GENERATOR, Outcome, Phase, RunError, RunHooks,
    ShearRun, ShearSummary, Specimen, TriaxialConfig, TriaxialEngine, TriaxialParams, compact,
    shear,
};

use crate::output::{self, Csv, create_dir};
use crate::plot::{LineChart, Series};
use crate::progress::bar;

type Res = Result<(), Box<dyn std::error::Error>>;

/// The built-in defaults (the repository's `crates/cli/assets/triaxial.toml`).
const DEFAULTS: &str = include_str!("../assets/triaxial.toml");

/// Arguments of `creep triaxial`.
#[derive(Debug, clap::Args)]
pub struct TriaxialArgs {
    /// Smoke-test size: 343 spheres, 10 % strain at I = 5e-3 (seconds; not quasi-static).
    #[arg(long)]
    quick: bool,
    /// Output directory (CSVs, SVG/PNG plots, SUMMARY.md, params.toml: the parameters used).
    #[arg(long, default_value = "triaxial")]
    out: PathBuf,
    /// Parameters file (TOML, the form of crates/cli/assets/triaxial.toml; keys not given keep
    /// its values, an unknown key is an error); default: the built-in copy of
    /// crates/cli/assets/triaxial.toml. A run's params.toml repeats that run.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Engine: `dem` (creep-dem, f64; the default) or `rapier` (the compliant regime);
    /// overrides the config file's `engine` key.
    #[arg(long)]
    engine: Option<String>,
    /// The shears' time step as a fraction (in (0, 0.3]) of the smallest ball's Rayleigh time;
    /// overrides the config file's `shear_rayleigh_fraction` (the compaction keeps
    /// `rayleigh_fraction`: docs/results/triaxial-timestep).
    #[arg(long)]
    shear_rayleigh_fraction: Option<f64>,
    /// Write snapshots into DIR: LAMMPS-style text dumps of the particles and of the contacts
    /// (OVITO, ParaView) and VTK .vtp files with .pvd series (ParaView), one subdirectory per
    /// phase (compaction, shear_coulomb, shear_creep). dem engine only.
    #[arg(long, value_name = "DIR")]
    dump: Option<PathBuf>,
    /// Steps between two snapshots (with --dump); each phase's last state is written too.
    #[arg(long, value_name = "N", default_value_t = 1000, requires = "dump")]
    dump_every: u64,
    /// Write a checkpoint (OUT/checkpoint.ckpt) every N steps, from which `--resume OUT`
    /// continues the run to the same results, bit for bit; one is always written on Ctrl-C.
    /// dem engine only.
    #[arg(long, value_name = "N")]
    checkpoint_every: Option<u64>,
    /// Continue the run stopped in DIR (its checkpoint.ckpt: the parameters, the phase, the
    /// engines with every contact history, the servo state, the rows so far); the results go to
    /// DIR.
    #[arg(long, value_name = "DIR", conflicts_with_all = ["quick", "config", "engine", "shear_rayleigh_fraction"])]
    resume: Option<PathBuf>,
    /// Testing: stop as Ctrl-C would (checkpoint, then exit with an error) at the first step
    /// boundary of PHASE (compaction, shear_coulomb or shear_creep) at or after engine step N
    /// (each shear's engine counts on from the compaction's last step).
    #[arg(long, value_name = "PHASE:N", hide = true)]
    stop_at: Option<String>,
}

/// The checkpoint's file name in the output directory.
pub const CHECKPOINT: &str = "checkpoint.ckpt";

/// Set by the Ctrl-C handler: the run checkpoints and stops at the next step boundary.
static INTERRUPTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Installs the Ctrl-C handler once per process.
fn catch_ctrl_c() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // Without a handler (another one installed first) Ctrl-C ends the process as usual.
        let _ = ctrlc::set_handler(|| {
            INTERRUPTED.store(true, std::sync::atomic::Ordering::SeqCst);
        });
    });
}

/// The configuration a run uses: the file (or the built-in defaults), then the flags
/// (`--engine` replaces the file's engine, `--quick` its size, rate, strain and rows).
fn config(args: &TriaxialArgs) -> Result<TriaxialConfig, Box<dyn std::error::Error>> {
    let text = match &args.config {
        Some(path) => {
            std::fs::read_to_string(path).map_err(|e| format!("reading {}: {e}", path.display()))?
        }
        None => DEFAULTS.to_string(),
    };
    let mut cfg = TriaxialConfig::from_toml(&text).map_err(|e| match &args.config {
        Some(path) => format!("{}: {e}", path.display()),
        None => e.to_string(),
    })?;
    if let Some(e) = &args.engine {
        cfg.engine = e.parse::<TriaxialEngine>()?;
    }
    if let Some(f) = args.shear_rayleigh_fraction {
        cfg.params.shear_rayleigh_fraction = f;
        cfg.params.validate()?;
    }
    if args.quick {
        let q = TriaxialParams::quick();
        let p = &mut cfg.params;
        p.n_per_side = q.n_per_side;
        p.inertial_number = q.inertial_number;
        p.axial_strain = q.axial_strain;
        p.rows_per_percent = q.rows_per_percent;
    }
    Ok(cfg)
}

/// `params.toml` of a run: the configuration it used, with the packing's generator named.
fn params_file(cfg: &TriaxialConfig) -> Result<String, Box<dyn std::error::Error>> {
    Ok(format!(
        "# The parameters of a `creep triaxial` run (SI units; --config reads this file to repeat\n\
         # the run). The packing's generator: {GENERATOR}, seeded with `seed`.\n\n{}",
        cfg.to_toml()?
    ))
}

/// Runs the test.
pub fn run(args: &TriaxialArgs, out: &mut dyn Write) -> Res {
    let (cfg, resumed, dir) = match &args.resume {
        Some(dir) => {
            let path = dir.join(CHECKPOINT);
            if !path.is_file() {
                return Err(format!(
                    "--resume {}: no {CHECKPOINT} there (a finished run removes it)",
                    dir.display()
                )
                .into());
            }
            let run = DemRun::load(&path)?;
            (*run.config(), Some(run), dir.clone())
        }
        None => (config(args)?, None, args.out.clone()),
    };
    let (engine, params) = (cfg.engine, cfg.params);
    if engine != TriaxialEngine::Dem && (args.dump.is_some() || args.checkpoint_every.is_some()) {
        return Err("--dump and --checkpoint-every need the dem engine".into());
    }
    if args.checkpoint_every == Some(0) {
        return Err("--checkpoint-every must be at least 1 step".into());
    }
    create_dir(&dir)?;
    // The parameters first: a run stopped half-way can still be repeated.
    output::write(&dir.join("params.toml"), &params_file(&cfg)?)?;
    let n = params.n_per_side.pow(3);
    let header = header(engine, &params);
    writeln!(out, "{header}")?;
    if args.quick {
        writeln!(
            out,
            "--quick: a smoke test (inertial number above the quasi-static 1e-3), not a result"
        )?;
    }
    let lines = vec![header.clone(), String::new()];
    match engine {
        TriaxialEngine::Dem => run_dem(args, &cfg, resumed, &dir, lines, n, out),
        TriaxialEngine::Rapier => run_rapier(params, &dir, lines, n, out),
    }
}

/// The header of the summary.
fn header(engine: TriaxialEngine, params: &TriaxialParams) -> String {
    let n = params.n_per_side.pow(3);
    let m = params.material;
    format!(
        "Drained triaxial compression, engine {} ({}), Coulomb-Mindlin vs creep-friction\n\
         {n} spheres, radius uniform in [{:.3e}, {:.3e}] m; G = {:.3e} Pa, nu = {}, rho = {} kg/m^3, mu = {}, e = {}\n\
         confining pressure {:.3e} Pa; axial strain rate {:.4} 1/s (inertial number {:.1e}) to {} % strain; dt = {:.3e} s ({} T_R) in the compaction, {:.3e} s ({} T_R) in the shears\n\
         packing generator {GENERATOR}, seed {}",
        engine.name(),
        match engine {
            TriaxialEngine::Dem => "creep-dem, f64",
            TriaxialEngine::Rapier => "the compliant regime of creep-rapier",
        },
        params.radius * (1.0 - params.radius_spread),
        params.radius * (1.0 + params.radius_spread),
        m.shear_modulus(),
        m.poisson_ratio(),
        m.density(),
        params.mu,
        params.restitution,
        params.confining_pressure,
        params.strain_rate(),
        params.inertial_number,
        params.axial_strain * 100.0,
        params.time_step(),
        params.rayleigh_fraction,
        params.shear_time_step(),
        params.shear_rayleigh_fraction,
        params.seed,
    )
}

/// The line of the compaction's summary.
fn compaction_line(summary: &CompactionSummary, secs: f64, cpu: Option<f64>, n: usize) -> String {
    format!(
        "Compaction (frictionless): {} steps in {secs:.1} s ({:.3e} particle-steps/s; CPU {}{}); solid fraction {:.4}, coordination {:.2}; p from walls {:.4e} Pa, from contacts {:.4e} Pa ({:+.2} %)",
        summary.steps,
        n as f64 * summary.steps as f64 / secs,
        cpu_text(cpu),
        rebuilds_text(summary.rebuilds),
        summary.solid_fraction,
        summary.coordination,
        summary.p_walls,
        summary.p_contacts,
        (summary.p_contacts / summary.p_walls - 1.0) * 100.0
    )
}

/// The test on the Rapier compliant regime (no snapshots, no checkpoints).
fn run_rapier(
    params: TriaxialParams,
    dir: &Path,
    mut lines: Vec<String>,
    n: usize,
    out: &mut dyn Write,
) -> Res {
    let t0 = Instant::now();
    let c0 = cpu_seconds();
    let pb = bar(1000, "isotropic compaction");
    let mut s = Specimen::generate(params)?;
    let summary = compact(&mut s, 2_000_000, &mut |f| {
        pb.set_position((f * 1000.0) as u64)
    })?;
    pb.finish();
    lines.push(compaction_line(
        &summary,
        t0.elapsed().as_secs_f64(),
        cpu_since(c0),
        n,
    ));
    writeln!(out, "{}", lines.last().unwrap_or(&String::new()))?;
    let mut runs: Vec<(ShearRun, f64)> = Vec::new();
    let mut cpus: Vec<Option<f64>> = Vec::new();
    for creep in [false, true] {
        let pb = bar(1000, shear_label(creep));
        let t = Instant::now();
        let c = cpu_seconds();
        let run = shear(&s, creep, &mut |f| pb.set_position((f * 1000.0) as u64))?;
        pb.finish();
        let secs = t.elapsed().as_secs_f64();
        cpus.push(cpu_since(c));
        write_csv(&dir.join(csv_name(creep)), &run.rows)?;
        runs.push((run, secs));
    }
    report(dir, lines, &runs, &cpus, n, out)
}

fn shear_label(creep: bool) -> &'static str {
    if creep {
        "shear, creep-friction"
    } else {
        "shear, Coulomb-Mindlin"
    }
}

fn csv_name(creep: bool) -> &'static str {
    if creep {
        "triaxial_creep.csv"
    } else {
        "triaxial_coulomb.csv"
    }
}

/// The test on creep-dem as one resumable run ([`DemRun`]): snapshots, checkpoints, Ctrl-C.
fn run_dem(
    args: &TriaxialArgs,
    cfg: &TriaxialConfig,
    resumed: Option<DemRun>,
    dir: &Path,
    mut lines: Vec<String>,
    n: usize,
    out: &mut dyn Write,
) -> Res {
    let resuming = resumed.is_some();
    let mut run = match resumed {
        Some(run) => {
            writeln!(
                out,
                "resuming from {} in the {} at step {}",
                dir.join(CHECKPOINT).display(),
                run.phase().map_or("finished run", |p| p.name()),
                run.engine_steps()
            )?;
            run
        }
        None => DemRun::new(*cfg, 2_000_000)?,
    };
    catch_ctrl_c();
    let checkpoint = dir.join(CHECKPOINT);
    // Shared by the boundary (every snapshot) and the phase's end (its last state).
    let snaps: std::cell::RefCell<Option<(Phase, Snapshots)>> = std::cell::RefCell::new(None);
    let dump_dir = args.dump.clone();
    let dump_every = args.dump_every;
    let every = args.checkpoint_every;
    let stop_at = match &args.stop_at {
        None => None,
        Some(text) => {
            let parsed = text.split_once(':').and_then(|(phase, n)| {
                let phase = [
                    Phase::Compaction,
                    Phase::Shear { creep: false },
                    Phase::Shear { creep: true },
                ]
                .into_iter()
                .find(|p| p.name() == phase)?;
                Some((phase, n.parse::<u64>().ok()?))
            });
            Some(parsed.ok_or_else(|| {
                format!("--stop-at {text}: expected PHASE:STEP, PHASE one of compaction, shear_coulomb, shear_creep")
            })?)
        }
    };
    let mut bars: Option<(Phase, indicatif::ProgressBar)> = None;
    let mut progress = |phase: Phase, f: f64| {
        if bars.as_ref().map(|b| b.0) != Some(phase) {
            if let Some((_, pb)) = bars.take() {
                pb.finish();
            }
            let label = match phase {
                Phase::Compaction => "isotropic compaction",
                Phase::Shear { creep } => shear_label(creep),
            };
            bars = Some((phase, bar(1000, label)));
        }
        if let Some((_, pb)) = &bars {
            pb.set_position((f * 1000.0) as u64);
        }
    };
    let mut boundary = |phase: Phase, dem: &Dem<Exact>| -> Result<Boundary, RunError> {
        if let Some(root) = &dump_dir {
            let mut snaps = snaps.borrow_mut();
            if snaps.as_ref().map(|s| s.0) != Some(phase) {
                let s = Snapshots::new(root.join(phase.name()), dump_every)
                    .and_then(|s| if resuming { s.adopt_existing() } else { Ok(s) })
                    .map_err(|e| SceneError::Parameter(format!("--dump: {e}")))?;
                *snaps = Some((phase, s));
            }
            if let Some((_, s)) = snaps.as_mut() {
                s.maybe_write(dem)
                    .map_err(|e| SceneError::Parameter(format!("--dump: {e}")))?;
            }
        }
        let steps = dem.steps();
        if INTERRUPTED.load(std::sync::atomic::Ordering::SeqCst)
            || stop_at.is_some_and(|(p, s)| p == phase && steps >= s)
        {
            return Ok(Boundary::Stop);
        }
        Ok(match every {
            Some(k) if steps > 0 && steps.is_multiple_of(k) => Boundary::Checkpoint,
            _ => Boundary::Continue,
        })
    };
    let mut phase_done = |phase: Phase, dem: &Dem<Exact>, run: &DemRun| -> Result<(), RunError> {
        if let Some((p, s)) = snaps.borrow_mut().as_mut()
            && *p == phase
            && s.written().last() != Some(dem.steps())
        {
            s.write(dem)
                .map_err(|e| SceneError::Parameter(format!("--dump: {e}")))?;
        }
        if let Phase::Shear { creep } = phase
            && let Some(r) = run.shears().last()
        {
            write_csv(&dir.join(csv_name(creep)), &r.rows)
                .map_err(|e| SceneError::Parameter(e.to_string()))?;
        }
        Ok(())
    };
    let t0 = Instant::now();
    let mut clock = || {
        [
            t0.elapsed().as_secs_f64(),
            cpu_seconds().unwrap_or(f64::NAN),
        ]
    };
    let outcome = run.run(&mut RunHooks {
        progress: &mut progress,
        boundary: &mut boundary,
        phase_done: &mut phase_done,
        clock: &mut clock,
        checkpoint: Some(&checkpoint),
    })?;
    if let Some((_, pb)) = bars.take() {
        pb.finish();
    }
    if let Outcome::Stopped { phase, steps } = outcome {
        return Err(format!(
            "stopped in the {} at step {steps}; the checkpoint is {}: `creep triaxial --resume {}` continues the run",
            phase.name(),
            checkpoint.display(),
            dir.display()
        )
        .into());
    }
    let secs = run.seconds;
    let cpu = |k: usize| Some(secs[k][1]).filter(|c| c.is_finite());
    let summary = run
        .compaction()
        .ok_or("the run finished without a compaction")?;
    lines.push(compaction_line(summary, secs[0][0], cpu(0), n));
    writeln!(out, "{}", lines.last().unwrap_or(&String::new()))?;
    let runs: Vec<(ShearRun, f64)> = run
        .shears()
        .iter()
        .enumerate()
        .map(|(k, r)| (r.clone(), secs[k + 1][0]))
        .collect();
    let cpus = vec![cpu(1), cpu(2)];
    report(dir, lines, &runs, &cpus, n, out)?;
    if checkpoint.is_file() {
        std::fs::remove_file(&checkpoint)
            .map_err(|e| format!("removing {}: {e}", checkpoint.display()))?;
    }
    Ok(())
}

/// The shears' table, SUMMARY.md and the plots.
fn report(
    dir: &Path,
    mut lines: Vec<String>,
    runs: &[(ShearRun, f64)],
    cpus: &[Option<f64>],
    n: usize,
    out: &mut dyn Write,
) -> Res {
    if runs.len() != 2 || cpus.len() != 2 {
        return Err("the report needs both shears".into());
    }
    let sums: Vec<ShearSummary> = runs.iter().map(|(r, _)| r.summary()).collect();
    lines.push(String::new());
    lines.push("| | Coulomb-Mindlin | creep-friction |".into());
    lines.push("|---|---|---|".into());
    let row = |name: &str, f: &dyn Fn(&ShearSummary) -> String| {
        format!("| {name} | {} | {} |", f(&sums[0]), f(&sums[1]))
    };
    lines.push(row("peak q/p", &|s| format!("{:.4}", s.peak_q_over_p)));
    lines.push(row("peak friction angle [deg]", &|s| {
        format!("{:.2}", s.peak_friction_angle_deg)
    }));
    lines.push(row("axial strain at peak [%]", &|s| {
        format!("{:.2}", s.peak_axial_strain * 100.0)
    }));
    lines.push(row("max dilatancy rate -d eps_v/d eps_a", &|s| {
        format!("{:.4}", s.max_dilatancy_rate)
    }));
    lines.push(row("dilatancy angle [deg]", &|s| {
        format!("{:.2}", s.dilatancy_angle_deg)
    }));
    lines.push(row("final volumetric strain [%]", &|s| {
        format!("{:.3}", s.final_volumetric_strain * 100.0)
    }));
    lines.push(row("final q/p", &|s| format!("{:.4}", s.final_q_over_p)));
    lines.push(row(
        "share of contacts sliding / rolling / creeping",
        &|s| {
            format!(
                "{:.3} / {:.3} / {:.3}",
                s.mean_shares[0], s.mean_shares[1], s.mean_shares[2]
            )
        },
    ));
    let run_row = |name: &str, f: &dyn Fn(&ShearRun, f64) -> String| {
        format!(
            "| {name} | {} | {} |",
            f(&runs[0].0, runs[0].1),
            f(&runs[1].0, runs[1].1)
        )
    };
    lines.push(run_row(
        "contact vs wall stress, largest gap [%]",
        &|r, _| format!("{:.2}", r.max_stress_mismatch * 100.0),
    ));
    lines.push(run_row("energy dissipated by slip / creep [J]", &|r, _| {
        format!("{:.3e} / {:.3e}", r.slip_dissipation, r.creep_dissipation)
    }));
    lines.push(run_row("steps, run time", &|r, secs| {
        format!("{}, {secs:.1} s", r.steps)
    }));
    lines.push(run_row("particle-steps per second", &|r, secs| {
        format!("{:.3e}", n as f64 * r.steps as f64 / secs)
    }));
    lines.push(format!(
        "| CPU time (this thread), neighbour-list rebuilds | {}{} | {}{} |",
        cpu_text(cpus[0]),
        rebuilds_text(runs[0].0.rebuilds),
        cpu_text(cpus[1]),
        rebuilds_text(runs[1].0.rebuilds)
    ));
    let d_phi = sums[1].peak_friction_angle_deg - sums[0].peak_friction_angle_deg;
    let d_psi = sums[1].dilatancy_angle_deg - sums[0].dilatancy_angle_deg;
    lines.push(String::new());
    lines.push(format!(
        "Creep-friction changes the peak friction angle by {d_phi:+.2} deg and the dilatancy angle by {d_psi:+.2} deg (the talk: \"a minimal effect of creep-friction\" in a dense packing)."
    ));
    for l in &lines[lines.len() - 17..] {
        writeln!(out, "{l}")?;
    }
    output::write(&dir.join("SUMMARY.md"), &(lines.join("\n") + "\n"))?;
    plots(dir, runs)?;
    writeln!(
        out,
        "wrote {}/{{triaxial_coulomb.csv, triaxial_creep.csv, SUMMARY.md, params.toml, triaxial_q_over_p.*, triaxial_volumetric.*, triaxial_contacts.*}}",
        dir.display()
    )?;
    Ok(())
}

/// CPU time of this thread so far \[s\] (Linux: the first field of
/// `/proc/thread-self/schedstat`, nanoseconds on a CPU); `None` where that file is missing.
/// The runs are single-threaded, so it is the run's CPU time, whatever else loads the machine.
fn cpu_seconds() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// CPU seconds since `start` (a [`cpu_seconds`] reading).
fn cpu_since(start: Option<f64>) -> Option<f64> {
    Some(cpu_seconds()? - start?)
}

fn cpu_text(cpu: Option<f64>) -> String {
    cpu.map_or_else(|| "n/a".into(), |c| format!("{c:.1} s"))
}

fn rebuilds_text(rebuilds: Option<usize>) -> String {
    rebuilds.map_or_else(String::new, |r| format!(", {r} rebuilds"))
}

/// A shear's rows as CSV: the scene's columns ([`CSV_HEADER`]) and number formats
/// (`TriaxialRow::csv`, numbers only), through the CLI's one CSV writer.
fn write_csv(path: &Path, rows: &[creep_scenes::triaxial::TriaxialRow]) -> Res {
    let header: Vec<&str> = CSV_HEADER.split(',').collect();
    let mut csv = Csv::new(&header);
    for r in rows {
        let line = r.csv();
        let parts: Vec<&str> = line.split(',').collect();
        let fields: Vec<&dyn std::fmt::Display> =
            parts.iter().map(|f| f as &dyn std::fmt::Display).collect();
        csv.row(&fields);
    }
    csv.write(path)?;
    Ok(())
}

fn plots(dir: &Path, runs: &[(ShearRun, f64)]) -> Res {
    let label = |r: &ShearRun| {
        if r.creep {
            "creep-friction"
        } else {
            "Coulomb-Mindlin"
        }
    };
    let curve = |r: &ShearRun, f: &dyn Fn(&creep_scenes::triaxial::TriaxialRow) -> f64| {
        r.rows
            .iter()
            .filter(|row| row.axial_strain > 0.0)
            .map(|row| (row.axial_strain * 100.0, f(row)))
            .collect::<Vec<_>>()
    };
    let mut q = LineChart::new(
        "Drained triaxial compression: stress ratio",
        "axial strain [%]",
        "q / p [-]",
    );
    let mut v = LineChart::new(
        "Drained triaxial compression: volume change",
        "axial strain [%]",
        "volumetric strain [%] (compression positive)",
    );
    let mut c = LineChart::new(
        "Ball-ball contacts by state",
        "axial strain [%]",
        "share of contacts [-]",
    );
    for (i, (r, _)) in runs.iter().enumerate() {
        let mut s = Series::line(label(r), curve(r, &|row| row.q_over_p)).color(i);
        let mut sv =
            Series::line(label(r), curve(r, &|row| row.volumetric_strain * 100.0)).color(i);
        if r.creep {
            s = s.dashed();
            sv = sv.dashed();
        }
        q = q.series(s);
        v = v.series(sv);
        let tag = if r.creep { "creep" } else { "Coulomb" };
        c = c.series(
            Series::line(
                format!("sliding ({tag})"),
                curve(r, &|row| row.share_sliding),
            )
            .color(0),
        );
        c = c.series(
            Series::line(
                format!("rolling ({tag})"),
                curve(r, &|row| row.share_rolling),
            )
            .color(1),
        );
        if r.creep {
            c = c.series(
                Series::line("creeping (creep)", curve(r, &|row| row.share_creeping)).color(2),
            );
        }
    }
    // Dashed for the creep run in the contacts chart too.
    c.series = c
        .series
        .into_iter()
        .map(|s| {
            if s.name.contains("(creep)") {
                s.dashed()
            } else {
                s
            }
        })
        .collect();
    q.write(&dir.join("triaxial_q_over_p"))?;
    v.write(&dir.join("triaxial_volumetric"))?;
    c.write(&dir.join("triaxial_contacts"))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(config: Option<PathBuf>, quick: bool, engine: Option<&str>) -> TriaxialArgs {
        TriaxialArgs {
            quick,
            out: PathBuf::from("unused"),
            config,
            engine: engine.map(String::from),
            shear_rayleigh_fraction: None,
            dump: None,
            dump_every: 1000,
            checkpoint_every: None,
            resume: None,
            stop_at: None,
        }
    }

    /// `--shear-rayleigh-fraction` replaces the file's key, range-checked before anything runs.
    #[test]
    fn the_shear_step_flag_overrides_the_file() {
        let a = TriaxialArgs {
            shear_rayleigh_fraction: Some(0.25),
            ..args(None, false, None)
        };
        let cfg = config(&a).unwrap();
        assert_eq!(cfg.params.shear_rayleigh_fraction, 0.25);
        assert_eq!(
            cfg.params.rayleigh_fraction,
            TriaxialParams::default().rayleigh_fraction
        );
        let text = params_file(&cfg).unwrap();
        assert!(text.contains("shear_rayleigh_fraction = 0.25"), "{text}");
        for f in [0.5, 0.0, f64::NAN] {
            let a = TriaxialArgs {
                shear_rayleigh_fraction: Some(f),
                ..args(None, false, None)
            };
            let e = config(&a).unwrap_err();
            assert!(
                e.to_string().contains("shear_rayleigh_fraction"),
                "{f}: {e}"
            );
        }
    }

    /// The flags override the file, and the params.toml a run writes reads back (through
    /// `--config`) to the same configuration, so the run can be repeated.
    #[test]
    fn params_toml_repeats_the_run() {
        let cfg = config(&args(None, true, Some("dem"))).unwrap();
        assert_eq!(cfg.engine, TriaxialEngine::Dem);
        assert_eq!(cfg.params.n_per_side, TriaxialParams::quick().n_per_side);
        assert_eq!(cfg.params.seed, TriaxialParams::default().seed);
        let text = params_file(&cfg).unwrap();
        assert!(text.contains(GENERATOR), "{text}");
        assert!(text.contains("seed = 2011"), "{text}");

        let dir =
            std::env::temp_dir().join(format!("creep-triaxial-params-{}", std::process::id()));
        create_dir(&dir).unwrap();
        let path = dir.join("params.toml");
        output::write(&path, &text).unwrap();
        assert_eq!(config(&args(Some(path.clone()), false, None)).unwrap(), cfg);
        // Without the flags the defaults file gives the defaults (and the dem engine).
        let plain = config(&args(None, false, None)).unwrap();
        assert_eq!(plain, TriaxialConfig::default());

        // An unknown key in a file is an error naming the key and the file.
        output::write(&path, "colour = \"blue\"\n").unwrap();
        let e = config(&args(Some(path.clone()), false, None)).unwrap_err();
        assert!(e.to_string().contains("colour"), "{e}");
        assert!(e.to_string().contains("params.toml"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The shear CSV keeps the scene's header and row format through the CSV writer.
    #[test]
    fn shear_csv_is_the_scenes_header_and_rows() {
        let row = creep_scenes::triaxial::TriaxialRow {
            axial_strain: 0.01,
            q_over_p: 0.5,
            contacts: 12,
            ..Default::default()
        };
        let dir = std::env::temp_dir().join(format!("creep-triaxial-csv-{}", std::process::id()));
        create_dir(&dir).unwrap();
        let path = dir.join("run.csv");
        write_csv(&path, &[row, row]).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let expected = format!("{CSV_HEADER}\n{}\n{}\n", row.csv(), row.csv());
        assert_eq!(text, expected);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
