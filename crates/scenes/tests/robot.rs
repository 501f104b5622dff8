//! The differential-drive robot (issue #17, part 4; creep-scenes `robot`): its kinematics
//! against the closed forms of a differential drive, its wheels' creepages, and the energy its
//! contacts dissipate with creep and in the Coulomb twin.

use creep_rapier::Fidelity;
use creep_scenes::robot::{self, RobotParams, RobotRun, WheelSpeeds};

fn print(name: &str, r: &RobotRun) {
    let s = &r.summary;
    eprintln!(
        "{name} {:?}: V {:.5} m/s, Omega {:.5} rad/s (closed form {:.5}), R {:.5} m (closed form {:.5}), rim {:.5} {:.5}",
        r.fidelity,
        s.speed,
        s.yaw_rate,
        s.yaw_rate_closed_form,
        s.radius,
        s.radius_closed_form,
        s.rim_speeds[0],
        s.rim_speeds[1]
    );
    for (w, c) in [
        ("left", &s.wheels[0]),
        ("right", &s.wheels[1]),
        ("caster", &s.caster),
    ] {
        eprintln!(
            "  {w}: P {:.4} N, V {:.5}, xi {:+.4e}, eta {:+.4e}, phi {:+.4e} 1/m (law: xi {:+.4e}, eta {:+.4e}), fx {:+.4e}, fy {:+.4e} N, mz {:+.4e} N m, power {:.4e} W (hook {:.4e})",
            c.p,
            c.speed,
            c.xi,
            c.eta,
            c.phi,
            c.law_creepage[0],
            c.law_creepage[1],
            c.fx,
            c.fy,
            c.mz,
            c.power,
            c.hook_power
        );
    }
    eprintln!(
        "  dissipated {:.5e} J, hook {:.5e} J over {:.3} s",
        s.dissipated, s.hook_energy, s.window
    );
}

/// Turning on the spot (rim speeds -0.1, +0.1 m/s; b = 0.2 m): the yaw rate follows the rim
/// speeds, `(v_r - v_l)/b`, within 2 % (creep: measured -1.0 %; twin -0.1 %); each wheel's spin
/// creepage is `2/b` within 3 % (it rolls on a circle of radius `b/2`; measured -1.6 %, +0.7 %);
/// the creep run's dissipation is mostly the wheels' spin creep (Kalker's twisting moment times
/// the relative spin, over 90 %), and equals the hook's booked creep energy within 20 %
/// (measured -15 %: the engine's own lateral slip, ~1e-2 as large in the Coulomb twin, works
/// against the spin's lateral force). The Coulomb twin's single patch point has no twisting
/// friction: it dissipates under a tenth of the creep run.
#[test]
fn robot_turns_on_the_spot_with_spin_creep() {
    let p = RobotParams::default();
    let speeds = WheelSpeeds::spot(0.1);
    let creep = robot::run(&p, speeds, Fidelity::Creep).unwrap();
    let coulomb = robot::run(&p, speeds, Fidelity::Coulomb).unwrap();
    print("spot", &creep);
    print("spot", &coulomb);
    for r in [&creep, &coulomb] {
        let s = &r.summary;
        let err = s.yaw_rate / s.yaw_rate_closed_form - 1.0;
        assert!(err.abs() < 0.02, "{:?}: yaw rate error {err}", r.fidelity);
    }
    let s = &creep.summary;
    let mut spin_energy = 0.0;
    for w in &s.wheels {
        let err = w.phi / (2.0 / p.track) - 1.0;
        assert!(
            err.abs() < 0.03,
            "spin creepage {} vs {}",
            w.phi,
            2.0 / p.track
        );
        assert!(w.mz > 0.0, "twisting moment {}", w.mz);
        spin_energy += w.mz * w.twist * s.window;
    }
    assert!(
        spin_energy > 0.9 * s.dissipated,
        "spin {spin_energy} of {}",
        s.dissipated
    );
    let err = s.dissipated / s.hook_energy - 1.0;
    assert!(
        err.abs() < 0.2,
        "dissipated {} vs hook {}",
        s.dissipated,
        s.hook_energy
    );
    assert!(
        coulomb.summary.dissipated < 0.1 * s.dissipated,
        "twin {} vs creep {}",
        coulomb.summary.dissipated,
        s.dissipated
    );
}

/// An arc (rim speeds 0.1 and 0.15 m/s): the radius follows the rim speeds,
/// `(b/2)(v_r + v_l)/(v_r - v_l)`, within 1 % with creep (measured -0.04 %) and 2 % in the
/// Coulomb twin (measured -1.3 %); each wheel spins with `phi = 1/(R ∓ b/2)` within 3 %; the
/// creep law asks the wheels for lateral creep (the outer wheel carries the larger lateral
/// force: its law creepage is at least 1e-3 and above the inner one's), and the creep run's
/// dissipation equals the hook's booked creep energy within 20 % (measured +6 %).
#[test]
fn robot_drives_an_arc() {
    let p = RobotParams::default();
    let speeds = WheelSpeeds::arc(0.1, 0.15);
    let creep = robot::run(&p, speeds, Fidelity::Creep).unwrap();
    let coulomb = robot::run(&p, speeds, Fidelity::Coulomb).unwrap();
    print("arc", &creep);
    print("arc", &coulomb);
    for (r, tol) in [(&creep, 0.01), (&coulomb, 0.02)] {
        let s = &r.summary;
        let err = s.radius / s.radius_closed_form - 1.0;
        assert!(err.abs() < tol, "{:?}: radius error {err}", r.fidelity);
    }
    let s = &creep.summary;
    for (w, ri) in s
        .wheels
        .iter()
        .zip([s.radius - 0.5 * p.track, s.radius + 0.5 * p.track])
    {
        let err = w.phi * ri - 1.0;
        assert!(err.abs() < 0.03, "spin creepage {} vs 1/{ri}", w.phi);
    }
    let (inner, outer) = (s.wheels[0].law_creepage[1], s.wheels[1].law_creepage[1]);
    assert!(
        outer.abs() > 1e-3 && outer.abs() > inner.abs(),
        "law's lateral creepages {inner} {outer}"
    );
    let err = s.dissipated / s.hook_energy - 1.0;
    assert!(
        err.abs() < 0.2,
        "dissipated {} vs hook {}",
        s.dissipated,
        s.hook_energy
    );
}

/// Bad parameters are typed errors.
#[test]
fn robot_refuses_bad_parameters() {
    let bad = [
        RobotParams {
            track: 0.0,
            ..RobotParams::default()
        },
        RobotParams {
            contact_ratio: 1.5,
            ..RobotParams::default()
        },
        RobotParams {
            caster_radius: 0.1,
            ..RobotParams::default()
        },
        RobotParams {
            dt: f64::NAN,
            ..RobotParams::default()
        },
    ];
    for p in bad {
        assert!(robot::Robot::new(&p, Fidelity::Creep).is_err(), "{p:?}");
    }
    let mut r = robot::Robot::new(&RobotParams::default(), Fidelity::Creep).unwrap();
    assert!(r.set_speeds(WheelSpeeds::arc(f64::INFINITY, 0.0)).is_err());
}
