//! `creep run repose`: the angle of repose of a collapsed column of monodisperse spheres
//! (creep-scenes' `repose`, on creep-dem) for Coulomb only, creep only and creep plus
//! contact-torque rolling resistance, against Zhou et al.'s (2002) DEM correlation. One CSV row
//! per case on stdout; `--out DIR` also writes `repose.csv` and the plot `repose.svg`/`.png`
//! (angle against the rolling coefficient, with the correlation).

use std::io::Write;
use std::path::PathBuf;

use creep_dem::dump::Snapshots;
use creep_scenes::SceneError;
use creep_scenes::repose::{self, ReposeParams};

use crate::output::{Csv, create_dir};
use crate::plot::{Legend, LineChart, Series};

type Res = Result<(), Box<dyn std::error::Error>>;

/// Arguments of `creep run repose`.
#[derive(Debug, clap::Args)]
pub struct ReposeArgs {
    /// Sliding friction coefficients mu [-], comma separated (one set of cases each).
    #[arg(long, value_delimiter = ',', default_value = "0.5")]
    mu: Vec<f64>,
    /// EPSD rolling coefficients mu_r [-] (torque cap mu_r R* P) of the creep + rolling torque
    /// cases, comma separated; the Coulomb-only and creep-only cases always run.
    #[arg(long, value_delimiter = ',', default_value = "0.1,0.3")]
    rolling: Vec<f64>,
    /// Grains in the column (about: a square column 4 diameters thick).
    #[arg(long, default_value_t = 784)]
    grains: usize,
    /// Longest settling time after the release [s].
    #[arg(long, default_value_t = 2.0)]
    max_time: f64,
    /// Seed of the base roughness and the column's jitter.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Directory for `repose.csv`, `repose_profiles.csv` and the plot `repose.svg`/`.png`.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Write snapshots into DIR, one subdirectory per case (e.g. `mu0.5_creep_rolling0.1`):
    /// LAMMPS-style text dumps of the particles and contacts (OVITO, ParaView) and VTK .vtp
    /// files with .pvd series (ParaView). The base's fixed grains are particles of type 1 too.
    #[arg(long, value_name = "DIR")]
    dump: Option<PathBuf>,
    /// Steps between two snapshots (with --dump); the settled pile's state is written too.
    #[arg(long, value_name = "N", default_value_t = 2000, requires = "dump")]
    dump_every: u64,
}

/// Why the arguments were refused.
#[derive(Debug, thiserror::Error)]
pub enum ReposeArgError {
    /// No sliding friction given.
    #[error("--mu needs at least one value")]
    NoMu,
    /// Too few grains for a pile.
    #[error("--grains {0}: at least 36 grains (a 3 x 3 x 4 column)")]
    TooFewGrains(usize),
}

fn field(v: Option<f64>) -> String {
    v.map(|x| format!("{x:.3}")).unwrap_or_default()
}

/// Runs every case; prints `mu,rolling,creep,angle_deg,correlation_deg` (rolling empty for
/// none, the correlation empty where it has no value).
pub fn run(a: &ReposeArgs, out: &mut dyn Write) -> Res {
    if a.mu.is_empty() {
        return Err(ReposeArgError::NoMu.into());
    }
    if a.grains < 36 {
        return Err(ReposeArgError::TooFewGrains(a.grains).into());
    }
    let base = ReposeParams {
        max_time: a.max_time,
        seed: a.seed,
        ..ReposeParams::with_grains(a.grains)
    };
    let mut cases = Vec::new();
    for &mu in &a.mu {
        cases.extend(repose::cases(&base, mu, &a.rolling));
    }
    for c in &cases {
        c.validate()?;
    }
    if let Some(dir) = &a.out {
        create_dir(dir)?;
    }
    let header = ["mu", "rolling", "creep", "angle_deg", "correlation_deg"];
    let mut csv = Csv::new(&header);
    let mut profiles = Csv::new(&["mu", "rolling", "creep", "x_m", "height_m", "fitted"]);
    writeln!(out, "{}", header.join(","))?;
    let mut runs = Vec::new();
    for c in &cases {
        let r = match &a.dump {
            None => repose::run(c, &mut |_| {})?,
            Some(root) => {
                let mut name = format!("mu{}_{}", c.mu, if c.creep { "creep" } else { "coulomb" });
                if let Some(r) = c.rolling {
                    name += &format!("_rolling{r}");
                }
                let mut snaps = Snapshots::new(root.join(name), a.dump_every)?;
                repose::run_observed(c, &mut |_| {}, &mut |dem, settled| {
                    let done = snaps.written().last() == Some(dem.steps());
                    let r = if settled && !done {
                        snaps.write(dem).map(|()| true)
                    } else {
                        snaps.maybe_write(dem)
                    };
                    r.map(|_| ())
                        .map_err(|e| SceneError::Parameter(format!("--dump: {e}")))
                })?
            }
        };
        let (mu, rolling, creep) = (format!("{}", c.mu), field(c.rolling), c.creep);
        let angle = format!("{:.2}", r.angle_deg);
        let corr = field(r.correlation_deg);
        writeln!(out, "{mu},{rolling},{creep},{angle},{corr}")?;
        out.flush()?;
        if !r.settled {
            eprintln!(
                "repose: mu = {mu}, rolling = {rolling}, creep = {creep} did not settle in {} s (fastest grain {:.3e} m/s); its angle is of the pile at that time",
                c.max_time, r.max_speed
            );
        }
        csv.row(&[&mu, &rolling, &creep, &angle, &corr]);
        for (i, (x, h)) in r.profile.x.iter().zip(&r.profile.height).enumerate() {
            let fitted = i >= r.profile.fitted.0 && i < r.profile.fitted.1;
            profiles.row(&[&mu, &rolling, &creep, x, h, &fitted]);
        }
        runs.push(r);
    }
    if let Some(dir) = &a.out {
        csv.write(&dir.join("repose.csv"))?;
        profiles.write(&dir.join("repose_profiles.csv"))?;
        plot(&runs, &a.rolling, &dir.join("repose"))?;
    }
    Ok(())
}

/// Angle against the rolling coefficient: per `mu`, the creep + rolling torque cases as a line
/// (the creep-only case at `mu_r = 0`), the Coulomb-only case as a marker at 0, and the
/// correlation (dashed) over the rolling coefficients given.
fn plot(runs: &[repose::ReposeRun], rolling: &[f64], stem: &std::path::Path) -> Res {
    let mut mus: Vec<f64> = runs.iter().map(|r| r.params.mu).collect();
    mus.dedup();
    let mut chart = LineChart::new(
        "Angle of repose against rolling resistance",
        "EPSD rolling coefficient \u{3bc}_r [-] (0: none)",
        "angle of repose [deg]",
    )
    .legend(Legend::LowerRight);
    let hi = rolling.iter().copied().fold(0.0f64, f64::max);
    for (k, &mu) in mus.iter().enumerate() {
        let of_mu = || runs.iter().filter(move |r| r.params.mu == mu);
        let creep: Vec<(f64, f64)> = of_mu()
            .filter(|r| r.params.creep)
            .map(|r| (r.params.rolling.unwrap_or(0.0), r.angle_deg))
            .collect();
        let coulomb: Vec<(f64, f64)> = of_mu()
            .filter(|r| !r.params.creep)
            .map(|r| (0.0, r.angle_deg))
            .collect();
        chart = chart
            .series(
                Series::line(format!("creep (+ rolling torque), \u{3bc} = {mu}"), creep)
                    .color(k)
                    .markers(),
            )
            .series(
                Series::line(format!("Coulomb only, \u{3bc} = {mu}"), coulomb)
                    .color(k)
                    .markers(),
            );
        if hi > 0.0 {
            let base = runs[0].params;
            let pts: Vec<(f64, f64)> = (1..=40)
                .map(|i| hi * i as f64 / 40.0)
                .filter_map(|m| {
                    let p = ReposeParams {
                        mu,
                        rolling: Some(m),
                        ..base
                    };
                    repose::correlation_for(&p).map(|c| (m, c))
                })
                .collect();
            chart = chart.series(
                Series::line(format!("Zhou et al. 2002, \u{3bc} = {mu}"), pts)
                    .color(k)
                    .dashed(),
            );
        }
    }
    chart.write(stem)?;
    Ok(())
}
