//! `creep run ...`: the scenarios of crate `creep-scenes`, measured against their closed forms.

use std::io::Write;

use crate::output::CsvWriter;

use clap::Subcommand;
use creep_law::Material;
use creep_scenes::{cue_ball, free_rolling, friction_drive, incline, wheels, wheels_spin};

type Res = Result<(), Box<dyn std::error::Error>>;

/// Scenarios (Rapier worlds with the creep-friction plugin).
#[derive(Debug, Subcommand)]
pub enum RunCommand {
    /// A 0.1 m steel ball rolling down an incline: acceleration vs (5/7) g sin(theta), creep slip
    /// vs Kalker's F_ss.
    Incline {
        /// Incline angle [degrees].
        #[arg(long, default_value_t = 20.0)]
        theta_deg: f64,
        /// Material of ball and incline (`steel` with mu = 0.5, `glass`, `rubber`: G = 1 MPa).
        #[arg(long, value_enum, default_value_t = MaterialName::Steel)]
        material: MaterialName,
        /// Time step [s].
        #[arg(long, default_value_t = 1.0 / 240.0)]
        dt: f64,
    },
    /// A driven steel sphere turning a braked one: the output lags by the creepage, swept over
    /// the brake torque up to slip.
    FrictionDrive {
        /// Print CSV (`brake_torque,p,q,q_over_mu_p,contact_radius,g,nu,mu,creepage_measured,creepage_expected`).
        #[arg(long)]
        csv: bool,
        /// Brake torques as fractions of the slip torque mu P R, comma separated, in [0, 1).
        #[arg(
            long,
            value_delimiter = ',',
            default_value = "0.1,0.2,0.3,0.4,0.5,0.6,0.7,0.8,0.9,0.94"
        )]
        ratios: Vec<f64>,
        /// Time step [s].
        #[arg(long, default_value_t = 1.0 / 240.0)]
        dt: f64,
    },
    /// A steel ball rolling freely on a level floor for 10 s: creep-friction adds no resistance.
    FreeRolling,
    /// A cue ball launched sliding: slip phase and final speed vs the closed forms.
    CueBall,
    /// A 0.1 m ball set rolling without slip on a level ground; CSV on stdout:
    /// `t,x,height,speed,omega_r,kinetic_energy,potential_energy` (s, m, m, m/s, m/s, J, J;
    /// `height` of the centre above the ground, potential relative to the start).
    RollingBall {
        /// Launch speed [m/s] (0: at rest).
        #[arg(long, default_value_t = 5.0)]
        speed: f64,
        /// Time step [s].
        #[arg(long, default_value_t = 1.0 / 60.0)]
        dt: f64,
        /// Ball and ground material.
        #[arg(long, value_enum, default_value_t = MaterialName::Steel)]
        material: MaterialName,
        /// Ground: `plane` (half-space), `trimesh` (flat, 1 m cells) or `heightfield` (flat).
        #[arg(long, default_value = "plane")]
        ground: String,
        /// Steps to run.
        #[arg(long, default_value_t = 600)]
        steps: usize,
        /// `plain` (no plugin at all, Rapier with the same integration parameters),
        /// `coulomb`, `auto` or `creep`.
        #[arg(long, default_value = "creep")]
        fidelity: String,
        /// Rapier's solver substeps (`num_solver_iterations`; 1 makes the plugin's rotation-gap
        /// correction exact, Rapier's default is 4).
        #[arg(long, default_value_t = 1)]
        substeps: usize,
    },
    /// A driven rigid wheel (Rapier cylinder) on a granular bed (creep-dem), coupled both ways
    /// (creep-bed); CSV on stdout: `t,slip,sinkage,drawbar_pull,torque` (s, -, m, N, N m).
    WheelOnSand(crate::wheel_cmd::WheelArgs),
    /// The angle of repose of a collapsed column of spheres (creep-dem) for Coulomb only, creep
    /// only and creep + rolling torque, against Zhou et al.'s (2002) DEM correlation; CSV on
    /// stdout: `mu,rolling,creep,angle_deg,correlation_deg`.
    Repose(crate::repose_cmd::ReposeArgs),
    /// 3-D creep in the rigid regime: a rubber ball spun about the normal while it
    /// rolls (spin decay vs Kalker's linear theory) and driven rubber wheels (line contact vs
    /// Carter, crowned with a/b = 0.5 vs the boundary elements): traction against creepage.
    Wheels,
    /// A differential-drive robot (two driven crowned rubber wheels, a caster ball) turning on
    /// the spot and on an arc, with creep and as a Coulomb twin: wheel creepages, arc radius
    /// against the closed form, dissipated energy; CSV on stdout (header:
    /// `robot_cmd::SUMMARY_HEADER`, or `--series`).
    Robot(crate::robot_cmd::RobotArgs),
}

/// Built-in materials (creep-law's presets).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MaterialName {
    /// Steel, with mu = 0.5.
    Steel,
    /// Soda-lime glass.
    Glass,
    /// Soft rubber (G = 1 MPa, mu = 0.9).
    Rubber,
}

impl MaterialName {
    /// creep-law's preset.
    pub fn material(self) -> Material {
        match self {
            MaterialName::Steel => Material::steel(),
            MaterialName::Glass => Material::glass(),
            MaterialName::Rubber => Material::rubber(),
        }
    }
}

/// Runs one scenario.
pub fn run(cmd: &RunCommand, out: &mut dyn Write) -> Res {
    match cmd {
        RunCommand::Incline {
            theta_deg,
            material,
            dt,
        } => {
            let mut p = incline::InclineParams {
                theta: theta_deg.to_radians(),
                dt: *dt,
                ..Default::default()
            };
            match material {
                MaterialName::Steel => {}
                MaterialName::Glass => p.material = Material::glass(),
                MaterialName::Rubber => p.material = Material::rubber(),
            }
            let r = incline::run(&p)?;
            writeln!(
                out,
                "incline {theta_deg} deg, 0.1 m {material:?} ball, mu = {}, dt = {dt:.5} s; Q/(mu P) = {:.3}",
                p.material.friction(),
                r.q_over_mu_p
            )?;
            writeln!(
                out,
                "  quantity                      measured       expected     error"
            )?;
            row(
                out,
                "acceleration [m/s^2]",
                r.creep.acceleration,
                r.acceleration_expected,
            )?;
            row(
                out,
                "creep slip (creep - Coulomb)",
                r.creepage_measured,
                r.creepage_expected,
            )?;
            writeln!(
                out,
                "  engine's own slip (Coulomb)   {:+.4e}",
                r.coulomb.slip
            )?;
        }
        RunCommand::FrictionDrive { csv, ratios, dt } => {
            let p = friction_drive::DriveParams {
                dt: *dt,
                ..Default::default()
            };
            if let Some(bad) = ratios.iter().find(|r| !(**r >= 0.0 && **r < 1.0)) {
                return Err(format!("--ratios must be in [0, 1), got {bad}").into());
            }
            let slip_torque = p.material.friction() * p.normal_force() * p.radius;
            let torques: Vec<f64> = ratios.iter().map(|r| r * slip_torque).collect();
            let rows = friction_drive::run(&p, &torques)?;
            if *csv {
                let mut w = CsvWriter::new(
                    out,
                    &[
                        "brake_torque",
                        "p",
                        "q",
                        "q_over_mu_p",
                        "contact_radius",
                        "g",
                        "nu",
                        "mu",
                        "creepage_measured",
                        "creepage_expected",
                    ],
                )?;
                for r in rows {
                    w.row(&[
                        &r.brake_torque,
                        &r.p,
                        &r.q,
                        &r.q_over_mu_p,
                        &r.contact_radius,
                        &r.g,
                        &r.nu,
                        &r.mu,
                        &r.creepage_measured,
                        &r.creepage_expected,
                    ])?;
                }
            } else {
                writeln!(
                    out,
                    "friction drive: 0.05 m steel spheres, 10 rad/s, P = m g, dt = {dt:.5} s"
                )?;
                writeln!(
                    out,
                    "  Q/(mu P)   creepage measured   Kalker F_ss     error    (engine's own slip)"
                )?;
                for r in rows {
                    writeln!(
                        out,
                        "  {:8.3}   {:17.4e}   {:11.4e}   {:+7.2}%   ({:+.2e})",
                        r.q_over_mu_p,
                        r.creepage_measured,
                        r.creepage_expected,
                        100.0 * (r.creepage_measured / r.creepage_expected - 1.0),
                        r.creepage_engine
                    )?;
                }
            }
        }
        RunCommand::Wheels => {
            let sp = wheels_spin::SpinParams::default();
            let (rate, expected) = wheels_spin::decay_rates(&sp)?;
            writeln!(
                out,
                "spinning ball (rubber, R {} m, {} m/s, spin {} rad/s, dt {:.5} s): decay rate {rate:.4} 1/s, Kalker's linear theory {expected:.4} 1/s ({:+.2} %)",
                sp.radius,
                sp.speed,
                sp.spin,
                sp.dt,
                100.0 * (rate / expected - 1.0)
            )?;
            let line = wheels::WheelParams::default();
            let crowned = wheels::WheelParams {
                crown: Some(wheels::crown_for_ratio(line.radius, 0.5)?),
                ..line
            };
            for (name, p) in [
                ("line contact, Carter", line),
                ("crowned a/b = 0.5, BEM", crowned),
            ] {
                writeln!(
                    out,
                    "driven wheel ({name}; R {} m, {} m wide, {} m/s): share,Q/(mu P),creepage,reference Q/(mu P),error",
                    p.radius, p.width, p.speed
                )?;
                for share in [0.1, 0.3, 0.5, 0.7, 0.8, 0.9] {
                    let row = wheels::driven(&p, share)?;
                    let s = row.force_ratio(p.material.friction());
                    let s_ref = wheels::reference_force_ratio(&p, &row)?;
                    writeln!(
                        out,
                        "{share},{s:.4},{:.4e},{s_ref:.4},{:+.4}",
                        row.creepage(),
                        s - s_ref
                    )?;
                }
            }
        }
        RunCommand::FreeRolling => {
            let r = free_rolling::run(Material::steel(), 2.0, 1.0 / 60.0, 10.0)?;
            writeln!(
                out,
                "free rolling 10 s at 1/60 s from 2 m/s: Coulomb {:.6} m/s, creep {:.6} m/s (difference {:+.1e})",
                r.coulomb_speed,
                r.creep_speed,
                r.creep_speed / r.coulomb_speed - 1.0
            )?;
        }
        RunCommand::RollingBall {
            speed,
            dt,
            material,
            ground,
            steps,
            fidelity,
            substeps,
        } => {
            let ball = creep_scenes::rolling_ball::RollingBall {
                material: material.material(),
                speed: *speed,
                dt: *dt,
                ground: creep_scenes::rolling_ball::Ground::parse(ground)?,
                stepper: creep_scenes::rolling_ball::Stepper::parse(fidelity)?,
                steps: *steps,
                substeps: *substeps,
            };
            let mut w = CsvWriter::new(
                out,
                &[
                    "t",
                    "x",
                    "height",
                    "speed",
                    "omega_r",
                    "kinetic_energy",
                    "potential_energy",
                ],
            )?;
            let mut failed = None;
            ball.run(|s| {
                if failed.is_none()
                    && let Err(e) = w.row(&[
                        &s.t,
                        &s.x,
                        &s.height,
                        &s.speed,
                        &s.omega_r,
                        &s.kinetic_energy,
                        &s.potential_energy,
                    ])
                {
                    failed = Some(e);
                }
            })?;
            if let Some(e) = failed {
                return Err(e.into());
            }
        }
        RunCommand::WheelOnSand(a) => crate::wheel_cmd::run(a, out)?,
        RunCommand::Robot(a) => crate::robot_cmd::run(a, out)?,
        RunCommand::Repose(a) => crate::repose_cmd::run(a, out)?,
        RunCommand::CueBall => {
            let r = cue_ball::run(Material::steel(), 2.0, 1.0 / 240.0)?;
            writeln!(out, "cue ball from 2 m/s, mu = 0.3, dt = 1/240 s")?;
            row(
                out,
                "final speed (creep) [m/s]",
                r.creep.final_speed,
                r.final_speed_expected,
            )?;
            row(
                out,
                "final speed (Coulomb) [m/s]",
                r.coulomb.final_speed,
                r.final_speed_expected,
            )?;
            row(
                out,
                "slip time (creep) [s]",
                r.creep.slip_time,
                r.slip_time_expected,
            )?;
        }
    }
    Ok(())
}

fn row(out: &mut dyn Write, name: &str, measured: f64, expected: f64) -> Res {
    writeln!(
        out,
        "  {name:<28}  {measured:12.5e}   {expected:12.5e}   {:+.3}%",
        100.0 * (measured / expected - 1.0)
    )?;
    Ok(())
}

/// The scenario part of the default tour.
pub fn tour(out: &mut dyn Write) -> Res {
    writeln!(
        out,
        "4. In Rapier (crate creep-rapier, rigid regime), measured against closed forms:"
    )?;
    run(
        &RunCommand::Incline {
            theta_deg: 20.0,
            material: MaterialName::Steel,
            dt: 1.0 / 240.0,
        },
        out,
    )?;
    run(
        &RunCommand::FrictionDrive {
            csv: false,
            ratios: vec![0.2, 0.5, 0.8, 0.94],
            dt: 1.0 / 240.0,
        },
        out,
    )?;
    run(&RunCommand::FreeRolling, out)?;
    writeln!(out)?;
    writeln!(
        out,
        "More: creep run incline|friction-drive [--csv]|free-rolling|cue-ball; creep law ...; creep ref ..."
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn friction_drive_csv_has_the_documented_header() {
        let mut buf = Vec::new();
        run(
            &RunCommand::FrictionDrive {
                csv: true,
                ratios: vec![0.5],
                dt: 1.0 / 240.0,
            },
            &mut buf,
        )
        .unwrap();
        let text = String::from_utf8(buf).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some(
                "brake_torque,p,q,q_over_mu_p,contact_radius,g,nu,mu,creepage_measured,creepage_expected"
            )
        );
        let cols: Vec<f64> = lines
            .next()
            .unwrap()
            .split(',')
            .map(|c| c.parse().unwrap())
            .collect();
        assert_eq!(cols.len(), 10);
        assert!((cols[8] / cols[9] - 1.0).abs() < 0.01, "{cols:?}");
    }

    #[test]
    fn rolling_ball_csv_has_the_documented_header_and_rolls() {
        let mut out = Vec::new();
        run(
            &RunCommand::RollingBall {
                speed: 5.0,
                dt: 1.0 / 60.0,
                material: MaterialName::Steel,
                ground: "plane".into(),
                steps: 60,
                fidelity: "creep".into(),
                substeps: 1,
            },
            &mut out,
        )
        .unwrap();
        let text = String::from_utf8(out).unwrap();
        let mut lines = text.lines();
        assert_eq!(
            lines.next(),
            Some("t,x,height,speed,omega_r,kinetic_energy,potential_energy")
        );
        let last: Vec<f64> = text
            .lines()
            .last()
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(text.lines().count(), 62);
        // One second at 5 m/s, rolling without slip.
        assert!((last[1] - 5.0).abs() < 0.01, "{last:?}");
        assert!((last[3] - last[4]).abs() < 1e-3 * last[3], "{last:?}");
        for bad in ["moon", ""] {
            let r = run(
                &RunCommand::RollingBall {
                    speed: 5.0,
                    dt: 1.0 / 60.0,
                    material: MaterialName::Steel,
                    ground: bad.into(),
                    steps: 1,
                    fidelity: "creep".into(),
                    substeps: 1,
                },
                &mut Vec::new(),
            );
            assert!(r.is_err());
        }
    }

    #[test]
    fn bad_ratio_is_an_error() {
        let mut buf = Vec::new();
        assert!(
            run(
                &RunCommand::FrictionDrive {
                    csv: true,
                    ratios: vec![1.2],
                    dt: 1.0 / 240.0
                },
                &mut buf
            )
            .is_err()
        );
    }
}
