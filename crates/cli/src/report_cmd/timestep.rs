//! The time-step section: the error of the rigid and compliant regimes against closed forms as
//! the step shrinks, with the observed order (the slope of `ln |error|` against `ln dt`,
//! [`super::fit::power_fit`]).
//!
//! * Rigid regime (`creep_scenes::incline`, `creep_scenes::friction_drive`), dt = 1/30 ...
//!   1/960 s: the incline's acceleration and creep slip, the friction drive's creepage.
//! * Compliant regime (`creep_scenes::impact`), dt = 0.4 ... 0.025 of the Rayleigh time step:
//!   a normal impact's contact duration, peak force and rebound against Hertz, and the
//!   restitution against the requested one.

use std::fmt::Write as _;
use std::path::Path;

use creep_scenes::incline::{G, InclineParams};
use creep_scenes::{friction_drive, impact, incline};
use indicatif::ProgressBar;

use super::fit::{local_orders, power_fit};
use super::{Config, ReportError, Section};
use crate::output::Csv;
use crate::plot::{Legend, LineChart, Series};

/// Steps per second of the rigid regime's runs (dt = 1/n s).
pub const RIGID_STEPS_PER_SECOND: [f64; 6] = [30.0, 60.0, 120.0, 240.0, 480.0, 960.0];

/// Time steps of the compliant regime's runs, as fractions of the Rayleigh time step.
pub const DEM_FRACTIONS: [f64; 5] = [0.4, 0.2, 0.1, 0.05, 0.025];

/// Friction-drive load: `Q/(mu P)` of its brake torque.
const DRIVE_LOAD: f64 = 0.5;

/// One convergence study: a quantity at each step, against its closed form.
#[derive(Debug, Clone)]
struct Study {
    regime: &'static str,
    name: &'static str,
    /// `(dt [s], dt / T_R or NaN, value, expected)`.
    points: Vec<(f64, f64, f64, f64)>,
}

impl Study {
    fn new(regime: &'static str, name: &'static str) -> Self {
        Study {
            regime,
            name,
            points: Vec::new(),
        }
    }

    /// The relative errors `value / expected - 1`.
    fn errors(&self) -> Vec<f64> {
        self.points.iter().map(|p| p.2 / p.3 - 1.0).collect()
    }

    /// `(x, |error|)` with x = dt (rigid) or dt / T_R (compliant).
    fn abs_errors(&self) -> Vec<(f64, f64)> {
        self.points
            .iter()
            .zip(self.errors())
            .map(|(p, e)| (if p.1.is_finite() { p.1 } else { p.0 }, e.abs()))
            .collect()
    }
}

/// The acceleration of a uniform sphere rolling down an incline with a constant creepage `xi`
/// (its contact slipping forwards by `xi v`, Kalker's creepage): `omega R = (1 - xi) v`,
/// `m a = m g sin(theta) - Q`, `I alpha = Q R` with `I = (2/5) m R^2` give
/// `a = g sin(theta) / (1 + (2/5)(1 - xi))`, Rapier-free; `(5/7) g sin(theta)` at `xi = 0`.
fn creeping_incline_acceleration(theta: f64, xi: f64) -> f64 {
    G * theta.sin() / (1.0 + 0.4 * (1.0 - xi))
}

/// Runs the studies.
fn measure(pb: &ProgressBar) -> Result<Vec<Study>, ReportError> {
    let mut acc = Study::new(
        "rigid",
        "incline: acceleration vs g sin(theta)/(1 + (2/5)(1 - F_ss))",
    );
    let mut acc_c = Study::new(
        "rigid",
        "incline (Rapier's Coulomb run): acceleration vs (5/7) g sin(theta)",
    );
    let mut slip = Study::new("rigid", "incline: creep slip vs Kalker's F_ss");
    let mut drive = Study::new(
        "rigid",
        "friction drive at Q/(mu P) = 0.5: creepage vs Kalker's F_ss",
    );
    for n in RIGID_STEPS_PER_SECOND {
        pb.set_message(format!("time step: rigid 1/{n:.0} s"));
        let dt = 1.0 / n;
        let p = InclineParams {
            dt,
            ..InclineParams::default()
        };
        let r = incline::run(&p)?;
        let a_creep = creeping_incline_acceleration(p.theta, r.creepage_expected);
        acc.points
            .push((dt, f64::NAN, r.creep.acceleration, a_creep));
        acc_c.points.push((
            dt,
            f64::NAN,
            r.coulomb.acceleration,
            r.acceleration_expected,
        ));
        slip.points
            .push((dt, f64::NAN, r.creepage_measured, r.creepage_expected));
        let dp = friction_drive::DriveParams {
            dt,
            ..Default::default()
        };
        let torque = DRIVE_LOAD * dp.material.friction() * dp.normal_force() * dp.radius;
        let rows = friction_drive::run(&dp, &[torque])?;
        if let Some(row) = rows.first() {
            drive
                .points
                .push((dt, f64::NAN, row.creepage_measured, row.creepage_expected));
        }
        pb.inc(1);
    }
    let mut duration = Study::new("compliant", "impact (e = 1): contact duration vs Hertz");
    let mut peak = Study::new("compliant", "impact (e = 1): peak force vs Hertz");
    let mut rebound = Study::new(
        "compliant",
        "impact (e = 1): rebound speed vs approach speed",
    );
    let mut restitution = Study::new(
        "compliant",
        "impact (e = 0.5, damped): restitution vs requested",
    );
    for f in DEM_FRACTIONS {
        pb.set_message(format!("time step: compliant {f} T_R"));
        let p = impact::ImpactParams {
            dt_over_rayleigh: f,
            ..Default::default()
        };
        let r = impact::run(&p)?;
        duration
            .points
            .push((r.dt, f, r.duration, r.hertz.duration));
        peak.points
            .push((r.dt, f, r.peak_force, r.hertz.peak_force));
        rebound.points.push((r.dt, f, r.rebound, 1.0));
        let e = 0.5;
        let r = impact::run(&impact::ImpactParams {
            restitution: e,
            ..p
        })?;
        restitution.points.push((r.dt, f, r.rebound, e));
        pb.inc(1);
    }
    Ok(vec![
        acc,
        acc_c,
        slip,
        drive,
        duration,
        peak,
        rebound,
        restitution,
    ])
}

/// `+1.23e-4`.
fn err_text(e: f64) -> String {
    if e.is_finite() {
        format!("{e:+.2e}")
    } else {
        "n/a".into()
    }
}

/// The time-step section (`timestep.csv`, `timestep_rigid.*`, `timestep_compliant.*`).
pub fn section(_cfg: &Config, dir: &Path, pb: &ProgressBar) -> Result<Section, ReportError> {
    pb.set_length((RIGID_STEPS_PER_SECOND.len() + DEM_FRACTIONS.len()) as u64);
    let studies = measure(pb)?;
    pb.set_message("time step: writing");
    let mut csv = Csv::new(&[
        "regime",
        "quantity",
        "dt_s",
        "dt_over_rayleigh",
        "value",
        "expected",
        "relative_error",
    ]);
    for s in &studies {
        for (p, e) in s.points.iter().zip(s.errors()) {
            let frac = if p.1.is_finite() {
                format!("{}", p.1)
            } else {
                String::new()
            };
            csv.row(&[
                &s.regime,
                &s.name.replace(',', ";"),
                &format_args!("{:.9e}", p.0),
                &frac,
                &format_args!("{:.9e}", p.2),
                &format_args!("{:.9e}", p.3),
                &format_args!("{e:.6e}"),
            ]);
        }
    }
    csv.write(&dir.join("timestep.csv"))?;
    let mut csv = Csv::new(&["regime", "quantity", "observed_order", "r2", "points"]);
    for s in &studies {
        // A study without two usable points has no order: empty fields, never a NaN.
        let (k, r2, n) =
            power_fit(&s.abs_errors()).map_or((String::new(), String::new(), 0), |f| {
                (
                    format!("{:.6}", f.exponent),
                    format!("{:.6}", f.r2),
                    f.points,
                )
            });
        csv.row(&[&s.regime, &s.name.replace(',', ";"), &k, &r2, &n]);
    }
    csv.write(&dir.join("timestep_orders.csv"))?;
    let mut md = String::from("## Time step: error against the step\n\n");
    md += "Relative error `value / closed form - 1` of each regime as the step shrinks, and the \
           observed order: the least-squares slope of `ln |error|` against `ln dt` over all \
           steps (with its R^2), and the local orders between consecutive steps (halvings). \
           Where the error reaches the measurement's own floor (f32 positions and angles summed \
           over the run: about 1e-4 of the incline's acceleration and a few 1e-3 of a creepage \
           of 3e-4) the local orders scatter and the fit over all steps understates the order. \
           Data: `timestep.csv`, the fits in `timestep_orders.csv`.\n\n";
    let _ = writeln!(
        md,
        "**Rigid regime** (Rapier's step, 4 substeps, the plugin at `Fidelity::Creep`): the \
         incline of `creep run incline` (0.1 m steel ball, 20 degrees, mu = 0.5, 1 s; creep \
         measured over the second half against a Coulomb run of the same scene; its acceleration \
         against the closed form of a sphere rolling with Kalker's creepage, which is (5/7) g \
         sin(theta) less 8e-5 of it) and the friction drive of `creep run friction-drive` (two \
         5 cm steel spheres, brake at Q/(mu P) = {DRIVE_LOAD}, 2 s).\n"
    );
    md += &table(
        &studies,
        "rigid",
        &RIGID_STEPS_PER_SECOND
            .iter()
            .map(|n| format!("1/{n:.0} s"))
            .collect::<Vec<_>>(),
    );
    md += "\n![rigid regime: error against the time step](timestep_rigid.png)\n\n";
    md += "**Compliant regime** (soft-sphere DEM, one solver iteration): a glass sphere (10 mm) \
           meets a glass wall head-on at 1 m/s, gravity off (`creep_scenes::impact`; Hertz's \
           contact lasts 6.9 Rayleigh time steps `T_R`). Contact duration interpolated to the \
           gap's zero crossings; rebound = speed after over speed before; the damped impact \
           against the restitution the colliders ask for (Hertz's duration and peak force do not \
           apply to it). Steps as fractions of `T_R` (the regime refuses more than 0.2 `T_R` by \
           default; the larger steps are allowed here for the study).\n\n";
    md += &table(
        &studies,
        "compliant",
        &DEM_FRACTIONS
            .iter()
            .map(|f| format!("{f} T_R"))
            .collect::<Vec<_>>(),
    );
    md += "\n![compliant regime: error against the time step](timestep_compliant.png)\n\n";
    plot(
        &studies,
        "rigid",
        "time step dt [s]",
        &dir.join("timestep_rigid"),
    )?;
    plot(
        &studies,
        "compliant",
        "time step dt / T_R [-]",
        &dir.join("timestep_compliant"),
    )?;
    Ok(Section {
        markdown: md,
        files: [
            "timestep.csv",
            "timestep_orders.csv",
            "timestep_rigid.svg",
            "timestep_rigid.png",
            "timestep_compliant.svg",
            "timestep_compliant.png",
        ]
        .map(String::from)
        .to_vec(),
    })
}

/// The Markdown table of one regime's studies.
fn table(studies: &[Study], regime: &str, steps: &[String]) -> String {
    let mut md = String::from("| quantity |");
    for s in steps {
        let _ = write!(md, " {s} |");
    }
    md += " observed order (R^2) | local orders |\n|---|";
    md += &"---|".repeat(steps.len() + 2);
    md.push('\n');
    for s in studies.iter().filter(|s| s.regime == regime) {
        let _ = write!(md, "| {} |", s.name);
        for e in s.errors() {
            let _ = write!(md, " {} |", err_text(e));
        }
        let pts = s.abs_errors();
        let fit = power_fit(&pts).map_or("n/a".to_string(), |f| {
            format!("{:.2} ({:.2})", f.exponent, f.r2)
        });
        let local: Vec<String> = local_orders(&pts)
            .into_iter()
            .map(|o| o.map_or("n/a".to_string(), |o| format!("{o:.1}")))
            .collect();
        let _ = writeln!(md, " {fit} | {} |", local.join(", "));
    }
    md
}

/// Log-log plot of `|error|` against the step for one regime.
fn plot(studies: &[Study], regime: &str, x_label: &str, stem: &Path) -> Result<(), ReportError> {
    let mut chart = LineChart::new(
        format!("{regime} regime: error against the time step"),
        x_label,
        "|relative error| [-]",
    )
    .legend(Legend::LowerRight);
    chart.size = (1000, 650);
    for (k, s) in studies.iter().filter(|s| s.regime == regime).enumerate() {
        chart = chart.series(Series::line(s.name, s.abs_errors()).color(k + 1));
    }
    chart.write_log_log(stem)?;
    Ok(())
}
