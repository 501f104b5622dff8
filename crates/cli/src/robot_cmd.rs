//! `creep run robot`: the differential-drive robot of creep-scenes `robot` (two driven crowned
//! rubber wheels and a caster ball) turning on the spot and on an arc, with creep and as a
//! Coulomb twin; one CSV row per (manoeuvre, fidelity), or with `--series` the time series of
//! one run.

use std::io::Write;

use creep_scenes::robot::{self, Fidelity, RobotParams, RobotRun, WheelSpeeds};

use crate::output::CsvWriter;

type Res = Result<(), Box<dyn std::error::Error>>;

/// The manoeuvres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Manoeuvre {
    /// Turning on the spot: rim speeds `-v, +v` (`--speed`).
    Spot,
    /// An arc: rim speeds `--left`, `--right`.
    Arc,
    /// Both (the summary only).
    Both,
}

/// Which runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Runs {
    /// Creep-friction only.
    Creep,
    /// The Coulomb twin only.
    Coulomb,
    /// Both.
    Both,
}

/// Arguments of `creep run robot`.
#[derive(Debug, clap::Args)]
pub struct RobotArgs {
    /// Manoeuvre.
    #[arg(long, value_enum, default_value_t = Manoeuvre::Both)]
    manoeuvre: Manoeuvre,
    /// Rim speed of the turn on the spot [m/s].
    #[arg(long, default_value_t = 0.1)]
    speed: f64,
    /// Left rim speed of the arc [m/s].
    #[arg(long, default_value_t = 0.1)]
    left: f64,
    /// Right rim speed of the arc [m/s].
    #[arg(long, default_value_t = 0.15)]
    right: f64,
    /// Creep, the Coulomb twin, or both.
    #[arg(long, value_enum, default_value_t = Runs::Both)]
    runs: Runs,
    /// Duration of each run [s] (means over its second half).
    #[arg(long, default_value_t = 4.0)]
    duration: f64,
    /// Time step [s].
    #[arg(long, default_value_t = 1.0 / 240.0)]
    dt: f64,
    /// Print the time series of the one run chosen (`--manoeuvre spot|arc --runs
    /// creep|coulomb`) instead of the summary: `t,x,z,yaw,speed,yaw_rate,v_left,v_right,
    /// xi_left,eta_left,phi_left,xi_right,eta_right,phi_right,xi_caster,eta_caster,phi_caster,
    /// power,hook_power,kinetic_energy` (s, m, m, rad, m/s, rad/s, m/s, m/s, -, -, 1/m, ..., W,
    /// W, J).
    #[arg(long)]
    series: bool,
}

/// The summary's header: per run, the manoeuvre (`spot`, `arc`), the fidelity (`creep`,
/// `coulomb`), the motor targets `v_left,v_right` [m/s], the measured means over the second
/// half: `speed` of the axle midpoint [m/s], `yaw_rate` [rad/s], the closed form from the
/// measured rim speeds `yaw_rate_closed_form` [rad/s], `radius` = speed/yaw_rate [m] and its
/// closed form `(b/2)(v_r+v_l)/(v_r-v_l)` [m]; per contact (left wheel, right wheel, caster)
/// the creepages `xi`, `eta` [-] and `phi` [1/m], normal force `p` [N], lateral force `fy` [N]
/// and twisting moment `mz` [N m]; the energy the contacts dissipated over the window
/// (`dissipated`, J, measured from Rapier's impulses and the plugin's moments), the hook's
/// creep power integrated (`hook_energy`, J) and the window's length [s].
pub const SUMMARY_HEADER: [&str; 33] = [
    "manoeuvre",
    "fidelity",
    "v_left",
    "v_right",
    "speed",
    "yaw_rate",
    "yaw_rate_closed_form",
    "radius",
    "radius_closed_form",
    "xi_left",
    "eta_left",
    "phi_left",
    "xi_right",
    "eta_right",
    "phi_right",
    "xi_caster",
    "eta_caster",
    "phi_caster",
    "p_left",
    "p_right",
    "p_caster",
    "fy_left",
    "fy_right",
    "fy_caster",
    "mz_left",
    "mz_right",
    "mz_caster",
    "power_left",
    "power_right",
    "power_caster",
    "dissipated",
    "hook_energy",
    "window",
];

/// Runs `creep run robot`.
pub fn run(a: &RobotArgs, out: &mut dyn Write) -> Res {
    let params = RobotParams {
        duration: a.duration,
        dt: a.dt,
        ..RobotParams::default()
    };
    let manoeuvres: Vec<(&str, WheelSpeeds)> = match a.manoeuvre {
        Manoeuvre::Spot => vec![("spot", WheelSpeeds::spot(a.speed))],
        Manoeuvre::Arc => vec![("arc", WheelSpeeds::arc(a.left, a.right))],
        Manoeuvre::Both => vec![
            ("spot", WheelSpeeds::spot(a.speed)),
            ("arc", WheelSpeeds::arc(a.left, a.right)),
        ],
    };
    let fidelities: Vec<Fidelity> = match a.runs {
        Runs::Creep => vec![Fidelity::Creep],
        Runs::Coulomb => vec![Fidelity::Coulomb],
        Runs::Both => vec![Fidelity::Creep, Fidelity::Coulomb],
    };
    if a.series {
        let ([(_, speeds)], [fidelity]) = (manoeuvres.as_slice(), fidelities.as_slice()) else {
            return Err(
                "--series needs one manoeuvre (spot or arc) and one run (creep or coulomb)".into(),
            );
        };
        let r = robot::run(&params, *speeds, *fidelity)?;
        return series(&r, out);
    }
    let mut w = CsvWriter::new(out, &SUMMARY_HEADER)?;
    for (name, speeds) in &manoeuvres {
        for fidelity in &fidelities {
            let r = robot::run(&params, *speeds, *fidelity)?;
            let s = &r.summary;
            let fid = match fidelity {
                Fidelity::Coulomb => "coulomb",
                _ => "creep",
            };
            let [l, rr] = &s.wheels;
            let c = &s.caster;
            w.row(&[
                name,
                &fid,
                &speeds.left,
                &speeds.right,
                &s.speed,
                &s.yaw_rate,
                &s.yaw_rate_closed_form,
                &s.radius,
                &s.radius_closed_form,
                &l.xi,
                &l.eta,
                &l.phi,
                &rr.xi,
                &rr.eta,
                &rr.phi,
                &c.xi,
                &c.eta,
                &c.phi,
                &l.p,
                &rr.p,
                &c.p,
                &l.fy,
                &rr.fy,
                &c.fy,
                &l.mz,
                &rr.mz,
                &c.mz,
                &l.power,
                &rr.power,
                &c.power,
                &s.dissipated,
                &s.hook_energy,
                &s.window,
            ])?;
            w.flush()?;
        }
    }
    Ok(())
}

/// The time series of one run (header in [`RobotArgs::series`]'s docs).
fn series(r: &RobotRun, out: &mut dyn Write) -> Res {
    let mut w = CsvWriter::new(
        out,
        &[
            "t",
            "x",
            "z",
            "yaw",
            "speed",
            "yaw_rate",
            "v_left",
            "v_right",
            "xi_left",
            "eta_left",
            "phi_left",
            "xi_right",
            "eta_right",
            "phi_right",
            "xi_caster",
            "eta_caster",
            "phi_caster",
            "power",
            "hook_power",
            "kinetic_energy",
        ],
    )?;
    for s in &r.samples {
        let [l, rr] = &s.wheels;
        let c = &s.caster;
        w.row(&[
            &s.t,
            &s.position.x,
            &s.position.z,
            &s.yaw,
            &s.speed,
            &s.yaw_rate,
            &s.rim_speeds[0],
            &s.rim_speeds[1],
            &l.xi,
            &l.eta,
            &l.phi,
            &rr.xi,
            &rr.eta,
            &rr.phi,
            &c.xi,
            &c.eta,
            &c.phi,
            &s.power(),
            &s.hook_creep_power,
            &s.kinetic_energy,
        ])?;
    }
    Ok(())
}
