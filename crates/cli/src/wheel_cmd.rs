//! `creep run wheel-on-sand`: a driven rigid wheel (a Rapier cylinder) on a granular bed
//! (creep-dem), coupled both ways by creep-bed. One slip and one contact model: the time series
//! on stdout; several slips or both contact models: one steady row per (model, slip), the bed
//! settled once and the wheel landed once per model (`creep_bed::wheel`).

use creep_dem::Cheap;
use creep_dem::dump::Snapshots;
use creep_law::CreepModel;
use creep_scenes::bed::{Drive, Progress, WheelOnSand, WheelRow, WheelSteady, settle, sweep};
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::output::{Csv, CsvWriter, create_dir};
use crate::plot::{Legend, LineChart, Series};

type Res = Result<(), Box<dyn std::error::Error>>;

/// Contact law at the grain contacts (grain-grain and grain-wheel).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Contact {
    /// Hertz-Mindlin with Kuhn's creep (the cheap tier's creep).
    Creep,
    /// Hertz-Mindlin (Coulomb limit) only, no creep.
    Coulomb,
    /// Both, from the same settled bed.
    Both,
}

/// Arguments of `creep run wheel-on-sand`.
#[derive(Debug, clap::Args)]
pub struct WheelArgs {
    /// Grains in the bed (about: 10 layers, 8 across a periodic slice, the rest along the
    /// travel; at least 640).
    #[arg(long, default_value_t = 2000)]
    grains: usize,
    /// Slip ratios s = 1 - v/(w R) of the driven wheel, each in [0, 1), comma separated.
    /// Several: one steady row per slip.
    #[arg(long, value_delimiter = ',', default_value = "0.2")]
    slip: Vec<f64>,
    /// Game steps driven (each 20 DEM steps); the steady values are means over the last half.
    #[arg(long, default_value_t = 1000)]
    steps: usize,
    /// Game steps the wheel sinks in at rest before driving.
    #[arg(long, default_value_t = 200)]
    sink_steps: usize,
    /// Wheel spin [rad/s].
    #[arg(long, default_value_t = 5.0)]
    spin: f64,
    /// Contact law at the grain contacts.
    #[arg(long, value_enum, default_value_t = Contact::Creep)]
    contact: Contact,
    /// Drives run at once on this many threads.
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Also write the CSVs (`wheel_series.csv`, `wheel_steady.csv`) and plots (SVG + PNG)
    /// into this directory.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Instead of the scene: the coupling's cost against the bed alone, interleaved
    /// (`--grains` grains, 5 layers, 20 across; `--rounds` blocks of 1,000 DEM steps each);
    /// prints `grains,rounds,steps_per_block,bed_alone_s_per_step,coupled_s_per_step,ratio,wheel_contacts,refreshes`.
    #[arg(long)]
    cost: bool,
    /// Rounds of `--cost`.
    #[arg(long, default_value_t = 5)]
    rounds: usize,
    /// Write snapshots of the grains into DIR, one subdirectory per drive (e.g.
    /// `creep_slip0.2`): LAMMPS-style text dumps of the particles and contacts (OVITO,
    /// ParaView) and VTK .vtp files with .pvd series (ParaView). The drives then run one after
    /// another (`--jobs` is ignored); the results are the same.
    #[arg(long, value_name = "DIR")]
    dump: Option<PathBuf>,
    /// DEM steps between two snapshots (with --dump; one per interval, checked after each game
    /// step); the drive's last state is written too.
    #[arg(long, value_name = "N", default_value_t = 1000, requires = "dump")]
    dump_every: u64,
}

/// A bad argument of the command.
#[derive(Debug, thiserror::Error)]
#[error("--{name} {value}: {why}")]
pub struct ArgError {
    name: &'static str,
    value: String,
    why: &'static str,
}

fn arg_error(name: &'static str, value: impl ToString, why: &'static str) -> ArgError {
    ArgError {
        name,
        value: value.to_string(),
        why,
    }
}

fn label(creep: bool) -> &'static str {
    if creep { "creep" } else { "coulomb" }
}

/// Runs the scene (or the cost measurement) and prints CSV.
pub fn run(a: &WheelArgs, out: &mut dyn Write) -> Res {
    if a.grains == 0 {
        return Err(arg_error("grains", a.grains, "at least one grain").into());
    }
    if a.cost {
        let nx = (a.grains / 100).max(4);
        let c = creep_bed::cost::coupling_cost([nx, 5, 20], a.rounds)?;
        writeln!(out, "{}", creep_bed::cost::CostReport::CSV_HEADER)?;
        writeln!(out, "{}", c.csv_row())?;
        return Ok(());
    }
    if a.slip.is_empty() {
        return Err(arg_error("slip", "", "at least one slip ratio").into());
    }
    for &s in &a.slip {
        if !(s.is_finite() && (0.0..1.0).contains(&s)) {
            return Err(arg_error("slip", s, "each slip ratio must be in [0, 1)").into());
        }
    }
    let mut s = WheelOnSand::with_grains(a.grains)?;
    s.drive_steps = a.steps;
    s.sink_steps = a.sink_steps;
    s.spin = a.spin;
    let models: Vec<Option<CreepModel>> = match a.contact {
        Contact::Creep => vec![Some(CreepModel::Kuhn)],
        Contact::Coulomb => vec![None],
        Contact::Both => vec![Some(CreepModel::Kuhn), None],
    };
    let clock = std::time::Instant::now();
    let report = |p: Progress<'_>| match p {
        Progress::Settled(n, steps, surface) => eprintln!(
            "# settled {n} grains in {steps} DEM steps ({:.0} s); surface at {surface:.4e} m",
            clock.elapsed().as_secs_f64()
        ),
        Progress::Landed(w) => eprintln!(
            "# landed at {:.0} s; wheel weight {w:.4e} N",
            clock.elapsed().as_secs_f64()
        ),
        Progress::Drove(d) => eprintln!(
            "# {} slip {}: sinkage {:.4e} m, pull {:.4e} N, torque {:.4e} N m, drifts {:.2e} {:.2e} {:.2e} ({:.0} s)",
            label(d.creep),
            d.slip,
            d.sinkage,
            d.drawbar_pull,
            d.torque,
            d.drift[0],
            d.drift[1],
            d.drift[2],
            d.seconds
        ),
    };
    let drives = match &a.dump {
        None => sweep::<Cheap>(&s, &a.slip, &models, a.jobs, report)?,
        Some(root) => sweep_with_dumps(&s, &a.slip, &models, root, a.dump_every, report)?,
    };

    let single = drives.len() == 1;
    if single {
        let mut w = CsvWriter::new(out, &["t", "slip", "sinkage", "drawbar_pull", "torque"])?;
        for r in &drives[0].rows {
            w.row(&[&r.t, &r.slip, &r.sinkage, &r.drawbar_pull, &r.torque])?;
        }
    } else {
        let mut w = CsvWriter::new(out, &STEADY_HEADER)?;
        for d in &drives {
            let f = steady_fields(&d.steady);
            let refs: Vec<&dyn std::fmt::Display> =
                f.iter().map(|x| x as &dyn std::fmt::Display).collect();
            w.row(&refs)?;
        }
    }
    if let Some(dir) = &a.out {
        write_out(dir, &drives, single)?;
    }
    Ok(())
}

/// [`sweep`] one drive after another with snapshots of the bed's grains: the bed settled
/// once, the wheel landed once per model, then each drive from a clone of the landed state
/// (`Landed::drive`'s steps, so the same results as the sweep).
fn sweep_with_dumps(
    s: &WheelOnSand,
    slips: &[f64],
    models: &[Option<CreepModel>],
    root: &Path,
    every: u64,
    report: impl Fn(Progress<'_>),
) -> Result<Vec<Drive>, Box<dyn std::error::Error>> {
    let settled = settle::<Cheap>(s)?;
    report(Progress::Settled(
        settled.grains(),
        settled.settle_steps,
        settled.surface,
    ));
    let mut out = Vec::new();
    for &model in models {
        let landed = settled.land(model)?;
        report(Progress::Landed(landed.weight));
        for &slip in slips {
            let name = format!("{}_slip{slip}", label(model.is_some()));
            let mut snaps = Snapshots::new(root.join(name), every)?;
            let mut d = landed.start(slip)?;
            snaps.maybe_write(d.bed().dem())?;
            let mut rows = Vec::with_capacity(s.drive_steps);
            for _ in 0..s.drive_steps {
                rows.push(d.step()?);
                snaps.maybe_write(d.bed().dem())?;
            }
            if snaps.written().last() != Some(d.bed().dem().steps()) {
                snaps.write(d.bed().dem())?;
            }
            let steady = d.finish()?;
            report(Progress::Drove(&steady));
            out.push(Drive { steady, rows });
        }
    }
    Ok(out)
}

const STEADY_HEADER: [&str; 14] = [
    "contact",
    "slip",
    "sinkage",
    "drawbar_pull",
    "torque",
    "pull_per_weight",
    "torque_per_weight_radius",
    "sinkage_rate",
    "drift_sinkage",
    "drift_pull",
    "drift_torque",
    "travel",
    "duration",
    "power",
];

/// One steady row: contact, slip, sinkage \[m\], pull \[N\], torque \[N m\], DP/W, T/(W R),
/// sinkage rate \[m/s\], the third-to-fourth-quarter drifts, travel \[m\], duration \[s\],
/// the power put into the bed \[W\] (`WheelSteady::power`).
fn steady_fields(s: &WheelSteady) -> Vec<String> {
    vec![
        label(s.creep).to_string(),
        s.slip.to_string(),
        s.sinkage.to_string(),
        s.drawbar_pull.to_string(),
        s.torque.to_string(),
        s.pull_coefficient().to_string(),
        s.torque_coefficient().to_string(),
        s.sinkage_rate.to_string(),
        s.drift[0].to_string(),
        s.drift[1].to_string(),
        s.drift[2].to_string(),
        s.travel.to_string(),
        s.duration.to_string(),
        s.power().to_string(),
    ]
}

fn steady_csv(drives: &[Drive]) -> Csv {
    let mut c = Csv::new(&STEADY_HEADER);
    for d in drives {
        let f = steady_fields(&d.steady);
        let refs: Vec<&dyn std::fmt::Display> =
            f.iter().map(|x| x as &dyn std::fmt::Display).collect();
        c.row(&refs);
    }
    c
}

fn write_out(dir: &Path, drives: &[Drive], single: bool) -> Res {
    create_dir(dir)?;
    let mut series = Csv::new(&["contact", "t", "slip", "sinkage", "drawbar_pull", "torque"]);
    for d in drives {
        for r in &d.rows {
            series.row(&[
                &label(d.steady.creep),
                &r.t,
                &r.slip,
                &r.sinkage,
                &r.drawbar_pull,
                &r.torque,
            ]);
        }
    }
    series.write(&dir.join("wheel_series.csv"))?;
    steady_csv(drives).write(&dir.join("wheel_steady.csv"))?;
    if single {
        let d = &drives[0];
        let w = d.steady.weight;
        let wr = w * d.steady.radius;
        let pts = |f: &dyn Fn(&WheelRow) -> f64| d.rows.iter().map(|r| (r.t, f(r))).collect();
        LineChart::new(
            format!(
                "Driven wheel on sand, slip {} ({})",
                d.steady.slip,
                label(d.steady.creep)
            ),
            "time since the drive started [s]",
            "DP/W, T/(W R), sinkage/R [-]",
        )
        .series(Series::line("drawbar pull DP/W", pts(&|r| r.drawbar_pull / w)).color(0))
        .series(Series::line("torque T/(W R)", pts(&|r| r.torque / wr)).color(1))
        .series(
            Series::line("sinkage z/R", pts(&|r| r.sinkage / d.steady.radius))
                .color(2)
                .dashed(),
        )
        .legend(Legend::UpperRight)
        .write(&dir.join("wheel_time"))?;
        return Ok(());
    }
    let curve = |creep: bool, f: &dyn Fn(&WheelSteady) -> f64| -> Vec<(f64, f64)> {
        let mut v: Vec<(f64, f64)> = drives
            .iter()
            .filter(|d| d.steady.creep == creep)
            .map(|d| (d.steady.slip, f(&d.steady)))
            .collect();
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
        v
    };
    let chart = |stem: &str, title: &str, y: &str, f: &dyn Fn(&WheelSteady) -> f64| {
        let mut c = LineChart::new(title, "slip ratio s [-]", y).legend(Legend::UpperLeft);
        for (k, creep) in [true, false].into_iter().enumerate() {
            let p = curve(creep, f);
            if !p.is_empty() {
                let mut s = Series::line(label(creep), p).color(k).markers();
                if !creep {
                    s = s.dashed();
                }
                c = c.series(s);
            }
        }
        c.write(&dir.join(stem))
    };
    chart(
        "wheel_pull",
        "Drawbar pull against slip (steady means)",
        "drawbar pull / weight DP/W [-]",
        &|s| s.pull_coefficient(),
    )?;
    chart(
        "wheel_torque",
        "Driving torque against slip (steady means)",
        "torque / (weight x radius) T/(W R) [-]",
        &|s| s.torque_coefficient(),
    )?;
    chart(
        "wheel_sinkage",
        "Sinkage against slip (steady means)",
        "sinkage / wheel radius z/R [-]",
        &|s| s.sinkage / s.radius,
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The drives with snapshots give the sweep's results, bit for bit, and write a series of
    /// dumps per drive that read back with every grain.
    #[test]
    fn drives_with_dumps_are_the_sweeps() {
        let mut s = WheelOnSand::with_grains(2000).unwrap();
        s.settle_steps = 300;
        s.sink_steps = 3;
        s.drive_steps = 6;
        let models = [Some(CreepModel::Kuhn)];
        let slips = [0.2];
        let plain = sweep::<Cheap>(&s, &slips, &models, 1, |_| {}).unwrap();
        let dir = std::env::temp_dir().join(format!("creep-wheel-dump-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let dumped = sweep_with_dumps(&s, &slips, &models, &dir, 50, |_| {}).unwrap();
        assert_eq!(plain.len(), 1);
        assert_eq!(plain[0].rows, dumped[0].rows);
        let (a, b) = (&plain[0].steady, &dumped[0].steady);
        assert_eq!(
            (a.sinkage, a.drawbar_pull, a.torque, a.travel),
            (b.sinkage, b.drawbar_pull, b.torque, b.travel)
        );
        let drive = dir.join("creep_slip0.2");
        let mut dumps: Vec<_> = std::fs::read_dir(&drive)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| {
                let name = p.file_name().unwrap().to_string_lossy().to_string();
                name.starts_with("particles.") && name.ends_with(".dump")
            })
            .collect();
        dumps.sort();
        // 6 game steps of 20 DEM steps, one snapshot per 50 steps, the start and the end.
        assert!(dumps.len() >= 3, "{dumps:?}");
        let text = std::fs::read_to_string(dumps.last().unwrap()).unwrap();
        let frames = creep_dem::dump::read_dump(&text).unwrap();
        let mut ids = frames[0].column("id").unwrap();
        ids.sort_by(f64::total_cmp);
        let n = ids.len();
        assert!(n >= 2000, "{n} grains");
        assert!(ids.iter().enumerate().all(|(k, &id)| id == (k + 1) as f64));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
