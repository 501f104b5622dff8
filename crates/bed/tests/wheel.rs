//! The driven wheel on a small bed: it sinks in, the settled and landed states are reused
//! exactly, more slip gives more drawbar pull and more torque, and bad input is a typed error.

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
