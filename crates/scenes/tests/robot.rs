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
            "  {w}: P {:.4} N, V {:.5}, xi {:+.4e}, eta {:+.4e}, phi {:+.4e} 1/m, fx {:+.4e}, fy {:+.4e} N, mz {:+.4e} N m, power {:.4e} W (hook {:.4e})",
            c.p, c.speed, c.xi, c.eta, c.phi, c.fx, c.fy, c.mz, c.power, c.hook_power
        );
    }
    eprintln!(
        "  dissipated {:.5e} J, hook {:.5e} J over {:.3} s",
        s.dissipated, s.hook_energy, s.window
    );
}

/// Turning on the spot: the yaw rate follows the wheels' rim speeds, `(v_r - v_l)/b`; each
/// wheel's spin creepage is `2/b` (it rolls on a circle of radius `b/2`) and its lateral
/// creepage is zero; the creep run's contacts dissipate what the hook books.
#[test]
fn robot_turns_on_the_spot_with_spin_creep() {
    let p = RobotParams::default();
    let speeds = WheelSpeeds::spot(0.1);
    let creep = robot::run(&p, speeds, Fidelity::Creep).unwrap();
    let coulomb = robot::run(&p, speeds, Fidelity::Coulomb).unwrap();
    print("spot", &creep);
    print("spot", &coulomb);
}

/// An arc: the radius follows the rim speeds, `(b/2)(v_r + v_l)/(v_r - v_l)`; the wheels
/// creep laterally.
#[test]
fn robot_drives_an_arc() {
    let p = RobotParams::default();
    let speeds = WheelSpeeds::arc(0.1, 0.15);
    let creep = robot::run(&p, speeds, Fidelity::Creep).unwrap();
    let coulomb = robot::run(&p, speeds, Fidelity::Coulomb).unwrap();
    print("arc", &creep);
    print("arc", &coulomb);
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

#[test]
fn scratch_heights() {
    let p = RobotParams::default();
    for f in [Fidelity::Creep, Fidelity::Coulomb] {
        let mut r = robot::Robot::new(&p, f).unwrap();
        r.set_speeds(WheelSpeeds::spot(0.1)).unwrap();
        for i in 0..960 {
            let s = r.step().unwrap();
            if i % 120 == 119 {
                let b = &r.world.physics.bodies;
                let h = |x: rapier3d::prelude::RigidBodyHandle| b[x].translation().y;
                let ws = &r.world.physics.bodies[r.wheels[0]];
                eprintln!(
                    "{f:?} t {:.2}: chassis y {:.6}, wheels {:.6} {:.6}, caster {:.6}; wheel0 angvel {:?} chassis {:?}; xi {:.3e} {:.3e} caster {:.3e}",
                    s.t,
                    h(r.chassis),
                    h(r.wheels[0]),
                    h(r.wheels[1]),
                    h(r.caster),
                    ws.angvel(),
                    b[r.chassis].angvel(),
                    s.wheels[0].xi,
                    s.wheels[1].xi,
                    s.caster.xi
                );
            }
        }
    }
}
