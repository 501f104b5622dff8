//! The drive stepped one game step at a time (`Landed::start`, `Driving::step`, what a viewer
//! does) is the same run as `Landed::drive`, and its read-only views (the wheel's pose, the
//! grains touching it) agree with the exchange.

use creep_bed::wheel::{WheelOnSand, settle};
use creep_dem::Cheap;
use creep_law::CreepModel;

/// The small bed of `tests/wheel.rs`: 300 grains, a wheel of 5 grain radii, seconds in debug.
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
