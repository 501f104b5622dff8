//! The driven wheel on a small bed: it sinks in, the settled and landed states are reused
//! exactly, more slip gives more drawbar pull and more torque, and bad input is a typed error; the drive stepped one game step at a time
//! (`Landed::start`, `Driving::step`, what a viewer does) is the same run as `Landed::drive`, and
//! its read-only views (the wheel's pose, the grains touching it) agree with the exchange.

use creep_bed::BedError;
use creep_bed::wheel::{WheelOnSand, settle, sweep};
use creep_dem::Cheap;
use creep_law::CreepModel;

/// A bed of 300 grains (10 x 5 x 6), a wheel of 5 grain radii, short phases: seconds in debug.
fn small() -> WheelOnSand {
    let mut s = WheelOnSand::with_grains(640).unwrap();
    s.bed.counts = [10, 5, 6];
    s.radius_factor = 5.0;
    s.settle_steps = 4000;
    s.sink_steps = 40;
    s.drive_steps = 60;
    s.spin = 10.0;
    s
}

#[test]
fn the_landed_state_is_reused_exactly_and_slip_raises_pull_and_torque() {
    let s = small();
    let settled = settle::<Cheap>(&s).unwrap();
    assert_eq!(settled.grains(), 300);
    let landed = settled.land(Some(CreepModel::Kuhn)).unwrap();
    let mut rows = Vec::new();
    let a = landed.drive(0.0, |r| rows.push(r)).unwrap();
    assert_eq!(rows.len(), s.drive_steps);
    for r in &rows {
        assert!(r.sinkage.is_finite() && r.drawbar_pull.is_finite() && r.torque.is_finite());
    }
    // A second drive from the same landed state is the same run, bit for bit.
    let mut again = Vec::new();
    let b = landed.drive(0.0, |r| again.push(r)).unwrap();
    assert_eq!(rows, again);
    assert_eq!(a.sinkage, b.sinkage);
    let c = landed.drive(0.6, |_| {}).unwrap();
    println!("slip 0: {a:?}\nslip 0.6: {c:?}");
    // The wheel rests in the bed, below the surface and above its own axle's depth.
    assert!(a.sinkage > 0.0 && a.sinkage < a.radius, "{}", a.sinkage);
    // The travel is what the prescribed speed gives: v = w R (1 - s).
    let v0 = s.spin * a.radius * a.duration;
    assert!((a.travel / v0 - 1.0).abs() < 1e-3, "{} vs {v0}", a.travel);
    assert!((c.travel / (0.4 * v0) - 1.0).abs() < 1e-3);
    // More slip: more thrust from the bed (drawbar pull) and a larger driving torque.
    assert!(
        c.drawbar_pull > a.drawbar_pull,
        "pull {} (slip 0.6) vs {} (slip 0)",
        c.drawbar_pull,
        a.drawbar_pull
    );
    assert!(c.torque > a.torque, "torque {} vs {}", c.torque, a.torque);
    assert!(c.torque > 0.0, "a slipping wheel needs a driving torque");
    // The bed dissipates what the motor, the carriage and gravity put in.
    assert!(
        c.power() > 0.0 && a.power() > 0.0,
        "{} {}",
        a.power(),
        c.power()
    );
}

#[test]
fn bad_input_is_a_typed_error() {
    assert!(matches!(
        WheelOnSand::with_grains(0),
        Err(BedError::Parameter { name: "grains", .. })
    ));
    let s = small();
    for slip in [-0.1, 1.0, 1.5, f64::NAN] {
        assert!(matches!(
            sweep::<Cheap>(&s, &[slip], &[None], 1, |_| {}),
            Err(BedError::Parameter { name: "slip", .. })
        ));
    }
    assert!(sweep::<Cheap>(&s, &[0.2], &[None], 0, |_| {}).is_err());
    assert!(sweep::<Cheap>(&s, &[], &[None], 1, |_| {}).is_err());
    let mut long = s;
    long.drive_steps = 100_000;
    assert!(matches!(
        settle::<Cheap>(&long),
        Err(BedError::Parameter {
            name: "drive_steps",
            ..
        })
    ));
    let mut walled = s;
    walled.bed.periodic_z = false;
    assert!(settle::<Cheap>(&walled).is_err());
    let mut spin = s;
    spin.spin = 0.0;
    assert!(settle::<Cheap>(&spin).is_err());
}

#[test]
fn stepping_a_drive_is_the_drive() {
    let s = small();
    let settled = settle::<Cheap>(&s).unwrap();
    let landed = settled.land(Some(CreepModel::Kuhn)).unwrap();
    let slip = 0.3;
    let mut rows = Vec::new();
    let whole = landed.drive(slip, |r| rows.push(r)).unwrap();

    let mut d = landed.start(slip).unwrap();
    assert_eq!(d.steps(), 0);
    let x0 = f64::from(d.wheel_pose().translation.x);
    let mut touched = 0;
    for (k, expected) in rows.iter().enumerate() {
        let r = d.step().unwrap();
        assert_eq!(&r, expected, "game step {k}");
        assert_eq!(d.steps(), k + 1);
        // The grains the viewer marks are those the exchange counted at the last sub-step.
        let e = d.bed().boundaries().exchange(0).unwrap();
        assert_eq!(d.bed().boundaries().touching(0).count(), e.contacts);
        touched += e.contacts;
        // Every touching grain id is a grain of the engine.
        assert!(
            d.bed()
                .boundaries()
                .touching(0)
                .all(|id| id < d.bed().dem().len())
        );
    }
    assert!(touched > 0, "the wheel never touched a grain");
    // The axle moved at the prescribed speed (f32 positions).
    let travel = f64::from(d.wheel_pose().translation.x) - x0;
    let expected = d.speed() * rows.len() as f64 * s.dt_rigid().unwrap();
    assert!(
        (travel / expected - 1.0).abs() < 1e-3,
        "{travel} vs {expected}"
    );
    assert!(!d.at_track_end());
    let stepped = d.finish().unwrap();
    assert_eq!(
        (stepped.sinkage, stepped.drawbar_pull, stepped.torque),
        (whole.sinkage, whole.drawbar_pull, whole.torque)
    );
    assert_eq!(stepped.travel, whole.travel);
    assert_eq!(stepped.sinkage_rate, whole.sinkage_rate);
    // An unknown boundary has no contacts; a bad slip is a typed error.
    assert_eq!(
        landed
            .start(0.0)
            .unwrap()
            .bed()
            .boundaries()
            .touching(7)
            .count(),
        0
    );
    assert!(landed.start(1.0).is_err());
    assert!(landed.start(f64::NAN).is_err());
    // Fewer than 4 game steps have no steady state.
    let mut short = landed.start(0.0).unwrap();
    short.step().unwrap();
    assert!(short.finish().is_err());
}
