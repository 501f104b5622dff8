//! `creep figure ...`: the talk's figures, written as CSV, SVG and PNG into a directory, with the
//! numbers behind them printed as tables.

use crate::output::{Csv, create_dir};
use crate::plot::{Legend, LineChart, LineStyle, Series};
use crate::progress::bar as progress;
use clap::{Args, Subcommand};
use creep_reference::parallel::parallel_map;
use creep_scenes::rolling_effect::{
    CompliantPath, CreepEffect, Curve, RATIOS, RollingEffect, RollingEffectConfig,
};
use indicatif::ProgressBar;
use std::io::Write;
use std::path::PathBuf;

type Res = Result<(), Box<dyn std::error::Error>>;

/// Figures of the talk, as CSV + SVG + PNG.
#[derive(Debug, Subcommand)]
pub enum FigureCommand {
    /// "Effect of rolling upon tangential force": Q/(mu P) against the sliding displacement
    /// delta G a/(mu P) of a Hertz contact that rolls r times as far as it slides, for
    /// r = 0, 1, 2, 5, 10, 20, 50, by the exact theory (transient boundary elements) and by
    /// Kuhn's rule, and Kuhn's rule run by the Rapier compliant regime on two balls driven
    /// kinematically. Writes rolling_effect.{csv,svg,png} and
    /// rolling_effect_error.{csv,svg,png}.
    RollingEffect(RollingEffectArgs),
}

/// Arguments of `creep figure rolling-effect`.
#[derive(Debug, Args)]
pub struct RollingEffectArgs {
    /// Output directory (created if missing).
    #[arg(long, default_value = "figures")]
    out: PathBuf,
    /// Boundary-element grid N: elements across the contact diameter, in [4, 256]. Cost per
    /// step grows as N^5 (32: about 0.05 s).
    #[arg(long, default_value_t = 32)]
    grid: usize,
    /// Recorded steps per path (each one or more boundary-element solves, rolling at most one
    /// element per solve), in [1, 100000].
    #[arg(long, default_value_t = 200)]
    steps: usize,
    /// Normal force P [N] (two glass spheres: G = 29 GPa, nu = 0.23, mu = 0.5).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    p: f64,
    /// Radius of each sphere [m].
    #[arg(long, default_value_t = 1e-3, allow_negative_numbers = true)]
    radius: f64,
    /// End of the paths, in delta G a/(mu P) (Cattaneo-Mindlin saturates at 0.66).
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    end: f64,
    /// Also measure the convergence of the exact curves: the r = 0 and r = 50 paths on the grid
    /// 2N (slow: a step on 2N costs about 30 times one on N), and the r = 50 path with twice
    /// the steps.
    #[arg(long)]
    check_grid: bool,
    /// More ratios r, computed for the table of the creep effect and the error plot only (not
    /// drawn in the figure); `--extra-ratios` with no value for none.
    #[arg(long, value_delimiter = ',', num_args = 0.., default_value = "30,70,100,150,200")]
    extra_ratios: Vec<f64>,
    /// Worker threads (one path per thread at a time), >= 1.
    #[arg(long, default_value_t = 2)]
    threads: usize,
}

/// Runs a `creep figure` command, printing its tables to `out`.
pub fn run(cmd: &FigureCommand, out: &mut dyn Write) -> Res {
    match cmd {
        FigureCommand::RollingEffect(args) => rolling_effect(args, out),
    }
}

/// Every path of `fig`, `threads` at a time; the progress bar advances per boundary-element
/// step.
fn run_paths(
    fig: &RollingEffect,
    ratios: &[f64],
    grid: usize,
    threads: usize,
    pb: &ProgressBar,
) -> Result<Vec<Curve>, Box<dyn std::error::Error>> {
    // The longest paths (largest r: most sub-steps) first, for load balance.
    let mut order: Vec<usize> = (0..ratios.len()).collect();
    order.sort_by(|&i, &j| ratios[j].total_cmp(&ratios[i]));
    let done = parallel_map(&order, threads, |&i| {
        let r = ratios[i];
        let mut tick = || pb.inc(1);
        let exact = fig.exact_path(r, grid, &mut tick)?;
        Ok::<_, creep_scenes::rolling_effect::RollingEffectError>((
            i,
            Curve {
                r,
                delta: fig.deltas(),
                exact,
                kuhn: fig.kuhn_path(r)?,
            },
        ))
    })?;
    // Back into the order of `ratios`.
    let mut curves: Vec<Option<Curve>> = (0..ratios.len()).map(|_| None).collect();
    for (i, c) in done {
        curves[i] = Some(c);
    }
    Ok(curves.into_iter().flatten().collect())
}

fn rolling_effect(args: &RollingEffectArgs, out: &mut dyn Write) -> Res {
    if args.threads == 0 {
        return Err("--threads must be >= 1".into());
    }
    let mut ratios = RATIOS.to_vec();
    for &r in &args.extra_ratios {
        if !ratios.contains(&r) {
            ratios.push(r);
        }
    }
    ratios.sort_by(f64::total_cmp);
    let config = RollingEffectConfig {
        ratios,
        radius: args.radius,
        normal_force: args.p,
        end: args.end,
        steps: args.steps,
        grid: args.grid,
        ..Default::default()
    };
    if !(args.radius.is_finite() && args.radius > 0.0) {
        return Err(format!("--radius must be finite and > 0, got {}", args.radius).into());
    }
    let fig = RollingEffect::new(config)?;
    let ratios = fig.config().ratios.clone();
    create_dir(&args.out)?;

    let m = fig.config().material;
    let c = fig.contact();
    writeln!(
        out,
        "Effect of rolling upon tangential force (Kuhn 2011): two glass spheres R = {} m, \
         G = {:.3e} Pa, nu = {}, mu = {}, P = {} N",
        args.radius,
        m.shear_modulus(),
        m.poisson_ratio(),
        m.friction(),
        args.p
    )?;
    writeln!(
        out,
        "Hertz a = {:.4e} m, p0 = {:.4e} Pa, epsilon = mu P/(G a^2) = {:.5}; Mindlin saturates \
         at delta G a/(mu P) = {:.4}; paths to {} in {} steps; exact: transient BEM N = {}",
        c.a(),
        c.p0(),
        fig.epsilon(),
        fig.mindlin_saturation(),
        args.end,
        args.steps,
        args.grid
    )?;

    let pb = progress((ratios.len() * args.steps) as u64, "exact paths");
    let t0 = std::time::Instant::now();
    let curves = run_paths(&fig, &ratios, args.grid, args.threads, &pb)?;
    pb.finish_and_clear();
    writeln!(
        out,
        "{} paths x {} steps in {:.1} s",
        ratios.len(),
        args.steps,
        t0.elapsed().as_secs_f64()
    )?;

    // The same paths through the Rapier compliant regime (Kuhn's rule from the engine's
    // poses and velocities), on the Kuhn path's increments.
    let t0 = std::time::Instant::now();
    let engine = curves
        .iter()
        .map(|cv| fig.compliant_path(cv.r))
        .collect::<Result<Vec<CompliantPath>, _>>()?;
    if let Some(e) = engine.first() {
        let engine_steps = args.steps * fig.config().kuhn_substeps;
        writeln!(
            out,
            "Rapier compliant regime: {} paths x {engine_steps} engine steps in {:.1} s; \
             dt = {:.4e} s (0.1 T_R), overlap {:.7e} m (f32 centres), P = {:.7} N \
             (Hertz at that overlap: {:+.2e} of P)",
            engine.len(),
            t0.elapsed().as_secs_f64(),
            e.dt,
            e.overlap,
            e.normal_force,
            e.normal_force / args.p - 1.0
        )?;
    }

    // The curves.
    let csv = args.out.join("rolling_effect.csv");
    let mut s = Csv::new(&["r", "source", "delta_normalised", "q_over_mu_p"]);
    for (cv, en) in curves.iter().zip(&engine) {
        for (source, delta, q) in [
            ("exact", &cv.delta, &cv.exact),
            ("kuhn", &cv.delta, &cv.kuhn),
            ("engine", &en.delta, &en.q),
        ] {
            for (d, q) in delta.iter().zip(q.iter()) {
                s.row(&[
                    &cv.r,
                    &source,
                    &format_args!("{d:.6}"),
                    &format_args!("{q:.8}"),
                ]);
            }
        }
    }
    s.write(&csv)?;
    let mut chart = LineChart::new(
        "Effect of rolling upon tangential force",
        "sliding displacement  \u{3b4} G a / (\u{3bc} P)",
        "Q / (\u{3bc} P)",
    )
    .x_range(0.0, args.end)
    .y_range(0.0, 1.05)
    .legend(Legend::LowerRight);
    // The engine's curve as dots on every `dot`-th record (it lies on the dashed one), each
    // curve's dots shifted by a fraction of `dot` so that they do not pile up near the origin.
    let dot = (args.steps / 20).max(1);
    let drawn = curves
        .iter()
        .zip(&engine)
        .filter(|(c, _)| RATIOS.contains(&c.r));
    for (i, (cv, en)) in drawn.enumerate() {
        let pts = |q: &[f64]| cv.delta.iter().copied().zip(q.iter().copied()).collect();
        let dots = en
            .delta
            .iter()
            .copied()
            .zip(en.q.iter().copied())
            .skip(i * dot / RATIOS.len())
            .step_by(dot)
            .collect();
        chart = chart
            .series(Series::line(format!("r = {}", cv.r), pts(&cv.exact)).color(i + 1))
            .series(Series::line("", pts(&cv.kuhn)).color(i + 1).dashed())
            .series(
                Series::line("", dots)
                    .color(i + 1)
                    .style(LineStyle::None)
                    .markers(),
            );
    }
    chart = chart
        .series(Series::line("exact (boundary elements)", vec![]))
        .series(Series::line("Kuhn's rule", vec![]).dashed())
        .series(
            Series::line("Kuhn's rule in Rapier (compliant)", vec![])
                .style(LineStyle::None)
                .markers(),
        );
    let [svg, png] = chart.write(&args.out.join("rolling_effect"))?;

    // Steady limits and the error of Kuhn's rule.
    writeln!(out)?;
    writeln!(
        out,
        "Q/(mu P) at the path's end, and steady rolling at creepage 1/r (exact: steady BEM N = {})",
        args.grid
    )?;
    writeln!(
        out,
        "{:>5} {:>10} {:>10} {:>10} {:>10} {:>10} | Kuhn - exact: {:>8} {:>8} {:>8} | \
         engine - Kuhn: {:>8} {:>8} at P': {:>8}",
        "r",
        "rolled/a",
        "end exact",
        "end Kuhn",
        "ss exact",
        "ss Kuhn",
        "max",
        "RMS",
        "end",
        "max",
        "end",
        "max"
    )?;
    let mut err_csv = Csv::new(&[
        "r",
        "max_error",
        "rms_error",
        "end_error",
        "end_exact",
        "end_kuhn",
        "steady_exact",
        "steady_kuhn",
        "engine_max_error",
        "engine_rms_error",
        "engine_end_error",
        "end_engine",
        "engine_max_error_at_engine_p",
    ]);
    let mut max_pts = Vec::new();
    let mut rms_pts = Vec::new();
    let (mut engine_worst, mut coupling_worst) = (0.0f64, 0.0f64);
    for (cv, en) in curves.iter().zip(&engine) {
        let e = cv.error();
        let ee = en.error_against(&cv.kuhn);
        // Kuhn's rule at the engine's P (its f32 overlap's Hertz force): the rest of the coupling.
        let coupling = en
            .error_against(&fig.kuhn_path_at(cv.r, en.normal_force)?)
            .max;
        engine_worst = engine_worst.max(ee.max);
        coupling_worst = coupling_worst.max(coupling);
        let (ss_exact, ss_kuhn) = if cv.r > 0.0 {
            fig.steady(cv.r, args.grid)?
        } else {
            (f64::NAN, f64::NAN)
        };
        let (end_e, end_k) = (
            *cv.exact.last().unwrap_or(&0.0),
            *cv.kuhn.last().unwrap_or(&0.0),
        );
        let rolled = cv.r * args.end * fig.epsilon();
        writeln!(
            out,
            "{:>5} {:>10.3} {:>10.4} {:>10.4} {:>10.4} {:>10.4} | {:>22.4} {:>8.4} {:>8.4} | \
             {:>23.1e} {:>8.1e} {:>14.1e}",
            cv.r,
            rolled,
            end_e,
            end_k,
            ss_exact,
            ss_kuhn,
            e.max,
            e.rms,
            e.end,
            ee.max,
            ee.end,
            coupling
        )?;
        // No steady state without rolling: empty fields.
        let opt = |v: f64| {
            if v.is_finite() {
                format!("{v:.6}")
            } else {
                String::new()
            }
        };
        err_csv.row(&[
            &cv.r,
            &format_args!("{:.6}", e.max),
            &format_args!("{:.6}", e.rms),
            &format_args!("{:.6}", e.end),
            &format_args!("{end_e:.6}"),
            &format_args!("{end_k:.6}"),
            &opt(ss_exact),
            &opt(ss_kuhn),
            &format_args!("{:.3e}", ee.max),
            &format_args!("{:.3e}", ee.rms),
            &format_args!("{:.3e}", ee.end),
            &format_args!("{:.8}", en.q.last().unwrap_or(&0.0)),
            &format_args!("{coupling:.3e}"),
        ]);
        max_pts.push((cv.r, e.max));
        rms_pts.push((cv.r, e.rms));
    }
    writeln!(
        out,
        "Rapier compliant regime against Kuhn's rule (the same law, so this is the engine's \
         coupling: kinematics, f32, the step): largest |dQ|/(mu P) over all paths {engine_worst:.1e}; \
         against Kuhn's rule at the engine's P (Hertz at its f32 overlap) {coupling_worst:.1e}"
    )?;
    err_csv.write(&args.out.join("rolling_effect_error.csv"))?;
    let [esvg, epng] = LineChart::new(
        "Error of Kuhn's rule against the exact theory",
        "ratio of rolling to sliding  r = |du_roll| / |du_disp|",
        "|Q_Kuhn - Q_exact| / (\u{3bc} P)",
    )
    .series(
        Series::line("max over the path", max_pts)
            .color(2)
            .markers(),
    )
    .series(
        Series::line("RMS over the path", rms_pts)
            .color(1)
            .markers()
            .dashed(),
    )
    .legend(Legend::UpperLeft)
    .write(&args.out.join("rolling_effect_error"))?;

    // The talk's conclusion in numbers.
    for level in [0.5, 0.9] {
        let ex = CreepEffect::measure(&curves, |c| &c.exact, level);
        let ku = CreepEffect::measure(&curves, |c| &c.kuhn, level);
        let (Some(ex), Some(ku)) = (ex, ku) else {
            writeln!(out, "\n(the r = 0 curves never reach Q = {level} mu P)")?;
            continue;
        };
        writeln!(out)?;
        writeln!(
            out,
            "Reduction of Q by rolling, 1 - Q_r/Q_0, at the sliding displacement where r = 0 \
             reaches Q = {level} mu P (exact: delta G a/(mu P) = {:.4}; Kuhn: {:.4})",
            ex.delta, ku.delta
        )?;
        write!(out, "{:>8}", "r")?;
        for (r, _) in &ex.change {
            write!(out, " {r:>7}")?;
        }
        writeln!(out)?;
        for (name, e) in [("exact", &ex), ("Kuhn", &ku)] {
            write!(out, "{name:>8}")?;
            for (_, c) in &e.change {
                write!(out, " {:>6.2}%", 100.0 * c)?;
            }
            writeln!(out)?;
        }
        for t in [0.01, 0.05, 0.20] {
            let f = |e: &CreepEffect| match e.threshold_ratio(t) {
                Some(r) => format!("{r:.2}"),
                None => format!("> {}", e.change.last().map_or(0.0, |c| c.0)),
            };
            writeln!(
                out,
                "  creep changes Q by more than {:>2.0} % from r = {} (exact), r = {} (Kuhn)",
                100.0 * t,
                f(&ex),
                f(&ku)
            )?;
        }
    }

    if args.check_grid {
        check_grid(&fig, &curves, args, out)?;
    }
    writeln!(out)?;
    for p in [&csv, &svg, &png, &esvg, &epng] {
        writeln!(out, "wrote {}", p.display())?;
    }
    writeln!(
        out,
        "wrote {}",
        args.out.join("rolling_effect_error.csv").display()
    )?;
    Ok(())
}

/// The exact curves' grid convergence: the r = 0 path against Mindlin's closed form, and the
/// r = 0 and largest-r paths on N against 2N.
fn check_grid(
    fig: &RollingEffect,
    curves: &[Curve],
    args: &RollingEffectArgs,
    out: &mut dyn Write,
) -> Res {
    writeln!(out)?;
    if let Some(c0) = curves.iter().find(|c| c.r == 0.0) {
        let e = c0
            .delta
            .iter()
            .zip(&c0.exact)
            .map(|(d, q)| (q - fig.mindlin_force(*d)).abs())
            .fold(0.0f64, f64::max);
        writeln!(
            out,
            "r = 0, BEM N = {} against Mindlin's closed form: max |dQ|/(mu P) = {e:.4}",
            args.grid
        )?;
    }
    let fine = 2 * args.grid;
    let largest = RATIOS[RATIOS.len() - 1];
    let picks: Vec<&Curve> = curves
        .iter()
        .filter(|c| c.r == 0.0 || c.r == largest)
        .collect();
    let ratios: Vec<f64> = picks.iter().map(|c| c.r).collect();
    let pb = progress((ratios.len() * args.steps) as u64, "grid check (2N)");
    let fine_curves = run_paths(fig, &ratios, fine, args.threads, &pb)?;
    pb.finish_and_clear();
    for (c, f) in picks.iter().zip(&fine_curves) {
        let d: Vec<f64> = c.exact.iter().zip(&f.exact).map(|(a, b)| a - b).collect();
        let max = d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        writeln!(
            out,
            "r = {}: exact N = {} against N = {fine}: max |dQ|/(mu P) = {max:.4}, at the end {:+.4}",
            c.r,
            args.grid,
            d.last().unwrap_or(&0.0)
        )?;
        if c.r > 0.0 {
            let (ss, _) = fig.steady(c.r, fine)?;
            writeln!(
                out,
                "r = {}: end N = {fine} {:.4}, steady BEM N = {fine} {ss:.4}",
                c.r,
                f.exact.last().unwrap_or(&0.0)
            )?;
        } else {
            let e = f
                .delta
                .iter()
                .zip(&f.exact)
                .map(|(d, q)| (q - fig.mindlin_force(*d)).abs())
                .fold(0.0f64, f64::max);
            writeln!(
                out,
                "r = 0, BEM N = {fine} against Mindlin's closed form: max |dQ|/(mu P) = {e:.4}"
            )?;
        }
    }
    // Step convergence: twice the steps on the same grid, compared at the common records.
    if let Some(c) = curves.iter().find(|c| c.r == largest) {
        let twice = RollingEffect::new(RollingEffectConfig {
            steps: 2 * args.steps,
            ratios: vec![largest],
            ..fig.config().clone()
        })?;
        let pb = progress((2 * args.steps) as u64, "step check (2 x steps)");
        let mut tick = || pb.inc(1);
        let f = twice.exact_path(largest, args.grid, &mut tick)?;
        pb.finish_and_clear();
        let max = c
            .exact
            .iter()
            .zip(f.iter().step_by(2))
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        writeln!(
            out,
            "r = {largest}: exact {} against {} steps (N = {}): max |dQ|/(mu P) = {max:.4}",
            args.steps,
            2 * args.steps,
            args.grid
        )?;
    }
    Ok(())
}
