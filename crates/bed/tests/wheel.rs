//! The driven wheel runs and the grains resist its spin.

use creep_bed::wheel::{WheelOnSand, wheel_on_sand};
use creep_dem::Cheap;

#[test]
fn a_driven_wheel_sinks_in_and_needs_a_driving_torque() {
    let mut s = WheelOnSand::with_grains(400, 0.3);
    s.bed.gravity = 100.0;
    s.settle_steps = 6000;
    s.sink_steps = 60;
    s.drive_steps = 60;
    s.spin = 5.0;
    let mut rows = Vec::new();
    let grains = wheel_on_sand::<Cheap>(&s, |r| rows.push(r)).unwrap();
    assert!(grains >= 384);
    assert_eq!(rows.len(), s.drive_steps);
    for r in &rows {
        assert!(
            r.t.is_finite()
                && r.sinkage.is_finite()
                && r.drawbar_pull.is_finite()
                && r.torque.is_finite()
        );
    }
    for r in &rows {
        println!(
            "{:.4e} {:.4e} {:.4e} {:.4e}",
            r.t, r.sinkage, r.drawbar_pull, r.torque
        );
    }
    // Over this short run the torque and the drawbar pull oscillate (a stick-slip cycle of about
    // 10 ms); their means over the whole drive are what is asserted: the motor does positive
    // work on average (the grains resist the spin), and the wheel digs in as it slips.
    let torque = rows.iter().map(|r| r.torque).sum::<f64>() / rows.len() as f64;
    let (first, last) = (rows[0].sinkage, rows[rows.len() - 1].sinkage);
    println!("mean torque {torque:.3e} N m, sinkage {first:.3e} -> {last:.3e} m");
    assert!(torque > 0.0, "the grains resist the spin: {torque}");
    assert!(
        first > 0.0 && last > first,
        "the wheel digs in: {first} -> {last}"
    );
    assert!(last < s.radius_factor * s.bed.radius, "{last}");
    // Bad input is a typed error.
    let mut bad = s;
    bad.slip = 1.5;
    assert!(wheel_on_sand::<Cheap>(&bad, |_| {}).is_err());
}
